// C API: worlds, their workers and stepping. Validation runs completely
// before anything is changed, so a failing call changes nothing.
#include <cloth/cloth.h>

#include <cmath>

#include "api_call.h"
#include "api_validation.h"

using namespace cloth;
using namespace cloth::api;

namespace {

Status check_world_desc(const cloth_world_desc& desc) {
    Status s =
        check_desc(desc.struct_size, sizeof(cloth_world_desc), desc.internal_cookie, "cloth_world_desc");
    if (!s.ok()) return s;
    if (!finite3(desc.gravity)) return Status::error(CLOTH_ERROR_NOT_FINITE, "gravity is not finite");
    if ((desc.alloc == nullptr) != (desc.free == nullptr)) {
        return Status::error(CLOTH_ERROR_INVALID_VALUE, "set both alloc and free, or neither");
    }
    if (desc.max_cloths < 1 || desc.max_cloths > CLOTH_MAX_CLOTHS || desc.max_fabrics < 1 ||
        desc.max_fabrics > CLOTH_MAX_FABRICS) {
        return Status::error(CLOTH_ERROR_INVALID_COUNT, "max_cloths and max_fabrics must be in 1..%d",
                             CLOTH_MAX_CLOTHS);
    }
    if ((desc.enqueue_task == nullptr) != (desc.finish_task == nullptr)) {
        return Status::error(CLOTH_ERROR_INVALID_VALUE, "set both enqueue_task and finish_task, or neither");
    }
    if (desc.worker_count > kMaxWorkers) {
        return Status::error(CLOTH_ERROR_INVALID_COUNT, "worker_count %u is more than %u", desc.worker_count,
                             kMaxWorkers);
    }
    if (desc.enqueue_task && desc.worker_count == 0) {
        return Status::error(CLOTH_ERROR_INVALID_COUNT,
                             "worker_count must be 1..%u with host task callbacks (the number of "
                             "worker indices the host passes)",
                             kMaxWorkers);
    }
    return {};
}

}  // namespace

extern "C" {

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
        Status s = check_world_desc(*desc);
        if (!s.ok()) return s;

        WorldTable& table = world_table();
        std::lock_guard<std::mutex> lock(table.mutex);
        const uint32_t index = table.worlds.free_slot();
        if (index == table.worlds.kFull)
            return Status::error(CLOTH_ERROR_CAPACITY, "%u worlds exist already", kMaxWorlds);
        const uint16_t generation = table.worlds[index].generation;

        const HostMemory memory{desc->alloc, desc->free, desc->user};
        void* storage = memory.allocate(sizeof(World), alignof(World));
        World* world = nullptr;
        try {
            world = new (storage) World(*desc, static_cast<uint16_t>(index), generation);
        } catch (...) {
            memory.deallocate(storage, sizeof(World));
            throw;
        }
        table.worlds.occupy(index, world);
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
            const uint32_t index = table.worlds.find(id.index1, id.generation);
            if (index == table.worlds.kFull)
                return is_null(id) ? null_handle_error("world") : no_world_error("world");
            world = table.worlds[index].object;
            table.worlds.release(index);
        }
        const HostMemory memory = *world->memory();
        world->~World();
        memory.deallocate(world, sizeof(World));
        return {};
    });
}

CLOTH_API bool cloth_world_is_valid(cloth_world_id id) { return find_world(id) != nullptr; }

CLOTH_API cloth_result cloth_world_set_worker_spin(cloth_world_id id, uint32_t microseconds) {
    return with_world(__func__, id, [&](World& world) -> Status {
        if (microseconds > kMaxWorkerSpinMicroseconds) {
            return Status::error(CLOTH_ERROR_INVALID_VALUE, "worker spin of %u us is more than %u us (1 s)",
                                 microseconds, kMaxWorkerSpinMicroseconds);
        }
        world.set_worker_spin(microseconds);
        return {};
    });
}

CLOTH_API cloth_result cloth_world_set_gravity(cloth_world_id id, const float gravity[3]) {
    return with_world(__func__, id, [&](World& world) -> Status {
        if (!gravity) return null_error("gravity");
        if (!finite3(gravity)) return Status::error(CLOTH_ERROR_NOT_FINITE, "gravity is not finite");
        world.gravity = Vec3(gravity[0], gravity[1], gravity[2]);
        world.wake_all();
        return {};
    });
}

CLOTH_API cloth_result cloth_world_shift_origin(cloth_world_id id, const float shift[3]) {
    return with_world(__func__, id, [&](World& world) -> Status {
        if (!shift) return null_error("shift");
        Status s = check_coordinates(shift, "shift");
        if (!s.ok()) return s;
        return world.shift_origin(Vec3(shift[0], shift[1], shift[2]));
    });
}

CLOTH_API cloth_result cloth_step(cloth_world_id id, float dt) {
    return with_world(__func__, id, [&](World& world) -> Status {
        if (!std::isfinite(dt)) return Status::error(CLOTH_ERROR_NOT_FINITE, "dt is not finite");
        if (!(dt >= CLOTH_MIN_DT && dt <= 1)) {
            return Status::error(CLOTH_ERROR_INVALID_VALUE, "dt %g is not in [CLOTH_MIN_DT, 1] = [%g, 1]",
                                 double(dt), double(CLOTH_MIN_DT));
        }
        return world.step(dt);
    });
}

}  // extern "C"
