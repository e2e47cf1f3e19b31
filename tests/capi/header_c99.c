/*
 * Compile-only check that <cloth/cloth.h> is valid, warning-free C99.
 *
 * Build as an object only (no main, no library needed), e.g.
 *   gcc -std=c99 -Wall -Wextra -Werror -pedantic -Iinclude -c tests/capi/header_c99.c
 *
 * Every type, enumerator and function of the header is used, and every
 * function is bound to a pointer of exactly the documented signature, so a
 * changed prototype is a compile error. The layout checks are duplicated in
 * header_cxx.cpp: C and C++ callers must see the same ABI.
 */
#include <cloth/cloth.h>
#include <cloth/cloth.h> /* the include guard must make a second inclusion harmless */

/* Every function and callback type carries the calling-convention macro
 * (empty here, __cdecl on Windows: tests/abi/win32_header.c). */
#ifndef CLOTH_CALL
#error "cloth.h must define CLOTH_CALL"
#endif

/* C99 has no _Static_assert: a negative array size fails to compile. */
#define CLOTH_HEADER_CHECK(name, cond) typedef char cloth_header_check_##name[(cond) ? 1 : -1]

/* Handles are small value types. */
CLOTH_HEADER_CHECK(world_id_size, sizeof(cloth_world_id) == 4);
CLOTH_HEADER_CHECK(fabric_id_size, sizeof(cloth_fabric_id) == 8);
CLOTH_HEADER_CHECK(cloth_id_size, sizeof(cloth_id) == 8);
CLOTH_HEADER_CHECK(body_id_size, sizeof(cloth_body_id) == 8);
CLOTH_HEADER_CHECK(collider_id_size, sizeof(cloth_collider_id) == 8);
CLOTH_HEADER_CHECK(version_size, sizeof(cloth_version) == 12);

/* Enums are forced to 32 bits. */
CLOTH_HEADER_CHECK(result_size, sizeof(cloth_result) == 4);
CLOTH_HEADER_CHECK(log_level_size, sizeof(cloth_log_level) == 4);
CLOTH_HEADER_CHECK(spring_kind_size, sizeof(cloth_spring_kind) == 4);
CLOTH_HEADER_CHECK(solver_kind_size, sizeof(cloth_solver_kind) == 4);
CLOTH_HEADER_CHECK(struct_kind_size, sizeof(cloth_struct_kind) == 4);

/* struct_size comes first in every versioned struct. */
CLOTH_HEADER_CHECK(world_desc_size_first, offsetof(cloth_world_desc, struct_size) == 0);
CLOTH_HEADER_CHECK(grid_desc_size_first, offsetof(cloth_grid_desc, struct_size) == 0);
CLOTH_HEADER_CHECK(mesh_desc_size_first, offsetof(cloth_mesh_desc, struct_size) == 0);
CLOTH_HEADER_CHECK(solver_size_first, offsetof(cloth_solver_settings, struct_size) == 0);
CLOTH_HEADER_CHECK(desc_size_first, offsetof(cloth_desc, struct_size) == 0);
CLOTH_HEADER_CHECK(stats_size_first, offsetof(cloth_stats, struct_size) == 0);

