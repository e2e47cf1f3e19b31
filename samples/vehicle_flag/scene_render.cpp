#include "scene_render.h"

#include <stb_image_write.h>

#include <algorithm>
#include <cmath>

#include "render_png.h"

namespace vehicle_flag {
namespace {

struct Mesh {
    std::vector<float> positions;
    std::vector<uint32_t> indices;
};

void append_box(const btTransform& pose, const btVector3& center, const btVector3& half, Mesh* mesh) {
    const uint32_t base = static_cast<uint32_t>(mesh->positions.size() / 3);
    for (int corner = 0; corner < 8; ++corner) {
        const btVector3 local =
            center + btVector3((corner & 1) ? half.x() : -half.x(), (corner & 2) ? half.y() : -half.y(),
                               (corner & 4) ? half.z() : -half.z());
        const btVector3 p = pose * local;
        mesh->positions.insert(mesh->positions.end(), {p.x(), p.y(), p.z()});
    }
    const uint32_t faces[6][4] = {{0, 1, 3, 2}, {4, 6, 7, 5}, {0, 4, 5, 1},
                                  {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 5, 7, 3}};
    for (const auto& f : faces) {
        mesh->indices.insert(mesh->indices.end(),
                             {base + f[0], base + f[1], base + f[2], base + f[0], base + f[2], base + f[3]});
    }
}

// A closed cylinder of `segments` sides around the local axis `axis` (0 = x, 1 = y).
void append_cylinder(const btTransform& pose, const btVector3& center, int axis, float radius,
                     float half_length, int segments, Mesh* mesh) {
    const uint32_t base = static_cast<uint32_t>(mesh->positions.size() / 3);
    for (int s = 0; s < segments; ++s) {
        const float angle = 6.2831853f * s / segments;
        const float a = radius * std::cos(angle), b = radius * std::sin(angle);
        for (int end = 0; end < 2; ++end) {
            const float along = end ? half_length : -half_length;
            const btVector3 local = axis == 0 ? btVector3(along, a, b) : btVector3(a, along, b);
            const btVector3 p = pose * (center + local);
            mesh->positions.insert(mesh->positions.end(), {p.x(), p.y(), p.z()});
        }
    }
    for (int end = 0; end < 2; ++end) {
        const btVector3 p = pose * (center + (axis == 0 ? btVector3(end ? half_length : -half_length, 0, 0)
                                                        : btVector3(0, end ? half_length : -half_length, 0)));
        mesh->positions.insert(mesh->positions.end(), {p.x(), p.y(), p.z()});
    }
    const uint32_t cap0 = base + 2 * segments, cap1 = cap0 + 1;
    for (int s = 0; s < segments; ++s) {
        const uint32_t a0 = base + 2 * s, a1 = a0 + 1;
        const uint32_t b0 = base + 2 * ((s + 1) % segments), b1 = b0 + 1;
        mesh->indices.insert(mesh->indices.end(), {a0, b0, b1, a0, b1, a1, cap0, b0, a0, cap1, a1, b1});
    }
}

cloth_samples::RenderMesh as_render_mesh(const Mesh& mesh, const float* normals, uint8_t r, uint8_t g,
                                         uint8_t b) {
    return {mesh.positions.data(),
            normals,
            static_cast<uint32_t>(mesh.positions.size() / 3),
            mesh.indices.data(),
            static_cast<uint32_t>(mesh.indices.size() / 3),
            {r, g, b}};
}

}  // namespace

Moment capture_moment(const std::string& label, float time, const VehicleWorld& vehicle,
                      const std::vector<float>& flag_positions, const std::vector<float>& flag_normals) {
    Moment m;
    m.label = label;
    m.time = time;
    m.chassis = vehicle.chassis_pose();
    for (int w = 0; w < vehicle.wheel_count(); ++w) m.wheels.push_back(vehicle.wheel_pose(w));
    m.flag_positions = flag_positions;
    m.flag_normals = flag_normals;
    return m;
}

bool render_moment(const Moment& m, const Terrain& terrain, const VehicleLayout& v,
                   const std::vector<uint32_t>& flag_triangles, int width, int height,
                   std::vector<uint8_t>* rgb, std::string* error) {
    const btVector3 origin = m.chassis.getOrigin();
    Mesh ground, body, pole, wheels;
    terrain.patch_mesh(origin.x(), origin.z(), 40.0f, &ground.positions, &ground.indices);
    append_box(m.chassis, btVector3(v.box_center[0], v.box_center[1], v.box_center[2]),
               btVector3(v.box_half_extents[0], v.box_half_extents[1], v.box_half_extents[2]), &body);
    append_cylinder(m.chassis,
                    btVector3(v.pole_base[0], v.pole_base[1] + 0.5f * v.pole_height, v.pole_base[2]), 1,
                    v.pole_radius, 0.5f * v.pole_height, 12, &pole);
    for (const btTransform& wheel : m.wheels) {
        append_cylinder(wheel, btVector3(0, 0, 0), 0, v.wheel_radius, v.wheel_half_width, 16, &wheels);
    }
    Mesh flag;
    flag.positions = m.flag_positions;
    flag.indices = flag_triangles;
    const cloth_samples::RenderMesh meshes[] = {
        as_render_mesh(ground, nullptr, 150, 170, 120),
        as_render_mesh(body, nullptr, 60, 90, 160),
        as_render_mesh(pole, nullptr, 200, 200, 205),
        as_render_mesh(wheels, nullptr, 40, 40, 45),
        as_render_mesh(flag, m.flag_normals.data(), 215, 40, 45),
    };
    // Chase camera behind and to the side of the vehicle, level with the world's up.
    const btVector3 eye = m.chassis * btVector3(4.5f, 3.4f, -6.5f);
    const btVector3 target = m.chassis * btVector3(0.0f, 2.0f, -1.5f);
    const cloth_samples::Camera camera{
        {eye.x(), eye.y(), eye.z()}, {target.x(), target.y(), target.z()}, {0, 1, 0}, 40.0f};
    cloth_samples::RenderOptions options;
    options.width = width;
    options.height = height;
    options.draw_ground_grid = false;
    return cloth_samples::render_rgb(camera, meshes, sizeof meshes / sizeof meshes[0], options, rgb, error);
}

bool render_moments(const std::string& path, const std::vector<Moment>& moments, const Terrain& terrain,
                    const VehicleLayout& v, const std::vector<uint32_t>& flag_triangles, int panel_width,
                    int panel_height, std::string* error) {
    if (moments.empty()) {
        *error = "no moments to render";
        return false;
    }
    const int columns = moments.size() > 1 ? 2 : 1;
    const int rows = static_cast<int>((moments.size() + columns - 1) / columns);
    const int width = columns * panel_width, height = rows * panel_height;
    std::vector<uint8_t> picture(static_cast<size_t>(width) * height * 3, 255);

    for (size_t i = 0; i < moments.size(); ++i) {
        std::vector<uint8_t> panel;
        if (!render_moment(moments[i], terrain, v, flag_triangles, panel_width, panel_height, &panel,
                           error)) {
            return false;
        }
        const int px = static_cast<int>(i % columns) * panel_width,
                  py = static_cast<int>(i / columns) * panel_height;
        for (int y = 0; y < panel_height; ++y) {
            std::copy(panel.begin() + static_cast<size_t>(y) * panel_width * 3,
                      panel.begin() + static_cast<size_t>(y + 1) * panel_width * 3,
                      picture.begin() + (static_cast<size_t>(py + y) * width + px) * 3);
        }
    }
    if (!stbi_write_png(path.c_str(), width, height, 3, picture.data(), width * 3)) {
        *error = "cannot write '" + path + "'";
        return false;
    }
    return true;
}

}  // namespace vehicle_flag
