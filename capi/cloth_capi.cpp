// The C ABI: validates every argument, converts to the core's types, calls
// the core, and turns every outcome (including exceptions, which never
// cross this boundary) into a cloth_result plus a message. Validation runs
// completely before anything is changed, so a failing call changes nothing.
#include <cloth/cloth.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <exception>
#include <mutex>
#include <new>

#include "errors.h"
#include "measure.h"
#include "world.h"

using namespace cloth;

namespace {

constexpr uint32_t kCookie = 0x636C7468;  // "clth": the desc came from cloth_default_*()
constexpr uint32_t kMaxWorlds = 128;

// ---------------------------------------------------------------- worlds

// Process-wide table of worlds, so that a world id can be checked before
// use (a stale or foreign id is an error, not a dangling pointer). Only
// create, destroy and lookup touch it, under the mutex.
struct WorldTable {
    std::mutex mutex;
    std::array<World*, kMaxWorlds> worlds{};
    std::array<uint16_t, kMaxWorlds> generations{};
};

WorldTable& world_table() {
    static WorldTable table;
    return table;
}

World* find_world(cloth_world_id id) {
    if (id.index1 == 0 || id.index1 > kMaxWorlds) return nullptr;
    WorldTable& table = world_table();
    std::lock_guard<std::mutex> lock(table.mutex);
    World* world = table.worlds[id.index1 - 1];
    if (!world || table.generations[id.index1 - 1] != id.generation) return nullptr;
    return world;
}

// The world a fabric or cloth id names, if that world is still alive.
template <class Id>
World* find_owning_world(Id id) {
    return find_world(cloth_world_id{id.world1, id.world_generation});
}

// ---------------------------------------------------------------- results

// Runs `body` (which returns a Status and may name the world to log to),
// turns exceptions into results, records the message and logs it.
template <class Body>
cloth_result api_call(const char* function, Body body) {
    const World* log_world = nullptr;
    Status status;
    try {
        status = body(log_world);
    } catch (const std::bad_alloc&) {
        status = Status::error(CLOTH_ERROR_OUT_OF_MEMORY, "the allocator returned NULL; nothing was changed");
    } catch (const std::exception& e) {
        status = Status::error(CLOTH_ERROR_INTERNAL, "internal error: %s", e.what());
    } catch (...) {
        status = Status::error(CLOTH_ERROR_INTERNAL, "internal error");
    }
    if (status.ok()) return CLOTH_OK;
    // Reporting allocates nothing (Status holds its message in place).
    char message[512];
    std::snprintf(message, sizeof message, "%s: %s", function, status.message);
    set_last_error(message);
    if (log_world) {
        const bool warning = status.code == CLOTH_ERROR_SOLVER_FAILED;
        try {
            log_world->log(warning ? CLOTH_LOG_WARNING : CLOTH_LOG_ERROR, status.code, message);
        } catch (...) {
            // A host callback that throws must not take the exception through the ABI.
        }
    }
    return status.code;
}

Status null_error(const char* what) { return Status::error(CLOTH_ERROR_NULL_POINTER, "%s is NULL", what); }

// ---------------------------------------------------------------- lookups

Status get_world(cloth_world_id id, World*& world, const World*& log_world) {
    world = find_world(id);
    if (!world)
        return Status::error(CLOTH_ERROR_INVALID_HANDLE, "world handle is null, destroyed or unknown");
    log_world = world;
    return {};
}

Status get_cloth(cloth_id id, ClothInstance*& cloth, const World*& log_world) {
    World* world = find_owning_world(id);
    cloth = world ? world->find_cloth(id) : nullptr;
    if (!cloth)
        return Status::error(CLOTH_ERROR_INVALID_HANDLE, "cloth handle is null, destroyed or unknown");
    log_world = world;
    return {};
}

Status get_fabric(cloth_fabric_id id, std::shared_ptr<const Fabric>& fabric, World*& world,
                  const World*& log_world) {
    world = find_owning_world(id);
    fabric = world ? world->find_fabric(id) : nullptr;
    if (!fabric)
        return Status::error(CLOTH_ERROR_INVALID_HANDLE, "fabric handle is null, destroyed or unknown");
    log_world = world;
    return {};
}

// ---------------------------------------------------------------- validation

bool finite3(const float* v) { return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]); }

