// C API: cloth instances (create, destroy, read back, teleport particles,
// material and air, stats).
#include <cloth/cloth.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>

#include "api_call.h"
#include "api_validation.h"
#include "step/cloth_measure.h"

using namespace cloth;
using namespace cloth::api;

namespace {

// cloth_stats as 1.6 had it: up to the strain-limit fields.
constexpr size_t kStatsSize16 = offsetof(cloth_stats, strain_limit_excess);
// 1.7 to 1.11 end before the rung the last step ran at.
constexpr size_t kStatsSize111 = offsetof(cloth_stats, last_max_iterations);
// cloth_stats as 1.12 had it: up to the strain-limit pass fields.
constexpr size_t kStatsSize112 = offsetof(cloth_stats, last_strain_passes);
// The strain limit's promise after every step: within the limit plus this.
constexpr float kStrainPromiseSlackOfAStep = 0.02f;

Status check_cloth_desc(const cloth_desc& desc, const Fabric& fabric) {
    if (!std::isfinite(desc.area_density))
        return Status::error(CLOTH_ERROR_NOT_FINITE, "area_density is not finite");
    if (!(desc.area_density > 0)) {
        return Status::error(CLOTH_ERROR_INVALID_VALUE, "area_density %g must be > 0",
                             double(desc.area_density));
    }
    Status s = check_non_negative(desc.particle_mass, "particle_mass");
    if (s.ok()) s = check_spring_params(desc.structural, "structural");
    if (s.ok()) s = check_spring_params(desc.shear, "shear");
    if (s.ok()) s = check_spring_params(desc.bend, "bend");
    if (s.ok()) s = check_solver(desc.solver);
    if (s.ok()) s = check_aero(desc.aero);
    if (s.ok() && desc.initial_positions) {
        s = check_points(desc.initial_positions, fabric.particle_count(), "initial_positions");
    }
    return s;
}

template <class Read>
cloth_result read_vectors(const char* function, cloth_id id, float* out, uint32_t capacity, Read read) {
    return with_scene_cloth(function, id, [&](SceneCloth& scene) -> Status {
        const ClothInstance& cloth = scene.cloth();
        Status s = check_capacity(out, capacity, 3 * static_cast<size_t>(cloth.particle_count()));
        if (!s.ok()) return s;
        copy_out(read(scene), cloth.fabric(), out);
        return {};
    });
}

}  // namespace

