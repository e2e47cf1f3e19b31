// OBJ files through tinyobjloader (Debian libtinyobjloader-dev); faces are
// triangulated by the loader, then built like any triangle mesh.
//
// The loader is compiled into the library from its header (this is the one
// translation unit that defines TINYOBJLOADER_IMPLEMENTATION), so libcloth
// needs no tinyobjloader at run time. Its namespace is renamed so that
// libcloth.a links next to a host's own tinyobjloader without duplicate
// symbols; in libcloth.so it is hidden like every other internal symbol.
#define TINYOBJLOADER_IMPLEMENTATION
// The macro is the namespace's own name, which is lower case.
// NOLINTNEXTLINE(readability-identifier-naming)
#define tinyobj cloth_tinyobj
#include <tiny_obj_loader.h>

#include <string>
#include <vector>

#include "fabric/fabric.h"

#if defined(_WIN32)
#ifndef NOMINMAX
#define NOMINMAX
#endif
#ifndef WIN32_LEAN_AND_MEAN
#define WIN32_LEAN_AND_MEAN
#endif
#include <windows.h>

#include <cstdio>
#endif

namespace cloth {

namespace {

// Parse the OBJ file at `path`, a UTF-8 string (cloth.h). Elsewhere the
// bytes name the file as they are; Windows' narrow file functions would
// read them in the ANSI code page, so there the path is converted to
// UTF-16 and the file read through _wfopen.
bool parse_obj_file(const char* path, const tinyobj::ObjReaderConfig& config, tinyobj::ObjReader& reader,
                    std::string& error) {
#if defined(_WIN32)
    const int wide_length = MultiByteToWideChar(CP_UTF8, MB_ERR_INVALID_CHARS, path, -1, nullptr, 0);
    if (wide_length <= 0) {
        error = "the path is not valid UTF-8";
        return false;
    }
    std::wstring wide(static_cast<size_t>(wide_length), L'\0');
    MultiByteToWideChar(CP_UTF8, MB_ERR_INVALID_CHARS, path, -1, &wide[0], wide_length);
    std::FILE* file = _wfopen(wide.c_str(), L"rb");
    if (!file) {
        error = "cannot open the file";
        return false;
    }
    std::string text;
    char chunk[16384];
    size_t n = 0;
    while ((n = std::fread(chunk, 1, sizeof chunk, file)) > 0) text.append(chunk, n);
    const bool read_error = std::ferror(file) != 0;
    std::fclose(file);
    if (read_error) {
        error = "cannot read the file";
        return false;
    }
    // Materials are not used: no .mtl text.
    if (!reader.ParseFromString(text, std::string(), config)) {
        error = reader.Error();
        return false;
    }
    return true;
#else
    if (!reader.ParseFromFile(path, config)) {
        error = reader.Error();
        return false;
    }
    return true;
#endif
}

}  // namespace

Status build_obj_fabric(const char* path, uint32_t spring_kinds, Fabric& out) {
    if (!path) return Status::error(CLOTH_ERROR_NULL_POINTER, "OBJ path is NULL");
    tinyobj::ObjReaderConfig config;
    config.triangulate = true;
    config.vertex_color = false;
    tinyobj::ObjReader reader;
    std::string error;
    if (!parse_obj_file(path, config, reader, error)) {
        return Status::error(CLOTH_ERROR_IO, "cannot load OBJ '%s': %s", path, error.c_str());
    }
    const auto& vertices = reader.GetAttrib().vertices;
    std::vector<uint32_t> indices;
    for (const auto& shape : reader.GetShapes()) {
        for (const auto& index : shape.mesh.indices) {
            if (index.vertex_index < 0) {
                return Status::error(CLOTH_ERROR_IO, "OBJ '%s' has a face with a bad vertex index", path);
            }
            indices.push_back(static_cast<uint32_t>(index.vertex_index));
        }
    }
    if (vertices.empty() || indices.empty()) {
        return Status::error(CLOTH_ERROR_IO, "OBJ '%s' has no triangles", path);
    }
    if (vertices.size() / 3 > kMaxParticles || indices.size() / 3 > kMaxTriangles) {
        return Status::error(CLOTH_ERROR_INVALID_COUNT, "OBJ '%s' has more than %u vertices or %u triangles",
                             path, kMaxParticles, kMaxTriangles);
    }
    return build_mesh_fabric(vertices.data(), static_cast<uint32_t>(vertices.size() / 3), indices.data(),
                             static_cast<uint32_t>(indices.size() / 3), spring_kinds, out);
}

}  // namespace cloth
