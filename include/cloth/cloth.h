/**
 * \file cloth.h
 * \brief cloth: real-time mass-spring cloth simulation, C API v1.
 *
 * The whole public interface of the library. C99, and valid C++. Only
 * <stdint.h>, <stddef.h> and <stdbool.h> are used; no C++ type crosses it
 * and no C++ exception ever leaves a call.
 *
 * Objects
 *   - world: owns everything below it, the host callbacks and the step.
 *   - fabric: the shared, immutable topology of a cloth (particles,
 *     triangles, springs, rest lengths, rest areas). Many cloths may share one.
 *   - cloth: one simulated instance of a fabric: positions, velocities,
 *     pins, material, solver settings, wind.
 *   - body and collider: rigid frames the host moves, and the shapes fixed
 *     to them that cloths collide with.
 *
 * Handles are small value structs (slot index + generation, all-zero is
 * null), all declared together under "Handles" with their null constants,
 * cloth_*_id_equal() and cloth_*_is_valid(). A destroyed, never-created or
 * foreign handle makes a call return CLOTH_ERROR_INVALID_HANDLE; it is
 * never dereferenced.
 *
 * Errors. Every fallible call returns a cloth_result. CLOTH_OK is 0. On
 * failure nothing is changed (the one documented exception: cloth_step
 * restores a cloth that went non-finite to its last finite state and
 * reports CLOTH_ERROR_NONFINITE_STATE). A NaN or infinite float argument
 * (or float field, or element of a float array) is reported as
 * CLOTH_ERROR_NOT_FINITE, never as a value out of its range. A call with
 * several faults reports one of them. cloth_get_last_error() returns a
 * message for the last failed call on the calling thread.
 *
 * Which log hears of an error. The world's log callback, if set, receives
 * the same message for every failed call that names a live world: through
 * a world handle, or through a fabric, cloth, body or collider handle whose
 * world part names a live world, even when the object itself is destroyed
 * or was never created (CLOTH_ERROR_INVALID_HANDLE is logged there too). A
 * call that names no live world (a null or stale world handle, an object
 * handle of a destroyed world, cloth_world_create) has no log to report
 * to: only cloth_get_last_error() tells of it.
 *
 * Versioned structs. A struct whose first field is `struct_size` is
 * versioned: struct_size holds sizeof the struct as the caller was built.
 * This version accepts exactly its own sizes, and a later minor version
 * will accept these sizes too, so a caller built against this header keeps
 * working. Fields are only ever appended to the outermost struct; a struct
 * embedded by value in another (cloth_spring_params, cloth_solver_settings,
 * cloth_aero_params) is frozen as it is, and later settings arrive as new
 * fields of the outer struct or through new functions. Structs without
 * struct_size (the ids, cloth_version, cloth_spring_params,
 * cloth_aero_params, cloth_task_record) are frozen.
 *
 * Which structs carry a cookie. Every description, that is every struct
 * whose name ends in `_desc`, also carries `internal_cookie`, which only
 * its cloth_default_*() function (or a cloth_get_*() call that fills one)
 * sets: a description must start from there, and one that was never
 * initialised is refused with CLOTH_ERROR_INVALID_DESC. All other
 * versioned structs carry struct_size only: settings, parameters and
 * policies (`_settings`, `_params`, `_policy`, cloth_strain_limit), which
 * a caller may fill field by field, and the structs the library fills
 * (cloth_stats, cloth_frame_profile, cloth_self_collision_stats), whose
 * struct_size the caller sets before the call.
 *
 * Pointers. The library keeps no pointer it is given except callbacks and
 * their user pointers (cloth_world_desc, cloth_world_set_zone_callbacks),
 * which it keeps until the world is destroyed or they are replaced. Every
 * other pointer, as an argument or as a field of a description, is read or
 * written only during the call: what it points to is copied, and the
 * caller may free or reuse it as soon as the call returns. Each pointer
 * field of a description says which of the two it is.
 *
 * Other languages. Public structs hold only fixed-width integers, floats,
 * doubles, pointers and 32-bit enums (no C bool: flags are uint8_t, 0 or 1,
 * and any other value counts as 1), and cloth_struct_size() returns the
 * library's size of each of them, so a binding can check its own layouts
 * at run time. What else a binding relies on (bindings/csharp/README.md
 * walks through it for C#):
 *   - Calling convention: cdecl for every function and callback type
 *     (CLOTH_CALL).
 *   - Strings the library returns (cloth_result_name, cloth_stage_name,
 *     cloth_get_last_error, the names passed to zone callbacks, the message
 *     passed to a log callback) are NUL-terminated UTF-8 owned by the
 *     library: the caller never frees them (declared as a managed string
 *     return, a marshaller frees them; declare a pointer and copy). Names
 *     are static ASCII; messages are UTF-8 and echo caller input such as an
 *     OBJ path. Strings the library takes (the OBJ path) are NUL-terminated
 *     UTF-8 and read during the call only.
 *   - bool in function signatures (the cloth_*_is_valid() returns and the
 *     bool* outputs of cloth_is_pinned, cloth_is_sleeping and
 *     cloth_get_teleported) is C99 _Bool: one byte, 0 or 1, on every
 *     platform the library builds for. A binding reads and writes exactly
 *     one byte (C#: byte, or bool with MarshalAs(UnmanagedType.U1); the
 *     default bool marshalling is a 4-byte BOOL and reads the return
 *     register's upper bytes, which the ABI leaves undefined).
 *   - Constants are macros and enums of this header: a binding generates
 *     them from it (bindings/csharp/generate.py does). The null ids
 *     (cloth_null_*_id) and cloth_*_id_equal() are header-only and need no
 *     symbol: a null id is all-zero, and two ids are equal exactly when
 *     every field is.
 *   - Descriptions (`_desc`) start from cloth_default_*() (see "Which
 *     structs carry a cookie"): a zero-filled one is refused. The
 *     cloth_default_*() functions and cloth_get_version return structs by
 *     value, in the platform's C convention; cloth_frame_profile (about
 *     4 KB) is never returned by value but filled through a pointer.
 *
 * Limits: every count the API takes has its limit as a CLOTH_MAX_* macro
 * (section "Limits"); a count above it is refused with
 * CLOTH_ERROR_INVALID_COUNT before any buffer it sizes is read.
 *
 * Units: metres, kilograms, seconds. Vectors are float[3] (x, y, z).
 *
 * Coordinates. Every coordinate, offset and length a call takes to place
 * something in the world (particle positions and pin targets, fabric rest
 * positions and grid edges, body and collider poses, attachment offsets,
 * shape sizes and points, heights, collision thickness, the origin shift)
 * must lie within [-CLOTH_MAX_COORDINATE, CLOTH_MAX_COORDINATE] metres:
 * else the call returns CLOTH_ERROR_INVALID_VALUE and changes nothing. The
 * simulation itself may carry a cloth farther (cloth_world_shift_origin
 * brings it back).
 *
 * Threading contract
 *   - A world is not internally synchronised for API calls: the host calls
 *     the functions of one world from one thread at a time (any thread).
 *     No call may be made on a world while cloth_step runs on it.
 *   - Different worlds are independent and may be used from different
 *     threads at the same time.
 *   - Creating and destroying worlds is thread-safe, and so is
 *     cloth_world_is_valid().
 *   - Callbacks (allocator, log) are called on the thread that made the API
 *     call, during that call. They must not call back into this API.
 *   - cloth_get_last_error() is per thread.
 *   - Results are bit-identical for identical inputs and call sequences.
 */
#ifndef CLOTH_CLOTH_H
#define CLOTH_CLOTH_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/// Marks a function the library exports (Windows: dllexport while the
/// library is built, dllimport for a caller of the DLL; elsewhere: default
/// visibility).
#if defined(_WIN32)
#if defined(CLOTH_BUILDING_SHARED)
#define CLOTH_API __declspec(dllexport)
#elif defined(CLOTH_USING_SHARED)
#define CLOTH_API __declspec(dllimport)
#else
#define CLOTH_API
#endif
#else
#define CLOTH_API __attribute__((visibility("default")))
#endif

/// The calling convention of every function of this header and of every
/// callback type (cloth_alloc_fn, cloth_log_fn, cloth_zone_begin_fn, ...):
/// the C convention, cdecl. On Windows it is spelled out as __cdecl, which
/// matters on 32-bit x86, where a caller may default to another one (C#
/// delegates default to stdcall there); on 64-bit Windows and elsewhere
/// there is one C convention and it changes nothing. A binding declares
/// every function and callback cdecl (C#: CallingConvention.Cdecl). Since 1.7.
#if defined(_WIN32)
#define CLOTH_CALL __cdecl
#else
#define CLOTH_CALL
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------------ */
/* Version                                                              */
/* ------------------------------------------------------------------ */

/// Major version of this header: a library of another major version is
/// not compatible with it.
#define CLOTH_VERSION_MAJOR 1
/// Minor version of this header: a library of the same major and at least
/// this minor version has every function and struct of this header.
#define CLOTH_VERSION_MINOR 14
/// Patch version of this header (fixes that change no interface).
#define CLOTH_VERSION_PATCH 0

/// Library version. A library with another major version than the header a
/// caller was built with is not compatible with it.
typedef struct cloth_version {
    /// CLOTH_VERSION_MAJOR of the library
    uint32_t major;
    /// CLOTH_VERSION_MINOR of the library
    uint32_t minor;
    /// CLOTH_VERSION_PATCH of the library
    uint32_t patch;
} cloth_version;

/// The version of the library that is loaded (not of the header).
CLOTH_API cloth_version CLOTH_CALL cloth_get_version(void);

/// Every public struct, for cloth_struct_size(). The values are ABI: a new
/// struct gets a new value at the end, and no value is ever reused.
typedef enum cloth_struct_kind {
    /// no struct (size 0)
    CLOTH_STRUCT_NONE = 0,
    /// cloth_version
    CLOTH_STRUCT_VERSION = 1,
    /// cloth_world_id
    CLOTH_STRUCT_WORLD_ID = 2,
    /// cloth_fabric_id
    CLOTH_STRUCT_FABRIC_ID = 3,
    /// cloth_id
    CLOTH_STRUCT_CLOTH_ID = 4,
    /// cloth_body_id
    CLOTH_STRUCT_BODY_ID = 5,
    /// cloth_collider_id
    CLOTH_STRUCT_COLLIDER_ID = 6,
    /// cloth_world_desc
    CLOTH_STRUCT_WORLD_DESC = 7,
    /// cloth_grid_desc
    CLOTH_STRUCT_GRID_DESC = 8,
    /// cloth_mesh_desc
    CLOTH_STRUCT_MESH_DESC = 9,
    /// cloth_spring_params
    CLOTH_STRUCT_SPRING_PARAMS = 10,
    /// cloth_solver_settings
    CLOTH_STRUCT_SOLVER_SETTINGS = 11,
    /// cloth_strain_limit
    CLOTH_STRUCT_STRAIN_LIMIT = 12,
    /// cloth_aero_params
    CLOTH_STRUCT_AERO_PARAMS = 13,
    /// cloth_desc
    CLOTH_STRUCT_CLOTH_DESC = 14,
    /// cloth_stats
    CLOTH_STRUCT_STATS = 15,
    /// cloth_frame_profile
    CLOTH_STRUCT_FRAME_PROFILE = 16,
    /// cloth_task_record
    CLOTH_STRUCT_TASK_RECORD = 17,
    /// cloth_quality_policy
    CLOTH_STRUCT_QUALITY_POLICY = 18,
    /// cloth_sleep_params
    CLOTH_STRUCT_SLEEP_PARAMS = 19,
    /// cloth_body_desc
    CLOTH_STRUCT_BODY_DESC = 20,
    /// cloth_collider_desc
    CLOTH_STRUCT_COLLIDER_DESC = 21,
    /// cloth_heightfield_desc
    CLOTH_STRUCT_HEIGHTFIELD_DESC = 22,
    /// cloth_collision_params
    CLOTH_STRUCT_COLLISION_PARAMS = 23,
    /// cloth_carrier_desc
    CLOTH_STRUCT_CARRIER_DESC = 24,
    /// cloth_self_collision_desc
    CLOTH_STRUCT_SELF_COLLISION_DESC = 25,
    /// cloth_self_collision_stats
    CLOTH_STRUCT_SELF_COLLISION_STATS = 26,
    /// cloth_skin_desc
    CLOTH_STRUCT_SKIN_DESC = 27,
    /// cloth_cloth_contact_desc
    CLOTH_STRUCT_CLOTH_CONTACT_DESC = 28,
    /// forces the enum to 32 bits; not a struct
    CLOTH_STRUCT_KIND_FORCE_U32 = 0x7FFFFFFF
} cloth_struct_kind;

/// sizeof the struct of `kind` as the loaded library was built, or 0 for a
/// kind it does not know (CLOTH_STRUCT_NONE, or a kind added by a later
/// version). One function for every struct, so that a binding checks all
/// its layouts with one symbol, and a later struct adds a kind, not a
/// function.
CLOTH_API size_t CLOTH_CALL cloth_struct_size(cloth_struct_kind kind);

/* ------------------------------------------------------------------ */
/* Results                                                              */
/* ------------------------------------------------------------------ */