Status check_desc(uint32_t struct_size, size_t expected, uint32_t cookie, const char* what) {
    if (cookie != kCookie) {
        return Status::error(CLOTH_ERROR_INVALID_DESC,
                             "%s was not initialised by its cloth_default_*() function", what);
    }
    if (struct_size != expected) {
        return Status::error(CLOTH_ERROR_INVALID_DESC, "%s.struct_size is %u, expected %zu", what,
                             struct_size, expected);
    }
    return {};
}

// A non-negative finite parameter.
Status check_non_negative(float value, const char* what) {
    if (!std::isfinite(value)) return Status::error(CLOTH_ERROR_NOT_FINITE, "%s is not finite", what);
    if (value < 0)
        return Status::error(CLOTH_ERROR_INVALID_VALUE, "%s is negative (%g)", what, double(value));
    return {};
}

Status check_spring_params(const cloth_spring_params& p, const char* what) {
    char name[64];
    std::snprintf(name, sizeof name, "%s stiffness", what);
    Status s = check_non_negative(p.stiffness, name);
    if (!s.ok()) return s;
    std::snprintf(name, sizeof name, "%s damping", what);
    return check_non_negative(p.damping, name);
}

Status check_solver(const cloth_solver_settings& s) {
    if (s.struct_size != sizeof(cloth_solver_settings)) {
        return Status::error(CLOTH_ERROR_INVALID_DESC,
                             "cloth_solver_settings.struct_size is %u, expected %zu", s.struct_size,
                             sizeof(cloth_solver_settings));
    }
    if (s.kind != CLOTH_SOLVER_DEFAULT && s.kind != CLOTH_SOLVER_JACOBI && s.kind != CLOTH_SOLVER_CG &&
        s.kind != CLOTH_SOLVER_EXPLICIT) {
        return Status::error(CLOTH_ERROR_INVALID_VALUE, "unknown solver kind %d", int(s.kind));
    }
    if (s.iterations < 1 || s.iterations > 256) {
        return Status::error(CLOTH_ERROR_INVALID_VALUE, "iterations %u is not in 1..256", s.iterations);
    }
    if (s.substeps < 1 || s.substeps > 64) {
        return Status::error(CLOTH_ERROR_INVALID_VALUE, "substeps %u is not in 1..64", s.substeps);
    }
    if (!std::isfinite(s.cg_tolerance))
        return Status::error(CLOTH_ERROR_NOT_FINITE, "cg_tolerance is not finite");
    if (!(s.cg_tolerance > 0 && s.cg_tolerance < 1)) {
        return Status::error(CLOTH_ERROR_INVALID_VALUE, "cg_tolerance %g is not in (0, 1)",
                             double(s.cg_tolerance));
    }
    if (s.cg_max_iterations < 1 || s.cg_max_iterations > 100000) {
        return Status::error(CLOTH_ERROR_INVALID_VALUE, "cg_max_iterations %u is not in 1..100000",
                             s.cg_max_iterations);
    }
    return {};
}

Status check_aero(const cloth_aero_params& a) {
    if (!finite3(a.wind)) return Status::error(CLOTH_ERROR_NOT_FINITE, "wind is not finite");
    Status s = check_non_negative(a.air_density, "air_density");
    if (s.ok()) s = check_non_negative(a.drag_coefficient, "drag_coefficient");
    if (s.ok()) s = check_non_negative(a.lift_coefficient, "lift_coefficient");
    if (s.ok()) s = check_non_negative(a.linear_drag, "linear_drag");
    return s;
}

Status check_indices(const uint32_t* indices, uint32_t count, uint32_t particle_count) {
    if (!indices) return null_error("indices");
    if (count == 0 || count > particle_count) {
        return Status::error(CLOTH_ERROR_INVALID_COUNT, "count %u is not in 1..%u", count, particle_count);
    }
    for (uint32_t k = 0; k < count; ++k) {
        if (indices[k] >= particle_count) {
            return Status::error(CLOTH_ERROR_INDEX_OUT_OF_RANGE,
                                 "indices[%u] = %u, but the cloth has %u particles", k, indices[k],
                                 particle_count);
        }
    }
    return {};
}

