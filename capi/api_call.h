// Shared machinery of the C API's files: the process-wide world table,
// api_call, which turns every outcome (including exceptions, which never
// cross the ABI) into a cloth_result plus a message, and the with_* calls
// that open every function taking a handle: they look the handle up and
// run the function's body only on a live object, so no function can
// forget the check.
#pragma once

#include <cloth/cloth.h>

#include <cstdio>
#include <exception>
#include <mutex>
#include <new>
#include <type_traits>

#include "base/id_pool.h"
#include "errors.h"
#include "scene/world.h"

namespace cloth::api {
inline constexpr uint32_t kCookie = 0x636C7468;  // "clth": the desc came from cloth_default_*()
inline constexpr uint32_t kMaxWorlds = CLOTH_MAX_WORLDS;
inline constexpr uint32_t kMaxWorkers = CLOTH_MAX_WORKERS;

// ---------------------------------------------------------------- worlds

// Process-wide table of worlds, so that a world id can be checked before
// use (a stale or foreign id is an error, not a dangling pointer). Its
// slots come from the C heap (no world's allocator outlives the table).
// Only create, destroy and lookup touch it, under the mutex.
struct WorldTable {
    std::mutex mutex;
    HostMemory heap;
    IdPool<World*> worlds{&heap, kMaxWorlds};

    WorldTable() { worlds.make_all_slots(); }
};

inline WorldTable& world_table() {
    static WorldTable table;
    return table;
}

inline World* find_world(cloth_world_id id) {
    WorldTable& table = world_table();
    std::lock_guard<std::mutex> lock(table.mutex);
    World** world = table.worlds.get(id.index1, id.generation);
    return world ? *world : nullptr;
}

// The world a fabric, cloth, body or collider id names, if that world is still alive.
template <class Id>
inline World* find_owning_world(Id id) {
    return find_world(cloth_world_id{id.world1, id.world_generation});
}

// ---------------------------------------------------------------- results

// Runs `body` (which returns a Status and may name the world to log to),
// turns exceptions into results, records the message and logs it. The
// lookups below name the world as soon as a handle's world part is found
// live, before the object itself is looked up: cloth.h's rule that every
// error of a call naming a live world reaches that world's log.
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
    end_at_utf8_boundary(message);
    set_last_error(message);
    if (log_world) {
        const bool warning =
            status.code == CLOTH_ERROR_SOLVER_FAILED || status.code == CLOTH_ERROR_OVER_BUDGET;
        try {
            log_world->log(warning ? CLOTH_LOG_WARNING : CLOTH_LOG_ERROR, status.code, message);
        } catch (...) {
            // A host callback that throws must not take the exception through the ABI.
        }
    }
    return status.code;
}

inline Status null_error(const char* what) {
    return Status::error(CLOTH_ERROR_NULL_POINTER, "%s is NULL", what);
}

// What is wrong with a handle that names no live object, from its fields
// alone: null (all zero), its world part naming no live world, or the
// object gone from a live world.
inline Status null_handle_error(const char* kind) {
    return Status::error(CLOTH_ERROR_INVALID_HANDLE, "%s handle is null", kind);
}
inline Status no_world_error(const char* kind) {
    return Status::error(CLOTH_ERROR_INVALID_HANDLE,
                         "%s handle names no live world (its world was destroyed, or the handle was "
                         "never handed out)",
                         kind);
}
inline Status no_object_error(const char* kind) {
    return Status::error(CLOTH_ERROR_INVALID_HANDLE,
                         "%s handle names no live %s in its world (destroyed, or never created)", kind, kind);
}

template <class Id>
bool is_null(const Id& id) {
    return id.index1 == 0 && id.world1 == 0 && id.generation == 0 && id.world_generation == 0;
}
inline bool is_null(const cloth_world_id& id) { return id.index1 == 0 && id.generation == 0; }

// ---------------------------------------------------------------- lookups

// The live object an id names in its world, or null.
inline ClothInstance* find_object(World& world, cloth_id id) { return world.find_cloth(id); }
inline const Fabric* find_object(World& world, cloth_fabric_id id) { return world.find_fabric(id).get(); }
inline BodyState* find_object(World& world, cloth_body_id id) {
    return world.contact().find_body(id.index1, id.generation);
}
inline Collider* find_object(World& world, cloth_collider_id id) {
    return world.contact().find_collider(id.index1, id.generation);
}