/// What a call did. Values are ABI and never change.
typedef enum cloth_result {
    /// success
    CLOTH_OK = 0,
    /// a required pointer argument was NULL
    CLOTH_ERROR_NULL_POINTER = 1,
    /// null, destroyed or foreign handle
    CLOTH_ERROR_INVALID_HANDLE = 2,
    /// description not from cloth_default_*() or wrong struct_size
    CLOTH_ERROR_INVALID_DESC = 3,
    /// a count is zero, negative or too large
    CLOTH_ERROR_INVALID_COUNT = 4,
    /// a particle or vertex index is out of range
    CLOTH_ERROR_INDEX_OUT_OF_RANGE = 5,
    /// a position or parameter is NaN or infinite
    CLOTH_ERROR_NOT_FINITE = 6,
    /// a value is out of its documented range (negative stiffness, dt < CLOTH_MIN_DT, a coordinate beyond
    /// CLOTH_MAX_COORDINATE, ...)
    CLOTH_ERROR_INVALID_VALUE = 7,
    /// zero-area triangle, repeated vertex, zero-length edge
    CLOTH_ERROR_DEGENERATE_GEOMETRY = 8,
    /// the allocator returned NULL
    CLOTH_ERROR_OUT_OF_MEMORY = 9,
    /// too many worlds, fabrics or cloths
    CLOTH_ERROR_CAPACITY = 10,
    /// a file could not be read or parsed
    CLOTH_ERROR_IO = 11,
    /// a step produced NaN/Inf; the cloth was restored to its last finite state
    CLOTH_ERROR_NONFINITE_STATE = 12,
    /// a solve did not converge (state still advanced, finite)
    CLOTH_ERROR_SOLVER_FAILED = 13,
    /// an unexpected internal error; the world is unchanged
    CLOTH_ERROR_INTERNAL = 14,
    /// the step took longer than the world's frame budget; every cloth still advanced
    CLOTH_ERROR_OVER_BUDGET = 15,
    /// a snapshot buffer is damaged, truncated, or not a snapshot this library reads (since 1.5)
    CLOTH_ERROR_CORRUPT_SNAPSHOT = 16,
    /// forces the enum to 32 bits; never returned
    CLOTH_RESULT_FORCE_U32 = 0x7FFFFFFF
} cloth_result;

/* ------------------------------------------------------------------ */
/* Limits                                                               */
/* ------------------------------------------------------------------ */

/// Most worlds that exist at once in a process.
#define CLOTH_MAX_WORLDS 128
/// Most fabrics a world holds (cloth_world_desc.max_fabrics).
#define CLOTH_MAX_FABRICS 65535
/// Most cloths a world holds (cloth_world_desc.max_cloths).
#define CLOTH_MAX_CLOTHS 65535
/// Most bodies a world holds.
#define CLOTH_MAX_BODIES 65535
/// Most colliders a world holds.
#define CLOTH_MAX_COLLIDERS 65535
/// Most particles of a fabric, 2^24: grid columns * rows, mesh vertex_count.
#define CLOTH_MAX_PARTICLES 16777216u
/// Most triangles of a mesh fabric (cloth_mesh_desc.triangle_count, or an
/// OBJ file's after triangulation), 2^25: a grid of CLOTH_MAX_PARTICLES
/// particles has almost that many.
#define CLOTH_MAX_TRIANGLES 33554432u
/// Most points of a convex hull collider.
#define CLOTH_MAX_HULL_POINTS 4096
/// Most vertices of a triangle mesh collider, 2^24.
#define CLOTH_MAX_MESH_COLLIDER_VERTICES 16777216u
/// Most triangles of a triangle mesh collider, 2^24.
#define CLOTH_MAX_MESH_COLLIDER_TRIANGLES 16777216u
/// Most samples along each side of a height field (columns, rows).
#define CLOTH_MAX_HEIGHTFIELD_SIDE 65536
/// Most task records a world keeps per frame (cloth_world_set_profiling), 2^24.
#define CLOTH_MAX_PROFILED_TASKS 16777216u
/// Most Jacobi sweeps or PCG/Chebyshev iterations (cloth_solver_settings.iterations,
/// cloth_quality_policy.max_iterations).
#define CLOTH_MAX_ITERATIONS 256
/// Most substeps per cloth_step (cloth_solver_settings.substeps, cloth_quality_policy.max_substeps).
#define CLOTH_MAX_SUBSTEPS 64
/// Most CG iterations (cloth_solver_settings.cg_max_iterations).
#define CLOTH_MAX_CG_ITERATIONS 100000
/// Most strain-limiting passes per substep (cloth_strain_limit.iterations).
#define CLOTH_MAX_STRAIN_LIMIT_ITERATIONS 64
/// Most self-collision projection passes per substep (cloth_self_collision_desc.passes).
#define CLOTH_MAX_SELF_COLLISION_PASSES 16

/// The largest magnitude, in metres, of any coordinate, offset or length a
/// call takes to place something in the world (see "Coordinates" above).
/// 1e6 m keeps every product the step forms (squared lengths, stiffness
/// times displacement) fifteen orders of magnitude below float overflow,
/// while floats still resolve 6 cm there.
#define CLOTH_MAX_COORDINATE 1.0e6f

/// The smallest dt cloth_step takes, in seconds (1 microsecond); a shorter
/// one is CLOTH_ERROR_INVALID_VALUE and nothing moves. A step divides by its
/// substep length h and by h^2 (pin velocities (target - x) / h, the
/// system's terms over h^2), which leave float range for a denormal dt; at
/// 1e-6 s and 64 substeps 1/h^2 is 4e15. And in a shorter step a cloth
/// moving at 1 m/s 16 m from the origin would move less than float
/// resolution there, so the step could not advance it anyway.
#define CLOTH_MIN_DT 1.0e-6f

/// A short constant name for a result ("CLOTH_ERROR_NULL_POINTER"), or
/// "CLOTH_ERROR_UNKNOWN" for a value this library does not know. Never NULL:
/// a static, NUL-terminated ASCII string, valid for the life of the process;
/// the caller must not free it.
CLOTH_API const char* CLOTH_CALL cloth_result_name(cloth_result result);

/// The message of the last failed call made on this thread ("" if none).
/// Never NULL: a NUL-terminated UTF-8 string in a buffer of the library's,
/// one per thread, that the caller must not free; it is valid until the
/// next failing call on this thread (copy it to keep it). It may echo
/// caller input (an OBJ path).
CLOTH_API const char* CLOTH_CALL cloth_get_last_error(void);

/* ------------------------------------------------------------------ */
/* Handles                                                              */
/* ------------------------------------------------------------------ */

/* Every id is a value struct: a slot index + 1 (0 means null) and the
 * slot's generation, which changes each time the slot's object is
 * destroyed, so a stale id never reaches a newer object in the same slot.
 * The ids of objects inside a world also name the world's slot and
 * generation, so they die with their world and are refused by any other
 * world. All-zero is the null id of every kind (the cloth_null_*_id
 * constants); two ids name the same object exactly when all their fields
 * are equal (cloth_*_id_equal()). */

/// A world. All-zero is the null handle.
typedef struct cloth_world_id {
    /// slot index + 1; 0 means null
    uint16_t index1;
    /// reuse counter of the slot
    uint16_t generation;
} cloth_world_id;

/// A fabric (shared topology) inside a world. All-zero is null. It names
/// its world's slot and generation too, so an id outlives neither its own
/// slot's reuse nor its world's.
typedef struct cloth_fabric_id {
    /// slot index + 1; 0 means null
    uint16_t index1;
    /// owning world index + 1
    uint16_t world1;
    /// reuse counter of the slot
    uint16_t generation;
    /// generation of the owning world
    uint16_t world_generation;
} cloth_fabric_id;

/// A cloth instance inside a world. All-zero is null. Same layout and
/// rules as cloth_fabric_id.
typedef struct cloth_id {
    /// slot index + 1; 0 means null
    uint16_t index1;
    /// owning world index + 1
    uint16_t world1;
    /// reuse counter of the slot
    uint16_t generation;
    /// generation of the owning world
    uint16_t world_generation;
} cloth_id;

/// A rigid body (moving frame) of a world. All-zero is null. Same layout
/// and rules as cloth_fabric_id.
typedef struct cloth_body_id {
    /// slot index + 1; 0 means null
    uint16_t index1;
    /// owning world index + 1
    uint16_t world1;
    /// reuse counter of the slot
    uint16_t generation;
    /// generation of the owning world
    uint16_t world_generation;
} cloth_body_id;

/// A collision shape of a world. All-zero is null. Same layout and rules
/// as cloth_fabric_id.
typedef struct cloth_collider_id {
    /// slot index + 1; 0 means null
    uint16_t index1;
    /// owning world index + 1
    uint16_t world1;
    /// reuse counter of the slot
    uint16_t generation;
    /// generation of the owning world
    uint16_t world_generation;
} cloth_collider_id;

/// The null world id: names no world.
static const cloth_world_id cloth_null_world_id = {0, 0};
/// The null fabric id: names no fabric.
static const cloth_fabric_id cloth_null_fabric_id = {0, 0, 0, 0};
/// The null cloth id: names no cloth.
static const cloth_id cloth_null_id = {0, 0, 0, 0};
/// The null body id: names no body (a static collider's body).
static const cloth_body_id cloth_null_body_id = {0, 0, 0, 0};
/// The null collider id: names no collider.
static const cloth_collider_id cloth_null_collider_id = {0, 0, 0, 0};

/// Whether two world ids are the same handle.
static inline bool cloth_world_id_equal(cloth_world_id a, cloth_world_id b) {
    return a.index1 == b.index1 && a.generation == b.generation;
}
/// Whether two fabric ids are the same handle.
static inline bool cloth_fabric_id_equal(cloth_fabric_id a, cloth_fabric_id b) {
    return a.index1 == b.index1 && a.world1 == b.world1 && a.generation == b.generation &&
           a.world_generation == b.world_generation;
}
/// Whether two cloth ids are the same handle.
static inline bool cloth_id_equal(cloth_id a, cloth_id b) {
    return a.index1 == b.index1 && a.world1 == b.world1 && a.generation == b.generation &&
           a.world_generation == b.world_generation;
}
/// Whether two body ids are the same handle.
static inline bool cloth_body_id_equal(cloth_body_id a, cloth_body_id b) {
    return a.index1 == b.index1 && a.world1 == b.world1 && a.generation == b.generation &&
           a.world_generation == b.world_generation;
}
/// Whether two collider ids are the same handle.
static inline bool cloth_collider_id_equal(cloth_collider_id a, cloth_collider_id b) {
    return a.index1 == b.index1 && a.world1 == b.world1 && a.generation == b.generation &&
           a.world_generation == b.world_generation;
}

/* The cloth_*_is_valid() functions return C99 bool: one byte, 0 or 1 (see
 * "Other languages" at the top: C# declares the return as byte, or as bool
 * with [return: MarshalAs(UnmanagedType.U1)]). */

/// Whether `world` names a live world: false for the null id, a destroyed
/// world and an id that was never handed out. Sets no error.
CLOTH_API bool CLOTH_CALL cloth_world_is_valid(cloth_world_id world);
/// Whether `fabric` names a live fabric of a live world (a fabric released
/// with cloth_fabric_destroy is not, even while cloths still use it).
CLOTH_API bool CLOTH_CALL cloth_fabric_is_valid(cloth_fabric_id fabric);
/// Whether `cloth` names a live cloth of a live world.
CLOTH_API bool CLOTH_CALL cloth_is_valid(cloth_id cloth);
/// Whether `body` names a live body of a live world.
CLOTH_API bool CLOTH_CALL cloth_body_is_valid(cloth_body_id body);
/// Whether `collider` names a live collider of a live world (a collider
/// dies with the body it is fixed to).
CLOTH_API bool CLOTH_CALL cloth_collider_is_valid(cloth_collider_id collider);

/* ------------------------------------------------------------------ */
/* World                                                                */
/* ------------------------------------------------------------------ */

/// Allocate `size` bytes aligned to `alignment` (a power of two <= 64).
/// Return NULL on failure: the call that needed the memory then returns
/// CLOTH_ERROR_OUT_OF_MEMORY and changes nothing.
typedef void* CLOTH_CALL cloth_alloc_fn(size_t size, size_t alignment, void* user);
/// Free memory returned by the matching cloth_alloc_fn. `ptr` is never NULL.
typedef void CLOTH_CALL cloth_free_fn(void* ptr, size_t size, void* user);

/// Severity of a message passed to cloth_log_fn.
typedef enum cloth_log_level {
    /// a call failed and changed nothing (or restored what it changed)
    CLOTH_LOG_ERROR = 0,
    /// a call succeeded in part (CLOTH_ERROR_SOLVER_FAILED, CLOTH_ERROR_OVER_BUDGET)
    CLOTH_LOG_WARNING = 1,
    /// information only
    CLOTH_LOG_INFO = 2,
    /// forces the enum to 32 bits
    CLOTH_LOG_LEVEL_FORCE_U32 = 0x7FFFFFFF
} cloth_log_level;

/// Receives every error message (and warnings) of the world's calls.
/// `message` is NUL-terminated UTF-8 owned by the library, valid during the
/// call only (copy it to keep it); the callee must not free it.
typedef void CLOTH_CALL cloth_log_fn(cloth_log_level level, cloth_result code, const char* message,
                                     void* user);

/// A range of a task the library hands to the host's job system: run items
/// [begin, end) as `worker` (an index < cloth_world_desc.worker_count that
/// no other thread uses at the same time), passing `task_context` back.
typedef void CLOTH_CALL cloth_task_fn(uint32_t begin, uint32_t end, uint32_t worker, void* task_context);
/// Host job system, Box2D v3.1 style: run `task` over items [0, item_count)
/// split in ranges of at least `min_range` items, on any of the host's
/// workers, and return a handle for cloth_finish_task_fn, or NULL if the
/// work already ran inside this call (then finish is not called). The
/// ranges may run in any order, concurrently; results do not depend on
/// the split or on which worker ran what.
typedef void* CLOTH_CALL cloth_enqueue_task_fn(cloth_task_fn* task, uint32_t item_count, uint32_t min_range,
                                               void* task_context, void* user);
/// Wait until every range of the enqueued task has run.
typedef void CLOTH_CALL cloth_finish_task_fn(void* host_task, void* user);