Status check_points(const float* xyz, uint32_t count, const char* what) {
    if (!xyz) return null_error(what);
    for (uint32_t k = 0; k < count; ++k) {
        if (!finite3(xyz + 3 * k))
            return Status::error(CLOTH_ERROR_NOT_FINITE, "%s[%u] is not finite", what, k);
    }
    return {};
}

Status check_capacity(const void* out, uint32_t capacity, size_t needed) {
    if (!out) return null_error("output buffer");
    if (capacity < needed) {
        return Status::error(CLOTH_ERROR_INVALID_COUNT, "capacity %u is less than the %zu values needed",
                             capacity, needed);
    }
    return {};
}

SolverSettings to_core(const cloth_solver_settings& s) {
    SolverSettings out;
    out.kind = s.kind == CLOTH_SOLVER_DEFAULT ? CLOTH_SOLVER_JACOBI : s.kind;
    out.iterations = s.iterations;
    out.substeps = s.substeps;
    out.cg_tolerance = s.cg_tolerance;
    out.cg_max_iterations = s.cg_max_iterations;
    out.compression_safe_jacobian = s.compression_safe_jacobian;
    return out;
}

AeroParams to_core(const cloth_aero_params& a) {
    AeroParams out;
    out.wind = Vec3(a.wind[0], a.wind[1], a.wind[2]);
    out.air_density = a.air_density;
    out.drag_coefficient = a.drag_coefficient;
    out.lift_coefficient = a.lift_coefficient;
    out.linear_drag = a.linear_drag;
    return out;
}

void copy_out(const Vec3Soa& values, float* out) {
    for (size_t i = 0; i < values.size(); ++i) {
        out[3 * i] = values.x[i];
        out[3 * i + 1] = values.y[i];
        out[3 * i + 2] = values.z[i];
    }
}

}  // namespace