extern "C" {

CLOTH_API cloth_desc cloth_default_desc(void) {
    const Material material;
    const AeroParams aero;
    cloth_desc d{};
    d.struct_size = sizeof(cloth_desc);
    d.area_density = material.area_density;
    d.particle_mass = material.particle_mass;
    d.structural = {material.springs[kStructural].stiffness, material.springs[kStructural].damping};
    d.shear = {material.springs[kShear].stiffness, material.springs[kShear].damping};
    d.bend = {material.springs[kBend].stiffness, material.springs[kBend].damping};
    d.solver = cloth_default_solver_settings();
    d.aero.air_density = aero.air_density;
    d.aero.drag_coefficient = aero.drag_coefficient;
    d.aero.lift_coefficient = aero.lift_coefficient;
    d.aero.linear_drag = aero.linear_drag;
    d.internal_cookie = kCookie;
    return d;
}

CLOTH_API cloth_result cloth_create(cloth_world_id id, const cloth_desc* desc, cloth_id* out_cloth) {
    return with_world(__func__, id, [&](World& world) -> Status {
        if (!desc) return null_error("desc");
        if (!out_cloth) return null_error("out_cloth");
        Status s = check_desc(desc->struct_size, sizeof(cloth_desc), desc->internal_cookie, "cloth_desc");
        if (!s.ok()) return s;
        s = check_same_world(desc->fabric, id, "fabric", "the call's world");
        if (!s.ok()) return s;
        std::shared_ptr<const Fabric> fabric = world.find_fabric(desc->fabric);
        if (!fabric) return no_object_error("fabric");
        s = check_cloth_desc(*desc, *fabric);
        if (!s.ok()) return s;

        Material material;
        material.springs[kStructural] = {desc->structural.stiffness, desc->structural.damping};
        material.springs[kShear] = {desc->shear.stiffness, desc->shear.damping};
        material.springs[kBend] = {desc->bend.stiffness, desc->bend.damping};
        material.area_density = desc->area_density;
        material.particle_mass = desc->particle_mass;
        return world.create_cloth(std::move(fabric), material, to_core(desc->solver), to_core(desc->aero),
                                  desc->initial_positions, out_cloth);
    });
}

CLOTH_API cloth_result cloth_destroy(cloth_id id) {
    return with_owning_world(__func__, id, "cloth",
                             [&](World& world) -> Status { return world.destroy_cloth(id); });
}

CLOTH_API bool cloth_is_valid(cloth_id id) { return is_live(id); }

CLOTH_API cloth_result cloth_get_particle_count(cloth_id id, uint32_t* out_count) {
    return with_cloth(__func__, id, [&](ClothInstance& cloth) -> Status {
        if (!out_count) return null_error("out_count");
        *out_count = cloth.particle_count();
        return {};
    });
}

CLOTH_API cloth_result cloth_read_positions(cloth_id id, float* out_xyz, uint32_t capacity) {
    return read_vectors(__func__, id, out_xyz, capacity,
                        [](const SceneCloth& c) -> const Vec3Soa& { return c.reported_positions(); });
}

CLOTH_API cloth_result cloth_read_velocities(cloth_id id, float* out_xyz, uint32_t capacity) {
    return read_vectors(__func__, id, out_xyz, capacity,
                        [](const SceneCloth& c) -> const Vec3Soa& { return c.cloth().velocities(); });
}

CLOTH_API cloth_result cloth_read_normals(cloth_id id, float* out_xyz, uint32_t capacity) {
    return read_vectors(__func__, id, out_xyz, capacity,
                        [](const SceneCloth& c) -> const Vec3Soa& { return c.reported_normals(); });
}

CLOTH_API cloth_result cloth_set_positions(cloth_id id, const uint32_t* indices, const float* positions_xyz,
                                           uint32_t count) {
    return with_scene_cloth(__func__, id, [&](SceneCloth& scene) -> Status {
        ClothInstance& cloth = scene.cloth();
        Status s = check_indices(indices, count, cloth.particle_count());
        if (s.ok()) s = check_points(positions_xyz, count, "positions");
        if (!s.ok()) return s;
        for (uint32_t k = 0; k < count; ++k) {
            const float* p = positions_xyz + 3 * k;
            cloth.set_position(cloth.fabric().particle(indices[k]), Vec3(p[0], p[1], p[2]));
        }
        scene.settle();  // a teleport shows at once
        return {};
    });
}

CLOTH_API cloth_result cloth_set_particle_masses(cloth_id id, const uint32_t* indices, const float* masses,
                                                 uint32_t count) {
    return with_cloth(__func__, id, [&](ClothInstance& cloth) -> Status {
        Status s = check_indices(indices, count, cloth.particle_count());
        if (!s.ok()) return s;
        if (!masses) return null_error("masses");
        for (uint32_t k = 0; k < count; ++k) {
            if (!std::isfinite(masses[k]))
                return Status::error(CLOTH_ERROR_NOT_FINITE, "masses[%u] is not finite", k);
            if (!(masses[k] > 0)) {
                return Status::error(CLOTH_ERROR_INVALID_VALUE, "masses[%u] = %g, but a mass must be > 0", k,
                                     double(masses[k]));
            }
        }
        for (uint32_t k = 0; k < count; ++k) cloth.set_mass(cloth.fabric().particle(indices[k]), masses[k]);
        return {};
    });
}

CLOTH_API cloth_result cloth_read_particle_masses(cloth_id id, float* out_masses, uint32_t capacity) {
    return with_cloth(__func__, id, [&](ClothInstance& cloth) -> Status {
        Status s = check_capacity(out_masses, capacity, cloth.particle_count());
        if (!s.ok()) return s;
        const HostVector<float>& mass = cloth.masses();
        for (uint32_t i = 0; i < cloth.particle_count(); ++i) out_masses[cloth.fabric().vertex(i)] = mass[i];
        return {};
    });
}

CLOTH_API cloth_result cloth_set_spring_params(cloth_id id, uint32_t kinds, cloth_spring_params params) {
    return with_cloth(__func__, id, [&](ClothInstance& cloth) -> Status {
        if (kinds == 0 || (kinds & ~static_cast<uint32_t>(CLOTH_SPRING_ALL))) {
            return Status::error(CLOTH_ERROR_INVALID_VALUE,
                                 "spring kinds 0x%x is not a non-empty set of kinds", kinds);
        }
        Status s = check_spring_params(params, "spring");
        if (!s.ok()) return s;
        Material material = cloth.material();
        for (int k = 0; k < kSpringKindCount; ++k) {
            if (kinds & (1u << k)) material.springs[k] = {params.stiffness, params.damping};
        }
        cloth.set_material(material);
        return {};
    });
}

CLOTH_API cloth_result cloth_set_aero(cloth_id id, const cloth_aero_params* params) {
    return with_cloth(__func__, id, [&](ClothInstance& cloth) -> Status {
        if (!params) return null_error("params");
        Status s = check_aero(*params);
        if (!s.ok()) return s;
        cloth.aero() = to_core(*params);
        cloth.wake();
        return {};
    });
}

CLOTH_API cloth_result cloth_set_wind(cloth_id id, const float wind[3]) {
    return with_cloth(__func__, id, [&](ClothInstance& cloth) -> Status {
        if (!wind) return null_error("wind");
        if (!finite3(wind)) return Status::error(CLOTH_ERROR_NOT_FINITE, "wind is not finite");
        cloth.aero().wind = Vec3(wind[0], wind[1], wind[2]);
        cloth.wake();
        return {};
    });
}

CLOTH_API cloth_result cloth_get_stats(cloth_id id, cloth_stats* out) {
    return with_cloth(__func__, id, [&](ClothInstance& cloth, World& world) -> Status {
        if (!out) return null_error("out_stats");
        // 1.6's struct ends where the strain-limit fields begin.
        const uint32_t size = out->struct_size;
        if (size != sizeof(cloth_stats) && size != kStatsSize112 && size != kStatsSize111 &&
            size != kStatsSize16) {
            return Status::error(
                CLOTH_ERROR_INVALID_DESC,
                "cloth_stats.struct_size is %u, expected %zu (or 1.12's %zu, 1.11's %zu, 1.6's %zu)", size,
                sizeof(cloth_stats), kStatsSize112, kStatsSize111, kStatsSize16);
        }
        const ClothMeasure m = measure(cloth, world.gravity);
        cloth_stats stats{};
        stats.struct_size = size;
        stats.kinetic_energy = m.kinetic_energy;
        stats.gravity_energy = m.gravity_energy;
        stats.elastic_energy = m.elastic_energy;
        stats.max_strain = m.max_strain;
        stats.mean_strain = m.mean_strain;
        stats.max_speed = m.max_speed;
        stats.last_solver_iterations = cloth.last_solve().iterations;
        stats.last_solver_residual = cloth.last_solve().residual;
        stats.last_step_result = cloth.last_step_result();
        const float limit = cloth.ran_strain_limit();
        const float strain = cloth.holds_compression() ? m.max_abs_strain : m.max_strain;
        stats.strain_limit_excess = limit > 0.0f ? std::max(0.0f, strain - limit) : 0.0f;
        stats.strain_limit_unmet = stats.strain_limit_excess > kStrainPromiseSlackOfAStep ? 1 : 0;
        if (cloth.last_step_ran()) {
            stats.last_max_iterations = cloth.last_frame_solver().iterations;
            stats.last_substeps = cloth.last_frame_solver().substeps;
            stats.last_strain_passes = cloth.last_strain_passes();
            stats.last_strain_pass_cap_hit = cloth.last_strain_capped() ? 1 : 0;
        }
        std::memcpy(out, &stats, size);
        return {};
    });
}

}  // extern "C"