/// How to create a world: gravity, capacities and the host's callbacks.
/// Function pointers and user pointers are kept for the world's lifetime.
typedef struct cloth_world_desc {
    /// sizeof(cloth_world_desc); set by cloth_default_world_desc()
    uint32_t struct_size;
    /// m/s^2; default (0, -9.81, 0)
    float gravity[3];
    /// optional; both alloc and free, or neither (CLOTH_ERROR_INVALID_VALUE); default: C heap; kept
    cloth_alloc_fn* alloc;
    /// optional; kept
    cloth_free_fn* free;
    /// optional; kept
    cloth_log_fn* log;
    /// passed to alloc, free and log; kept, never dereferenced
    void* user;
    /// capacity of the cloth table; default 1024, 1..CLOTH_MAX_CLOTHS
    uint32_t max_cloths;
    /// capacity of the fabric table; default 256, 1..CLOTH_MAX_FABRICS
    uint32_t max_fabrics;
    /// set by the struct\'s cloth_default_*() function; do not change
    uint32_t internal_cookie;
    /// Threads that run the step's tasks, the thread calling cloth_step
    /// among them; 0 or 1 = everything on the calling thread (default 0,
    /// no thread is started). Without host callbacks the world starts
    /// worker_count - 1 threads of its own (at most 256 workers); with
    /// them, worker indices passed to the tasks are < worker_count (1..CLOTH_MAX_WORKERS).
    uint32_t worker_count;
    /// optional host job system; both enqueue and finish, or neither; kept
    cloth_enqueue_task_fn* enqueue_task;
    /// optional; kept
    cloth_finish_task_fn* finish_task;
    /// passed to enqueue_task and finish_task; kept, never dereferenced
    void* task_user;
} cloth_world_desc;

/// A world description with every default set (and its cookie).
CLOTH_API cloth_world_desc CLOTH_CALL cloth_default_world_desc(void);

/// Create a world. At most CLOTH_MAX_WORLDS worlds exist at once.
CLOTH_API cloth_result CLOTH_CALL cloth_world_create(const cloth_world_desc* desc, cloth_world_id* out_world);
/// Destroy a world and every fabric and cloth in it.
CLOTH_API cloth_result CLOTH_CALL cloth_world_destroy(cloth_world_id world);
/// Change gravity (m/s^2).
CLOTH_API cloth_result CLOTH_CALL cloth_world_set_gravity(cloth_world_id world, const float gravity[3]);

/// Move the world's origin to the point `shift` of the current world frame
/// (origin rebasing, as PhysX's shiftOrigin): `shift` is subtracted from
/// every particle position and pin target, every body pose and every static
/// collider's pose; velocities, attachments, carriers and sleep are
/// unchanged. Floats resolve 1.5e-5 m at 128 m from the origin and 3e-5 m
/// at 256 m, so a host whose cloth travels far keeps it near the origin by
/// shifting now and then, and adds its own (double) origin back when it
/// reads positions. With a shift in whole multiples of 32 m, every position
/// the shift brings nearer the origin moves exactly; one it takes farther
/// away rounds as any position there would. Call it between steps, like
/// every other call on the world. NULL is CLOTH_ERROR_NULL_POINTER, a non-finite shift
/// CLOTH_ERROR_NOT_FINITE, and a shift with a component beyond
/// CLOTH_MAX_COORDINATE or one that would take any position out of float
/// range CLOTH_ERROR_INVALID_VALUE; each leaves the world unchanged.
CLOTH_API cloth_result CLOTH_CALL cloth_world_shift_origin(cloth_world_id world, const float shift[3]);

/// Advance every cloth of the world by `dt` seconds, CLOTH_MIN_DT <= dt <= 1
/// (else CLOTH_ERROR_INVALID_VALUE before anything moves; NaN or infinity:
/// CLOTH_ERROR_NOT_FINITE). Each cloth takes its own number of substeps. If a cloth's state becomes
/// non-finite, that cloth is restored to its state before this call, the
/// other cloths advance normally, and CLOTH_ERROR_NONFINITE_STATE is
/// returned (cloth_stats.last_step_result tells which cloth). The same
/// holds with CLOTH_ERROR_OUT_OF_MEMORY if the CG reference solver cannot
/// allocate (it is the only part of a step that allocates, and it uses the
/// C++ heap). CLOTH_ERROR_SOLVER_FAILED means CG stopped at its iteration
/// limit; the cloth still advanced. A step allocates nothing from the
/// world's allocator. With more cloths to step than workers, each worker
/// steps whole cloths, so a cloth's data stays in one worker's cache
/// through its frame; with fewer, each stage of every cloth runs over all
/// the workers. The results are the same bits either way (since 1.12.1).
CLOTH_API cloth_result CLOTH_CALL cloth_step(cloth_world_id world, float dt);

/* ------------------------------------------------------------------ */
/* Fabric (shared topology)                                             */
/* ------------------------------------------------------------------ */

/// Spring kinds, as bits of cloth_grid_desc.spring_kinds and cloth_mesh_desc.spring_kinds.
typedef enum cloth_spring_kind {
    /// mesh edges (grid rows and columns)
    CLOTH_SPRING_STRUCTURAL = 1,
    /// grid cell diagonals (grids only)
    CLOTH_SPRING_SHEAR = 2,
    /// skip-one on grids; across shared triangle edges on meshes
    CLOTH_SPRING_BEND = 4,
    /// every kind
    CLOTH_SPRING_ALL = 7,
    /// forces the enum to 32 bits
    CLOTH_SPRING_KIND_FORCE_U32 = 0x7FFFFFFF
} cloth_spring_kind;

/// A rectangular grid of `columns` x `rows` particles. Particle (c, r) has
/// index r * columns + c and sits at origin + c/(columns-1) * u + r/(rows-1) * v.
typedef struct cloth_grid_desc {
    /// sizeof(cloth_grid_desc)
    uint32_t struct_size;
    /// >= 2, and columns * rows <= CLOTH_MAX_PARTICLES; default 32
    uint32_t columns;
    /// >= 2; default 32
    uint32_t rows;
    /// position of particle (0, 0); default (0, 0, 0)
    float origin[3];
    /// edge along columns; default (1, 0, 0)
    float u[3];
    /// edge along rows; default (0, -1, 0) (hangs down)
    float v[3];
    /// bit set of cloth_spring_kind; default CLOTH_SPRING_ALL
    uint32_t spring_kinds;
    /// set by the struct\'s cloth_default_*() function; do not change
    uint32_t internal_cookie;
} cloth_grid_desc;

/// A grid description with every default set (and its cookie).
CLOTH_API cloth_grid_desc CLOTH_CALL cloth_default_grid_desc(void);

/// An arbitrary triangle mesh. Structural springs on every edge, bend
/// springs across every edge shared by two triangles; no shear springs.
/// Every vertex must belong to a triangle (it gets its mass from them), and
/// no triangle may have zero area: else CLOTH_ERROR_DEGENERATE_GEOMETRY.
typedef struct cloth_mesh_desc {
    /// sizeof(cloth_mesh_desc)
    uint32_t struct_size;
    /// vertex_count * 3 floats (m); copied during the call
    const float* positions;
    /// 3..CLOTH_MAX_PARTICLES
    uint32_t vertex_count;
    /// triangle_count * 3 vertex indices; copied during the call
    const uint32_t* indices;
    /// 1..CLOTH_MAX_TRIANGLES
    uint32_t triangle_count;
    /// default CLOTH_SPRING_ALL (shear is ignored)
    uint32_t spring_kinds;
    /// set by the struct\'s cloth_default_*() function; do not change
    uint32_t internal_cookie;
} cloth_mesh_desc;

/// A mesh description with every default set (and its cookie); positions
/// and indices are NULL and must be set.
CLOTH_API cloth_mesh_desc CLOTH_CALL cloth_default_mesh_desc(void);

/// Build a fabric from a grid description. At most max_fabrics per world.
CLOTH_API cloth_result CLOTH_CALL cloth_fabric_create_grid(cloth_world_id world, const cloth_grid_desc* desc,
                                                           cloth_fabric_id* out_fabric);
/// Build a fabric from a triangle mesh (its arrays are copied).
CLOTH_API cloth_result CLOTH_CALL cloth_fabric_create_mesh(cloth_world_id world, const cloth_mesh_desc* desc,
                                                           cloth_fabric_id* out_fabric);
/// Load a triangle mesh from a Wavefront OBJ file (faces are triangulated),
/// with the limits of cloth_mesh_desc. `path` is a NUL-terminated UTF-8
/// string, read during the call only (on Windows it is converted to UTF-16
/// to open the file; elsewhere its bytes name the file as they are).
CLOTH_API cloth_result CLOTH_CALL cloth_fabric_create_obj(cloth_world_id world, const char* path,
                                                          uint32_t spring_kinds, cloth_fabric_id* out_fabric);
/// Release the handle. Cloths made from the fabric keep working; the
/// memory is freed when the last of them is destroyed.
CLOTH_API cloth_result CLOTH_CALL cloth_fabric_destroy(cloth_fabric_id fabric);

/// Number of particles of the fabric (grid: columns * rows; mesh: vertices).
CLOTH_API cloth_result CLOTH_CALL cloth_fabric_get_particle_count(cloth_fabric_id fabric,
                                                                  uint32_t* out_count);
/// Number of triangles of the fabric (grid: 2 per cell).
CLOTH_API cloth_result CLOTH_CALL cloth_fabric_get_triangle_count(cloth_fabric_id fabric,
                                                                  uint32_t* out_count);
/// Number of springs of the given kinds (a bit set of cloth_spring_kind).
CLOTH_API cloth_result CLOTH_CALL cloth_fabric_get_spring_count(cloth_fabric_id fabric, uint32_t kinds,
                                                                uint32_t* out_count);
/// Copy the triangle indices (3 per triangle) into `out_indices`, which
/// holds `capacity` uint32 values (at least 3 * triangle count).
CLOTH_API cloth_result CLOTH_CALL cloth_fabric_read_triangles(cloth_fabric_id fabric, uint32_t* out_indices,
                                                              uint32_t capacity);

/* ------------------------------------------------------------------ */
/* Cloth                                                                */
/* ------------------------------------------------------------------ */

/// How a cloth's implicit step is solved (cloth_solver_settings.kind).
typedef enum cloth_solver_kind {
    /// the library's choice: PCG preconditioned by multigrid, 5 iterations, substeps picked per step from
    /// gamma = dt^2 k_max / m_min and no longer than 1/120 s, and an 8 % strain limit unless one is set
    /// (docs/accuracy.md); a cloth of 16 particles or fewer gets block-Jacobi PCG with 16 iterations.
    /// With a strain limit its step takes the forces 0.7 of the way through each substep instead of at
    /// its end (a theta step, which damps the motion less than backward Euler at the same cost), and
    /// takes them at the end (backward Euler) in a substep after one whose strain-limit passes left a
    /// spring more than 0.01 past the limit, and in every substep when the limit is 0 (off) or the
    /// cloth is too stiff for its step in 16 substeps. A quiet cloth (no free particle faster than
    /// 1 cm/s at the start of this step and of the last one, no pin moving faster, a step since
    /// the host last changed it, no carrier, attachment, collider or skin, and no spring past the
    /// strain limit in its last step) takes substeps of up to 1/60 s whatever its gamma, backward
    /// Euler where gamma asks for more: a hanging 64x64 cloth at rest costs about a quarter of a
    /// falling one
    CLOTH_SOLVER_DEFAULT = 0,
    /// linearized backward Euler, `iterations` Jacobi sweeps (1 = the paper's method)
    CLOTH_SOLVER_JACOBI = 1,
    /// the same system solved with conjugate gradient to `cg_tolerance` (reference)
    CLOTH_SOLVER_CG = 2,
    /// symplectic Euler (baseline; needs tiny steps for stiff cloth)
    CLOTH_SOLVER_EXPLICIT = 3,
    /// block-Jacobi-preconditioned CG on the library's own parallel passes: at most `iterations` iterations,
    /// stops early at `cg_tolerance`
    CLOTH_SOLVER_PCG = 4,
    /// Chebyshev-accelerated block Jacobi, `iterations` iterations, no dot products
    CLOTH_SOLVER_CHEBYSHEV = 5,
    /// forces the enum to 32 bits
    CLOTH_SOLVER_KIND_FORCE_U32 = 0x7FFFFFFF
} cloth_solver_kind;

/// Stiffness and damping of one spring kind.
typedef struct cloth_spring_params {
    /// N/m, >= 0
    float stiffness;
    /// N s/m along the spring, >= 0
    float damping;
} cloth_spring_params;

/// How a cloth advances.
typedef struct cloth_solver_settings {
    /// sizeof(cloth_solver_settings)
    uint32_t struct_size;
    /// default CLOTH_SOLVER_DEFAULT
    cloth_solver_kind kind;
    /// Jacobi sweeps or PCG/Chebyshev iterations, 1..CLOTH_MAX_ITERATIONS; default 1 (CLOTH_SOLVER_DEFAULT
    /// picks its own)
    uint32_t iterations;
    /// steps per cloth_step call, 1..CLOTH_MAX_SUBSTEPS; default 1 (CLOTH_SOLVER_DEFAULT may use more)
    uint32_t substeps;
    /// CG relative residual, (0, 1); default 1e-6
    float cg_tolerance;
    /// 1..CLOTH_MAX_CG_ITERATIONS; default 1000
    uint32_t cg_max_iterations;
    /// 1: paper eq. 12 for compressed springs; 0 or 1, default 1
    uint8_t compression_safe_jacobian;
} cloth_solver_settings;

/// Solver settings with every default set.
CLOTH_API cloth_solver_settings CLOTH_CALL cloth_default_solver_settings(void);

