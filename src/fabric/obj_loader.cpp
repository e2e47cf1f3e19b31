// OBJ files through tinyobjloader (Debian libtinyobjloader-dev); faces are
// triangulated by the loader, then built like any triangle mesh.
#include <tiny_obj_loader.h>

#include <vector>

#include "fabric/fabric.h"

namespace cloth {

Status build_obj_fabric(const char* path, uint32_t spring_kinds, Fabric& out) {
    if (!path) return Status::error(CLOTH_ERROR_NULL_POINTER, "OBJ path is NULL");
    tinyobj::ObjReaderConfig config;
    config.triangulate = true;
    config.vertex_color = false;
    tinyobj::ObjReader reader;
    if (!reader.ParseFromFile(path, config)) {
        return Status::error(CLOTH_ERROR_IO, "cannot load OBJ '%s': %s", path, reader.Error().c_str());
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
