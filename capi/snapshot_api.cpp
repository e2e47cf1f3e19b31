// C API: snapshots (save and restore a cloth's dynamic state) and sleep.
#include <cloth/cloth.h>

#include <cmath>

#include "api_call.h"
#include "api_validation.h"

using namespace cloth;
using namespace cloth::api;

extern "C" {

CLOTH_API cloth_result cloth_get_snapshot_size(cloth_id id, size_t* out_size) {
    return api_call(__func__, [&](const World*& log_world) -> Status {
        ClothInstance* cloth;
        Status s = get_cloth(id, cloth, log_world);
        if (!s.ok()) return s;
        if (!out_size) return null_error("out_size");
        *out_size = cloth->snapshot_size();
        return {};
    });
}

CLOTH_API cloth_result cloth_save_snapshot(cloth_id id, void* buffer, size_t capacity) {
    return api_call(__func__, [&](const World*& log_world) -> Status {
        ClothInstance* cloth;
        Status s = get_cloth(id, cloth, log_world);
        if (!s.ok()) return s;
        if (!buffer) return null_error("buffer");
        if (capacity < cloth->snapshot_size()) {
            return Status::error(CLOTH_ERROR_INVALID_COUNT, "capacity %zu is less than the %zu bytes needed",
                                 capacity, cloth->snapshot_size());
        }
        cloth->save_snapshot(buffer);
        return {};
    });
}

CLOTH_API cloth_result cloth_restore_snapshot(cloth_id id, const void* buffer, size_t size) {
    return api_call(__func__, [&](const World*& log_world) -> Status {
        ClothInstance* cloth;
        Status s = get_cloth(id, cloth, log_world);
        if (!s.ok()) return s;
        if (!buffer) return null_error("buffer");
        return cloth->restore_snapshot(buffer, size);
    });
}

CLOTH_API cloth_sleep_params cloth_default_sleep_params(void) {
    const SleepSettings core;
    cloth_sleep_params p{};
    p.struct_size = sizeof p;
    p.enabled = core.enabled;
    p.max_speed = core.max_speed;
    p.frames = core.frames;
    return p;
}

CLOTH_API cloth_result cloth_set_sleep(cloth_id id, const cloth_sleep_params* params) {
    return api_call(__func__, [&](const World*& log_world) -> Status {
        ClothInstance* cloth;
        Status s = get_cloth(id, cloth, log_world);
        if (!s.ok()) return s;
        if (!params) return null_error("params");
        if (params->struct_size != sizeof(cloth_sleep_params)) {
            return Status::error(CLOTH_ERROR_INVALID_DESC,
                                 "cloth_sleep_params.struct_size is %u, expected %zu", params->struct_size,
                                 sizeof(cloth_sleep_params));
        }
        s = check_non_negative(params->max_speed, "max_speed");
        if (!s.ok()) return s;
        if (params->frames < 1) return Status::error(CLOTH_ERROR_INVALID_VALUE, "frames must be at least 1");
        cloth->set_sleep(SleepSettings{params->enabled, params->max_speed, params->frames});
        return {};
    });
}

CLOTH_API cloth_result cloth_wake(cloth_id id) {
    return api_call(__func__, [&](const World*& log_world) -> Status {
        ClothInstance* cloth;
        Status s = get_cloth(id, cloth, log_world);
        if (!s.ok()) return s;
        cloth->wake();
        return {};
    });
}

CLOTH_API cloth_result cloth_is_sleeping(cloth_id id, bool* out_sleeping) {
    return api_call(__func__, [&](const World*& log_world) -> Status {
        ClothInstance* cloth;
        Status s = get_cloth(id, cloth, log_world);
        if (!s.ok()) return s;
        if (!out_sleeping) return null_error("out_sleeping");
        *out_sleeping = cloth->sleeping();
        return {};
    });
}

}  // extern "C"