/// Strain limiting, in two parts. Inside the solve (every kind but
/// CLOTH_SOLVER_EXPLICIT): a spring longer than (1 + max_strain) times its
/// rest length (CLOTH_SOLVER_DEFAULT: 1 + 0.975 max_strain, so that a cloth
/// too heavy for its springs rests on the cable inside the limit) is held
/// by a cable 100 times as stiff as the spring, which the implicit solve
/// spreads over the whole cloth at once (stats count its energy). After
/// every substep: first each free particle that the fabric
/// links to pinned or attached particles is pulled back within
/// (1 + max_strain) times its rest distance of each of its four nearest
/// ones (tethers, or long-range attachments: one pass that holds the whole
/// cloth's stretch, however far the pins moved; changing which particles
/// are pinned or attached plans them anew at the next step, once per
/// change: on a grid one pass over particles and pins, on a mesh a search
/// along the springs, about 16 ms for 16,384 particles with a pinned row);
/// then (Provot 1995)
/// structural and shear springs still longer than the limit, and
/// structural springs shorter than (1 - max_strain) times their rest
/// length (cloth buckles rather than shortens), are brought back in
/// parallel passes (on a grid, in the same passes, each particle
/// and the one four places on along its row and column are held within
/// the limit of their rest distance, which carries the pull across the
/// cloth in fewer passes), moving positions and velocities together
/// (with every kind but CLOTH_SOLVER_EXPLICIT each pass but the last also
/// carries on along the previous passes' move, a Chebyshev acceleration):
/// `iterations` passes, fewer once a pass finds no spring past the limit,
/// and up to 4 times as many while a spring is past it by more than 0.01
/// (so the cost of a frame follows how hard it pulls). Off by default, but
/// CLOTH_SOLVER_DEFAULT limits strain to 0.08 for itself until
/// cloth_set_strain_limit is called; from then on the limit set applies to
/// every solver kind, and a max_strain of 0 turns limiting off for
/// CLOTH_SOLVER_DEFAULT too. cloth_set_solver keeps it. Where pins or
/// attachments are moved apart farther than the cloth reaches within the
/// limit in one step (a spring between two pins, or two pins a particle is
/// tethered to), no state meets it: for that substep the cable and the
/// passes hold the strain the pins ask instead, so the stretch spreads
/// over the cloth between them, and cloth_get_stats reports the step unmet.
typedef struct cloth_strain_limit {
    /// sizeof(cloth_strain_limit)
    uint32_t struct_size;
    /// >= 0, finite; 0 turns limiting off; default 0
    float max_strain;
    /// passes per substep, 1..CLOTH_MAX_STRAIN_LIMIT_ITERATIONS; default 4
    /// (see above: fewer when nothing is past the limit, up to 4 times as
    /// many while a spring is past it by more than 0.01, unless a quality
    /// policy has taken the cloth below half its iterations: see "Frame budget")
    uint32_t iterations;
} cloth_strain_limit;

/// A strain limit with every default set (limiting off).
CLOTH_API cloth_strain_limit CLOTH_CALL cloth_default_strain_limit(void);

/// Aerodynamics: wind, drag and lift per triangle against the relative air
/// velocity, plus linear air drag per particle.
typedef struct cloth_aero_params {
    /// air velocity, m/s; default (0, 0, 0)
    float wind[3];
    /// kg/m^3, >= 0; default 1.2
    float air_density;
    /// >= 0; default 1.0
    float drag_coefficient;
    /// >= 0; default 0.5
    float lift_coefficient;
    /// 1/s, >= 0: force -linear_drag * m * v per particle; default 0.02
    float linear_drag;
} cloth_aero_params;

/// How to create a cloth: its fabric, material, solver and air.
typedef struct cloth_desc {
    /// sizeof(cloth_desc)
    uint32_t struct_size;
    /// required
    cloth_fabric_id fabric;
    /// kg/m^2, > 0; default 0.2
    float area_density;
    /// kg, >= 0; if > 0, every particle gets this mass instead
    float particle_mass;
    /// optional particle_count * 3 floats (m), in the fabric's vertex order;
    /// default NULL: the fabric's rest positions; copied during the call
    const float* initial_positions;
    /// default {1000, 0.5}
    cloth_spring_params structural;
    /// default {200, 0.2}
    cloth_spring_params shear;
    /// default {20, 0.05}
    cloth_spring_params bend;
    /// default cloth_default_solver_settings()
    cloth_solver_settings solver;
    /// see cloth_aero_params
    cloth_aero_params aero;
    /// set by the struct\'s cloth_default_*() function; do not change
    uint32_t internal_cookie;
} cloth_desc;

/// A cloth description with every default set (and its cookie); the
/// fabric is null and must be set.
CLOTH_API cloth_desc CLOTH_CALL cloth_default_desc(void);

/// Create a cloth of a fabric of the same world, at the fabric's rest
/// positions (or desc->initial_positions), at rest. At most max_cloths per world.
CLOTH_API cloth_result CLOTH_CALL cloth_create(cloth_world_id world, const cloth_desc* desc,
                                               cloth_id* out_cloth);
/// Destroy a cloth (its fabric lives on while its handle or another cloth uses it).
CLOTH_API cloth_result CLOTH_CALL cloth_destroy(cloth_id cloth);

/// Number of particles of the cloth (those of its fabric).
CLOTH_API cloth_result CLOTH_CALL cloth_get_particle_count(cloth_id cloth, uint32_t* out_count);

/// Copy positions (3 floats per particle) into `out_xyz`, which holds
/// `capacity` floats (at least 3 * particle count).
CLOTH_API cloth_result CLOTH_CALL cloth_read_positions(cloth_id cloth, float* out_xyz, uint32_t capacity);
/// Copy velocities (m/s), same layout as positions.
CLOTH_API cloth_result CLOTH_CALL cloth_read_velocities(cloth_id cloth, float* out_xyz, uint32_t capacity);
/// Copy unit per-vertex normals (area-weighted triangle normals), same layout.
CLOTH_API cloth_result CLOTH_CALL cloth_read_normals(cloth_id cloth, float* out_xyz, uint32_t capacity);

/// Calls that take `indices` and `count` need 1 <= count <= particle count
/// (else CLOTH_ERROR_INVALID_COUNT) and every index < particle count (else
/// CLOTH_ERROR_INDEX_OUT_OF_RANGE); they change nothing unless all are valid.

/// Teleport particles: set positions (and zero their velocities).
CLOTH_API cloth_result CLOTH_CALL cloth_set_positions(cloth_id cloth, const uint32_t* indices,
                                                      const float* positions_xyz, uint32_t count);

/// Set particles' masses in kg, each finite (else CLOTH_ERROR_NOT_FINITE)
/// and > 0 (else CLOTH_ERROR_INVALID_VALUE): a weighted hem, a light trim.
/// They replace what cloth_desc gave them (particle_mass or area_density)
/// and stay through cloth_set_spring_params; a pinned particle keeps its
/// mass for when it is unpinned. Snapshots do not carry masses (nor the
/// rest of the material). CLOTH_SOLVER_DEFAULT chooses its substeps from
/// the lightest free particle: a few light particles among heavy ones
/// make every step of the cloth dearer. Since 1.6.
CLOTH_API cloth_result CLOTH_CALL cloth_set_particle_masses(cloth_id cloth, const uint32_t* indices,
                                                            const float* masses, uint32_t count);
/// Copy every particle's mass in kg, vertex order (capacity >= particle
/// count). Since 1.6.
CLOTH_API cloth_result CLOTH_CALL cloth_read_particle_masses(cloth_id cloth, float* out_masses,
                                                             uint32_t capacity);

/// Pin particles where they are: they become kinematic (infinite mass).
CLOTH_API cloth_result CLOTH_CALL cloth_pin(cloth_id cloth, const uint32_t* indices, uint32_t count);
/// Release pinned particles; they keep their current velocity.
CLOTH_API cloth_result CLOTH_CALL cloth_unpin(cloth_id cloth, const uint32_t* indices, uint32_t count);
/// Move pinned particles: each reaches its target at the end of the next
/// cloth_step, moving linearly across substeps, and carries the matching
/// velocity. Every index must be pinned.
CLOTH_API cloth_result CLOTH_CALL cloth_set_pin_targets(cloth_id cloth, const uint32_t* indices,
                                                        const float* targets_xyz, uint32_t count);
/// Whether particle `index` is pinned. *out_pinned is one byte (C99 bool), 1 or 0.
CLOTH_API cloth_result CLOTH_CALL cloth_is_pinned(cloth_id cloth, uint32_t index, bool* out_pinned);

/// Change how the cloth is solved (keeps its strain limit; wakes it).
CLOTH_API cloth_result CLOTH_CALL cloth_set_solver(cloth_id cloth, const cloth_solver_settings* settings);
/// Fills the whole struct, struct_size included.
CLOTH_API cloth_result CLOTH_CALL cloth_get_solver(cloth_id cloth, cloth_solver_settings* out_settings);
/// Set the cloth's strain limit (see cloth_strain_limit).
CLOTH_API cloth_result CLOTH_CALL cloth_set_strain_limit(cloth_id cloth, const cloth_strain_limit* limit);
/// Fills the whole struct, struct_size included.
CLOTH_API cloth_result CLOTH_CALL cloth_get_strain_limit(cloth_id cloth, cloth_strain_limit* out_limit);
/// Change one or more spring kinds (a bit set of cloth_spring_kind).
CLOTH_API cloth_result CLOTH_CALL cloth_set_spring_params(cloth_id cloth, uint32_t kinds,
                                                          cloth_spring_params params);
/// Change wind, drag and lift (wakes the cloth).
CLOTH_API cloth_result CLOTH_CALL cloth_set_aero(cloth_id cloth, const cloth_aero_params* params);
/// Shorthand: change only the wind velocity (m/s).
CLOTH_API cloth_result CLOTH_CALL cloth_set_wind(cloth_id cloth, const float wind[3]);

/// Measurements of a cloth's current state.
typedef struct cloth_stats {
    /// set by the caller to sizeof(cloth_stats)
    uint32_t struct_size;
    /// J, free particles only
    double kinetic_energy;
    /// J, -m g . x (height energy relative to the origin), free particles only
    double gravity_energy;
    /// J, sum of k (L - l0)^2 / 2 over springs, plus taut strain cables
    double elastic_energy;
    /// max over structural springs of (L - l0) / l0
    float max_strain;
    /// mean of |L - l0| / l0 over structural springs
    float mean_strain;
    /// m/s
    float max_speed;
    /// iterations of the last solve (CG: last substep), also of a step that was undone
    uint32_t last_solver_iterations;
    /// relative residual of the last solve (CG only; else 0)
    float last_solver_residual;
    /// CLOTH_OK, or what the last cloth_step reported for this cloth
    cloth_result last_step_result;
    /// how far the structural spring farthest from its rest length is past
    /// the strain limit the last step ran with: the largest
    /// |L - l0| / l0 - max_strain (CLOTH_SOLVER_DEFAULT, which holds
    /// structural springs against compression too; since 1.8 the other kinds,
    /// which hold them against stretch only, count (L - l0) / l0), or 0 when
    /// every one is within it or no limit ran (see cloth_strain_limit). Since 1.7.
    float strain_limit_excess;
    /// 1 when strain_limit_excess is above 0.02, the slack the strain limit
    /// promises after every step: the last step could not meet its
    /// constraints, because a pin, attachment or collider moved farther than
    /// the cloth can follow in one step or pins pull it apart. The state is
    /// finite and the following steps bring the cloth back; else 0. Since 1.7.
    uint8_t strain_limit_unmet;
    /// the most iterations a solve of the last step could run: the solver's
    /// setting, CLOTH_SOLVER_DEFAULT's own choice or a frame budget's cap
    /// (last_solver_iterations is fewer where the solve stopped early).
    /// Since 1.12.
    uint32_t last_max_iterations;
    /// the substeps of the last step (the same sources). Since 1.12.
    uint32_t last_substeps;
    /// the strain limit's passes the last step ran, over its substeps (0
    /// without a strain limit): the effort of holding the limit. Since 1.13.
    uint32_t last_strain_passes;
    /// 1 when a substep of the last step stopped its strain-limit passes at
    /// their cap with a spring still past the limit and its slack (the
    /// limit was not held there), else 0. Since 1.13.
    uint8_t last_strain_pass_cap_hit;
} cloth_stats;

/// Measure the cloth now; the caller sets out_stats->struct_size first
/// (the sizes of 1.6, without the strain-limit fields, of 1.7 to 1.11,
/// without last_max_iterations and last_substeps, and of 1.12, without
/// last_strain_passes and last_strain_pass_cap_hit, are accepted too).
CLOTH_API cloth_result CLOTH_CALL cloth_get_stats(cloth_id cloth, cloth_stats* out_stats);

/* ------------------------------------------------------------------ */
/* Jobs, frame budget and profiling                                   */
/* ------------------------------------------------------------------ */

/* Jobs. A step is a sequence of stages (air, forces, assembly, solver
 * sweeps, integration, ...), each a loop over particle groups of about 256
 * particles; the stages of all cloths of a world run together, so many
 * cloths share the workers. The world runs them on the host's job system
 * (cloth_world_desc.enqueue_task/finish_task), on its own threads
 * (cloth_world_desc.worker_count) or on the calling thread. Results are
 * bit-identical in every case: every sum is formed in a fixed order, with
 * no atomics or locks, whatever worker runs a group. Task callbacks must
 * not call back into this API. */

/// How long an idle worker of the world's own threads (worker_count > 1,
/// no host callbacks) keeps polling for work before it sleeps, in
/// microseconds; default 500, at most 1000000. Polling costs CPU time on
/// those threads while nothing runs; sleeping makes the next cloth_step
/// wait for its workers to wake up (tens of microseconds, and on a busy
/// machine their caches go cold): Jobs/Speedup* in tests/bench measure
/// both. A host that calls cloth_step back to back, or wants the most
/// from two cores, raises it above the time between its steps; 0 sleeps
/// at once. A worker reads the value when it goes idle, so a change
/// reaches a worker already polling or asleep after its next job. Results
/// do not depend on it. Without the world's own threads the value is kept
/// and has no effect.
CLOTH_API cloth_result CLOTH_CALL cloth_world_set_worker_spin(cloth_world_id world, uint32_t microseconds);