/* Result codes are ABI: their values never change. */
CLOTH_HEADER_CHECK(ok_is_zero, CLOTH_OK == 0);
CLOTH_HEADER_CHECK(code_1, CLOTH_ERROR_NULL_POINTER == 1);
CLOTH_HEADER_CHECK(code_2, CLOTH_ERROR_INVALID_HANDLE == 2);
CLOTH_HEADER_CHECK(code_3, CLOTH_ERROR_INVALID_DESC == 3);
CLOTH_HEADER_CHECK(code_4, CLOTH_ERROR_INVALID_COUNT == 4);
CLOTH_HEADER_CHECK(code_5, CLOTH_ERROR_INDEX_OUT_OF_RANGE == 5);
CLOTH_HEADER_CHECK(code_6, CLOTH_ERROR_NOT_FINITE == 6);
CLOTH_HEADER_CHECK(code_7, CLOTH_ERROR_INVALID_VALUE == 7);
CLOTH_HEADER_CHECK(code_8, CLOTH_ERROR_DEGENERATE_GEOMETRY == 8);
CLOTH_HEADER_CHECK(code_9, CLOTH_ERROR_OUT_OF_MEMORY == 9);
CLOTH_HEADER_CHECK(code_10, CLOTH_ERROR_CAPACITY == 10);
CLOTH_HEADER_CHECK(code_11, CLOTH_ERROR_IO == 11);
CLOTH_HEADER_CHECK(code_12, CLOTH_ERROR_NONFINITE_STATE == 12);
CLOTH_HEADER_CHECK(code_13, CLOTH_ERROR_SOLVER_FAILED == 13);
CLOTH_HEADER_CHECK(code_14, CLOTH_ERROR_INTERNAL == 14);
CLOTH_HEADER_CHECK(code_15, CLOTH_ERROR_OVER_BUDGET == 15);
CLOTH_HEADER_CHECK(code_16, CLOTH_ERROR_CORRUPT_SNAPSHOT == 16);
CLOTH_HEADER_CHECK(max_triangles, CLOTH_MAX_TRIANGLES == 2u * CLOTH_MAX_PARTICLES);
CLOTH_HEADER_CHECK(spring_all,
                   CLOTH_SPRING_ALL == (CLOTH_SPRING_STRUCTURAL | CLOTH_SPRING_SHEAR | CLOTH_SPRING_BEND));
CLOTH_HEADER_CHECK(solver_default_zero, CLOTH_SOLVER_DEFAULT == 0);
CLOTH_HEADER_CHECK(version_major, CLOTH_VERSION_MAJOR == 1);

/* Exact layout on 64-bit targets (LP64 and LLP64 agree for these structs).
 * The same numbers are checked in header_cxx.cpp. */
#if UINTPTR_MAX == 0xFFFFFFFFFFFFFFFFu
CLOTH_HEADER_CHECK(world_desc_layout, sizeof(cloth_world_desc) == 88 &&
                                          offsetof(cloth_world_desc, alloc) == 16 &&
                                          offsetof(cloth_world_desc, user) == 40 &&
                                          offsetof(cloth_world_desc, internal_cookie) == 56 &&
                                          offsetof(cloth_world_desc, worker_count) == 60 &&
                                          offsetof(cloth_world_desc, enqueue_task) == 64 &&
                                          offsetof(cloth_world_desc, task_user) == 80);
CLOTH_HEADER_CHECK(grid_desc_layout,
                   sizeof(cloth_grid_desc) == 56 && offsetof(cloth_grid_desc, spring_kinds) == 48);
CLOTH_HEADER_CHECK(mesh_desc_layout, sizeof(cloth_mesh_desc) == 48 &&
                                         offsetof(cloth_mesh_desc, indices) == 24 &&
                                         offsetof(cloth_mesh_desc, internal_cookie) == 40);
CLOTH_HEADER_CHECK(solver_layout, sizeof(cloth_solver_settings) == 28 &&
                                      offsetof(cloth_solver_settings, compression_safe_jacobian) == 24);
CLOTH_HEADER_CHECK(aero_layout, sizeof(cloth_aero_params) == 28);
CLOTH_HEADER_CHECK(spring_params_layout, sizeof(cloth_spring_params) == 8);
CLOTH_HEADER_CHECK(desc_layout, sizeof(cloth_desc) == 120 && offsetof(cloth_desc, initial_positions) == 24 &&
                                    offsetof(cloth_desc, solver) == 56 && offsetof(cloth_desc, aero) == 84 &&
                                    offsetof(cloth_desc, internal_cookie) == 112);
