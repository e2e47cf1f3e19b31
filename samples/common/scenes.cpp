#include "scenes.h"

#include <cmath>

namespace cloth_samples {

const char* scene_name(SceneKind kind) {
    switch (kind) {
        case SceneKind::kHanging:
            return "hanging";
        case SceneKind::kFallingFlat:
            return "falling_flat";
        case SceneKind::kFlagInWind:
            return "flag_in_wind";
        case SceneKind::kDrapedSphere:
            return "draped_sphere";
    }
    return "unknown";
}

Scene::Scene(const SceneConfig& config) : kind_(config.kind) {
    auto fail = [this](const char* what, cloth_result r) {
        error_ = std::string(what) + ": " + cloth_result_name(r) + " " + cloth_get_last_error();
    };
    cloth_world_desc world_desc = config.world;
    cloth_result r = cloth_world_create(&world_desc, &world_);
    if (r != CLOTH_OK) {
        fail("cloth_world_create", r);
        return;
    }

    const uint32_t n = config.resolution;
    cloth_grid_desc grid = cloth_default_grid_desc();
    grid.columns = n;
    grid.rows = n;
    grid.spring_kinds = config.spring_kinds;
    grid.origin[1] = 1.5f;
    if (config.kind == SceneKind::kFallingFlat || config.kind == SceneKind::kDrapedSphere) {
        // horizontal: rows run along +z
        grid.v[1] = 0.0f;
        grid.v[2] = 1.0f;
    }
    if (config.mesh) {
        // The grid's vertices, row by row, and two triangles per cell.
        std::vector<float> vertices;
        std::vector<uint32_t> triangles;
        for (uint32_t row = 0; row < n; ++row) {
            for (uint32_t column = 0; column < n; ++column) {
                const float s = static_cast<float>(column) / static_cast<float>(n - 1);
                const float t = static_cast<float>(row) / static_cast<float>(n - 1);
                for (int k = 0; k < 3; ++k)
                    vertices.push_back(grid.origin[k] + s * grid.u[k] + t * grid.v[k]);
                if (row + 1 < n && column + 1 < n) {
                    const uint32_t a = row * n + column, b = a + 1, c = a + n, d = c + 1;
                    triangles.insert(triangles.end(), {a, b, d, a, d, c});
                }
            }
        }
        cloth_mesh_desc mesh = cloth_default_mesh_desc();
        mesh.positions = vertices.data();
        mesh.vertex_count = n * n;
        mesh.indices = triangles.data();
        mesh.triangle_count = static_cast<uint32_t>(triangles.size() / 3);
        mesh.spring_kinds = config.spring_kinds;
        r = cloth_fabric_create_mesh(world_, &mesh, &fabric_);
    } else {
        r = cloth_fabric_create_grid(world_, &grid, &fabric_);
    }
    if (r != CLOTH_OK) {
        fail(config.mesh ? "cloth_fabric_create_mesh" : "cloth_fabric_create_grid", r);
        return;
    }

    cloth_desc desc = cloth_default_desc();
    desc.fabric = fabric_;
    desc.area_density = config.total_mass;  // 1 m^2
    desc.structural = desc.shear = desc.bend = cloth_spring_params{config.stiffness, config.damping};
    desc.solver = config.solver;
    if (config.kind == SceneKind::kFlagInWind) {
        // Wind blows along the flag (from the pole outwards) with a small
        // cross component, so the flag streams and flutters.
        desc.aero.wind[0] = config.wind_speed;
        desc.aero.wind[2] = 0.1f * config.wind_speed;
    }
    if (config.still_air) {
        desc.aero = cloth_default_desc().aero;
        desc.aero.air_density = 0;
        desc.aero.linear_drag = 0;
    }
    particle_count_ = n * n;
    std::vector<float> start(3 * static_cast<size_t>(particle_count_));
    if (config.out_of_plane > 0) {
        const float normal[3] = {grid.u[1] * grid.v[2] - grid.u[2] * grid.v[1],
                                 grid.u[2] * grid.v[0] - grid.u[0] * grid.v[2],
                                 grid.u[0] * grid.v[1] - grid.u[1] * grid.v[0]};
        uint32_t seed = 12345;
        for (uint32_t i = 0; i < particle_count_; ++i) {
            seed = seed * 1664525u + 1013904223u;  // a fixed sequence, the same on every machine
            const float offset = config.out_of_plane * (static_cast<float>(seed >> 8) / 8388608.0f - 1.0f);
            const float s = static_cast<float>(i % n) / static_cast<float>(n - 1);
            const float t = static_cast<float>(i / n) / static_cast<float>(n - 1);
            for (int k = 0; k < 3; ++k)
                start[3 * i + k] = grid.origin[k] + s * grid.u[k] + t * grid.v[k] + offset * normal[k];
        }
        desc.initial_positions = start.data();
    }
    for (uint32_t copy = 0; copy < config.copies; ++copy) {
        cloth_id cloth{};
        if (copy > 0) {
            // The same cloth 1.5 m further along z.
            r = cloth_read_positions(cloths_[0], start.data(), static_cast<uint32_t>(start.size()));
            for (size_t i = 2; i < start.size(); i += 3) start[i] += 1.5f * static_cast<float>(copy);
            desc.initial_positions = start.data();
        }
        r = cloth_create(world_, &desc, &cloth);
        if (r != CLOTH_OK) {
            fail("cloth_create", r);
            return;
        }
        cloths_.push_back(cloth);
        if (config.strain_limit > 0) {
            cloth_strain_limit limit = cloth_default_strain_limit();
            limit.max_strain = config.strain_limit;
            r = cloth_set_strain_limit(cloth, &limit);
            if (r != CLOTH_OK) {
                fail("cloth_set_strain_limit", r);
                return;
            }
        }
    }

    std::vector<uint32_t> pins;
    if (config.kind == SceneKind::kFlagInWind) {
        for (uint32_t row = 0; row < n; ++row) pins.push_back(row * n);
    } else if (config.kind == SceneKind::kDrapedSphere) {
        return;  // free: it comes to rest on the sphere
    } else {
        pins = {0, n - 1};
    }
    for (cloth_id cloth : cloths_) {
        r = cloth_pin(cloth, pins.data(), static_cast<uint32_t>(pins.size()));
        if (r != CLOTH_OK) {
            fail("cloth_pin", r);
            return;
        }
    }
}

Scene::~Scene() {
    if (world_.index1) cloth_world_destroy(world_);
}

cloth_result Scene::step(float dt) {
    const cloth_result result = cloth_step(world_, dt);
    if (kind_ != SceneKind::kDrapedSphere || result != CLOTH_OK) return result;
    for (cloth_id cloth : cloths_) {
        scratch_.resize(3 * static_cast<size_t>(particle_count_));
        cloth_read_positions(cloth, scratch_.data(), static_cast<uint32_t>(scratch_.size()));
        inside_.clear();
        moved_.clear();
        for (uint32_t i = 0; i < particle_count_; ++i) {
            float d[3], length2 = 0;
            for (int c = 0; c < 3; ++c) {
                d[c] = scratch_[3 * i + c] - kSphereCenter[c];
                length2 += d[c] * d[c];
            }
            if (length2 >= kSphereRadius * kSphereRadius || length2 == 0) continue;
            const float scale = kSphereRadius / std::sqrt(length2);
            inside_.push_back(i);
            for (int c = 0; c < 3; ++c) moved_.push_back(kSphereCenter[c] + d[c] * scale);
        }
        if (inside_.empty()) continue;
        const cloth_result r =
            cloth_set_positions(cloth, inside_.data(), moved_.data(), static_cast<uint32_t>(inside_.size()));
        if (r != CLOTH_OK) return r;
    }
    return result;
}

cloth_stats Scene::stats() const {
    cloth_stats stats{};
    stats.struct_size = sizeof stats;
    cloth_get_stats(cloth(), &stats);
    return stats;
}

std::vector<float> Scene::positions() const {
    std::vector<float> xyz(3 * static_cast<size_t>(particle_count_));
    cloth_read_positions(cloth(), xyz.data(), static_cast<uint32_t>(xyz.size()));
    return xyz;
}

}  // namespace cloth_samples