extern "C" {

// ================================================================ version

CLOTH_API cloth_version cloth_get_version(void) {
    return cloth_version{CLOTH_VERSION_MAJOR, CLOTH_VERSION_MINOR, CLOTH_VERSION_PATCH};
}

// ================================================================ world

CLOTH_API cloth_world_desc cloth_default_world_desc(void) {
    cloth_world_desc d{};
    d.struct_size = sizeof(cloth_world_desc);
    d.gravity[1] = -9.81f;
    d.max_cloths = 1024;
    d.max_fabrics = 256;
    d.internal_cookie = kCookie;
    return d;
}

CLOTH_API cloth_result cloth_world_create(const cloth_world_desc* desc, cloth_world_id* out_world) {
    return api_call(__func__, [&](const World*&) -> Status {
        if (!desc) return null_error("desc");
        if (!out_world) return null_error("out_world");
        Status s = check_desc(desc->struct_size, sizeof(cloth_world_desc), desc->internal_cookie,
                              "cloth_world_desc");
        if (!s.ok()) return s;
        if (!finite3(desc->gravity)) return Status::error(CLOTH_ERROR_NOT_FINITE, "gravity is not finite");
        if ((desc->alloc == nullptr) != (desc->free == nullptr)) {
            return Status::error(CLOTH_ERROR_INVALID_VALUE, "set both alloc and free, or neither");
        }
        if (desc->max_cloths < 1 || desc->max_cloths > 65535 || desc->max_fabrics < 1 ||
            desc->max_fabrics > 65535) {
            return Status::error(CLOTH_ERROR_INVALID_COUNT, "max_cloths and max_fabrics must be in 1..65535");
        }

        WorldTable& table = world_table();
        std::lock_guard<std::mutex> lock(table.mutex);
        uint16_t index = 0;
        while (index < kMaxWorlds && table.worlds[index]) ++index;
        if (index == kMaxWorlds)
            return Status::error(CLOTH_ERROR_CAPACITY, "%u worlds exist already", kMaxWorlds);
        if (table.generations[index] == 0) table.generations[index] = 1;
        const uint16_t generation = table.generations[index];

        const HostMemory memory{desc->alloc, desc->free, desc->user};
        void* storage = memory.allocate(sizeof(World), alignof(World));
        World* world = nullptr;
        try {
            world = new (storage) World(*desc, index, generation);
        } catch (...) {
            memory.deallocate(storage, sizeof(World));
            throw;
        }
        table.worlds[index] = world;
        *out_world = cloth_world_id{static_cast<uint16_t>(index + 1), generation};
        return {};
    });
}

CLOTH_API cloth_result cloth_world_destroy(cloth_world_id id) {
    return api_call(__func__, [&](const World*&) -> Status {
        WorldTable& table = world_table();
        World* world = nullptr;
        {
            std::lock_guard<std::mutex> lock(table.mutex);
            if (id.index1 == 0 || id.index1 > kMaxWorlds || !table.worlds[id.index1 - 1] ||
                table.generations[id.index1 - 1] != id.generation) {
                return Status::error(CLOTH_ERROR_INVALID_HANDLE,
                                     "world handle is null, destroyed or unknown");
            }
            world = table.worlds[id.index1 - 1];
            table.worlds[id.index1 - 1] = nullptr;
            uint16_t& generation = table.generations[id.index1 - 1];
            generation = static_cast<uint16_t>(generation + 1 == 0 ? 1 : generation + 1);
        }
        const HostMemory memory = *world->memory();
        world->~World();
        memory.deallocate(world, sizeof(World));
        return {};
    });
}

CLOTH_API cloth_result cloth_world_set_gravity(cloth_world_id id, const float gravity[3]) {
    return api_call(__func__, [&](const World*& log_world) -> Status {
        World* world;
        Status s = get_world(id, world, log_world);
        if (!s.ok()) return s;
        if (!gravity) return null_error("gravity");
        if (!finite3(gravity)) return Status::error(CLOTH_ERROR_NOT_FINITE, "gravity is not finite");
        world->gravity = Vec3(gravity[0], gravity[1], gravity[2]);
        return {};
    });
}

CLOTH_API cloth_result cloth_step(cloth_world_id id, float dt) {
    return api_call(__func__, [&](const World*& log_world) -> Status {
        World* world;
        Status s = get_world(id, world, log_world);
        if (!s.ok()) return s;
        if (!std::isfinite(dt)) return Status::error(CLOTH_ERROR_NOT_FINITE, "dt is not finite");
        if (!(dt > 0 && dt <= 1))
            return Status::error(CLOTH_ERROR_INVALID_VALUE, "dt %g is not in (0, 1]", double(dt));
        return world->step(dt);
    });
}

// ================================================================ fabric

CLOTH_API cloth_grid_desc cloth_default_grid_desc(void) {
    cloth_grid_desc d{};
    d.struct_size = sizeof(cloth_grid_desc);
    d.columns = 32;
    d.rows = 32;
    d.u[0] = 1.0f;
    d.v[1] = -1.0f;
    d.spring_kinds = CLOTH_SPRING_ALL;
    d.internal_cookie = kCookie;
    return d;
}

CLOTH_API cloth_mesh_desc cloth_default_mesh_desc(void) {
    cloth_mesh_desc d{};
    d.struct_size = sizeof(cloth_mesh_desc);
    d.spring_kinds = CLOTH_SPRING_ALL;
    d.internal_cookie = kCookie;
    return d;
}

CLOTH_API cloth_result cloth_fabric_create_grid(cloth_world_id id, const cloth_grid_desc* desc,
                                                cloth_fabric_id* out_fabric) {
    return api_call(__func__, [&](const World*& log_world) -> Status {
        World* world;
        Status s = get_world(id, world, log_world);
        if (!s.ok()) return s;
        if (!desc) return null_error("desc");
        if (!out_fabric) return null_error("out_fabric");
        s = check_desc(desc->struct_size, sizeof(cloth_grid_desc), desc->internal_cookie, "cloth_grid_desc");
        if (!s.ok()) return s;
        return world->create_fabric([&](Fabric& f) { return build_grid_fabric(*desc, f); }, out_fabric);
    });
}

CLOTH_API cloth_result cloth_fabric_create_mesh(cloth_world_id id, const cloth_mesh_desc* desc,
                                                cloth_fabric_id* out_fabric) {
    return api_call(__func__, [&](const World*& log_world) -> Status {
        World* world;
        Status s = get_world(id, world, log_world);
        if (!s.ok()) return s;
        if (!desc) return null_error("desc");
        if (!out_fabric) return null_error("out_fabric");
        s = check_desc(desc->struct_size, sizeof(cloth_mesh_desc), desc->internal_cookie, "cloth_mesh_desc");
        if (!s.ok()) return s;
        return world->create_fabric(
            [&](Fabric& f) {
                return build_mesh_fabric(desc->positions, desc->vertex_count, desc->indices,
                                         desc->triangle_count, desc->spring_kinds, f);
            },
            out_fabric);
    });
}

CLOTH_API cloth_result cloth_fabric_create_obj(cloth_world_id id, const char* path, uint32_t spring_kinds,
                                               cloth_fabric_id* out_fabric) {
    return api_call(__func__, [&](const World*& log_world) -> Status {
        World* world;
        Status s = get_world(id, world, log_world);
        if (!s.ok()) return s;
        if (!path) return null_error("path");
        if (!out_fabric) return null_error("out_fabric");
        return world->create_fabric([&](Fabric& f) { return build_obj_fabric(path, spring_kinds, f); },
                                    out_fabric);
    });
}

CLOTH_API cloth_result cloth_fabric_destroy(cloth_fabric_id id) {
    return api_call(__func__, [&](const World*& log_world) -> Status {
        World* world = find_owning_world(id);
        if (!world)
            return Status::error(CLOTH_ERROR_INVALID_HANDLE, "fabric handle is null, destroyed or unknown");
        log_world = world;
        return world->destroy_fabric(id);
    });
}

CLOTH_API cloth_result cloth_fabric_get_particle_count(cloth_fabric_id id, uint32_t* out_count) {
    return api_call(__func__, [&](const World*& log_world) -> Status {
        std::shared_ptr<const Fabric> fabric;
        World* world;
        Status s = get_fabric(id, fabric, world, log_world);
        if (!s.ok()) return s;
        if (!out_count) return null_error("out_count");
        *out_count = fabric->particle_count();
        return {};
    });
}

CLOTH_API cloth_result cloth_fabric_get_triangle_count(cloth_fabric_id id, uint32_t* out_count) {
    return api_call(__func__, [&](const World*& log_world) -> Status {
        std::shared_ptr<const Fabric> fabric;
        World* world;
        Status s = get_fabric(id, fabric, world, log_world);
        if (!s.ok()) return s;
        if (!out_count) return null_error("out_count");
        *out_count = fabric->triangle_count();
        return {};
    });
}

CLOTH_API cloth_result cloth_fabric_get_spring_count(cloth_fabric_id id, uint32_t kinds,
                                                     uint32_t* out_count) {
    return api_call(__func__, [&](const World*& log_world) -> Status {
        std::shared_ptr<const Fabric> fabric;
        World* world;
        Status s = get_fabric(id, fabric, world, log_world);
        if (!s.ok()) return s;
        if (!out_count) return null_error("out_count");
        if (kinds & ~static_cast<uint32_t>(CLOTH_SPRING_ALL)) {
            return Status::error(CLOTH_ERROR_INVALID_VALUE, "unknown spring kind bits 0x%x", kinds);
        }
        uint32_t count = 0;
        for (int k = 0; k < kSpringKindCount; ++k) {
            if (kinds & (1u << k)) count += fabric->springs_of_kind[k];
        }
        *out_count = count;
        return {};
    });
}

CLOTH_API cloth_result cloth_fabric_read_triangles(cloth_fabric_id id, uint32_t* out_indices,
                                                   uint32_t capacity) {
    return api_call(__func__, [&](const World*& log_world) -> Status {
        std::shared_ptr<const Fabric> fabric;
        World* world;
        Status s = get_fabric(id, fabric, world, log_world);
        if (!s.ok()) return s;
        s = check_capacity(out_indices, capacity, fabric->triangles.size());
        if (!s.ok()) return s;
        std::copy(fabric->triangles.begin(), fabric->triangles.end(), out_indices);
        return {};
    });
}

// ================================================================ cloth

CLOTH_API cloth_solver_settings cloth_default_solver_settings(void) {
    const SolverSettings core;
    cloth_solver_settings s{};
    s.struct_size = sizeof(cloth_solver_settings);
    s.kind = core.kind;
    s.iterations = core.iterations;
    s.substeps = core.substeps;
    s.cg_tolerance = core.cg_tolerance;
    s.cg_max_iterations = core.cg_max_iterations;
    s.compression_safe_jacobian = core.compression_safe_jacobian;
    return s;
}

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
    return api_call(__func__, [&](const World*& log_world) -> Status {
        World* world;
        Status s = get_world(id, world, log_world);
        if (!s.ok()) return s;
        if (!desc) return null_error("desc");
        if (!out_cloth) return null_error("out_cloth");
        s = check_desc(desc->struct_size, sizeof(cloth_desc), desc->internal_cookie, "cloth_desc");
        if (!s.ok()) return s;
        if (desc->fabric.world1 != id.index1 || desc->fabric.world_generation != id.generation) {
            return Status::error(CLOTH_ERROR_INVALID_HANDLE, "fabric handle belongs to another world");
        }
        std::shared_ptr<const Fabric> fabric = world->find_fabric(desc->fabric);
        if (!fabric)
            return Status::error(CLOTH_ERROR_INVALID_HANDLE, "fabric handle is null, destroyed or unknown");
        if (!std::isfinite(desc->area_density))
            return Status::error(CLOTH_ERROR_NOT_FINITE, "area_density is not finite");
        if (!(desc->area_density > 0)) {
            return Status::error(CLOTH_ERROR_INVALID_VALUE, "area_density %g must be > 0",
                                 double(desc->area_density));
        }
        s = check_non_negative(desc->particle_mass, "particle_mass");
        if (s.ok()) s = check_spring_params(desc->structural, "structural");
        if (s.ok()) s = check_spring_params(desc->shear, "shear");
        if (s.ok()) s = check_spring_params(desc->bend, "bend");
        if (s.ok()) s = check_solver(desc->solver);
        if (s.ok()) s = check_aero(desc->aero);
        if (s.ok() && desc->initial_positions) {
            s = check_points(desc->initial_positions, fabric->particle_count(), "initial_positions");
        }
        if (!s.ok()) return s;

        Material material;
        material.springs[kStructural] = {desc->structural.stiffness, desc->structural.damping};
        material.springs[kShear] = {desc->shear.stiffness, desc->shear.damping};
        material.springs[kBend] = {desc->bend.stiffness, desc->bend.damping};
        material.area_density = desc->area_density;
        material.particle_mass = desc->particle_mass;
        return world->create_cloth(std::move(fabric), material, to_core(desc->solver), to_core(desc->aero),
                                   desc->initial_positions, out_cloth);
    });
}