CLOTH_HEADER_CHECK(stats_layout, sizeof(cloth_stats) == 80 && offsetof(cloth_stats, kinetic_energy) == 8 &&
                                     offsetof(cloth_stats, last_step_result) == 52 &&
                                     offsetof(cloth_stats, strain_limit_excess) == 56 &&
                                     offsetof(cloth_stats, strain_limit_unmet) == 60 &&
                                     offsetof(cloth_stats, last_max_iterations) == 64 &&
                                     offsetof(cloth_stats, last_substeps) == 68 &&
                                     offsetof(cloth_stats, last_strain_passes) == 72 &&
                                     offsetof(cloth_stats, last_strain_pass_cap_hit) == 76);
#endif

/* Callbacks of exactly the documented types. */
static void* header_alloc(size_t size, size_t alignment, void* user) {
    (void)size;
    (void)alignment;
    (void)user;
    return NULL;
}
static void header_free(void* ptr, size_t size, void* user) {
    (void)ptr;
    (void)size;
    (void)user;
}
static void header_log(cloth_log_level level, cloth_result code, const char* message, void* user) {
    (void)level;
    (void)code;
    (void)message;
    (void)user;
}

/* Every function, bound to a pointer of the documented signature. */
struct cloth_header_api {
    cloth_version (*get_version)(void);
    const char* (*result_name)(cloth_result);
    const char* (*get_last_error)(void);
    cloth_world_desc (*default_world_desc)(void);
    cloth_result (*world_create)(const cloth_world_desc*, cloth_world_id*);
    cloth_result (*world_destroy)(cloth_world_id);
    cloth_result (*world_set_gravity)(cloth_world_id, const float[3]);
    cloth_result (*step)(cloth_world_id, float);
    cloth_grid_desc (*default_grid_desc)(void);
    cloth_mesh_desc (*default_mesh_desc)(void);
    cloth_result (*fabric_create_grid)(cloth_world_id, const cloth_grid_desc*, cloth_fabric_id*);
    cloth_result (*fabric_create_mesh)(cloth_world_id, const cloth_mesh_desc*, cloth_fabric_id*);
    cloth_result (*fabric_create_obj)(cloth_world_id, const char*, uint32_t, cloth_fabric_id*);
    cloth_result (*fabric_destroy)(cloth_fabric_id);
    cloth_result (*fabric_get_particle_count)(cloth_fabric_id, uint32_t*);
    cloth_result (*fabric_get_triangle_count)(cloth_fabric_id, uint32_t*);
    cloth_result (*fabric_get_spring_count)(cloth_fabric_id, uint32_t, uint32_t*);
    cloth_result (*fabric_read_triangles)(cloth_fabric_id, uint32_t*, uint32_t);
    cloth_solver_settings (*default_solver_settings)(void);
    cloth_desc (*default_desc)(void);
    cloth_result (*create)(cloth_world_id, const cloth_desc*, cloth_id*);
    cloth_result (*destroy)(cloth_id);
    cloth_result (*get_particle_count)(cloth_id, uint32_t*);
    cloth_result (*read_positions)(cloth_id, float*, uint32_t);
    cloth_result (*read_velocities)(cloth_id, float*, uint32_t);
    cloth_result (*read_normals)(cloth_id, float*, uint32_t);
    cloth_result (*set_positions)(cloth_id, const uint32_t*, const float*, uint32_t);
    cloth_result (*set_particle_masses)(cloth_id, const uint32_t*, const float*, uint32_t);
    cloth_result (*read_particle_masses)(cloth_id, float*, uint32_t);
    cloth_result (*pin)(cloth_id, const uint32_t*, uint32_t);
    cloth_result (*unpin)(cloth_id, const uint32_t*, uint32_t);
    cloth_result (*set_pin_targets)(cloth_id, const uint32_t*, const float*, uint32_t);
    cloth_result (*is_pinned)(cloth_id, uint32_t, bool*);
    cloth_result (*set_solver)(cloth_id, const cloth_solver_settings*);
    cloth_result (*get_solver)(cloth_id, cloth_solver_settings*);
    cloth_result (*set_spring_params)(cloth_id, uint32_t, cloth_spring_params);
    cloth_result (*set_aero)(cloth_id, const cloth_aero_params*);
    cloth_result (*set_wind)(cloth_id, const float[3]);
    cloth_result (*get_stats)(cloth_id, cloth_stats*);
    size_t (*struct_size)(cloth_struct_kind);
    bool (*world_is_valid)(cloth_world_id);
    bool (*fabric_is_valid)(cloth_fabric_id);
    bool (*is_valid)(cloth_id);
    bool (*body_is_valid)(cloth_body_id);
    bool (*collider_is_valid)(cloth_collider_id);
    bool (*world_id_equal)(cloth_world_id, cloth_world_id);
    bool (*fabric_id_equal)(cloth_fabric_id, cloth_fabric_id);
    bool (*id_equal)(cloth_id, cloth_id);
    bool (*body_id_equal)(cloth_body_id, cloth_body_id);
    bool (*collider_id_equal)(cloth_collider_id, cloth_collider_id);
};