/// The stages of a step, as profiles and traces name them. The values are
/// numbered in the order the stages were added, not in run order; a substep
/// runs, of those its cloth uses: AIR, FORCES, then EXPLICIT, or ASSEMBLE,
/// one solve (JACOBI_SWEEP, SERIAL_SOLVE or ITERATIVE_SOLVE, each possibly
/// several rounds) and INTEGRATE; then COLLISIONS; SELF_COLLISION,
/// SELF_SORT, SELF_CONTACTS, SELF_PROJECT, SELF_RESPOND; and STRAIN_LIMIT,
/// with rounds of LIMIT_COLLISIONS after its passes and, with
/// self-collision, a SELF_PROJECT after each pass and the SELF_RESPOND after
/// the last instead of before the passes.
typedef enum cloth_stage {
    /// per triangle: wind drag and lift
    CLOTH_STAGE_AIR = 0,
    /// external forces; per spring: force, Jacobian, A_s
    CLOTH_STAGE_FORCES = 1,
    /// per particle: W_ii, W_ii^-1, b, p
    CLOTH_STAGE_ASSEMBLE = 2,
    /// one Jacobi sweep
    CLOTH_STAGE_JACOBI_SWEEP = 3,
    /// the CG reference solve (one task per cloth)
    CLOTH_STAGE_SERIAL_SOLVE = 4,
    /// v += dv, x += h v
    CLOTH_STAGE_INTEGRATE = 5,
    /// explicit baseline: forces and Euler
    CLOTH_STAGE_EXPLICIT = 6,
    /// colliders and attachments
    CLOTH_STAGE_COLLISIONS = 7,
    /// self-collision: region checks and hash keys (per group)
    CLOTH_STAGE_SELF_COLLISION = 8,
    /// self-collision: counting sort into buckets (one task per cloth)
    CLOTH_STAGE_SELF_SORT = 9,
    /// self-collision: each particle's contact list
    CLOTH_STAGE_SELF_CONTACTS = 10,
    /// self-collision: one projection pass (repeated while overlaps remain,
    /// and one after each strain-limit pass)
    CLOTH_STAGE_SELF_PROJECT = 11,
    /// self-collision: velocity response (paper eq. 13) and friction
    CLOTH_STAGE_SELF_RESPOND = 12,
    /// PCG / Chebyshev passes (each iteration is several rounds)
    CLOTH_STAGE_ITERATIVE_SOLVE = 13,
    /// strain-limiting passes (when a limit is set)
    CLOTH_STAGE_STRAIN_LIMIT = 14,
    /// the colliders again inside the strain limit: after its last pass,
    /// and after each of its passes while the substep touches a collider.
    /// Since 1.7.
    CLOTH_STAGE_LIMIT_COLLISIONS = 15,
    /// the frame's skinned positions and normals (cloth_set_skin), in its
    /// first substep. Since 1.8; in cloth_world_get_stage_profile only.
    CLOTH_STAGE_SKINNING = 16,
    /// free particles into their max distances and out of their backstops
    /// (cloth_set_max_distances, cloth_set_backstops). Since 1.8; in
    /// cloth_world_get_stage_profile only.
    CLOTH_STAGE_SKIN_CONSTRAINTS = 17,
    /// contact between two cloths, once a substep before their strain
    /// limits, while both cloths wait: both cloths' particles gathered,
    /// hashed, their contacts found and projected (cloth_set_cloth_contact).
    /// Since 1.13; in cloth_world_get_stage_profile only.
    CLOTH_STAGE_CLOTH_CONTACT = 18,
    /// a cloth's velocities relative to the other cloths of its pairs, after
    /// its strain limit. Since 1.13; in cloth_world_get_stage_profile only.
    CLOTH_STAGE_CLOTH_CONTACT_RESPOND = 19,
    /// forces the enum to 32 bits
    CLOTH_STAGE_FORCE_U32 = 0x7FFFFFFF
} cloth_stage;

/// Entries of the per-stage arrays of cloth_frame_profile: the stages
/// 0..CLOTH_MAX_STAGES-1. Every stage, later ones included, through
/// cloth_world_get_stage_profile.
#define CLOTH_MAX_STAGES 16
/// Entries of the per-worker arrays of cloth_frame_profile: the most workers a world has.
#define CLOTH_MAX_WORKERS 256

/// A stage's short name: its enumerator's without CLOTH_STAGE_, in lower
/// case ("forces", "jacobi_sweep", ...; since 1.7 also "self_collision",
/// which was "self_hash"); "?" if unknown.
/// Never NULL: a static, NUL-terminated ASCII string, valid for the life of
/// the process; the caller must not free it.
CLOTH_API const char* CLOTH_CALL cloth_stage_name(cloth_stage stage);

/// What the last cloth_step of a world cost. Filled by
/// cloth_world_get_frame_profile; times in milliseconds of wall time.
/// Stage and worker times are measured while profiling is enabled or a
/// frame budget is set, and are zero otherwise.
typedef struct cloth_frame_profile {
    /// set by the caller to sizeof(cloth_frame_profile)
    uint32_t struct_size;
    /// workers of the world's task system (entries of the worker arrays)
    uint32_t worker_count;
    /// number of cloth_step calls so far, this one included
    uint64_t frame;
    /// the whole cloth_step call
    double step_ms;
    /// the world's frame budget (0: none)
    double budget_ms;
    /// step_ms / budget_ms (0 without a budget)
    double budget_used;
    /// 1 if step_ms > budget_ms, else 0 (always 0 without a budget)
    uint8_t overrun;
    /// cloths that stepped
    uint32_t awake_cloths;
    /// cloths skipped because they sleep
    uint32_t sleeping_cloths;
    /// per cloth_stage: wall time of its rounds, summed; in a step with
    /// more cloths to step than workers, where each worker runs whole
    /// cloths and no round spans the world, the time of its tasks, summed
    /// over the workers (since 1.12.1)
    double stage_ms[CLOTH_MAX_STAGES];
    /// per cloth_stage: tasks run
    uint32_t stage_tasks[CLOTH_MAX_STAGES];
    /// per worker: time inside tasks
    double worker_busy_ms[CLOTH_MAX_WORKERS];
    /// per worker: step_ms - busy
    double worker_idle_ms[CLOTH_MAX_WORKERS];
    /// task records kept for this frame (cloth_world_read_task_records)
    uint32_t task_count;
    /// tasks beyond the profiling capacity, not recorded
    uint32_t tasks_dropped;
    /// frames over budget since the world was created
    uint64_t overrun_frames;
} cloth_frame_profile;

/// One task of a frame: a group of one cloth's particles in one stage.
typedef struct cloth_task_record {
    /// the cloth whose group it was
    cloth_id cloth;
    /// the stage the task belongs to
    cloth_stage stage;
    /// particle group of the cloth
    uint32_t group;
    /// worker that ran it
    uint32_t worker;
    /// substep of the cloth's step (0-based)
    uint32_t substep;
    /// microseconds since the world was created
    double start_us;
    /// microseconds since the world was created
    double end_us;
} cloth_task_record;

/// Record every task of each frame, up to `max_tasks_per_frame` (the
/// memory is allocated here, from the world's allocator), at most
/// CLOTH_MAX_PROFILED_TASKS; 0 turns recording off and frees it. Stage and worker times are measured while
/// it is on. Off by default.
CLOTH_API cloth_result CLOTH_CALL cloth_world_set_profiling(cloth_world_id world,
                                                            uint32_t max_tasks_per_frame);
/// The profile of the last cloth_step.
CLOTH_API cloth_result CLOTH_CALL cloth_world_get_frame_profile(cloth_world_id world,
                                                                cloth_frame_profile* out_profile);
/// One stage's wall time in the last cloth_step (ms, summed over its rounds)
/// and the tasks it ran, for any cloth_stage (cloth_frame_profile holds
/// the first CLOTH_MAX_STAGES). A value that is no cloth_stage is
/// CLOTH_ERROR_INVALID_VALUE. Since 1.8.
CLOTH_API cloth_result CLOTH_CALL cloth_world_get_stage_profile(cloth_world_id world, cloth_stage stage,
                                                                double* out_ms, uint32_t* out_tasks);
/// Copy the last frame's task records (at most `capacity`); *out_count
/// receives the number copied.
CLOTH_API cloth_result CLOTH_CALL cloth_world_read_task_records(cloth_world_id world,
                                                                cloth_task_record* out_records,
                                                                uint32_t capacity, uint32_t* out_count);
/// The last frame as Chrome trace-event JSON (opens in Perfetto and
/// chrome://tracing): one event for the step, one per stage used (on its
/// own track, duration = the stage's summed wall time, starting at its
/// first task) and one per recorded task (on its worker's track). Writes
/// at most `capacity` bytes including the terminating NUL; *out_size
/// receives the bytes needed including the NUL. With buffer NULL and
/// capacity 0 it only reports the size; a buffer too small gives
/// CLOTH_ERROR_INVALID_COUNT and writes nothing.
CLOTH_API cloth_result CLOTH_CALL cloth_world_write_trace_json(cloth_world_id world, char* buffer,
                                                               size_t capacity, size_t* out_size);

/// Profiler zones for the host's profiler (Tracy, Unreal Insights, ...):
/// begin and end are called on the thread that runs the work, around
/// every cloth_step ("cloth_step", worker 0) and every task (the stage's
/// name, as a static string, and the worker index). `name` is static,
/// NUL-terminated ASCII: the same pointer for the same name every time, so
/// a host may key a cache on it; the callee must not free it. They must be cheap,
/// must not call this API, and may run concurrently on different workers.
typedef void CLOTH_CALL cloth_zone_begin_fn(const char* name, uint32_t worker, void* user);
/// Ends the zone the matching cloth_zone_begin_fn opened (same name and worker).
typedef void CLOTH_CALL cloth_zone_end_fn(const char* name, uint32_t worker, void* user);
/// Install (or, with both NULL, remove) zone callbacks.
CLOTH_API cloth_result CLOTH_CALL cloth_world_set_zone_callbacks(cloth_world_id world,
                                                                 cloth_zone_begin_fn* begin,
                                                                 cloth_zone_end_fn* end, void* user);

/* Frame budget. A world may have a per-frame budget for cloth_step in
 * milliseconds of wall time. Every frame then reports in its profile
 * whether it overran, and a step that overran returns
 * CLOTH_ERROR_OVER_BUDGET (logged as a warning): the world advanced
 * completely, nothing was lost, and a failure of a cloth in the same step
 * (CLOTH_ERROR_NONFINITE_STATE, ...) is returned instead. Without a budget
 * that code never occurs. Cloths with an enabled quality policy have their
 * iterations and substeps lowered after a frame over budget and raised
 * again after several frames well under it (below 70%), within the
 * policy's bounds, as far as the measured cost of their recent frames
 * predicts. Lowering goes down a ladder from the top (the policy's maximum,
 * or what a CLOTH_SOLVER_DEFAULT cloth chooses by itself each step within
 * the policy's maximum: an enabled policy bounds the default's own choice
 * even with no budget set, so max_substeps 1 runs it in one substep): the
 * iterations to half the top's, then one substep fewer with the iterations
 * back at the top's, and so on; raising retraces it, never past the top.
 * At the policy's fewest substeps and half the iterations, a policy with
 * a max_update_rate above 1 next doubles the cloth's update rate (see
 * "Importance and update rate") up to that rate: each step keeps its
 * iterations, substeps and strain-limit passes over a longer dt, and the
 * cloth steps less often (a cloth a body carries keeps rate 1). Down to
 * there a CLOTH_SOLVER_DEFAULT step the budget capped still runs no
 * substep longer than 1/15 s (two at rate 8 and 60 Hz; since 1.12.1), and
 * none longer than twice its last step's substep or than the time its
 * fastest free particle takes to cross three mean structural rest lengths
 * relative to its pins (since 1.12.5; these two never below 1/60 s, and
 * within the policy's max_substeps), where a longer one stretches the
 * cloth past its limit: a flapping cloth eases into a slow rate over a
 * few steps of more substeps. Past that the iterations go below
 * half only once most of the last frames ran over budget (a load, not a
 * spike), and there the strain limit runs only the passes asked for
 * (cloth_strain_limit.iterations), not the extra passes it otherwise adds
 * while a spring stays past the limit: the frame keeps to the budget and
 * the strain gives. Raising retraces the ladder: the rate comes back to 1
 * before the iterations rise past half. And in a frame within budget, the
 * most relevant cloth below its top goes one rung up if lowering less
 * relevant cloths (to their floors, with their rates) pays for it.
 * cloth_stats.last_max_iterations and last_substeps show the rung a step
 * ran at, and setting the
 * policy again (or the solver) lifts the policy's cuts. */

/// Set the world's frame budget in milliseconds, >= 0 (0: no budget, the default).
CLOTH_API cloth_result CLOTH_CALL cloth_world_set_frame_budget(cloth_world_id world, float milliseconds);

/// Bounds within which a world's frame budget may change a cloth's
/// iterations and substeps (see "Frame budget").
typedef struct cloth_quality_policy {
    /// sizeof(cloth_quality_policy)
    uint32_t struct_size;
    /// 1: on; 0 or 1, default 0
    uint8_t enabled;
    /// 1..max_iterations; default 1
    uint32_t min_iterations;
    /// ..CLOTH_MAX_ITERATIONS; default 8
    uint32_t max_iterations;
    /// 1..max_substeps; default 1
    uint32_t min_substeps;
    /// ..CLOTH_MAX_SUBSTEPS; default 4
    uint32_t max_substeps;
    /// the slowest update rate the budget may give the cloth: 1, 2, 4 or 8;
    /// default 1 (since 1.11; the 1.10 struct_size reads as 1)
    uint32_t max_update_rate;
} cloth_quality_policy;