CLOTH_API cloth_result cloth_destroy(cloth_id id) {
    return api_call(__func__, [&](const World*& log_world) -> Status {
        World* world = find_owning_world(id);
        if (!world)
            return Status::error(CLOTH_ERROR_INVALID_HANDLE, "cloth handle is null, destroyed or unknown");
        log_world = world;
        return world->destroy_cloth(id);
    });
}

CLOTH_API cloth_result cloth_get_particle_count(cloth_id id, uint32_t* out_count) {
    return api_call(__func__, [&](const World*& log_world) -> Status {
        ClothInstance* cloth;
        Status s = get_cloth(id, cloth, log_world);
        if (!s.ok()) return s;
        if (!out_count) return null_error("out_count");
        *out_count = cloth->particle_count();
        return {};
    });
}

}  // extern "C"

namespace {

template <class Read>
cloth_result read_vectors(const char* function, cloth_id id, float* out, uint32_t capacity, Read read) {
    return api_call(function, [&](const World*& log_world) -> Status {
        ClothInstance* cloth;
        Status s = get_cloth(id, cloth, log_world);
        if (!s.ok()) return s;
        s = check_capacity(out, capacity, 3 * static_cast<size_t>(cloth->particle_count()));
        if (!s.ok()) return s;
        copy_out(read(*cloth), out);
        return {};
    });
}

}  // namespace

