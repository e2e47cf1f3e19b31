// C API: a world's frame budget and the quality policy by which it trades
// a cloth's iterations and substeps for time.
#include <cloth/cloth.h>

#include "api_call.h"
#include "api_validation.h"

using namespace cloth;
using namespace cloth::api;

extern "C" {

CLOTH_API cloth_result cloth_world_set_frame_budget(cloth_world_id id, float milliseconds) {
    return with_world(__func__, id, [&](World& world) -> Status {
        Status s = check_non_negative(milliseconds, "milliseconds");
        if (!s.ok()) return s;
        world.set_frame_budget(milliseconds);
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
    return p;
}

CLOTH_API cloth_result cloth_set_quality_policy(cloth_id id, const cloth_quality_policy* policy) {
    return with_cloth(__func__, id, [&](ClothInstance& cloth) -> Status {
        if (!policy) return null_error("policy");
        if (policy->struct_size != sizeof(cloth_quality_policy)) {
            return Status::error(CLOTH_ERROR_INVALID_DESC,
                                 "cloth_quality_policy.struct_size is %u, expected %zu", policy->struct_size,
                                 sizeof(cloth_quality_policy));
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
        cloth.set_quality_policy(core);
        return {};
    });
}

}  // extern "C"