/// A quality policy with every default set (off).
CLOTH_API cloth_quality_policy CLOTH_CALL cloth_default_quality_policy(void);
/// Let the world's budget change this cloth's iterations and substeps within
/// the bounds (enabling clamps the current settings into them; the current
/// values are read back with cloth_get_solver, or for CLOTH_SOLVER_DEFAULT
/// with cloth_get_stats: see "Frame budget").
CLOTH_API cloth_result CLOTH_CALL cloth_set_quality_policy(cloth_id cloth,
                                                           const cloth_quality_policy* policy);

/* Importance and update rate (since 1.11). Under a frame budget the world
 * lowers the least relevant cloths first and raises the most relevant
 * first: a cloth's relevance is its importance (default 1) or, once the
 * world has a viewer, its importance times its bounding sphere's radius
 * over the sphere's distance from the viewer (at most 1, inside it). Of
 * equal relevance the most expensive cloth is lowered first, as before
 * 1.11. Without a budget, importance changes nothing.
 *
 * A cloth at update rate N (1, 2, 4 or 8; default 1) steps in every Nth
 * cloth_step of its world, over N times that call's dt at once, so it
 * costs about 1/N of its cost at rate 1. The world staggers cloths of one
 * rate over the calls (each takes the phase with the fewest particles of
 * its rate), so a world of rate-2 cloths steps half of them in each call.
 * A cloth's step then ends N - 1 calls ahead of the world, and between its
 * steps cloth_read_positions and cloth_read_normals give the positions
 * interpolated between its last two states at the world's current call:
 * the motion a reader sees is smooth, and a change of rate makes no jump.
 * What the cloth follows (pin targets, skin, moving colliders) it reaches
 * N - 1 calls late, so a rate above 1 suits a cloth far from the viewer. A
 * cloth attached to a body or carried by one (cloth_attach,
 * cloth_set_carrier) steps in every call: a rate above 1 is refused for
 * it, and one it had goes back to 1 at the next call. cloth_set_positions and restoring a
 * snapshot show at once (the interpolation ends there). Velocities, stats
 * and snapshots are the cloth's state, not the interpolation. Two cloths
 * in contact (cloth_set_cloth_contact) touch only after calls in which
 * both step to the same state: give them the same rate, and the world
 * gives them the same phase. */

/// Set how much the cloth matters under a frame budget: finite and >= 0
/// (else CLOTH_ERROR_NOT_FINITE or CLOTH_ERROR_INVALID_VALUE); default 1.
/// 0: lowered before any cloth that matters. Since 1.11.
CLOTH_API cloth_result CLOTH_CALL cloth_set_importance(cloth_id cloth, float importance);
/// Read the cloth's importance. Since 1.11.
CLOTH_API cloth_result CLOTH_CALL cloth_get_importance(cloth_id cloth, float* out_importance);
/// Set the world's viewer, a point (see "Coordinates"), whose distance
/// scales each cloth's relevance; NULL removes it (the default). Since 1.11.
CLOTH_API cloth_result CLOTH_CALL cloth_world_set_viewer(cloth_world_id world, const float position[3]);
/// Set the cloth's update rate: 1, 2, 4 or 8, and 1 for a cloth a body
/// carries (else CLOTH_ERROR_INVALID_VALUE).
/// A rate above 1 allocates two copies of the positions, freed when the
/// cloth is back at rate 1 and has caught up with the world.
/// Since 1.11.
CLOTH_API cloth_result CLOTH_CALL cloth_set_update_rate(cloth_id cloth, uint32_t rate);
/// Read the cloth's update rate and its phase (the calls, counted from the
/// world's creation, in which its steps end are those with count % rate
/// == phase); either pointer may be NULL, not both. Since 1.11.
CLOTH_API cloth_result CLOTH_CALL cloth_get_update_rate(cloth_id cloth, uint32_t* out_rate,
                                                        uint32_t* out_phase);

/* Level of detail (since 1.14). A cloth on a grid fabric of at least 5 x 5
 * particles can step at a coarser level of its grid: level 1 has a quarter
 * of its particles (each 2 x 2 block one particle), level 2 a sixteenth,
 * down to 3 levels below the full grid (level 0, the default) while a
 * level keeps at least 3 columns and rows; mesh fabrics have level 0
 * only. A coarse level costs about what a grid of its size costs, keeps
 * the cloth's settings, masses (each coarse particle weighs its block) and
 * pins (a coarse particle is pinned if any of its block is), and
 * cloth_read_positions and cloth_read_normals still give every particle
 * of the full grid, interpolated from the coarse one (pinned particles on
 * their targets). The full grid's positions, velocities and snapshots are
 * that interpolation; cloth_set_positions and restoring a snapshot reach
 * the coarse level at the next step. A change of level makes no jump:
 * going down averages the positions and velocities of each block (the
 * momentum is kept), going up continues from the interpolation. A cloth
 * with a skin, attachments or a carrier, self-collision or contact with
 * another cloth steps at level 0: a coarser level is refused for it, and
 * one it had goes back to 0 at its next step. Stats describe the full
 * grid's last step at level 0. */

/// Set the level the cloth steps at: 0 (the full grid, the default) up to
/// its level count - 1 (else CLOTH_ERROR_INDEX_OUT_OF_RANGE). A level
/// above 0 on a cloth whose fabric has no coarser level (a mesh, a grid
/// under 5 x 5), or which has a skin, attachments, a carrier,
/// self-collision or contact with another cloth, is CLOTH_ERROR_INVALID_VALUE.
/// The first use of a level allocates its coarse cloth, kept until the
/// cloth is destroyed (CLOTH_ERROR_OUT_OF_MEMORY changes nothing).
/// Since 1.14.
CLOTH_API cloth_result CLOTH_CALL cloth_set_lod_level(cloth_id cloth, uint32_t level);
/// Read the level the cloth steps at and how many levels its fabric has
/// (1 on meshes); either pointer may be NULL, not both. Since 1.14.
CLOTH_API cloth_result CLOTH_CALL cloth_get_lod_level(cloth_id cloth, uint32_t* out_level,
                                                      uint32_t* out_level_count);

/* Sleep. A cloth whose particles all move slower than max_speed for
 * `frames` consecutive frames goes to sleep (a particle's speed is its
 * velocity, or, while no velocity passes ten times max_speed, its move over
 * the frame: a cloth held at its strain limit keeps velocities that move
 * nothing): its velocities become zero and
 * cloth_step skips it (it costs nothing) until something that changes its
 * motion wakes it: pinning, unpinning, pin targets, cloth_set_positions,
 * solver, spring, air or wind settings, gravity, self-collision settings,
 * colliders and attachments, restoring a snapshot of an awake cloth, or
 * cloth_wake. */
/// When a cloth goes to sleep.
typedef struct cloth_sleep_params {
    /// sizeof(cloth_sleep_params)
    uint32_t struct_size;
    /// 1: on; 0 or 1, default 1
    uint8_t enabled;
    /// m/s, >= 0; default 0.001
    float max_speed;
    /// >= 1; default 60
    uint32_t frames;
} cloth_sleep_params;

/// Sleep parameters with every default set (sleep on).
CLOTH_API cloth_sleep_params CLOTH_CALL cloth_default_sleep_params(void);
/// Change when the cloth sleeps (wakes it).
CLOTH_API cloth_result CLOTH_CALL cloth_set_sleep(cloth_id cloth, const cloth_sleep_params* params);
/// Put the cloth to sleep now, whatever its motion (a cloth out of view):
/// cloth_step skips it and it costs nothing. Unlike a cloth that fell
/// asleep at rest it keeps its velocities, so waking it continues its
/// motion where it stopped, and moving bodies do not wake it: it wakes on
/// cloth_wake or on anything else listed above. A cloth with a carrier
/// stays where it was while the carrier moves on; its first step after
/// waking moves it with the carrier as a teleport of the carrier would
/// (unless cloth_set_positions placed it first). Particles attached to a
/// body without a carrier are pulled to where their body is now in that
/// step. Snapshots keep whether the host put the cloth to sleep. Since 1.12.
CLOTH_API cloth_result CLOTH_CALL cloth_sleep(cloth_id cloth);
/// Wake the cloth: it steps again from the next cloth_step.
CLOTH_API cloth_result CLOTH_CALL cloth_wake(cloth_id cloth);
/// Whether the cloth sleeps. *out_sleeping is one byte (C99 bool), 1 or 0.
CLOTH_API cloth_result CLOTH_CALL cloth_is_sleeping(cloth_id cloth, bool* out_sleeping);

/* ------------------------------------------------------------------ */
/* Snapshots                                                          */
/* ------------------------------------------------------------------ */

/* A snapshot is a cloth's dynamic state in a caller's buffer: positions,
 * velocities, pins and pin targets, solver kind, iterations and substeps,
 * air and wind, the sleep state, whether CLOTH_SOLVER_DEFAULT's next
 * substep is backward Euler and whether the cloth is quiet
 * (cloth_solver_kind), and a skinned cloth's
 * skin state ("Character cloth"). Restoring it into a cloth
 * of the same fabric and stepping again reproduces the same bits (replays,
 * rollback networking). Material, spring settings and feature settings
 * are not in it, nor is what a frame budget decided (a quality policy's
 * caps, and the last substep the caps' growth starts from): a cloth under
 * a budget steps after a restore as the budget then decides. The bytes
 * are native-endian: for this library build and machine.
 *
 * A snapshot opens with a header: a magic number, the snapshot format
 * version, the version of the library that wrote it, the size of the whole
 * snapshot, an identity of its fabric (a hash of the fabric's particle,
 * triangle and spring counts and its rest data, so equal for fabrics built
 * from the same description) and a 64-bit checksum (XXH3) of every other
 * byte. A restored snapshot is therefore either exactly what was saved or
 * refused with CLOTH_ERROR_CORRUPT_SNAPSHOT, the cloth unchanged.
 *
 * Versions. A library reads snapshots of its own snapshot format only. The
 * format with this header is the one of 1.5.0; the snapshots of 1.4 and
 * older had none and are refused with CLOTH_ERROR_CORRUPT_SNAPSHOT. A later
 * library that changes the format says so here; one that keeps it reads
 * snapshots written by any library of the same format, except that a
 * snapshot holding state a library does not know is refused as corrupt:
 * a skinned cloth's needs a library of 1.12.1 on, a quiet cloth's 1.12.2. */

/// Bytes a snapshot of this cloth needs.
CLOTH_API cloth_result CLOTH_CALL cloth_get_snapshot_size(cloth_id cloth, size_t* out_size);
/// Write a snapshot into `buffer` of `capacity` bytes (at least the snapshot size).
CLOTH_API cloth_result CLOTH_CALL cloth_save_snapshot(cloth_id cloth, void* buffer, size_t capacity);
/// Restore a snapshot of `size` bytes (exactly the size it was saved with).
/// A buffer that is truncated, has any byte changed, is no snapshot or one
/// of another format is CLOTH_ERROR_CORRUPT_SNAPSHOT; an intact snapshot of
/// a cloth of another particle count is CLOTH_ERROR_INVALID_COUNT; of
/// another fabric with the same count, or one whose skin does not match
/// the cloth's (a skinned cloth's into a cloth without the same skin
/// source and joint count, or an unskinned cloth's, or one saved before
/// 1.12.1, into a skinned cloth), it is CLOTH_ERROR_INVALID_VALUE. In
/// every case the cloth is unchanged.
CLOTH_API cloth_result CLOTH_CALL cloth_restore_snapshot(cloth_id cloth, const void* buffer, size_t size);

/* ------------------------------------------------------------------ */
/* Bodies, colliders and attachments                                  */
/* ------------------------------------------------------------------ */

/*
 * Bodies are rigid frames the host moves (a vehicle chassis, a character
 * bone). Each frame the host sets a body's pose (and velocities) before
 * cloth_step; the step moves the body from the pose it had at the end of
 * the previous step to the new one across the substeps (position linearly,
 * rotation by slerp), so whatever rides on it follows without a one-frame
 * lag. The cloth never pushes bodies back (one-way coupling).
 *
 * Colliders are shapes the cloth's particles stay out of (by the cloth's
 * collision thickness). A collider is fixed to a body (it moves with it) or
 * static (world frame). Any number of cloths collide with one collider; a
 * cloth collides with the colliders whose `group_bits` meet its
 * cloth_collision_params.collider_mask. A collider that moves fast is swept:
 * a particle's path is tested in the collider's moving frame, so a collider
 * passing through a cloth within one substep pushes it instead of tunneling.
 *
 * Attachments fix particles to a body at local offsets: they follow the
 * body's pose exactly, every substep, and the solver treats them as
 * kinematic (like pins).
 *
 * The carrier of a cloth is the body it travels with: the cloth simulates
 * partly relative to it (inertia scales), with a speed limit and teleport
 * handling. See cloth_carrier_desc.
 *
 * Rotations are unit quaternions (x, y, z, w); a rotation whose length is
 * not within 1e-2 of 1 is CLOTH_ERROR_INVALID_VALUE, and it is normalised.
 * Shapes are given in the collider's local frame; a collider's world pose
 * is body pose * local pose (or the local pose alone if static).
 */

/// How to create a body: its pose and velocities.
typedef struct cloth_body_desc {
    /// sizeof(cloth_body_desc)
    uint32_t struct_size;
    /// m; default (0, 0, 0)
    float position[3];
    /// unit quaternion (x, y, z, w); default (0, 0, 0, 1)
    float rotation[4];
    /// m/s of the body origin; default 0
    float linear_velocity[3];
    /// rad/s, world frame; default 0
    float angular_velocity[3];
    /// set by the struct\'s cloth_default_*() function; do not change
    uint32_t internal_cookie;
} cloth_body_desc;

/// A body description with every default set (and its cookie).
CLOTH_API cloth_body_desc CLOTH_CALL cloth_default_body_desc(void);

/// Create a body at the description's pose. At most CLOTH_MAX_BODIES bodies per world.
CLOTH_API cloth_result CLOTH_CALL cloth_body_create(cloth_world_id world, const cloth_body_desc* desc,
                                                    cloth_body_id* out_body);
