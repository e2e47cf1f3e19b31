// What CLOTH_SOLVER_DEFAULT runs. The choice depends on how stiff the
// cloth is for its mass, through the particle gamma
//     Gamma = h^2 max over free particles i of (sum of k over i's springs) / m_i,
// Gershgorin's bound on h^2 times the largest eigenvalue of M^-1 K, the
// number that decides whether a cheap step holds (algorithm.md 6). See
// docs/accuracy.md for the measurements behind the thresholds.
#pragma once

#include "fabric/fabric.h"
#include "forces/material.h"
#include "solve/solver_settings.h"

namespace cloth {

// max over free particles of (sum of k over the particle's springs) / m
// (0 if every particle is pinned or no spring is stiff). A pass over the
// incidence lists: callers keep the result until the material, the masses
// or the pins change.
float stiffness_over_mass(const Fabric& fabric, const Material& material, const float* mass,
                          const float* pinned);

// The default: PCG with at most kDefaultPcgIterations iterations (stopping
// early at kDefaultPcgTolerance) and S = ceil(sqrt(Gamma / kDefaultSubstepGamma))
// substeps, Gamma of the whole frame, so that each substep's Gamma is at
// most kDefaultSubstepGamma (up to kDefaultMaxSubsteps).
// Measured in docs/accuracy.md: in a grid with every spring kind at k, Gamma
// is 30 dt^2 k / m of an interior particle (a free corner has 5 springs and
// a sixth of the mass), and a threshold of 14 000, an interior dt^2 k / m of
// about 470 per substep, with 16 PCG iterations keeps a 1 kg cloth under
// 10 % strain and within 0.01 J of its starting energy over 600 frames at
// 64x64 and 128x128, 1e3 and 1e4 N/m (21 000 let a hanging 128x128 cloth
// gain 0.014 J). The threshold used to be 700 on dt^2 k_max / m_min, the
// lightest particle's: that ran 1.5-2x the substeps for the same hold. Softer
// springs stretch more than 10 % near the pins even when solved exactly (a
// corner spring of a 64x64, 1 kg cloth at 1e3 N/m carries ~5 N: strain ~
// F / (k l0) ~ 0.3), so the default also limits strain to
// kDefaultStrainLimit unless the user set a limit.
constexpr uint32_t kDefaultPcgIterations = 16;
constexpr float kDefaultPcgTolerance = 1e-4f;
constexpr double kDefaultSubstepGamma = 14000.0;
constexpr uint32_t kDefaultMaxSubsteps = 16;
// And never a substep longer than this, whatever Gamma: at 1/20 s the
// strain cable (101 times the springs' stiffness, which Gamma does not
// count) is left unconverged by 16 iterations, and a 32x32 cloth at
// Gamma 30 x 250 per substep gained 354 J (docs/stability.md).
constexpr double kDefaultLongestSubstep = 1.0 / 30.0;
constexpr float kDefaultStrainLimit = 0.08f;
constexpr uint32_t kDefaultStrainLimitPasses = 4;
// The strain cable's stiffness as a multiple of the spring's own
// (springs.h): at 10x a 128 x 128 cloth at 1e3 N/m still reached 9.5 %
// strain with the 8 % limit, at 100x 8.3 %, and the implicit solvers stay
// as stable as without it (docs/accuracy.md).
constexpr float kStrainCableStiffness = 100.0f;

// The settings a step of `dt` runs with: `requested` itself unless its kind
// is CLOTH_SOLVER_DEFAULT, in which case kind, iterations and substeps
// follow from Gamma as above (requested.substeps is a lower bound).
SolverSettings resolve_solver(const SolverSettings& requested, float dt, float stiffness_per_mass);

}  // namespace cloth
