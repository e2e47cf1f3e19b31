// Headless software rendering of triangle meshes to a PNG file, used by the samples
// to show the cloth as a picture.
//
// Conventions: right-handed world, y is up. Positions and normals are packed xyz
// triplets, indices are packed triangle triplets. Rendering is perspective with a
// z-buffer, smooth (per-pixel interpolated) normals and two-sided Lambert + ambient
// lighting, 2x2 supersampling for images of up to 2048 x 2048 pixels; triangles
// with a vertex closer than 0.01 units to the eye (or behind it) are dropped.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace cloth_samples {

struct Camera {
    float eye[3];
    float target[3];
    float up[3];          // need not be orthogonal to the view direction, must not be parallel to it
    float fov_y_degrees;  // vertical field of view, in (0, 180)
};

struct RenderMesh {
    const float* positions;  // vertex_count xyz triplets
    const float* normals;    // vertex_count xyz triplets, or null: flat face normals are used
    uint32_t vertex_count;
    const uint32_t* indices;  // triangle_count index triplets, each < vertex_count
    uint32_t triangle_count;
    uint8_t color[3];  // base RGB colour
};

struct RenderOptions {
    int width = 800;   // 1..8192
    int height = 600;  // 1..8192
    uint8_t background[3] = {235, 238, 242};
    float light_dir[3] = {-0.4f, 0.8f, 0.45f};  // direction towards the light; normalized internally
    bool draw_ground_grid = true;               // thin lines on the plane y = ground_y, sized to the meshes
    float ground_y = 0.0f;
};

// Renders the meshes and writes an RGB PNG to `path`. Returns false and, when
// `error` is non-null, stores a message in *error if the input is invalid (null
// pointers, index out of range, non-finite values, size outside 1..8192, degenerate
// camera) or the file cannot be written. Invalid input never creates a file.
bool render_png(const std::string& path, const Camera& camera, const RenderMesh* meshes, size_t mesh_count,
                const RenderOptions& options, std::string* error);

// Same rendering into memory: on success *rgb holds options.width x
// options.height RGB pixels, rows top to bottom (for composing several views
// into one picture). Same validation as render_png; on failure *rgb is unchanged.
bool render_rgb(const Camera& camera, const RenderMesh* meshes, size_t mesh_count,
                const RenderOptions& options, std::vector<uint8_t>* rgb, std::string* error);

// Tiles panels of panel_width x panel_height RGB pixels (each as
// render_rgb leaves it), two to a row, into one PNG; false with a message
// in *error if a panel has the wrong size or the file cannot be written.
bool write_panels_png(const std::string& path, const std::vector<std::vector<uint8_t>>& panels,
                      int panel_width, int panel_height, std::string* error);

// Prints "wrote PATH: [label, t=T s] ..." for moments with a `label`
// string and a `time` in seconds.
template <class Moments>
void print_written_moments(const std::string& path, const Moments& moments) {
    std::printf("wrote %s:", path.c_str());
    for (const auto& m : moments)
        std::printf(" [%s, t=%.2f s]", m.label.c_str(), static_cast<double>(m.time));
    std::printf("\n");
}

}  // namespace cloth_samples
