// Shared machinery of the C API's files: the process-wide world table,
// handle lookups, and api_call, which turns every outcome (including
// exceptions, which never cross the ABI) into a cloth_result plus a message.
#pragma once

#include <cloth/cloth.h>

#include <array>
#include <cstdio>
#include <exception>
#include <mutex>
#include <new>

#include "errors.h"
#include "step/world.h"

namespace cloth::api {
inline constexpr uint32_t kCookie = 0x636C7468;  // "clth": the desc came from cloth_default_*()
inline constexpr uint32_t kMaxWorlds = 128;
inline constexpr uint32_t kMaxWorkers = 256;

// ---------------------------------------------------------------- worlds

// Process-wide table of worlds, so that a world id can be checked before
// use (a stale or foreign id is an error, not a dangling pointer). Only
// create, destroy and lookup touch it, under the mutex.
struct WorldTable {
    std::mutex mutex;
    std::array<World*, kMaxWorlds> worlds{};
    std::array<uint16_t, kMaxWorlds> generations{};
};

inline WorldTable& world_table() {
    static WorldTable table;
    return table;
}

inline World* find_world(cloth_world_id id) {
    if (id.index1 == 0 || id.index1 > kMaxWorlds) return nullptr;
    WorldTable& table = world_table();
    std::lock_guard<std::mutex> lock(table.mutex);
    World* world = table.worlds[id.index1 - 1];
    if (!world || table.generations[id.index1 - 1] != id.generation) return nullptr;
    return world;
}

// The world a fabric or cloth id names, if that world is still alive.
template <class Id>
inline World* find_owning_world(Id id) {
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

// ---------------------------------------------------------------- lookups

inline Status get_world(cloth_world_id id, World*& world, const World*& log_world) {
    world = find_world(id);
    if (!world)
        return Status::error(CLOTH_ERROR_INVALID_HANDLE, "world handle is null, destroyed or unknown");
    log_world = world;
    return {};
}

inline Status get_cloth(cloth_id id, ClothInstance*& cloth, const World*& log_world) {
    World* world = find_owning_world(id);
    cloth = world ? world->find_cloth(id) : nullptr;
    if (!cloth)
        return Status::error(CLOTH_ERROR_INVALID_HANDLE, "cloth handle is null, destroyed or unknown");
    log_world = world;
    return {};
}

inline Status get_fabric(cloth_fabric_id id, std::shared_ptr<const Fabric>& fabric, World*& world,
                         const World*& log_world) {
    world = find_owning_world(id);
    fabric = world ? world->find_fabric(id) : nullptr;
    if (!fabric)
        return Status::error(CLOTH_ERROR_INVALID_HANDLE, "fabric handle is null, destroyed or unknown");
    log_world = world;
    return {};
}
}  // namespace cloth::api
