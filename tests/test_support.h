// Helpers for tests that drive the C++ core directly (no C API).
#pragma once

#include <memory>
#include <random>
#include <stdexcept>
#include <vector>

#include "fabric/fabric.h"
#include "step/cloth_instance.h"

namespace cloth::testing {

inline const HostMemory* heap() {
    static const HostMemory memory{};
    return &memory;
}

// A columns x rows grid of 1 m x 1 m hanging in the xy plane from y = 0.
inline std::shared_ptr<Fabric> make_grid(uint32_t columns, uint32_t rows, uint32_t kinds = CLOTH_SPRING_ALL) {
    auto fabric = std::make_shared<Fabric>(heap());
    cloth_grid_desc desc = cloth_default_grid_desc();
    desc.columns = columns;
    desc.rows = rows;
    desc.spring_kinds = kinds;
    const Status status = build_grid_fabric(desc, *fabric);
    if (!status.ok()) throw std::runtime_error(status.message);
    return fabric;
}

// The same grid's particles and triangles as a general mesh (index-pair
// springs: structural and bend, no shear).
inline std::shared_ptr<Fabric> make_mesh_from_grid(uint32_t columns, uint32_t rows) {
    auto grid = make_grid(columns, rows);
    std::vector<float> positions;
    for (const Vec3& p : grid->rest_positions) positions.insert(positions.end(), {p.x(), p.y(), p.z()});
    auto mesh = std::make_shared<Fabric>(heap());
    const Status status = build_mesh_fabric(positions.data(), grid->particle_count(), grid->triangles.data(),
                                            grid->triangle_count(), CLOTH_SPRING_ALL, *mesh);
    if (!status.ok()) throw std::runtime_error(status.message);
    return mesh;
}

inline Material uniform_material(float stiffness, float damping, float area_density) {
    Material material;
    for (auto& spring : material.springs) spring = {stiffness, damping};
    material.area_density = area_density;
    return material;
}

inline AeroParams still_air() {
    AeroParams air;
    air.air_density = 0;
    air.linear_drag = 0;
    return air;
}

// Displace every free particle randomly (deterministic seed) so a step
// starts far from equilibrium.
inline void perturb(ClothInstance& cloth, float amount, unsigned seed = 7) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> uniform(-amount, amount);
    for (uint32_t i = 0; i < cloth.particle_count(); ++i) {
        if (cloth.is_pinned(i)) continue;
        cloth.set_position(i, cloth.positions().get(i) + Vec3(uniform(rng), uniform(rng), uniform(rng)));
    }
}

inline std::vector<Vec3> positions_of(const ClothInstance& cloth) {
    std::vector<Vec3> out(cloth.particle_count());
    for (uint32_t i = 0; i < cloth.particle_count(); ++i) out[i] = cloth.positions().get(i);
    return out;
}

}  // namespace cloth::testing
