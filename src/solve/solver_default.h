// What CLOTH_SOLVER_DEFAULT runs (docs/method.md, "What the default adds").
// The choice depends on gamma = h^2 k_max / m_min, the stiffest spring over
// the lightest free particle: the number that decides whether a cheap step
// holds (docs/method.md, "Where one iteration stops holding"). The
// thresholds below are measured in docs/measurements.md, "Substeps and the
// integrator".
#pragma once

#include "forces/material.h"
#include "solve/solver_settings.h"

namespace cloth {

// max over spring kinds of k, over the lightest free particle's mass (0 if
// every particle is pinned or no spring is stiff).
float stiffness_over_mass(const Material& material, float lightest_free_mass);
// The lightest free particle's mass (0 if every particle is pinned).
float lightest_free_mass(const float* mass, const float* pinned, uint32_t count);

// The default: PCG preconditioned by multigrid (multigrid.h), at most
// kDefaultMultigridIterations iterations (fewer once kDefaultPcgTolerance is
// met), S = ceil(sqrt(gamma / kDefaultMultigridSubstepGamma)) substeps for
// the frame's gamma (at most kDefaultMaxSubsteps), none longer than
// kDefaultLongestSubstep. Multigrid's iteration count does not grow with
// stiffness, so the substeps are there for accuracy: the longest substep
// sets the error, and the gamma term adds substeps only where a stiff cloth
// would gain energy, as two substeps of gamma 67500 did
// (docs/measurements.md, "A substep gamma of up to 20000"; docs/method.md,
// "Substeps from gamma").
constexpr uint32_t kDefaultMultigridIterations = 5;
constexpr double kDefaultMultigridSubstepGamma = 20000.0;
// A cloth of at most Multigrid::kCoarsestSize particles has no coarse
// levels and gets block-Jacobi PCG: a substep gamma of 700 with 16
// iterations keeps a 1 kg 64x64 cloth at 1e4 N/m under 10 % strain without
// energy gain.
constexpr uint32_t kDefaultPcgIterations = 16;
constexpr float kDefaultPcgTolerance = 1e-4f;
// The default's stop in physical units (SolverSettings::velocity_tolerance):
// a solve stops once no particle's velocity change can be off by more than
// this, whatever the relative residual. A cloth near rest has a small
// right-hand side, which the relative stop must still cut 1e4-fold; this
// lets it run the fewer iterations its motion needs. r.z is about the
// error's W-norm, which over-counts stiff error modes, so the bound on the
// lightest particle is a loose one: a still 64x64 cloth runs one iteration.
constexpr float kDefaultVelocityTolerance = 1e-2f;
constexpr double kDefaultSubstepGamma = 700.0;
constexpr uint32_t kDefaultMaxSubsteps = 16;
// Two substeps at 60 Hz, which the flag in wind needs (one converged
// substep of 1/60 s is 186 mm from the reference at 64x64). It also bounds
// how far a long step pulls the strain cable, which gamma does not count
// (docs/measurements.md, "The stability map").
constexpr double kDefaultLongestSubstep = 1.0 / 120.0;
// A quiet cloth (ClothInstance::starts_quiet: no free particle faster
// than kDefaultQuietSpeed at this frame's start and the last's, no spring
// past the strain limit, pins as slow, no change by the host, no bodies
// to follow, no skin) takes substeps of up to a 60 Hz frame whatever its
// gamma, so its solve and strain limit run once a frame, not in each of
// its substeps; past the gamma limit the substep runs backward Euler,
// whose damping a still cloth does not see. Whatever pulls it ends the
// quiet in that frame or the next.
constexpr double kDefaultQuietLongestSubstep = 1.0 / 60.0;
constexpr float kDefaultQuietSpeed = 1e-2f;  // m/s, as kDefaultVelocityTolerance
// Softer springs stretch more than 10 % near the pins even when solved
// exactly (a corner spring of a 64x64, 1 kg cloth at 1e3 N/m carries ~5 N:
// strain ~ F / (k l0) ~ 0.3), so the default limits strain unless the user
// set a limit.
constexpr float kDefaultStrainLimit = 0.08f;
constexpr uint32_t kDefaultStrainLimitPasses = 4;
// The strain cable's stiffness as a multiple of the spring's own
// (springs.h): enough to hold a 128x128 cloth at 1e3 N/m near the 8 %
// limit, and the implicit solvers stay as stable as without it
// (docs/measurements.md, "The strain cable").
constexpr float kStrainCableStiffness = 100.0f;
// The default's cable pulls from this fraction of the strain limit, its
// stiffness in the Jacobian kStrainCableApproach of the limit before that
// (springs.h; 0.002 strain at the default's 8 %): a cloth whose springs
// cannot carry it within the limit then rests on the cable just inside
// the limit instead of being put back by the passes every substep, which
// never let it settle.
constexpr float kStrainCableInside = 0.975f;
constexpr float kStrainCableApproach = 0.025f;
// The theta step (integrate.h): backward Euler's own damping, not the
// solve, is most of its error in calm scenes; at 0.7 the 64x64 flag in
// wind is 121 mm from the converged reference at the same cost
// (docs/measurements.md, "The theta step"). A less damped cloth snaps
// harder when something yanks it, so substeps where nothing holds the
// strain, or past the substep gamma (the default's most substeps, or a
// cap, put them there), run backward Euler (docs/method.md, "The theta
// step"; resolve_solver and step/frame_plan.cpp).
constexpr float kDefaultTheta = 0.7f;
// The ceiling on a substep a frame budget's caps lengthen (s): a flag
// stepping every 8th frame at 60 Hz in one substep of 2/15 s stretches to
// 0.14, in two of 1/15 s to 0.10 (docs/measurements.md, "A slow rate's
// substeps").
constexpr float kLongestCappedSubstep = 1.0f / 15.0f;
// Below that ceiling, a capped substep is no longer than
// kCappedSubstepGrowth times the cloth's last substep, nor than the time
// its fastest free particle takes to cross kCappedSubstepEdges mean
// structural rest lengths (its speed relative to its pins, which a carrier
// may move fast): a flag that flapped in short substeps and is then given
// 1/15 s ones passes the limit before their damping has calmed it
// (docs/measurements.md, "A slow rate's first steps"). These two bounds
// never go below kCappedSubstepBoundFloor, so that a 60 Hz frame's single
// substep stays the budget's to take.
constexpr float kCappedSubstepGrowth = 2.0f;
constexpr float kCappedSubstepEdges = 3.0f;
constexpr float kCappedSubstepBoundFloor = 1.0f / 60.0f;
// The longest substep a budget's caps leave a cloth whose last substep
// was `last_substep` (0: none yet), whose fastest free particle moves at
// `fastest_speed` relative to its pins, and whose structural springs are
// `rest_length` long on average.
float longest_capped_substep(float last_substep, float fastest_speed, float rest_length);

// Whether `substeps` of a step of `dt` bring the substep's gamma within the
// default's limit: past it the theta step gains energy, and the default
// runs backward Euler (theta 1).
bool within_substep_gamma(float dt, float stiffness_per_mass, uint32_t substeps, bool multigrid);

// The settings a step of `dt` runs with: `requested` itself unless its kind
// is CLOTH_SOLVER_DEFAULT, in which case kind, preconditioner, iterations
// and substeps follow from gamma as above (requested.substeps is a lower
// bound), and theta is kDefaultTheta unless the strain limit is off or
// the substep gamma stays past its limit at kDefaultMaxSubsteps;
// `multigrid`: whether the cloth has coarse levels; `quiet`: whether the
// cloth is quiet (kDefaultQuietLongestSubstep instead of
// kDefaultLongestSubstep).
SolverSettings resolve_solver(const SolverSettings& requested, float dt, float stiffness_per_mass,
                              bool multigrid, bool quiet = false);

}  // namespace cloth
