// Compile-only check that <cloth/cloth.h> is valid, warning-free C++.
//
// Build as an object only (no main, no library needed), e.g.
//   g++ -std=c++17 -Wall -Wextra -Werror -pedantic -Iinclude -c tests/capi/header_cxx.cpp
//
// Every type, enumerator and function of the header is used; every function
// is checked against its documented signature with std::is_same, every struct
// is checked to be a C-compatible (standard-layout, trivial) type, and the
// layout numbers are the same ones header_c99.c checks, so C and C++ callers
// see one ABI.
#include <cloth/cloth.h>
#include <cloth/cloth.h>  // the include guard must make a second inclusion harmless

#include <cstddef>
#include <cstdint>
#include <type_traits>

namespace {

template <typename T>
struct IsCType
    : std::integral_constant<bool, std::is_standard_layout<T>::value && std::is_trivial<T>::value> {};

static_assert(IsCType<cloth_version>::value, "cloth_version must be a C type");
static_assert(IsCType<cloth_world_id>::value, "cloth_world_id must be a C type");
static_assert(IsCType<cloth_fabric_id>::value, "cloth_fabric_id must be a C type");
static_assert(IsCType<cloth_id>::value, "cloth_id must be a C type");
static_assert(IsCType<cloth_world_desc>::value, "cloth_world_desc must be a C type");
static_assert(IsCType<cloth_grid_desc>::value, "cloth_grid_desc must be a C type");
static_assert(IsCType<cloth_mesh_desc>::value, "cloth_mesh_desc must be a C type");
static_assert(IsCType<cloth_spring_params>::value, "cloth_spring_params must be a C type");
static_assert(IsCType<cloth_solver_settings>::value, "cloth_solver_settings must be a C type");
static_assert(IsCType<cloth_aero_params>::value, "cloth_aero_params must be a C type");
static_assert(IsCType<cloth_desc>::value, "cloth_desc must be a C type");
static_assert(IsCType<cloth_stats>::value, "cloth_stats must be a C type");

// Handles are small value types.
static_assert(sizeof(cloth_world_id) == 4, "");
static_assert(sizeof(cloth_fabric_id) == 8, "");
static_assert(sizeof(cloth_id) == 8, "");
static_assert(sizeof(cloth_version) == 12, "");

// Enums are forced to 32 bits.
static_assert(sizeof(cloth_result) == 4, "");
static_assert(sizeof(cloth_log_level) == 4, "");
static_assert(sizeof(cloth_spring_kind) == 4, "");
static_assert(sizeof(cloth_solver_kind) == 4, "");
static_assert(sizeof(bool) == 1, "cloth_solver_settings carries a bool: it must match C's _Bool");

// struct_size comes first in every versioned struct.
static_assert(offsetof(cloth_world_desc, struct_size) == 0, "");
static_assert(offsetof(cloth_grid_desc, struct_size) == 0, "");
static_assert(offsetof(cloth_mesh_desc, struct_size) == 0, "");
static_assert(offsetof(cloth_solver_settings, struct_size) == 0, "");
static_assert(offsetof(cloth_desc, struct_size) == 0, "");
static_assert(offsetof(cloth_stats, struct_size) == 0, "");

// Result codes are ABI: their values never change.
static_assert(CLOTH_OK == 0, "");
static_assert(CLOTH_ERROR_NULL_POINTER == 1, "");
static_assert(CLOTH_ERROR_INVALID_HANDLE == 2, "");
static_assert(CLOTH_ERROR_INVALID_DESC == 3, "");
static_assert(CLOTH_ERROR_INVALID_COUNT == 4, "");
static_assert(CLOTH_ERROR_INDEX_OUT_OF_RANGE == 5, "");
static_assert(CLOTH_ERROR_NOT_FINITE == 6, "");
static_assert(CLOTH_ERROR_INVALID_VALUE == 7, "");
static_assert(CLOTH_ERROR_DEGENERATE_GEOMETRY == 8, "");
static_assert(CLOTH_ERROR_OUT_OF_MEMORY == 9, "");
static_assert(CLOTH_ERROR_CAPACITY == 10, "");
static_assert(CLOTH_ERROR_IO == 11, "");
static_assert(CLOTH_ERROR_NONFINITE_STATE == 12, "");
static_assert(CLOTH_ERROR_SOLVER_FAILED == 13, "");
static_assert(CLOTH_ERROR_INTERNAL == 14, "");
static_assert(CLOTH_ERROR_OVER_BUDGET == 15, "");
static_assert(CLOTH_ERROR_CORRUPT_SNAPSHOT == 16, "");
static_assert(CLOTH_SPRING_ALL == (CLOTH_SPRING_STRUCTURAL | CLOTH_SPRING_SHEAR | CLOTH_SPRING_BEND), "");
static_assert(CLOTH_SOLVER_DEFAULT == 0, "");
static_assert(CLOTH_VERSION_MAJOR == 1, "");

// Exact layout on 64-bit targets; the same numbers as header_c99.c.
#if UINTPTR_MAX == 0xFFFFFFFFFFFFFFFFu
static_assert(sizeof(cloth_world_desc) == 88, "");
static_assert(offsetof(cloth_world_desc, worker_count) == 60, "");
static_assert(offsetof(cloth_world_desc, enqueue_task) == 64, "");
static_assert(offsetof(cloth_world_desc, task_user) == 80, "");
static_assert(offsetof(cloth_world_desc, alloc) == 16, "");
static_assert(offsetof(cloth_world_desc, user) == 40, "");
static_assert(offsetof(cloth_world_desc, internal_cookie) == 56, "");
static_assert(sizeof(cloth_grid_desc) == 56, "");
static_assert(offsetof(cloth_grid_desc, spring_kinds) == 48, "");
static_assert(sizeof(cloth_mesh_desc) == 48, "");
static_assert(offsetof(cloth_mesh_desc, indices) == 24, "");
static_assert(offsetof(cloth_mesh_desc, internal_cookie) == 40, "");
static_assert(sizeof(cloth_solver_settings) == 28, "");
static_assert(offsetof(cloth_solver_settings, compression_safe_jacobian) == 24, "");
static_assert(sizeof(cloth_aero_params) == 28, "");
static_assert(sizeof(cloth_spring_params) == 8, "");
static_assert(sizeof(cloth_desc) == 120, "");
static_assert(offsetof(cloth_desc, initial_positions) == 24, "");
static_assert(offsetof(cloth_desc, solver) == 56, "");
static_assert(offsetof(cloth_desc, aero) == 84, "");
static_assert(offsetof(cloth_desc, internal_cookie) == 112, "");
static_assert(sizeof(cloth_stats) == 80, "");
static_assert(offsetof(cloth_stats, kinetic_energy) == 8, "");
static_assert(offsetof(cloth_stats, last_step_result) == 52, "");
#endif

// Every function has exactly its documented signature.
#define CLOTH_CHECK_SIGNATURE(fn, type) static_assert(std::is_same<decltype(&fn), type>::value, #fn)
CLOTH_CHECK_SIGNATURE(cloth_get_version, cloth_version (*)());
CLOTH_CHECK_SIGNATURE(cloth_result_name, const char* (*)(cloth_result));
CLOTH_CHECK_SIGNATURE(cloth_get_last_error, const char* (*)());
CLOTH_CHECK_SIGNATURE(cloth_default_world_desc, cloth_world_desc (*)());
CLOTH_CHECK_SIGNATURE(cloth_world_create, cloth_result (*)(const cloth_world_desc*, cloth_world_id*));
CLOTH_CHECK_SIGNATURE(cloth_world_destroy, cloth_result (*)(cloth_world_id));
CLOTH_CHECK_SIGNATURE(cloth_world_set_gravity, cloth_result (*)(cloth_world_id, const float*));
CLOTH_CHECK_SIGNATURE(cloth_world_shift_origin, cloth_result (*)(cloth_world_id, const float*));
CLOTH_CHECK_SIGNATURE(cloth_world_set_worker_spin, cloth_result (*)(cloth_world_id, uint32_t));
CLOTH_CHECK_SIGNATURE(cloth_step, cloth_result (*)(cloth_world_id, float));
CLOTH_CHECK_SIGNATURE(cloth_default_grid_desc, cloth_grid_desc (*)());
CLOTH_CHECK_SIGNATURE(cloth_default_mesh_desc, cloth_mesh_desc (*)());
CLOTH_CHECK_SIGNATURE(cloth_fabric_create_grid,
                      cloth_result (*)(cloth_world_id, const cloth_grid_desc*, cloth_fabric_id*));
CLOTH_CHECK_SIGNATURE(cloth_fabric_create_mesh,
                      cloth_result (*)(cloth_world_id, const cloth_mesh_desc*, cloth_fabric_id*));
CLOTH_CHECK_SIGNATURE(cloth_fabric_create_obj,
                      cloth_result (*)(cloth_world_id, const char*, uint32_t, cloth_fabric_id*));
CLOTH_CHECK_SIGNATURE(cloth_fabric_destroy, cloth_result (*)(cloth_fabric_id));
CLOTH_CHECK_SIGNATURE(cloth_fabric_get_particle_count, cloth_result (*)(cloth_fabric_id, uint32_t*));
CLOTH_CHECK_SIGNATURE(cloth_fabric_get_triangle_count, cloth_result (*)(cloth_fabric_id, uint32_t*));
CLOTH_CHECK_SIGNATURE(cloth_fabric_get_spring_count, cloth_result (*)(cloth_fabric_id, uint32_t, uint32_t*));
CLOTH_CHECK_SIGNATURE(cloth_fabric_read_triangles, cloth_result (*)(cloth_fabric_id, uint32_t*, uint32_t));
CLOTH_CHECK_SIGNATURE(cloth_default_solver_settings, cloth_solver_settings (*)());
CLOTH_CHECK_SIGNATURE(cloth_default_desc, cloth_desc (*)());
CLOTH_CHECK_SIGNATURE(cloth_create, cloth_result (*)(cloth_world_id, const cloth_desc*, cloth_id*));
CLOTH_CHECK_SIGNATURE(cloth_destroy, cloth_result (*)(cloth_id));
CLOTH_CHECK_SIGNATURE(cloth_get_particle_count, cloth_result (*)(cloth_id, uint32_t*));
CLOTH_CHECK_SIGNATURE(cloth_read_positions, cloth_result (*)(cloth_id, float*, uint32_t));
CLOTH_CHECK_SIGNATURE(cloth_read_velocities, cloth_result (*)(cloth_id, float*, uint32_t));
CLOTH_CHECK_SIGNATURE(cloth_read_normals, cloth_result (*)(cloth_id, float*, uint32_t));
CLOTH_CHECK_SIGNATURE(cloth_set_positions,
                      cloth_result (*)(cloth_id, const uint32_t*, const float*, uint32_t));
CLOTH_CHECK_SIGNATURE(cloth_set_particle_masses,
                      cloth_result (*)(cloth_id, const uint32_t*, const float*, uint32_t));
CLOTH_CHECK_SIGNATURE(cloth_read_particle_masses, cloth_result (*)(cloth_id, float*, uint32_t));
CLOTH_CHECK_SIGNATURE(cloth_pin, cloth_result (*)(cloth_id, const uint32_t*, uint32_t));
CLOTH_CHECK_SIGNATURE(cloth_unpin, cloth_result (*)(cloth_id, const uint32_t*, uint32_t));
CLOTH_CHECK_SIGNATURE(cloth_set_pin_targets,
                      cloth_result (*)(cloth_id, const uint32_t*, const float*, uint32_t));
CLOTH_CHECK_SIGNATURE(cloth_is_pinned, cloth_result (*)(cloth_id, uint32_t, bool*));
CLOTH_CHECK_SIGNATURE(cloth_set_solver, cloth_result (*)(cloth_id, const cloth_solver_settings*));
CLOTH_CHECK_SIGNATURE(cloth_get_solver, cloth_result (*)(cloth_id, cloth_solver_settings*));
CLOTH_CHECK_SIGNATURE(cloth_set_spring_params, cloth_result (*)(cloth_id, uint32_t, cloth_spring_params));
CLOTH_CHECK_SIGNATURE(cloth_set_aero, cloth_result (*)(cloth_id, const cloth_aero_params*));
CLOTH_CHECK_SIGNATURE(cloth_set_wind, cloth_result (*)(cloth_id, const float*));
CLOTH_CHECK_SIGNATURE(cloth_get_stats, cloth_result (*)(cloth_id, cloth_stats*));
CLOTH_CHECK_SIGNATURE(cloth_default_self_collision_desc, cloth_self_collision_desc (*)(void));
CLOTH_CHECK_SIGNATURE(cloth_set_self_collision, cloth_result (*)(cloth_id, const cloth_self_collision_desc*));
CLOTH_CHECK_SIGNATURE(cloth_get_self_collision, cloth_result (*)(cloth_id, cloth_self_collision_desc*));
CLOTH_CHECK_SIGNATURE(cloth_get_self_collision_stats,
                      cloth_result (*)(cloth_id, cloth_self_collision_stats*));
#undef CLOTH_CHECK_SIGNATURE

// Callback typedefs accept ordinary functions of the documented shape.
static_assert(std::is_same<cloth_alloc_fn, void*(std::size_t, std::size_t, void*)>::value, "");
static_assert(std::is_same<cloth_free_fn, void(void*, std::size_t, void*)>::value, "");
static_assert(std::is_same<cloth_log_fn, void(cloth_log_level, cloth_result, const char*, void*)>::value, "");

void* HeaderAlloc(std::size_t, std::size_t, void*) { return nullptr; }
void HeaderFree(void*, std::size_t, void*) {}
void HeaderLog(cloth_log_level, cloth_result, const char*, void*) {}

}  // namespace