// Whether `id` names a live object (the cloth_*_is_valid functions).
template <class Id>
bool is_live(Id id) {
    World* world = find_owning_world(id);
    return world && find_object(*world, id);
}

// The world a handle argument must belong to (that of the call's own
// handle), with `owner` naming it in messages ("the cloth", "the call's
// world"): null, another world, or no live object there.
template <class Id>
Status check_same_world(Id id, cloth_world_id world, const char* kind, const char* owner) {
    if (is_null(id)) return null_handle_error(kind);
    if (id.world1 != world.index1 || id.world_generation != world.generation) {
        return Status::error(CLOTH_ERROR_INVALID_HANDLE, "%s handle belongs to another world than %s", kind,
                             owner);
    }
    return {};
}

// The body a cloth refers to, which must live in the cloth's world.
inline Status find_body_of_cloth(cloth_id cloth, cloth_body_id id, const BodyState*& body) {
    body = nullptr;
    Status s =
        check_same_world(id, cloth_world_id{cloth.world1, cloth.world_generation}, "body", "the cloth");
    if (!s.ok()) return s;
    World* world = find_owning_world(id);
    body = world ? find_object(*world, id) : nullptr;
    if (!body) return no_object_error("body");
    return {};
}

// Runs `body(world)` on the live world `id` names; else the call fails
// with CLOTH_ERROR_INVALID_HANDLE and `body` does not run.
template <class Body>
cloth_result with_world(const char* function, cloth_world_id id, Body body) {
    return api_call(function, [&](const World*& log_world) -> Status {
        World* world = find_world(id);
        if (!world) return is_null(id) ? null_handle_error("world") : no_world_error("world");
        log_world = world;
        return body(*world);
    });
}

// Runs `body(world)` on the live world a fabric or cloth id names, for the
// destroy calls, whose World method checks the object itself.
template <class Id, class Body>
cloth_result with_owning_world(const char* function, Id id, const char* kind, Body body) {
    return api_call(function, [&](const World*& log_world) -> Status {
        World* world = find_owning_world(id);
        if (!world) return is_null(id) ? null_handle_error(kind) : no_world_error(kind);
        log_world = world;
        return body(*world);
    });
}

// Runs `body(object)`, or `body(object, world)`, on the live object `id`
// names (ClothInstance, const Fabric, BodyState or Collider); else the
// call fails with CLOTH_ERROR_INVALID_HANDLE and `body` does not run.
template <class Id, class Body>
cloth_result with_object(const char* function, Id id, const char* kind, Body body) {
    return api_call(function, [&](const World*& log_world) -> Status {
        World* world = find_owning_world(id);
        if (!world) return is_null(id) ? null_handle_error(kind) : no_world_error(kind);
        log_world = world;  // the object may be gone; its world still hears of the error
        auto* object = find_object(*world, id);
        if (!object) return no_object_error(kind);
        if constexpr (std::is_invocable_v<Body&, decltype(*object), World&>) {
            return body(*object, *world);
        } else {
            return body(*object);
        }
    });
}

template <class Body>
cloth_result with_cloth(const char* function, cloth_id id, Body body) {
    return with_object(function, id, "cloth", body);
}
// As with_cloth, with the scene's record of the cloth (scene/scene_cloth.h):
// `body(scene)` or `body(scene, world)`.
template <class Body>
cloth_result with_scene_cloth(const char* function, cloth_id id, Body body) {
    return api_call(function, [&](const World*& log_world) -> Status {
        World* world = find_owning_world(id);
        if (!world) return is_null(id) ? null_handle_error("cloth") : no_world_error("cloth");
        log_world = world;
        SceneCloth* scene = world->find_scene_cloth(id);
        if (!scene) return no_object_error("cloth");
        if constexpr (std::is_invocable_v<Body&, SceneCloth&, World&>) {
            return body(*scene, *world);
        } else {
            return body(*scene);
        }
    });
}
template <class Body>
cloth_result with_fabric(const char* function, cloth_fabric_id id, Body body) {
    return with_object(function, id, "fabric", body);
}
template <class Body>
cloth_result with_body(const char* function, cloth_body_id id, Body body) {
    return with_object(function, id, "body", body);
}
template <class Body>
cloth_result with_collider(const char* function, cloth_collider_id id, Body body) {
    return with_object(function, id, "collider", body);
}
}  // namespace cloth::api