/// Destroy a body, the colliders fixed to it, every attachment to it (those
/// particles become free, keeping their velocity) and every carrier link to it.
CLOTH_API cloth_result CLOTH_CALL cloth_body_destroy(cloth_body_id body);
/// The pose the body reaches at the end of the next cloth_step; it moves
/// there from its current pose across the step's substeps.
CLOTH_API cloth_result CLOTH_CALL cloth_body_set_pose(cloth_body_id body, const float position[3],
                                                      const float rotation[4]);
/// Many bodies' poses in one call, as cloth_body_set_pose gives each (a
/// character's bones each frame): body k reaches positions_xyz[3k..3k+2]
/// and rotations_xyzw[4k..4k+3] at the end of the next cloth_step. Every
/// body must live in `world`; a body listed twice takes its last pose.
/// Every entry is checked before any body moves: a rejected call moves none
/// and its message names the entry. count: 1..CLOTH_MAX_BODIES. Since 1.8.
CLOTH_API cloth_result CLOTH_CALL cloth_world_set_body_poses(cloth_world_id world,
                                                             const cloth_body_id* bodies,
                                                             const float* positions_xyz,
                                                             const float* rotations_xyzw, uint32_t count);
/// Jump to a pose: the next step starts there (no sweep, no interpolation).
/// Attachments jump with it; free particles stay where they are unless the
/// cloth's carrier teleport handling moves them (cloth_carrier_desc).
CLOTH_API cloth_result CLOTH_CALL cloth_body_teleport(cloth_body_id body, const float position[3],
                                                      const float rotation[4]);
/// Velocities of the body (origin velocity in m/s, angular velocity in rad/s,
/// world frame). Used for friction against its colliders.
CLOTH_API cloth_result CLOTH_CALL cloth_body_set_velocity(cloth_body_id body, const float linear[3],
                                                          const float angular[3]);
/// The pose set last (position, rotation quaternion x, y, z, w).
CLOTH_API cloth_result CLOTH_CALL cloth_body_get_pose(cloth_body_id body, float out_position[3],
                                                      float out_rotation[4]);

/// Common part of every collider.
typedef struct cloth_collider_desc {
    /// sizeof(cloth_collider_desc)
    uint32_t struct_size;
    /// the body it is fixed to; null (default): static, in the world frame
    cloth_body_id body;
    /// m, in the body's frame (or world); default 0
    float local_position[3];
    /// unit quaternion (x, y, z, w); default (0, 0, 0, 1)
    float local_rotation[4];
    /// collides with cloths whose collider_mask meets these bits; default 1
    uint32_t group_bits;
    /// set by the struct\'s cloth_default_*() function; do not change
    uint32_t internal_cookie;
} cloth_collider_desc;

/// A collider description with every default set (and its cookie): static,
/// at the origin.
CLOTH_API cloth_collider_desc CLOTH_CALL cloth_default_collider_desc(void);

/// A sphere of `radius` > 0 m centred on the local origin.
CLOTH_API cloth_result CLOTH_CALL cloth_collider_create_sphere(cloth_world_id world,
                                                               const cloth_collider_desc* desc, float radius,
                                                               cloth_collider_id* out_collider);
/// A capsule along the local y axis: the segment from (0, -half_height, 0) to
/// (0, half_height, 0), swept by `radius` > 0 (half_height >= 0), as
/// btCapsuleShape (up axis y) with half_height = its getHalfHeight().
CLOTH_API cloth_result CLOTH_CALL cloth_collider_create_capsule(cloth_world_id world,
                                                                const cloth_collider_desc* desc, float radius,
                                                                float half_height,
                                                                cloth_collider_id* out_collider);
/// A tapered capsule along the local y axis: the convex hull of a sphere of
/// `bottom_radius` at (0, -half_height, 0) and one of `top_radius` at
/// (0, half_height, 0), a limb's shape (Jolt's TaperedCapsuleShape, NvCloth's
/// cone between two spheres). Radii > 0, half_height >= 0, and the radii
/// differ by less than 2 * half_height (else one sphere holds the other:
/// CLOTH_ERROR_INVALID_VALUE; use a sphere). Exact and swept like the other
/// shapes; equal radii give the capsule. Since 1.9.
CLOTH_API cloth_result CLOTH_CALL cloth_collider_create_tapered_capsule(cloth_world_id world,
                                                                        const cloth_collider_desc* desc,
                                                                        float bottom_radius, float top_radius,
                                                                        float half_height,
                                                                        cloth_collider_id* out_collider);
/// A box with the given half extents (each > 0) centred on the local origin.
CLOTH_API cloth_result CLOTH_CALL cloth_collider_create_box(cloth_world_id world,
                                                            const cloth_collider_desc* desc,
                                                            const float half_extents[3],
                                                            cloth_collider_id* out_collider);
/// The solid half-space { p : dot(normal, p) <= offset } in the local frame
/// (btStaticPlaneShape's normal and constant). `normal` need not be unit
/// length but must not be zero.
CLOTH_API cloth_result CLOTH_CALL cloth_collider_create_plane(cloth_world_id world,
                                                              const cloth_collider_desc* desc,
                                                              const float normal[3], float offset,
                                                              cloth_collider_id* out_collider);
/// The convex hull of `point_count` local points (4..CLOTH_MAX_HULL_POINTS, 3 floats each, not
/// all in one plane: else CLOTH_ERROR_DEGENERATE_GEOMETRY).
CLOTH_API cloth_result CLOTH_CALL cloth_collider_create_convex_hull(cloth_world_id world,
                                                                    const cloth_collider_desc* desc,
                                                                    const float* points_xyz,
                                                                    uint32_t point_count,
                                                                    cloth_collider_id* out_collider);
/// A triangle mesh (typically static: terrain, walls). Triangles are
/// one-sided solids of shallow depth: the front is where the winding
/// (counter-clockwise) normal points. A particle closer than the thickness
/// in front, or whose path crosses a triangle from the front, is pushed back
/// in front. 3..CLOTH_MAX_MESH_COLLIDER_VERTICES vertices and
/// 1..CLOTH_MAX_MESH_COLLIDER_TRIANGLES triangles; no degenerate triangle; the
/// vertices' span must fit a float (else CLOTH_ERROR_INVALID_VALUE).
CLOTH_API cloth_result CLOTH_CALL cloth_collider_create_triangle_mesh(
    cloth_world_id world, const cloth_collider_desc* desc, const float* vertices_xyz, uint32_t vertex_count,
    const uint32_t* indices, uint32_t triangle_count, cloth_collider_id* out_collider);

/// A height field in the local frame, solid below. Sample (c, r) sits at
/// (c * spacing_x, heights[r * columns + c], r * spacing_z); cell (c, r) is
/// split into triangles (c,r)-(c+1,r)-(c,r+1) and (c+1,r)-(c+1,r+1)-(c,r+1)
/// (btHeightfieldTerrainShape's default split, up axis y, with its origin
/// moved to the first sample).
typedef struct cloth_heightfield_desc {
    /// sizeof(cloth_heightfield_desc)
    uint32_t struct_size;
    /// samples along x, 2..CLOTH_MAX_HEIGHTFIELD_SIDE; default 2
    uint32_t columns;
    /// samples along z, 2..CLOTH_MAX_HEIGHTFIELD_SIDE; default 2
    uint32_t rows;
    /// m, > 0; default 1
    float spacing_x;
    /// m, > 0; default 1
    float spacing_z;
    /// columns * rows heights, m, row-major (required); copied during the call
    const float* heights;
    /// set by the struct\'s cloth_default_*() function; do not change
    uint32_t internal_cookie;
} cloth_heightfield_desc;

/// A height field description with every default set (and its cookie);
/// heights is NULL and must be set.
CLOTH_API cloth_heightfield_desc CLOTH_CALL cloth_default_heightfield_desc(void);

/// A height field (cloth_heightfield_desc); its heights are copied.
CLOTH_API cloth_result CLOTH_CALL cloth_collider_create_heightfield(cloth_world_id world,
                                                                    const cloth_collider_desc* desc,
                                                                    const cloth_heightfield_desc* heightfield,
                                                                    cloth_collider_id* out_collider);
/// Destroy a collider; cloths stop colliding with it from the next step.
CLOTH_API cloth_result CLOTH_CALL cloth_collider_destroy(cloth_collider_id collider);
/// Change which cloths collide with it (see cloth_collision_params.collider_mask).
CLOTH_API cloth_result CLOTH_CALL cloth_collider_set_group_bits(cloth_collider_id collider,
                                                                uint32_t group_bits);

/// How a cloth meets colliders.
typedef struct cloth_collision_params {
    /// sizeof(cloth_collision_params)
    uint32_t struct_size;
    /// m, >= 0: particles keep this distance from colliders; default 0.01
    float thickness;
    /// Coulomb coefficient, >= 0; default 0.3
    float friction;
    /// collide with colliders whose group_bits meet this; default all; 0: none
    uint32_t collider_mask;
} cloth_collision_params;

/// Collision parameters with every default set.
CLOTH_API cloth_collision_params CLOTH_CALL cloth_default_collision_params(void);
/// Change how the cloth meets colliders.
CLOTH_API cloth_result CLOTH_CALL cloth_set_collision(cloth_id cloth, const cloth_collision_params* params);
/// Fills the whole struct, struct_size included.
CLOTH_API cloth_result CLOTH_CALL cloth_get_collision(cloth_id cloth, cloth_collision_params* out_params);

/// Attach particles to a body, particle indices[k] at body-local offset
/// local_offsets_xyz[3k..3k+2] (m). With local_offsets_xyz NULL, each stays
/// where it is now relative to the body's current pose. Attached particles
/// are kinematic (cloth_is_pinned reports them pinned): every substep they
/// sit exactly at body pose * offset, the body pose interpolated across the
/// step. Re-attaching a particle moves it to the new body and offset. The
/// body must be in the cloth's world.
CLOTH_API cloth_result CLOTH_CALL cloth_attach(cloth_id cloth, cloth_body_id body, const uint32_t* indices,
                                               const float* local_offsets_xyz, uint32_t count);
/// Release attached particles (each must be attached); they keep their
/// velocity. cloth_unpin releases attached particles too.
CLOTH_API cloth_result CLOTH_CALL cloth_detach(cloth_id cloth, const uint32_t* indices, uint32_t count);
/// Whether particle `index` is attached, and to which body (null if not).
CLOTH_API cloth_result CLOTH_CALL cloth_get_attachment(cloth_id cloth, uint32_t index,
                                                       cloth_body_id* out_body, float out_local_offset[3]);

/// What a carrier teleport does to the cloth (cloth_carrier_desc.teleport_mode).
typedef enum cloth_teleport_mode {
    /// CLOTH_TELEPORT_MOVE
    CLOTH_TELEPORT_DEFAULT = 0,
    /// move the cloth rigidly with the carrier, keeping its shape and motion
    CLOTH_TELEPORT_MOVE = 1,
    /// put the cloth in its reference shape at the new pose, at rest on the carrier
    CLOTH_TELEPORT_AND_RESET = 2,
    /// forces the enum to 32 bits
    CLOTH_TELEPORT_MODE_FORCE_U32 = 0x7FFFFFFF
} cloth_teleport_mode;

/// How a cloth travels with its carrier body. Each step the carrier's
/// motion over the frame is measured from its poses: the change of its
/// velocity (linear) and of its rotation (angular, with Coriolis) and the
/// centripetal part of its rotation are given to the cloth's free particles
/// scaled by (1 - inertia). Inertia 1 is physical (the carrier's motion is
/// felt fully through the attachments only), 0 makes the cloth move with
/// the carrier as if it were rigidly fixed to it.
typedef struct cloth_carrier_desc {
    /// sizeof(cloth_carrier_desc)
    uint32_t struct_size;
    /// 0..1; default 1
    float linear_inertia;
    /// 0..1 (Euler and Coriolis terms); default 1
    float angular_inertia;
    /// 0..1; default 1
    float centrifugal_inertia;
    /// m/s, >= 0: clamp of particle speed relative to the carrier; 0 (default): none
    float max_relative_speed;
    /// m, >= 0: a frame's carrier move beyond this is a teleport; 0 (default): off
    float teleport_distance;
    /// rad, >= 0: a frame's carrier turn beyond this is a teleport; 0 (default): off
    float teleport_rotation;
    /// default CLOTH_TELEPORT_MOVE
    cloth_teleport_mode teleport_mode;
    /// set by the struct\'s cloth_default_*() function; do not change
    uint32_t internal_cookie;
} cloth_carrier_desc;

/// A carrier description with every default set (and its cookie).
CLOTH_API cloth_carrier_desc CLOTH_CALL cloth_default_carrier_desc(void);

/// Make `body` the cloth's carrier (a null body removes the carrier; desc is
/// then ignored and may be NULL). The cloth's current positions relative to
/// the body's current pose become its reference shape for
/// CLOTH_TELEPORT_AND_RESET.
CLOTH_API cloth_result CLOTH_CALL cloth_set_carrier(cloth_id cloth, cloth_body_id body,
                                                    const cloth_carrier_desc* desc);
/// Whether the carrier teleport handling fired in the last step of this
/// cloth. *out_teleported is one byte (C99 bool), 1 or 0.
CLOTH_API cloth_result CLOTH_CALL cloth_get_teleported(cloth_id cloth, bool* out_teleported);

/* ------------------------------------------------------------------ */
/* Character cloth: skin, max distance, backstop                      */
/* ------------------------------------------------------------------ */

