// What one frame of one cloth runs, decided before the frame starts, in
// one place (as Box2D's b2StepContext): the solver kind resolved, its
// iterations and substeps, theta and the strain limiter's most passes.
// A pure function of what the host set, the quality policy's bounds, the
// budget's caps, the record the last frame left and the cloth's motion;
// the frame reads the decision and changes none of it.
//
// Cloths in contact share their substeps (the most of the two): that rule
// is share_substeps, applied by the world before the frame starts.
#pragma once

#include <cstdint>

#include "solve/solver_settings.h"

namespace cloth {

// The bounds a quality policy puts on a cloth's iterations and substeps
// (scene/cloth_quality.h), and where the budget put the cloth within them:
// caps on CLOTH_SOLVER_DEFAULT's own choice, or what another kind runs
// instead of the host's settings (0: none).
struct BudgetBounds {
    bool enabled = false;
    uint32_t min_iterations = 1, max_iterations = 8;
    uint32_t max_substeps = 4;
    uint32_t iterations = 0, substeps = 0;
};

// The fewest iterations a budget's ladder runs above its fewest substeps:
// half the top's, rounded up, and at least the policy's least.
inline uint32_t ladder_floor(uint32_t top_iterations, uint32_t min_iterations) {
    const uint32_t fewest = min_iterations < top_iterations ? min_iterations : top_iterations;
    const uint32_t half = (top_iterations + 1) / 2;
    return half < fewest ? fewest : half > top_iterations ? top_iterations : half;
}

struct FrameDecision {
    // The settings the frame runs: CLOTH_SOLVER_DEFAULT resolved.
    SolverSettings solver;
    // What the default chose by itself within the policy's maxima, before
    // the caps: the top of a budget's ladder.
    uint32_t own_iterations = 0, own_substeps = 0;
    // The substeps a budget's cap left before the longest-substep floor
    // added any: the rung the budget put the cloth on.
    uint32_t capped_substeps = 0;
    // Whether the budget took the cloth below its ladder's floor (fewer
    // iterations than half the top's): a solve that no longer holds the
    // cloth, whose strain limiter then runs only the passes asked for.
    bool below_floor = false;
    // The strain limiter's most passes in a substep.
    uint32_t strain_passes_cap = 0;
    bool started_slow = false;  // for the next frame's record
    float h = 0;                // the substep, s
};

// What a frame leaves behind for the next frame's decision and for those
// who read what it ran (stats, the budget's ladder): the frame's own
// context is the frame's alone. Its strained and quiet flags are saved in
// snapshots.
struct LastFrameRecord {
    FrameDecision decision;  // what it ran (decision.h: 0 before the first frame)
    bool strained = false;   // its last substep ended past the strain limit's promise
    // It started slow with no spring past the strain limit, and the host
    // has not changed the cloth since.
    bool quiet = false;
    uint32_t strain_passes = 0;  // the strain limiter's passes over its substeps
    bool strain_capped = false;  // a substep's passes stopped at their cap
};

struct FrameInputs {
    SolverSettings host;  // what the host set
    float dt = 0;         // the frame, s
    // The material's stiffness over the lightest free mass (solver_default.h).
    float stiffness_per_mass = 0;
    bool multigrid = false;  // the cloth has coarse levels for PCG
    BudgetBounds budget;
    LastFrameRecord last;
    // The cloth's motion at the frame's start: no free particle faster
    // than kDefaultQuietSpeed (only for a default that may be quiet), no
    // pin moving faster over the frame, and the fastest free particle
    // relative to the pins (read only under a substep cap).
    bool starts_slow = false;
    bool pins_slow = false;
    float fastest_free_speed = 0;  // m/s
    float mean_rest_length = 0;    // m: the structural springs'
    float lightest_free_mass = 0;  // kg (for CLOTH_SOLVER_DEFAULT only)
};

FrameDecision decide_frame(const FrameInputs& in);

// The decision with at least `substeps` substeps (a cloth in contact with
// one that runs more): past the substep gamma they run backward Euler.
FrameDecision share_substeps(const FrameDecision& decision, uint32_t substeps, const FrameInputs& in);

}  // namespace cloth