/* Prototypes for the two exported functions (keeps -Wmissing-prototypes quiet too). */
const struct cloth_header_api* cloth_header_c99_api(void);
uint32_t cloth_header_c99_uses_every_type(void);

const struct cloth_header_api* cloth_header_c99_api(void) {
    static const struct cloth_header_api api = {
        cloth_get_version,
        cloth_result_name,
        cloth_get_last_error,
        cloth_default_world_desc,
        cloth_world_create,
        cloth_world_destroy,
        cloth_world_set_gravity,
        cloth_step,
        cloth_default_grid_desc,
        cloth_default_mesh_desc,
        cloth_fabric_create_grid,
        cloth_fabric_create_mesh,
        cloth_fabric_create_obj,
        cloth_fabric_destroy,
        cloth_fabric_get_particle_count,
        cloth_fabric_get_triangle_count,
        cloth_fabric_get_spring_count,
        cloth_fabric_read_triangles,
        cloth_default_solver_settings,
        cloth_default_desc,
        cloth_create,
        cloth_destroy,
        cloth_get_particle_count,
        cloth_read_positions,
        cloth_read_velocities,
        cloth_read_normals,
        cloth_set_positions,
        cloth_set_particle_masses,
        cloth_read_particle_masses,
        cloth_pin,
        cloth_unpin,
        cloth_set_pin_targets,
        cloth_is_pinned,
        cloth_set_solver,
        cloth_get_solver,
        cloth_set_spring_params,
        cloth_set_aero,
        cloth_set_wind,
        cloth_get_stats,
        cloth_struct_size,
        cloth_world_is_valid,
        cloth_fabric_is_valid,
        cloth_is_valid,
        cloth_body_is_valid,
        cloth_collider_is_valid,
        cloth_world_id_equal,
        cloth_fabric_id_equal,
        cloth_id_equal,
        cloth_body_id_equal,
        cloth_collider_id_equal,
    };
    return &api;
}