/* Cloth worn by an animated character (a cape, a skirt) follows a skinned
 * position per particle: the fabric's rest positions and normals (the bind
 * pose) skinned by the character's joints inside the step (linear blend
 * skinning, up to 4 joints per particle), or positions and normals the
 * host skinned itself. Over a frame's substeps the skinned positions move
 * linearly from where the last frame left them to this frame's, as pins
 * do, except across a teleport of the cloth's carrier (cloth_set_carrier:
 * make the character's root body the carrier, with teleport thresholds or
 * cloth_body_teleport): there the skin jumps, the particles pinned to it
 * start the frame on it, and the carrier moves the rest (since 1.9). Two
 * constraints hold a particle near its skinned position, checked at the
 * end of every substep and so of every step:
 *  - max distance: the particle stays within it of its skinned position.
 *    0 makes it a pin whose target is its skinned position (it costs what
 *    a pin costs and is not solved; cloth_is_pinned reports it);
 *  - backstop (distance d, radius r): the particle stays outside the
 *    sphere of radius r centred d behind its skinned position along the
 *    skinned normal, so a cape cannot pass into the back it hangs on where
 *    the body's colliders are coarse. With r <= d the skinned position
 *    itself is outside it.
 * They run after each of the strain limiter's passes, so its next pass
 * works where they hold the particles, and last in each substep, after the
 * colliders: where they conflict, the max distance wins, then the backstop
 * (a collider or the strain limit may be left unmet there). A cloth
 * without a skin pays nothing for any of this; with one, the skinning
 * costs a pass over the particles once a frame, and the constraints a pass
 * over the particles with a max distance above 0 or a backstop after each
 * strain-limit pass and once more at the end of each substep
 * (docs/character_cloth.md gives the cost per particle).
 * Joint matrices map the bind pose to the world and may carry a uniform
 * scale; normals are rotated by them and renormalised. A snapshot of a
 * skinned cloth carries its skin's state (where the skin ended the last
 * step, and the joint matrices or skinned positions the host gave last;
 * since 1.12.1), not the skin itself (joints, weights, max distances and
 * backstops are settings): restore it into a cloth given the same skin
 * (a snapshot without a skin's state is refused by a skinned cloth).
 * All since 1.8. */

/// A cloth's skin: the joints each particle follows.
typedef struct cloth_skin_desc {
    /// sizeof(cloth_skin_desc)
    uint32_t struct_size;
    /// the particles the arrays give, which must be the cloth's particle count
    uint32_t particle_count;
    /// joints the matrices of cloth_set_joint_matrices give: 1..CLOTH_MAX_JOINTS
    uint32_t joint_count;
    /// joints per particle, 1..4
    uint32_t influences;
    /// particle_count x influences joint indices, by vertex (each < joint_count)
    const uint32_t* joints;
    /// particle_count x influences weights, each >= 0 and each particle's
    /// summing to 1 within 1e-3; NULL with influences 1 (weight 1)
    const float* weights;
    /// set by the struct\'s cloth_default_*() function; do not change
    uint32_t internal_cookie;
} cloth_skin_desc;

/// The most joints a skin has.
#define CLOTH_MAX_JOINTS 65535

/// How cloth_set_joint_matrices reads a matrix.
typedef enum cloth_matrix_layout {
    /// 16 floats, column-major 4x4 (OpenGL, Eigen, glm); the last row is
    /// (0, 0, 0, 1) and is not read
    CLOTH_MATRIX_COLUMN_MAJOR_4X4 = 0,
    /// 12 floats, row-major 3x4: rows (r00 r01 r02 tx), (r10 r11 r12 ty),
    /// (r20 r21 r22 tz)
    CLOTH_MATRIX_ROW_MAJOR_3X4 = 1,
    /// forces the enum to 32 bits
    CLOTH_MATRIX_LAYOUT_FORCE_U32 = 0x7FFFFFFF
} cloth_matrix_layout;

/// A skin description with every default set (and its cookie); no arrays.
CLOTH_API cloth_skin_desc CLOTH_CALL cloth_default_skin_desc(void);
/// Bind the cloth to joints (replacing any skin); the joint matrices start
/// as identities (the rest pose). Wakes the cloth.
CLOTH_API cloth_result CLOTH_CALL cloth_set_skin(cloth_id cloth, const cloth_skin_desc* desc);
/// This frame's joint matrices: matrix_count (at least the skin's
/// joint_count) matrices in `layout`, each finite. The next cloth_step
/// skins the particles with them; the skin follows the joints from now on.
/// Wakes the cloth.
CLOTH_API cloth_result CLOTH_CALL cloth_set_joint_matrices(cloth_id cloth, const float* matrices,
                                                           uint32_t matrix_count, cloth_matrix_layout layout);
/// Positions and normals the host skinned, for the end of the next
/// cloth_step: count (the cloth's particle count) points and normals by
/// vertex, finite, each normal of length above 1e-6 (it is normalised).
/// The skin follows them from now on. Wakes the cloth.
CLOTH_API cloth_result CLOTH_CALL cloth_set_skinned_positions(cloth_id cloth, const float* positions_xyz,
                                                              const float* normals_xyz, uint32_t count);
/// The skinned positions and normals of the last step's end, by vertex
/// (capacity: floats in each array, at least 3 x the particle count);
/// out_normals_xyz may be NULL. CLOTH_ERROR_INVALID_VALUE before a step
/// has skinned the cloth.
CLOTH_API cloth_result CLOTH_CALL cloth_read_skinned_positions(cloth_id cloth, float* out_positions_xyz,
                                                               float* out_normals_xyz, uint32_t capacity);
/// Every particle's max distance (m, by vertex, count = the particle
/// count): >= 0, +INFINITY for none (the default). 0 pins the particle to
/// its skinned position; a particle a max distance of 0 pinned is unpinned
/// when its max distance becomes positive. The cloth needs a skin
/// (cloth_set_skin or cloth_set_skinned_positions); a particle attached to
/// a body cannot have 0. Wakes the cloth.
CLOTH_API cloth_result CLOTH_CALL cloth_set_max_distances(cloth_id cloth, const float* distances,
                                                          uint32_t count);
/// Every particle's backstop (by vertex, count = the particle count):
/// distance >= 0 and radius >= 0, finite; radius 0 (with distance 0) for
/// none, the default. A radius of 0 with a positive distance is
/// CLOTH_ERROR_INVALID_VALUE. The cloth needs a skin. Wakes the cloth.
CLOTH_API cloth_result CLOTH_CALL cloth_set_backstops(cloth_id cloth, const float* distances,
                                                      const float* radii, uint32_t count);

/* ------------------------------------------------------------------ */
/* Self-collision                                                     */
/* ------------------------------------------------------------------ */

/* Particle-particle self-collision (paper section IV): particles of one
 * cloth closer than `thickness` are pushed apart to `thickness` and lose
 * the approaching part of their relative velocity (paper eq. 13), with
 * optional Coulomb friction on the sliding part. Candidates come from a
 * spatial hash; collision-free regions (Volino: patches whose normals stay
 * within a cone and whose outline does not cross itself, re-checked every
 * substep) skip pairs that cannot collide. Rest neighbours (particles
 * joined by a spring or a few triangle edges apart) never repel. Runs after
 * every substep; results are bit-identical for any thread count.
 * Off by default: a cloth allocates nothing for it until it is enabled,
 * and frees it again when it is disabled. */

/// Self-collision settings of a cloth.
typedef struct cloth_self_collision_desc {
    /// sizeof(cloth_self_collision_desc)
    uint32_t struct_size;
    /// 1: on; 0 or 1, default 0
    uint8_t enabled;
    /// theta_c, m; > 0 and at most twice the fabric's mean rest edge; default 0.01
    float thickness;
    /// Coulomb coefficient on the sliding velocity, >= 0; default 0
    float friction;
    /// 1: skip pairs inside collision-free regions; 0 or 1, default 1
    uint8_t use_regions;
    /// at most this many projection passes per substep, 1..CLOTH_MAX_SELF_COLLISION_PASSES; default 8
    /// (with a strain limit, one more after each of its passes)
    uint32_t passes;
    /// set by the struct\'s cloth_default_*() function; do not change
    uint32_t internal_cookie;
} cloth_self_collision_desc;

/// Self-collision settings with every default set (and its cookie); off.
CLOTH_API cloth_self_collision_desc CLOTH_CALL cloth_default_self_collision_desc(void);

/// Enable, change or disable (desc->enabled = 0) self-collision of a
/// cloth. Enabling allocates (CLOTH_ERROR_OUT_OF_MEMORY changes nothing);
/// a thickness above twice the fabric's mean rest edge is
/// CLOTH_ERROR_INVALID_VALUE (rest neighbours would need too many rings).
CLOTH_API cloth_result CLOTH_CALL cloth_set_self_collision(cloth_id cloth,
                                                           const cloth_self_collision_desc* desc);
/// The current settings (enabled = 0 and defaults while off).
CLOTH_API cloth_result CLOTH_CALL cloth_get_self_collision(cloth_id cloth,
                                                           cloth_self_collision_desc* out_desc);

/// What the last substep's self-collision did (all zero while off).
typedef struct cloth_self_collision_stats {
    /// set by the caller to sizeof(cloth_self_collision_stats)
    uint32_t struct_size;
    /// pairs closer than thickness when contacts were searched
    uint32_t contacts;
    /// collision-free region candidates of the fabric
    uint32_t regions;
    /// of those, collision-free at the last check
    uint32_t valid_regions;
    /// particles with more close neighbours than contact slots (16)
    uint32_t overflowed_particles;
    /// projection passes run in the last substep (at most `passes`; those
    /// after the strain limit's passes are not counted)
    uint32_t passes;
} cloth_self_collision_stats;

/// What the last substep's self-collision did; the caller sets
/// out_stats->struct_size first.
CLOTH_API cloth_result CLOTH_CALL cloth_get_self_collision_stats(cloth_id cloth,
                                                                 cloth_self_collision_stats* out_stats);

/* ------------------------------------------------------------------ */
/* Contact between cloths                                             */
/* ------------------------------------------------------------------ */

/* Contact between two cloths of one world (since 1.10; NvCloth calls it
 * inter-collision), for garments worn together: particles of one cloth
 * closer than `thickness` to the other cloth's surface are pushed out to
 * `thickness` and lose the approaching part of their relative velocity,
 * with optional Coulomb friction on the sliding part, as in
 * self-collision. Each end moves by its share of the depth (its inverse
 * mass over the pair's); pinned particles, max-distance-0 particles
 * included, do not move.
 *
 * The other cloth's surface is seen through its particles: each stands
 * for the plane through it normal to the surface there, and a particle is
 * kept on the side of it where the last substep left it, so a particle that
 * crossed within a substep is pushed back; one that went round the other
 * cloth's border (a hem) is on its new side. Cloths that intersect when
 * the pair is turned on stay on the sides they are on then: turn it on
 * with the cloths apart.
 *
 * It is resolved inside both cloths' substeps, which step together: once a
 * substep, after both integrated and met their colliders and before their
 * strain limits, both cloths' contacts are found (within a search that
 * grows with their speeds) and projected; each cloth's strain-limit passes
 * then take back the stretch the pushes made, and its velocities lose
 * the part approaching the other cloth; the skin's max distances and
 * backstops come last, so those still win. The two cloths run the same
 * number of substeps (the more of the two: a stiff cloth in contact with
 * a soft one makes it run more), and a cloth is in contact with at most 4
 * others (CLOTH_ERROR_CAPACITY). Results are bit-identical for any thread
 * count.
 *
 * Off for every pair by default. A pair costs nothing while it is off, and
 * two bound computations a frame while the cloths' bounds, grown by
 * `thickness`, the larger mean rest edge and how far their particles move
 * in the frame, do not meet. A cloth that sleeps beside one that steps is
 * a still surface to it, and wakes when it is touched. A pair is turned
 * off when either cloth is destroyed; it is not part of either cloth's
 * snapshot. */

/// Contact settings of a pair of cloths.
typedef struct cloth_cloth_contact_desc {
    /// sizeof(cloth_cloth_contact_desc)
    uint32_t struct_size;
    /// 1: on; 0 or 1, default 0
    uint8_t enabled;
    /// m; > 0 and at most twice the larger of the two fabrics' mean rest edges; default 0.01
    float thickness;
    /// Coulomb coefficient on the sliding velocity, >= 0; default 0
    float friction;
    /// at most this many projection passes per substep (per frame before
    /// 1.13), 1..CLOTH_MAX_SELF_COLLISION_PASSES; default 4
    uint32_t passes;
    /// set by the struct\'s cloth_default_*() function; do not change
    uint32_t internal_cookie;
} cloth_cloth_contact_desc;

/// Contact settings with every default set (and its cookie); off. Since 1.10.
CLOTH_API cloth_cloth_contact_desc CLOTH_CALL cloth_default_cloth_contact_desc(void);

/// Turn on, change or turn off (desc->enabled = 0) contact between two
/// cloths of one world; the order of `a` and `b` does not matter. Turning
/// a pair on allocates (CLOTH_ERROR_OUT_OF_MEMORY changes nothing) and
/// wakes both cloths. A cloth and itself is CLOTH_ERROR_INVALID_VALUE;
/// cloths of two worlds, CLOTH_ERROR_INVALID_HANDLE; a new pair with a
/// cloth already in contact with 4 others, CLOTH_ERROR_CAPACITY (since
/// 1.13), and nothing changes. Since 1.10.
CLOTH_API cloth_result CLOTH_CALL cloth_set_cloth_contact(cloth_id a, cloth_id b,
                                                          const cloth_cloth_contact_desc* desc);
/// The pair's settings (enabled = 0 and defaults while off). Since 1.10.
CLOTH_API cloth_result CLOTH_CALL cloth_get_cloth_contact(cloth_id a, cloth_id b,
                                                          cloth_cloth_contact_desc* out_desc);
/// Particles of either cloth within `thickness` of the other cloth when
/// the last substep looked (0 while the pair is off or the cloths were
/// apart), and the projection passes it ran then. Since 1.10.
CLOTH_API cloth_result CLOTH_CALL cloth_get_cloth_contact_count(cloth_id a, cloth_id b,
                                                                uint32_t* out_contacts, uint32_t* out_passes);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* CLOTH_CLOTH_H */