extern "C" {

CLOTH_API cloth_result cloth_read_positions(cloth_id id, float* out_xyz, uint32_t capacity) {
    return read_vectors(__func__, id, out_xyz, capacity,
                        [](const ClothInstance& c) -> const Vec3Soa& { return c.positions(); });
}

CLOTH_API cloth_result cloth_read_velocities(cloth_id id, float* out_xyz, uint32_t capacity) {
    return read_vectors(__func__, id, out_xyz, capacity,
                        [](const ClothInstance& c) -> const Vec3Soa& { return c.velocities(); });
}

CLOTH_API cloth_result cloth_read_normals(cloth_id id, float* out_xyz, uint32_t capacity) {
    return read_vectors(__func__, id, out_xyz, capacity,
                        [](const ClothInstance& c) -> const Vec3Soa& { return c.normals(); });
}

CLOTH_API cloth_result cloth_set_positions(cloth_id id, const uint32_t* indices, const float* positions_xyz,
                                           uint32_t count) {
    return api_call(__func__, [&](const World*& log_world) -> Status {
        ClothInstance* cloth;
        Status s = get_cloth(id, cloth, log_world);
        if (s.ok()) s = check_indices(indices, count, cloth->particle_count());
        if (s.ok()) s = check_points(positions_xyz, count, "positions");
        if (!s.ok()) return s;
        for (uint32_t k = 0; k < count; ++k) {
            const float* p = positions_xyz + 3 * k;
            cloth->set_position(indices[k], Vec3(p[0], p[1], p[2]));
        }
        return {};
    });
}

CLOTH_API cloth_result cloth_pin(cloth_id id, const uint32_t* indices, uint32_t count) {
    return api_call(__func__, [&](const World*& log_world) -> Status {
        ClothInstance* cloth;
        Status s = get_cloth(id, cloth, log_world);
        if (s.ok()) s = check_indices(indices, count, cloth->particle_count());
        if (!s.ok()) return s;
        cloth->set_pinned(indices, count, true);
        return {};
    });
}

CLOTH_API cloth_result cloth_unpin(cloth_id id, const uint32_t* indices, uint32_t count) {
    return api_call(__func__, [&](const World*& log_world) -> Status {
        ClothInstance* cloth;
        Status s = get_cloth(id, cloth, log_world);
        if (s.ok()) s = check_indices(indices, count, cloth->particle_count());
        if (!s.ok()) return s;
        cloth->set_pinned(indices, count, false);
        return {};
    });
}

CLOTH_API cloth_result cloth_set_pin_targets(cloth_id id, const uint32_t* indices, const float* targets_xyz,
                                             uint32_t count) {
    return api_call(__func__, [&](const World*& log_world) -> Status {
        ClothInstance* cloth;
        Status s = get_cloth(id, cloth, log_world);
        if (s.ok()) s = check_indices(indices, count, cloth->particle_count());
        if (s.ok()) s = check_points(targets_xyz, count, "targets");
        if (!s.ok()) return s;
        for (uint32_t k = 0; k < count; ++k) {
            if (!cloth->is_pinned(indices[k])) {
                return Status::error(CLOTH_ERROR_INVALID_VALUE, "particle %u is not pinned", indices[k]);
            }
        }
        for (uint32_t k = 0; k < count; ++k) {
            const float* p = targets_xyz + 3 * k;
            cloth->set_pin_target(indices[k], Vec3(p[0], p[1], p[2]));
        }
        return {};
    });
}

CLOTH_API cloth_result cloth_is_pinned(cloth_id id, uint32_t index, bool* out_pinned) {
    return api_call(__func__, [&](const World*& log_world) -> Status {
        ClothInstance* cloth;
        Status s = get_cloth(id, cloth, log_world);
        if (!s.ok()) return s;
        if (!out_pinned) return null_error("out_pinned");
        if (index >= cloth->particle_count()) {
            return Status::error(CLOTH_ERROR_INDEX_OUT_OF_RANGE, "index %u, but the cloth has %u particles",
                                 index, cloth->particle_count());
        }
        *out_pinned = cloth->is_pinned(index);
        return {};
    });
}

CLOTH_API cloth_result cloth_set_solver(cloth_id id, const cloth_solver_settings* settings) {
    return api_call(__func__, [&](const World*& log_world) -> Status {
        ClothInstance* cloth;
        Status s = get_cloth(id, cloth, log_world);
        if (!s.ok()) return s;
        if (!settings) return null_error("settings");
        s = check_solver(*settings);
        if (!s.ok()) return s;
        cloth->solver() = to_core(*settings);
        return {};
    });
}

CLOTH_API cloth_result cloth_get_solver(cloth_id id, cloth_solver_settings* out) {
    return api_call(__func__, [&](const World*& log_world) -> Status {
        ClothInstance* cloth;
        Status s = get_cloth(id, cloth, log_world);
        if (!s.ok()) return s;
        if (!out) return null_error("out_settings");
        const SolverSettings& core = cloth->solver();
        *out = cloth_default_solver_settings();
        out->kind = core.kind;
        out->iterations = core.iterations;
        out->substeps = core.substeps;
        out->cg_tolerance = core.cg_tolerance;
        out->cg_max_iterations = core.cg_max_iterations;
        out->compression_safe_jacobian = core.compression_safe_jacobian;
        return {};
    });
}

CLOTH_API cloth_result cloth_set_spring_params(cloth_id id, uint32_t kinds, cloth_spring_params params) {
    return api_call(__func__, [&](const World*& log_world) -> Status {
        ClothInstance* cloth;
        Status s = get_cloth(id, cloth, log_world);
        if (!s.ok()) return s;
        if (kinds == 0 || (kinds & ~static_cast<uint32_t>(CLOTH_SPRING_ALL))) {
            return Status::error(CLOTH_ERROR_INVALID_VALUE,
                                 "spring kinds 0x%x is not a non-empty set of kinds", kinds);
        }
        s = check_spring_params(params, "spring");
        if (!s.ok()) return s;
        Material material = cloth->material();
        for (int k = 0; k < kSpringKindCount; ++k) {
            if (kinds & (1u << k)) material.springs[k] = {params.stiffness, params.damping};
        }
        cloth->set_material(material);
        return {};
    });
}

CLOTH_API cloth_result cloth_set_aero(cloth_id id, const cloth_aero_params* params) {
    return api_call(__func__, [&](const World*& log_world) -> Status {
        ClothInstance* cloth;
        Status s = get_cloth(id, cloth, log_world);
        if (!s.ok()) return s;
        if (!params) return null_error("params");
        s = check_aero(*params);
        if (!s.ok()) return s;
        cloth->aero() = to_core(*params);
        return {};
    });
}

CLOTH_API cloth_result cloth_set_wind(cloth_id id, const float wind[3]) {
    return api_call(__func__, [&](const World*& log_world) -> Status {
        ClothInstance* cloth;
        Status s = get_cloth(id, cloth, log_world);
        if (!s.ok()) return s;
        if (!wind) return null_error("wind");
        if (!finite3(wind)) return Status::error(CLOTH_ERROR_NOT_FINITE, "wind is not finite");
        cloth->aero().wind = Vec3(wind[0], wind[1], wind[2]);
        return {};
    });
}

CLOTH_API cloth_result cloth_get_stats(cloth_id id, cloth_stats* out) {
    return api_call(__func__, [&](const World*& log_world) -> Status {
        ClothInstance* cloth;
        Status s = get_cloth(id, cloth, log_world);
        if (!s.ok()) return s;
        if (!out) return null_error("out_stats");
        if (out->struct_size != sizeof(cloth_stats)) {
            return Status::error(CLOTH_ERROR_INVALID_DESC, "cloth_stats.struct_size is %u, expected %zu",
                                 out->struct_size, sizeof(cloth_stats));
        }
        const World* world = log_world;
        const ClothMeasure m = measure(*cloth, world->gravity);
        out->kinetic_energy = m.kinetic_energy;
        out->gravity_energy = m.gravity_energy;
        out->elastic_energy = m.elastic_energy;
        out->max_strain = m.max_strain;
        out->mean_strain = m.mean_strain;
        out->max_speed = m.max_speed;
        out->last_solver_iterations = cloth->last_solve().iterations;
        out->last_solver_residual = cloth->last_solve().residual;
        out->last_step_result = cloth->last_step_result();
        return {};
    });
}

}  // extern "C"
