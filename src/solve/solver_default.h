// What CLOTH_SOLVER_DEFAULT runs. The choice depends on the stiffest
// spring over the lightest free particle through
//     gamma = h^2 k_max / m_min   (algorithm.md 6),
// the number that decides whether a cheap step holds. See docs/accuracy.md
// for the measurements behind the thresholds.
#pragma once

#include "forces/material.h"
#include "solve/solver_settings.h"

namespace cloth {

// max over spring kinds of k, over the lightest free particle's mass (0 if
// every particle is pinned or no spring is stiff).
float stiffness_over_mass(const Material& material, const float* mass, const float* pinned, uint32_t count);

// The default: PCG preconditioned by multigrid (multigrid.h) with at most
// kDefaultMultigridIterations iterations (stopping early at
// kDefaultPcgTolerance) and S = ceil(sqrt(gamma / kDefaultMultigridSubstepGamma))
// substeps, gamma = dt^2 k_max / m_min of the whole frame (up to
// kDefaultMaxSubsteps), and no substep longer than kDefaultLongestSubstep.
// A cloth too small for coarse levels (at most Multigrid::kCoarsestSize
// particles) gets block-Jacobi PCG with kDefaultPcgIterations and
// kDefaultSubstepGamma instead.
//
// Multigrid converges in a number of iterations that does not grow with
// stiffness (frontier.md), so its substeps are there for accuracy, not to
// let the solve converge, and implicit Euler's error follows the substep's
// length, not the resolution: the longest substep (below) sets the
// accuracy, the same at every resolution, and the substep gamma only adds
// substeps where a stiff cloth would gain energy. Measured
// (docs/accuracy.md): with the theta step and substeps of at most
// 1/120 s, a substep gamma of up to 20000 leaves the stability map as it
// was at 8000 (no cell gaining energy or blowing up up to 100000) and holds
// the default matrix's hanging and falling cloths, where two substeps of
// a 128x128 falling cloth at about 30000 each gained 0.015 J and at 67500
// 0.21 J. Against 8000 it runs 1e4 N/m cloth at 64x64 in two substeps
// instead of three and at 128x128 in four instead of six (25-40 % less
// per frame), at the price of the longer substeps' error (64x64, 1e4 N/m:
// falling flat 30 -> 50 mm, flag 127 -> 146 mm from the converged
// reference); soft cloth (1e3 N/m) runs the two substeps of the 1/120 s
// bound either way.
constexpr uint32_t kDefaultMultigridIterations = 5;
constexpr double kDefaultMultigridSubstepGamma = 20000.0;
// Block Jacobi, measured in docs/accuracy.md: a substep gamma of ~700 with 16 PCG
// iterations keeps a 1 kg cloth under 10 % strain without energy gain at
// 64x64 and k = 1e4 N/m. Softer springs stretch more than 10 % near the pins
// even when solved exactly (a corner spring of a 64x64, 1 kg cloth at
// 1e3 N/m carries ~5 N: strain ~ F / (k l0) ~ 0.3), so the default also
// limits strain to kDefaultStrainLimit unless the user set a limit.
constexpr uint32_t kDefaultPcgIterations = 16;
constexpr float kDefaultPcgTolerance = 1e-4f;
constexpr double kDefaultSubstepGamma = 700.0;
constexpr uint32_t kDefaultMaxSubsteps = 16;
// And never a substep longer than this, whatever gamma: two substeps at
// 60 Hz, which the flag in wind needs (one substep of 1/60 s, converged,
// is 186 mm from the reference at 64x64). It also bounds how far a long
// step of a soft or heavy cloth pulls the strain cable (101 times the
// springs' stiffness, which gamma does not count): such cells of the
// stability map gained 16 J to 8e4 J at 1/10 s with one substep, and none
// gains with this bound (docs/stability.md).
constexpr double kDefaultLongestSubstep = 1.0 / 120.0;
constexpr float kDefaultStrainLimit = 0.08f;
constexpr uint32_t kDefaultStrainLimitPasses = 4;
// The strain cable's stiffness as a multiple of the spring's own
// (springs.h): at 10x a 128 x 128 cloth at 1e3 N/m still reached 9.5 %
// strain with the 8 % limit, at 100x 8.3 %, and the implicit solvers stay
// as stable as without it (docs/accuracy.md).
constexpr float kStrainCableStiffness = 100.0f;
// The default's theta step (integrate.h): backward Euler (theta = 1) damps
// a cloth's motion by itself, and that damping, not the solve, is most of
// the default's error against the converged reference in calm scenes. At
// 0.7 the 64x64 hanging, falling and flag scenes are 0.33 / 18 / 121 mm
// off instead of 0.82 / 31 / 141 at the same cost, and the stability map
// does not lose a cell (docs/accuracy.md). But the less damped cloth snaps
// harder when something yanks it (a pin moved 10 m, a flag's edge at
// 30 m/s), so a substep after one whose strain limiter ended past its
// promise runs backward Euler (step/frame_plan.cpp), as does every substep
// of a cloth without a strain limit (nothing watches its strain) and of a
// step whose substep gamma stays past kDefaultMultigridSubstepGamma at
// kDefaultMaxSubsteps (stiff cloth at long steps, where the theta step
// gained energy: 41 J on a 128x128, 1e7 N/m cloth falling flat at 1/10 s).
constexpr float kDefaultTheta = 0.7f;

// The settings a step of `dt` runs with: `requested` itself unless its kind
// is CLOTH_SOLVER_DEFAULT, in which case kind, preconditioner, iterations
// and substeps follow from gamma as above (requested.substeps is a lower
// bound), and theta is kDefaultTheta unless the strain limit is off;
// `multigrid`: whether the cloth has coarse levels.
SolverSettings resolve_solver(const SolverSettings& requested, float dt, float stiffness_per_mass,
                              bool multigrid);

}  // namespace cloth