/* Every type of the header, as a C caller would fill and read it. */
uint32_t cloth_header_c99_uses_every_type(void) {
    cloth_version version = {CLOTH_VERSION_MAJOR, CLOTH_VERSION_MINOR, CLOTH_VERSION_PATCH};
    cloth_result results[] = {
        CLOTH_OK,
        CLOTH_ERROR_NULL_POINTER,
        CLOTH_ERROR_INVALID_HANDLE,
        CLOTH_ERROR_INVALID_DESC,
        CLOTH_ERROR_INVALID_COUNT,
        CLOTH_ERROR_INDEX_OUT_OF_RANGE,
        CLOTH_ERROR_NOT_FINITE,
        CLOTH_ERROR_INVALID_VALUE,
        CLOTH_ERROR_DEGENERATE_GEOMETRY,
        CLOTH_ERROR_OUT_OF_MEMORY,
        CLOTH_ERROR_CAPACITY,
        CLOTH_ERROR_IO,
        CLOTH_ERROR_NONFINITE_STATE,
        CLOTH_ERROR_SOLVER_FAILED,
        CLOTH_ERROR_INTERNAL,
        CLOTH_ERROR_OVER_BUDGET,
        CLOTH_ERROR_CORRUPT_SNAPSHOT,
        CLOTH_RESULT_FORCE_U32,
    };
    cloth_log_level levels[] = {CLOTH_LOG_ERROR, CLOTH_LOG_WARNING, CLOTH_LOG_INFO,
                                CLOTH_LOG_LEVEL_FORCE_U32};
    cloth_spring_kind kinds[] = {CLOTH_SPRING_STRUCTURAL, CLOTH_SPRING_SHEAR, CLOTH_SPRING_BEND,
                                 CLOTH_SPRING_ALL, CLOTH_SPRING_KIND_FORCE_U32};
    cloth_solver_kind solvers[] = {CLOTH_SOLVER_DEFAULT, CLOTH_SOLVER_JACOBI, CLOTH_SOLVER_CG,
                                   CLOTH_SOLVER_EXPLICIT, CLOTH_SOLVER_KIND_FORCE_U32};
    cloth_world_id world = {0, 0};
    cloth_fabric_id fabric = {0, 0, 0, 0};
    cloth_id cloth = {0, 0, 0, 0};
    cloth_alloc_fn* alloc = header_alloc;
    cloth_free_fn* free_fn = header_free;
    cloth_log_fn* log = header_log;
    cloth_world_desc world_desc;
    cloth_grid_desc grid_desc;
    cloth_mesh_desc mesh_desc;
    cloth_spring_params spring = {1000.0f, 0.5f};
    cloth_solver_settings solver;
    cloth_aero_params aero = {{0.0f, 0.0f, 0.0f}, 1.2f, 1.0f, 0.5f, 0.02f};
    cloth_desc desc;
    cloth_stats stats;
    uint32_t sum = 0;
    size_t i;

    world_desc.struct_size = (uint32_t)sizeof world_desc;
    world_desc.gravity[0] = 0.0f;
    world_desc.gravity[1] = -9.81f;
    world_desc.gravity[2] = 0.0f;
    world_desc.alloc = alloc;
    world_desc.free = free_fn;
    world_desc.log = log;
    world_desc.user = NULL;
    world_desc.max_cloths = 1024;
    world_desc.max_fabrics = 256;
    world_desc.internal_cookie = 0;

    grid_desc.struct_size = (uint32_t)sizeof grid_desc;
    grid_desc.columns = 32;
    grid_desc.rows = 32;
    for (i = 0; i < 3; ++i) {
        grid_desc.origin[i] = 0.0f;
        grid_desc.u[i] = 0.0f;
        grid_desc.v[i] = 0.0f;
    }
    grid_desc.spring_kinds = (uint32_t)CLOTH_SPRING_ALL;
    grid_desc.internal_cookie = 0;

    mesh_desc.struct_size = (uint32_t)sizeof mesh_desc;
    mesh_desc.positions = NULL;
    mesh_desc.vertex_count = 3;
    mesh_desc.indices = NULL;
    mesh_desc.triangle_count = 1;
    mesh_desc.spring_kinds = (uint32_t)(CLOTH_SPRING_STRUCTURAL | CLOTH_SPRING_BEND);
    mesh_desc.internal_cookie = 0;

    solver.struct_size = (uint32_t)sizeof solver;
    solver.kind = CLOTH_SOLVER_JACOBI;
    solver.iterations = 1;
    solver.substeps = 1;
    solver.cg_tolerance = 1e-6f;
    solver.cg_max_iterations = 1000;
    solver.compression_safe_jacobian = true;

    desc.struct_size = (uint32_t)sizeof desc;
    desc.fabric = fabric;
    desc.area_density = 0.2f;
    desc.particle_mass = 0.0f;
    desc.initial_positions = NULL;
    desc.structural = spring;
    desc.shear = spring;
    desc.bend = spring;
    desc.solver = solver;
    desc.aero = aero;
    desc.internal_cookie = 0;

    stats.struct_size = (uint32_t)sizeof stats;
    stats.kinetic_energy = 0.0;
    stats.gravity_energy = 0.0;
    stats.elastic_energy = 0.0;
    stats.max_strain = 0.0f;
    stats.mean_strain = 0.0f;
    stats.max_speed = 0.0f;
    stats.last_solver_iterations = 0;
    stats.last_solver_residual = 0.0f;
    stats.last_step_result = CLOTH_OK;

    sum += version.major + version.minor + version.patch;
    for (i = 0; i < sizeof results / sizeof results[0]; ++i) sum += (uint32_t)results[i];
    for (i = 0; i < sizeof levels / sizeof levels[0]; ++i) sum += (uint32_t)levels[i];
    for (i = 0; i < sizeof kinds / sizeof kinds[0]; ++i) sum += (uint32_t)kinds[i];
    for (i = 0; i < sizeof solvers / sizeof solvers[0]; ++i) sum += (uint32_t)solvers[i];
    sum += world.index1 + world.generation;
    sum += (uint32_t)cloth_world_id_equal(world, cloth_null_world_id) +
           (uint32_t)cloth_fabric_id_equal(fabric, cloth_null_fabric_id) +
           (uint32_t)cloth_id_equal(cloth, cloth_null_id) +
           (uint32_t)cloth_body_id_equal(cloth_null_body_id, cloth_null_body_id) +
           (uint32_t)cloth_collider_id_equal(cloth_null_collider_id, cloth_null_collider_id);
    sum += (uint32_t)CLOTH_STRUCT_SELF_COLLISION_STATS + (uint32_t)CLOTH_STRUCT_KIND_FORCE_U32;
    sum += fabric.index1 + fabric.world1 + fabric.generation;
    sum += cloth.index1 + cloth.world1 + cloth.generation;
    sum +=
        world_desc.struct_size + world_desc.max_cloths + world_desc.max_fabrics + world_desc.internal_cookie;
    sum += (world_desc.alloc(1, 1, world_desc.user) == NULL) ? 1u : 0u;
    world_desc.free(&sum, 0, world_desc.user);
    world_desc.log(CLOTH_LOG_ERROR, CLOTH_OK, "", world_desc.user);
    sum += (uint32_t)(world_desc.gravity[1] < 0.0f);
    sum += grid_desc.columns + grid_desc.rows + grid_desc.spring_kinds + grid_desc.internal_cookie;
    sum += (uint32_t)(grid_desc.origin[0] + grid_desc.u[0] + grid_desc.v[0]);
    sum += mesh_desc.vertex_count + mesh_desc.triangle_count + mesh_desc.spring_kinds +
           mesh_desc.internal_cookie;
    sum += (uint32_t)(mesh_desc.positions == NULL) + (uint32_t)(mesh_desc.indices == NULL);
    sum += desc.struct_size + desc.fabric.index1 + desc.internal_cookie +
           (uint32_t)(desc.initial_positions == NULL);
    sum += (uint32_t)(desc.area_density + desc.particle_mass + desc.structural.stiffness +
                      desc.shear.damping + desc.bend.stiffness);
    sum += desc.solver.struct_size + (uint32_t)desc.solver.kind + desc.solver.iterations +
           desc.solver.substeps + desc.solver.cg_max_iterations +
           (uint32_t)desc.solver.compression_safe_jacobian;
    sum += (uint32_t)(desc.solver.cg_tolerance > 0.0f);
    sum += (uint32_t)(desc.aero.wind[0] + desc.aero.air_density + desc.aero.drag_coefficient +
                      desc.aero.lift_coefficient + desc.aero.linear_drag);
    sum += stats.struct_size + stats.last_solver_iterations + (uint32_t)stats.last_step_result;
    sum += (uint32_t)(stats.kinetic_energy + stats.gravity_energy + stats.elastic_energy);
    sum += (uint32_t)(stats.max_strain + stats.mean_strain + stats.max_speed + stats.last_solver_residual);
    return sum;
}
