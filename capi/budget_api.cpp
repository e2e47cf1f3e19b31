// C API: a world's frame budget and the quality policy by which it trades
// a cloth's iterations, substeps and update rate for time.
#include <cloth/cloth.h>

#include <cstddef>

#include "api_call.h"
#include "api_validation.h"
#include "scene/update_rate.h"

using namespace cloth;
using namespace cloth::api;

namespace {
constexpr size_t kPolicySize110 = offsetof(cloth_quality_policy, max_update_rate);
}  // namespace

extern "C" {

CLOTH_API cloth_result cloth_world_set_frame_budget(cloth_world_id id, float milliseconds) {
    return with_world(__func__, id, [&](World& world) -> Status {
        Status s = check_non_negative(milliseconds, "milliseconds");
        if (!s.ok()) return s;
        world.budget().set_ms(milliseconds);
        return {};
    });
}

CLOTH_API cloth_quality_policy cloth_default_quality_policy(void) {
    const QualityPolicy core;
    cloth_quality_policy p{};
    p.struct_size = sizeof p;
    p.enabled = core.enabled;
    p.min_iterations = core.min_iterations;
    p.max_iterations = core.max_iterations;
    p.min_substeps = core.min_substeps;
    p.max_substeps = core.max_substeps;
    p.max_update_rate = core.max_update_rate;
    return p;
}

CLOTH_API cloth_result cloth_set_quality_policy(cloth_id id, const cloth_quality_policy* policy) {
    return with_scene_cloth(__func__, id, [&](SceneCloth& cloth) -> Status {
        if (!policy) return null_error("policy");
        // 1.10's struct ends before max_update_rate.
        const bool before_rates = policy->struct_size == kPolicySize110;
        if (policy->struct_size != sizeof(cloth_quality_policy) && !before_rates) {
            return Status::error(CLOTH_ERROR_INVALID_DESC,
                                 "cloth_quality_policy.struct_size is %u, expected %zu (or %zu, 1.10's)",
                                 policy->struct_size, sizeof(cloth_quality_policy), kPolicySize110);
        }
        const uint32_t max_rate = before_rates ? 1 : policy->max_update_rate;
        if (!UpdateRate::valid(max_rate)) {
            return Status::error(CLOTH_ERROR_INVALID_VALUE, "max_update_rate %u is not 1, 2, 4 or 8",
                                 max_rate);
        }
        if (policy->min_iterations < 1 || policy->min_iterations > policy->max_iterations ||
            policy->max_iterations > CLOTH_MAX_ITERATIONS) {
            return Status::error(CLOTH_ERROR_INVALID_VALUE, "iterations bounds %u..%u are not within 1..256",
                                 policy->min_iterations, policy->max_iterations);
        }
        if (policy->min_substeps < 1 || policy->min_substeps > policy->max_substeps ||
            policy->max_substeps > CLOTH_MAX_SUBSTEPS) {
            return Status::error(CLOTH_ERROR_INVALID_VALUE, "substeps bounds %u..%u are not within 1..64",
                                 policy->min_substeps, policy->max_substeps);
        }
        QualityPolicy core;
        core.enabled = policy->enabled;
        core.min_iterations = policy->min_iterations;
        core.max_iterations = policy->max_iterations;
        core.min_substeps = policy->min_substeps;
        core.max_substeps = policy->max_substeps;
        core.max_update_rate = max_rate;
        cloth.set_quality_policy(core);
        return {};
    });
}

}  // extern "C"
