#include "step/frame_decision.h"

#include <algorithm>
#include <cmath>

#include "solve/solver_default.h"
#include "solve/strain_limit.h"

namespace cloth {

namespace {

// Substeps past the substep gamma run backward Euler, whether the
// default's most substeps, a cap or a partner in contact put them there.
void hold_theta_within_gamma(FrameDecision& d, const FrameInputs& in) {
    if (in.host.kind == CLOTH_SOLVER_DEFAULT &&
        !within_substep_gamma(in.dt, in.stiffness_per_mass, d.solver.substeps, in.multigrid))
        d.solver.theta = 1.0f;
}

}  // namespace

FrameDecision decide_frame(const FrameInputs& in) {
    const BudgetBounds& budget = in.budget;
    const bool by_default = in.host.kind == CLOTH_SOLVER_DEFAULT;
    FrameDecision d;
    d.solver = resolve_solver(in.host, in.dt, in.stiffness_per_mass, in.multigrid);
    // A kind the host chose runs the budget's rung where it has one.
    if (!by_default && budget.iterations > 0) d.solver.iterations = budget.iterations;
    if (!by_default && budget.substeps > 0) d.solver.substeps = budget.substeps;
    // The default's own choice within a quality policy's maxima (the
    // host's bounds), then the budget's caps on it: the host's budget wins.
    if (budget.enabled && by_default) {
        d.solver.iterations = std::min(d.solver.iterations, budget.max_iterations);
        d.solver.substeps = std::min(d.solver.substeps, budget.max_substeps);
    }
    d.own_iterations = d.solver.iterations;
    d.own_substeps = d.solver.substeps;
    if (by_default && budget.iterations > 0)
        d.solver.iterations = std::min(d.solver.iterations, budget.iterations);
    if (by_default && budget.substeps > 0) d.solver.substeps = std::min(d.solver.substeps, budget.substeps);
    // Below the floor of the ladder the budget moves the cloth along: its
    // top is the default's own choice, or the policy's maxima.
    const uint32_t top = by_default ? d.own_iterations : budget.max_iterations;
    d.below_floor = budget.enabled && d.solver.iterations < ladder_floor(top, budget.min_iterations);
    // A quiet cloth's fewer substeps come last: its own choice, which a
    // budget's ladder starts from, is that of a moving cloth.
    d.started_slow = by_default && in.starts_slow;
    if (in.last.quiet && d.started_slow && in.pins_slow) {
        const SolverSettings quiet =
            resolve_solver(in.host, in.dt, in.stiffness_per_mass, in.multigrid, true);
        if (quiet.substeps < d.solver.substeps) {
            d.solver.substeps = quiet.substeps;
            d.solver.theta = quiet.theta;
        }
    }
    d.capped_substeps = d.solver.substeps;
    // Down to the ladder's floor a budget's cap never stretches a substep
    // past longest_capped_substep (a slow update rate's step is long:
    // solver_default.h); below it the budget wins and the strain gives.
    if (by_default && budget.substeps > 0 && !d.below_floor) {
        const float longest =
            longest_capped_substep(in.last.decision.h, in.fastest_free_speed, in.mean_rest_length);
        const auto least = static_cast<uint32_t>(std::min(
            std::ceil(static_cast<double>(in.dt) / longest - 1e-4), static_cast<double>(d.own_substeps)));
        d.solver.substeps = std::max(d.solver.substeps, least);
    }
    hold_theta_within_gamma(d, in);
    d.h = in.dt / static_cast<float>(d.solver.substeps);
    // The passes past those asked for are quality the budget cannot
    // predict: below the floor, behind a solve that no longer holds the
    // cloth, they grow, and the frame with them (docs/vehicle_flag.md).
    const uint32_t asked = d.solver.strain_limit.iterations;
    d.strain_passes_cap = d.below_floor ? asked : kStrainLimitMorePasses * asked;
    return d;
}

FrameDecision share_substeps(const FrameDecision& decision, uint32_t substeps, const FrameInputs& in) {
    if (substeps <= decision.solver.substeps) return decision;
    FrameDecision d = decision;
    d.solver.substeps = substeps;
    hold_theta_within_gamma(d, in);
    d.h = in.dt / static_cast<float>(substeps);
    return d;
}

}  // namespace cloth
