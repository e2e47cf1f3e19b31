// C API: when a cloth sleeps (skipped by the step until something wakes it).
#include <cloth/cloth.h>

#include "api_call.h"
#include "api_validation.h"

using namespace cloth;
using namespace cloth::api;

extern "C" {

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
    return with_cloth(__func__, id, [&](ClothInstance& cloth) -> Status {
        if (!params) return null_error("params");
        if (params->struct_size != sizeof(cloth_sleep_params)) {
            return Status::error(CLOTH_ERROR_INVALID_DESC,
                                 "cloth_sleep_params.struct_size is %u, expected %zu", params->struct_size,
                                 sizeof(cloth_sleep_params));
        }
        Status s = check_non_negative(params->max_speed, "max_speed");
        if (!s.ok()) return s;
        if (params->frames < 1) return Status::error(CLOTH_ERROR_INVALID_VALUE, "frames must be at least 1");
        cloth.set_sleep(SleepSettings{params->enabled != 0, params->max_speed, params->frames});
        return {};
    });
}

CLOTH_API cloth_result cloth_sleep(cloth_id id) {
    return with_cloth(__func__, id, [&](ClothInstance& cloth) -> Status {
        cloth.hold_asleep();
        return {};
    });
}

CLOTH_API cloth_result cloth_wake(cloth_id id) {
    return with_cloth(__func__, id, [&](ClothInstance& cloth) -> Status {
        cloth.wake();
        return {};
    });
}

CLOTH_API cloth_result cloth_is_sleeping(cloth_id id, bool* out_sleeping) {
    return with_cloth(__func__, id, [&](ClothInstance& cloth) -> Status {
        if (!out_sleeping) return null_error("out_sleeping");
        *out_sleeping = cloth.sleeping();
        return {};
    });
}

}  // extern "C"
