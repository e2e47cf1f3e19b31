// A cloth's side of the frame budget (cloth_quality.h).
#include "step/cloth_quality.h"

#include <algorithm>

namespace cloth {

void ClothQuality::set_policy(const QualityPolicy& policy) {
    policy_ = policy;
    costs_.clear();
    wanted_rate_ = 0;
    rate_cut_ = false;
    // A default solver the policy had capped goes back to its own choice.
    solver_.default_iteration_cap = solver_.default_substep_cap = 0;
    if (!policy.enabled) return;
    solver_.iterations = std::clamp(solver_.iterations, policy.min_iterations, policy.max_iterations);
    solver_.substeps = std::clamp(solver_.substeps, policy.min_substeps, policy.max_substeps);
}

SolverSettings ClothQuality::settings() const {
    if (solver_.kind != CLOTH_SOLVER_DEFAULT) return solver_;
    SolverSettings out = solver_;
    out.iterations =
        solver_.default_iteration_cap > 0 ? solver_.default_iteration_cap : frame_.decision.solver.iterations;
    out.substeps =
        solver_.default_substep_cap > 0 ? solver_.default_substep_cap : frame_.decision.solver.substeps;
    return out;
}

void ClothQuality::set_settings(const SolverSettings& settings) {
    if (solver_.kind != CLOTH_SOLVER_DEFAULT) {
        solver_ = settings;
        return;
    }
    // Caps at or above the default's own choice of the last frame change
    // nothing: drop them, so the default follows its own choice again.
    const bool below = settings.iterations < frame_.decision.own_iterations ||
                       settings.substeps < frame_.decision.own_substeps;
    solver_.default_iteration_cap = below ? settings.iterations : 0;
    solver_.default_substep_cap = below ? settings.substeps : 0;
}

QualityLadder ClothQuality::ladder() const {
    const QualityRung top = solver_.kind == CLOTH_SOLVER_DEFAULT
                                ? QualityRung{frame_.decision.own_iterations, frame_.decision.own_substeps}
                                : QualityRung{policy_.max_iterations, policy_.max_substeps};
    return {top, policy_.min_iterations, policy_.min_substeps, policy_.max_update_rate};
}

bool ClothQuality::can_rise() const {
    return solver_.kind != CLOTH_SOLVER_DEFAULT || solver_.default_iteration_cap > 0 ||
           solver_.default_substep_cap > 0 || (policy_.max_update_rate > 1 && rate() > 1);
}

BudgetBounds ClothQuality::bounds() const {
    BudgetBounds b;
    b.enabled = policy_.enabled;
    b.min_iterations = policy_.min_iterations;
    b.max_iterations = policy_.max_iterations;
    b.max_substeps = policy_.max_substeps;
    b.iteration_cap = solver_.default_iteration_cap;
    b.substep_cap = solver_.default_substep_cap;
    return b;
}

}  // namespace cloth
