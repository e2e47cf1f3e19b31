// A cloth's side of the frame budget (cloth_quality.h).
#include "scene/cloth_quality.h"

#include <algorithm>

namespace cloth {

void ClothQuality::set_policy(const QualityPolicy& policy) {
    const SolverSettings ran = settings();
    policy_ = policy;
    costs_.clear();
    wanted_rate_ = 0;
    rate_cut_ = false;
    // A default solver the policy had capped goes back to its own choice.
    if (by_default()) iterations_ = substeps_ = 0;
    if (!policy.enabled || by_default()) return;
    iterations_ = std::clamp(ran.iterations, policy.min_iterations, policy.max_iterations);
    substeps_ = std::clamp(ran.substeps, policy.min_substeps, policy.max_substeps);
}

void ClothQuality::host_set_solver() {
    costs_.clear();
    iterations_ = substeps_ = 0;
}

BudgetBounds ClothQuality::bounds() const {
    BudgetBounds b;
    b.enabled = policy_.enabled;
    b.min_iterations = policy_.min_iterations;
    b.max_iterations = policy_.max_iterations;
    b.max_substeps = policy_.max_substeps;
    b.iterations = iterations_;
    b.substeps = substeps_;
    return b;
}

SolverSettings ClothQuality::settings() const {
    SolverSettings out = cloth_.solver();
    if (!by_default()) {
        if (iterations_ > 0) out.iterations = iterations_;
        if (substeps_ > 0) out.substeps = substeps_;
        return out;
    }
    const FrameDecision& last = cloth_.last_frame_decision();
    out.iterations = iterations_ > 0 ? iterations_ : last.solver.iterations;
    out.substeps = substeps_ > 0 ? substeps_ : last.solver.substeps;
    return out;
}

void ClothQuality::set_settings(const SolverSettings& settings) {
    if (!by_default()) {
        iterations_ = settings.iterations;
        substeps_ = settings.substeps;
        return;
    }
    // Caps at or above the default's own choice of the last frame change
    // nothing: drop them, so the default follows its own choice again.
    const FrameDecision& last = cloth_.last_frame_decision();
    const bool below = settings.iterations < last.own_iterations || settings.substeps < last.own_substeps;
    iterations_ = below ? settings.iterations : 0;
    substeps_ = below ? settings.substeps : 0;
}

QualityLadder ClothQuality::ladder() const {
    const FrameDecision& last = cloth_.last_frame_decision();
    const QualityRung top = by_default() ? QualityRung{last.own_iterations, last.own_substeps}
                                         : QualityRung{policy_.max_iterations, policy_.max_substeps};
    return {top, policy_.min_iterations, policy_.min_substeps, policy_.max_update_rate};
}

bool ClothQuality::can_rise() const {
    return !by_default() || iterations_ > 0 || substeps_ > 0 || (policy_.max_update_rate > 1 && rate() > 1);
}

}  // namespace cloth