// Exported so nothing above is "unused"; never called.
std::uint32_t cloth_header_cxx_uses_every_type();

std::uint32_t cloth_header_cxx_uses_every_type() {
    const cloth_version version{CLOTH_VERSION_MAJOR, CLOTH_VERSION_MINOR, CLOTH_VERSION_PATCH};
    const cloth_result results[] = {
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
    const cloth_log_level levels[] = {CLOTH_LOG_ERROR, CLOTH_LOG_WARNING, CLOTH_LOG_INFO,
                                      CLOTH_LOG_LEVEL_FORCE_U32};
    const cloth_spring_kind kinds[] = {CLOTH_SPRING_STRUCTURAL, CLOTH_SPRING_SHEAR, CLOTH_SPRING_BEND,
                                       CLOTH_SPRING_ALL, CLOTH_SPRING_KIND_FORCE_U32};
    const cloth_solver_kind solvers[] = {CLOTH_SOLVER_DEFAULT, CLOTH_SOLVER_JACOBI, CLOTH_SOLVER_CG,
                                         CLOTH_SOLVER_EXPLICIT, CLOTH_SOLVER_KIND_FORCE_U32};
    const cloth_world_id world{};
    const cloth_fabric_id fabric{};
    const cloth_id cloth{};
    cloth_alloc_fn* const alloc = HeaderAlloc;
    cloth_free_fn* const free_fn = HeaderFree;
    cloth_log_fn* const log = HeaderLog;
    const cloth_world_desc world_desc{sizeof(cloth_world_desc),
                                      {0.0f, -9.81f, 0.0f},
                                      alloc,
                                      free_fn,
                                      log,
                                      nullptr,
                                      1024,
                                      256,
                                      0,
                                      0,
                                      nullptr,
                                      nullptr,
                                      nullptr};
    const cloth_grid_desc grid_desc{
        sizeof(cloth_grid_desc), 32, 32, {0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, {0.0f, -1.0f, 0.0f},
        CLOTH_SPRING_ALL,        0};
    const cloth_mesh_desc mesh_desc{sizeof(cloth_mesh_desc), nullptr, 3, nullptr, 1, CLOTH_SPRING_ALL, 0};
    const cloth_spring_params spring{1000.0f, 0.5f};
    const cloth_solver_settings solver{
        sizeof(cloth_solver_settings), CLOTH_SOLVER_JACOBI, 1, 1, 1e-6f, 1000, true};
    const cloth_aero_params aero{{0.0f, 0.0f, 0.0f}, 1.2f, 1.0f, 0.5f, 0.02f};
    const cloth_desc desc{
        sizeof(cloth_desc), fabric, 0.2f, 0.0f, nullptr, spring, spring, spring, solver, aero, 0};
    const cloth_stats stats{
        sizeof(cloth_stats), 0.0, 0.0, 0.0, 0.0f, 0.0f, 0.0f, 0, 0.0f, CLOTH_OK, 0.0f, 0, 0, 0, 0, 0};

    std::uint32_t sum = version.major + version.minor + version.patch;
    for (cloth_result r : results) sum += static_cast<std::uint32_t>(r);
    for (cloth_log_level l : levels) sum += static_cast<std::uint32_t>(l);
    for (cloth_spring_kind k : kinds) sum += static_cast<std::uint32_t>(k);
    for (cloth_solver_kind s : solvers) sum += static_cast<std::uint32_t>(s);
    sum += world.index1 + world.generation + fabric.index1 + fabric.world1 + fabric.generation;
    sum += cloth.index1 + cloth.world1 + cloth.generation;
    sum +=
        world_desc.struct_size + world_desc.max_cloths + world_desc.max_fabrics + world_desc.internal_cookie;
    sum += world_desc.alloc(1, 1, world_desc.user) == nullptr ? 1u : 0u;
    world_desc.free(&sum, 0, world_desc.user);
    world_desc.log(CLOTH_LOG_ERROR, CLOTH_OK, "", world_desc.user);
    sum += world_desc.gravity[1] < 0.0f ? 1u : 0u;
    sum += grid_desc.columns + grid_desc.rows + grid_desc.spring_kinds + grid_desc.internal_cookie;
    sum += grid_desc.origin[0] + grid_desc.u[0] + grid_desc.v[1] < 0.0f ? 1u : 0u;
    sum += mesh_desc.vertex_count + mesh_desc.triangle_count + mesh_desc.spring_kinds +
           mesh_desc.internal_cookie;
    sum += (mesh_desc.positions == nullptr ? 1u : 0u) + (mesh_desc.indices == nullptr ? 1u : 0u);
    sum += desc.struct_size + desc.fabric.index1 + desc.internal_cookie + (desc.initial_positions ? 0u : 1u);
    sum += desc.area_density + desc.particle_mass + desc.structural.stiffness + desc.shear.damping +
                       desc.bend.stiffness >
                   0.0f
               ? 1u
               : 0u;
    sum += desc.solver.struct_size + static_cast<std::uint32_t>(desc.solver.kind) + desc.solver.iterations +
           desc.solver.substeps + desc.solver.cg_max_iterations +
           (desc.solver.compression_safe_jacobian ? 1u : 0u);
    sum += desc.solver.cg_tolerance > 0.0f ? 1u : 0u;
    sum += desc.aero.wind[0] + desc.aero.air_density + desc.aero.drag_coefficient +
                       desc.aero.lift_coefficient + desc.aero.linear_drag >
                   0.0f
               ? 1u
               : 0u;
    sum +=
        stats.struct_size + stats.last_solver_iterations + static_cast<std::uint32_t>(stats.last_step_result);
    sum += stats.kinetic_energy + stats.gravity_energy + stats.elastic_energy > 0.0 ? 1u : 0u;
    sum +=
        stats.max_strain + stats.mean_strain + stats.max_speed + stats.last_solver_residual > 0.0f ? 1u : 0u;
    return sum;
}
