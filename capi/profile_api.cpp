// C API: frame profiles, task records, Chrome trace export and profiler
// zone callbacks of a world.
#include <cloth/cloth.h>

#include <algorithm>

#include "api_call.h"
#include "api_validation.h"
#include "scene/frame_profile.h"

using namespace cloth;
using namespace cloth::api;

static_assert(
    static_cast<int>(CLOTH_STAGE_AIR) == static_cast<int>(Stage::kAir) &&
        static_cast<int>(CLOTH_STAGE_SELF_COLLISION) == static_cast<int>(Stage::kSelfCollision) &&
        static_cast<int>(CLOTH_STAGE_SELF_RESPOND) == static_cast<int>(Stage::kSelfRespond) &&
        static_cast<int>(CLOTH_STAGE_LIMIT_COLLISIONS) == static_cast<int>(Stage::kLimitCollisions) &&
        static_cast<int>(CLOTH_STAGE_SKINNING) == static_cast<int>(Stage::kSkinning) &&
        static_cast<int>(CLOTH_STAGE_SKIN_CONSTRAINTS) == static_cast<int>(Stage::kSkinConstraints) &&
        static_cast<int>(CLOTH_STAGE_CLOTH_CONTACT_RESPOND) == static_cast<int>(Stage::kClothContactRespond),
    "cloth_stage mirrors cloth::Stage");
// cloth_frame_profile's arrays hold the first CLOTH_MAX_STAGES stages;
// cloth_world_get_stage_profile reads every one.
static_assert(kStageCount >= CLOTH_MAX_STAGES, "the profile's arrays are filled");
static_assert(kMaxWorkers <= CLOTH_MAX_WORKERS, "the profile has room for every worker");

extern "C" {

CLOTH_API const char* cloth_stage_name(cloth_stage stage) {
    const int32_t bits = enum_bits(stage);
    if (bits < 0 || static_cast<uint32_t>(bits) >= kStageCount) return "?";
    return stage_name(static_cast<Stage>(bits));
}

CLOTH_API cloth_result cloth_world_set_profiling(cloth_world_id id, uint32_t max_tasks_per_frame) {
    return with_world(__func__, id, [&](World& world) -> Status {
        if (max_tasks_per_frame > CLOTH_MAX_PROFILED_TASKS) {
            return Status::error(CLOTH_ERROR_INVALID_COUNT, "max_tasks_per_frame %u is more than %u",
                                 max_tasks_per_frame, CLOTH_MAX_PROFILED_TASKS);
        }
        world.set_profiling(max_tasks_per_frame);
        return {};
    });
}

CLOTH_API cloth_result cloth_world_get_stage_profile(cloth_world_id id, cloth_stage stage, double* out_ms,
                                                     uint32_t* out_tasks) {
    return with_world(__func__, id, [&](World& world) -> Status {
        if (!out_ms) return null_error("out_ms");
        if (!out_tasks) return null_error("out_tasks");
        const int32_t bits = enum_bits(stage);
        if (bits < 0 || static_cast<uint32_t>(bits) >= kStageCount) {
            return Status::error(CLOTH_ERROR_INVALID_VALUE, "stage %d is not a cloth_stage", bits);
        }
        const FrameProfile& p = world.frame_profile();
        *out_ms = static_cast<double>(p.stage_ns[bits]) * 1e-6;
        *out_tasks = p.stage_tasks[bits];
        return {};
    });
}

CLOTH_API cloth_result cloth_world_get_frame_profile(cloth_world_id id, cloth_frame_profile* out) {
    return with_world(__func__, id, [&](World& world) -> Status {
        if (!out) return null_error("out_profile");
        if (out->struct_size != sizeof(cloth_frame_profile)) {
            return Status::error(CLOTH_ERROR_INVALID_DESC,
                                 "cloth_frame_profile.struct_size is %u, expected %zu", out->struct_size,
                                 sizeof(cloth_frame_profile));
        }
        const FrameProfile& p = world.frame_profile();
        cloth_frame_profile r{};
        r.struct_size = sizeof r;
        r.worker_count = static_cast<uint32_t>(std::min<size_t>(p.worker_busy_ns.size(), CLOTH_MAX_WORKERS));
        r.frame = p.frame;
        r.step_ms = p.step_ms();
        r.budget_ms = p.budget_ms;
        r.budget_used = p.budget_ms > 0 ? r.step_ms / p.budget_ms : 0.0;
        r.overrun = p.overrun;
        r.awake_cloths = p.awake_cloths;
        r.sleeping_cloths = p.sleeping_cloths;
        for (uint32_t st = 0; st < CLOTH_MAX_STAGES; ++st) {
            r.stage_ms[st] = static_cast<double>(p.stage_ns[st]) * 1e-6;
            r.stage_tasks[st] = p.stage_tasks[st];
        }
        for (uint32_t w = 0; w < r.worker_count; ++w) {
            r.worker_busy_ms[w] = static_cast<double>(p.worker_busy_ns[w]) * 1e-6;
            r.worker_idle_ms[w] = std::max(0.0, r.step_ms - r.worker_busy_ms[w]);
        }
        r.task_count = static_cast<uint32_t>(p.tasks.size());
        r.tasks_dropped = p.tasks_dropped;
        r.overrun_frames = world.budget().overrun_frames();
        *out = r;
        return {};
    });
}

CLOTH_API cloth_result cloth_world_read_task_records(cloth_world_id id, cloth_task_record* out_records,
                                                     uint32_t capacity, uint32_t* out_count) {
    return with_world(__func__, id, [&](World& world) -> Status {
        if (!out_count) return null_error("out_count");
        if (!out_records && capacity > 0) return null_error("out_records");
        const FrameProfile& p = world.frame_profile();
        const uint32_t n = std::min(capacity, static_cast<uint32_t>(p.tasks.size()));
        for (uint32_t i = 0; i < n; ++i) {
            const TaskRecord& t = p.tasks[i];
            out_records[i] = cloth_task_record{world.cloth_id_of(t.cloth_slot, t.cloth_generation),
                                               static_cast<cloth_stage>(t.stage),
                                               t.group,
                                               t.worker,
                                               t.substep,
                                               static_cast<double>(t.start_ns - p.origin_ns) * 1e-3,
                                               static_cast<double>(t.end_ns - p.origin_ns) * 1e-3};
        }
        *out_count = n;
        return {};
    });
}

CLOTH_API cloth_result cloth_world_write_trace_json(cloth_world_id id, char* buffer, size_t capacity,
                                                    size_t* out_size) {
    return with_world(__func__, id, [&](World& world) -> Status {
        if (!out_size) return null_error("out_size");
        if (!buffer && capacity > 0) return null_error("buffer");
        const size_t needed = write_trace_json(world.frame_profile(), buffer, capacity);
        *out_size = needed;
        if (buffer && capacity < needed) {
            return Status::error(CLOTH_ERROR_INVALID_COUNT, "capacity %zu is less than the %zu bytes needed",
                                 capacity, needed);
        }
        return {};
    });
}

CLOTH_API cloth_result cloth_world_set_zone_callbacks(cloth_world_id id, cloth_zone_begin_fn* begin,
                                                      cloth_zone_end_fn* end, void* user) {
    return with_world(__func__, id, [&](World& world) -> Status {
        if ((begin == nullptr) != (end == nullptr)) {
            return Status::error(CLOTH_ERROR_INVALID_VALUE, "set both zone callbacks, or neither");
        }
        world.set_zone_callbacks(begin, end, user);
        return {};
    });
}

}  // extern "C"
