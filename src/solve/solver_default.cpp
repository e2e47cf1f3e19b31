#include "solve/solver_default.h"

#include <algorithm>
#include <cmath>

namespace cloth {

float lightest_free_mass(const float* mass, const float* pinned, uint32_t count) {
    float m = 0;
    for (uint32_t i = 0; i < count; ++i) {
        if (pinned[i] != 0.0f) continue;
        m = m == 0 ? mass[i] : std::min(m, mass[i]);
    }
    return m;
}

float stiffness_over_mass(const Material& material, float lightest_free_mass) {
    float k = 0;
    for (const SpringParams& s : material.springs) k = std::max(k, s.stiffness);
    return lightest_free_mass > 0 ? k / lightest_free_mass : 0.0f;
}

float longest_capped_substep(float last_substep, float fastest_speed, float rest_length) {
    float longest = kLongestCappedSubstep;
    if (last_substep > 0) longest = std::min(longest, kCappedSubstepGrowth * last_substep);
    if (fastest_speed > 0 && rest_length > 0)
        longest = std::min(longest, kCappedSubstepEdges * rest_length / fastest_speed);
    return std::max(longest, kCappedSubstepBoundFloor);
}

bool within_substep_gamma(float dt, float stiffness_per_mass, uint32_t substeps, bool multigrid) {
    const double gamma_limit = multigrid ? kDefaultMultigridSubstepGamma : kDefaultSubstepGamma;
    const double gamma = static_cast<double>(dt) * dt * stiffness_per_mass;
    return gamma <= gamma_limit * double(substeps) * substeps;
}

SolverSettings resolve_solver(const SolverSettings& requested, float dt, float stiffness_per_mass,
                              bool multigrid, bool quiet) {
    if (requested.kind != CLOTH_SOLVER_DEFAULT) return requested;
    SolverSettings out = requested;
    out.kind = CLOTH_SOLVER_PCG;
    out.multigrid = multigrid;
    out.iterations = multigrid ? kDefaultMultigridIterations : kDefaultPcgIterations;
    out.cg_tolerance = kDefaultPcgTolerance;
    out.velocity_tolerance = kDefaultVelocityTolerance;
    const double gamma_limit = multigrid ? kDefaultMultigridSubstepGamma : kDefaultSubstepGamma;
    // Substeps: the fewest that bring the substep's gamma to the limit
    // (gamma falls with the square of the substep count). The gamma is the
    // springs' own: a taut strain cable is 101 times as stiff, and the choice
    // does not count it (it would multiply the cost of every stiff cloth);
    // kDefaultLongestSubstep bounds the cable's pull instead, and
    // docs/stability.md maps where this holds.
    const double gamma = static_cast<double>(dt) * dt * stiffness_per_mass;
    const double wanted = quiet
                              ? std::ceil(static_cast<double>(dt) / kDefaultQuietLongestSubstep - 1e-6)
                              : std::max(std::ceil(std::sqrt(gamma / gamma_limit)),
                                         std::ceil(static_cast<double>(dt) / kDefaultLongestSubstep - 1e-6));
    const uint32_t substeps = static_cast<uint32_t>(
        std::min<double>(std::max(wanted, 1.0), static_cast<double>(kDefaultMaxSubsteps)));
    out.substeps = std::max(requested.substeps, substeps);
    if (!out.strain_limit.chosen)
        out.strain_limit = StrainLimit{kDefaultStrainLimit, kDefaultStrainLimitPasses};
    const bool limited = out.strain_limit.max_strain > 0 && out.strain_limit.iterations > 0;
    // Past the substep gamma above (the substep cap binds) the theta step
    // gains energy and backward Euler's damping holds it
    // (docs/measurements.md, "Backward Euler past the substep cap").
    out.theta = limited && within_substep_gamma(dt, stiffness_per_mass, out.substeps, multigrid)
                    ? kDefaultTheta
                    : 1.0f;
    return out;
}

}  // namespace cloth
