// Runs one standard scene (samples/common/scenes.h) with one solver setting
// and measures what the study reports: time per frame, strain, energy.
#pragma once

#include <string>
#include <vector>

#include "scenes.h"

namespace tradeoff {

struct RunResult {
    bool ok = true;           // every frame stepped without an error
    std::string error;        // first error, if any
    double ms_per_frame = 0;  // median wall time of cloth_step, ms
    double max_strain = 0;    // max over frames of the structural max strain
    // Grids: max over frames of |L - l0| / l0 over row and column
    // neighbours (compression counts too), read from the positions.
    double max_abs_strain = 0;
    double mean_strain = 0;       // max over frames of the structural mean |strain|
    double energy_gain = 0;       // max over frames of E(t) - E(0), J (kinetic + gravity + elastic)
    double energy_change = 0;     // E(end) - E(0), J
    double late_energy_rise = 0;  // max E over the second half minus max E over the first half, J
    uint32_t frames = 0;
    std::vector<float> positions;  // at the end
};

RunResult run_scene(const cloth_samples::SceneConfig& config, float dt, uint32_t frames);

// The unit every cost is quoted in: the median wall time of one frame of
// `dt` of the same scene (resolution, stiffness, wind) stepped with the
// paper's method, JACOBI with one sweep and one substep, timed here so the
// ratio compares two runs of the same process on the same machine state.
// Frames after a failed step (JACOBI k=1 blows up in some scenes) are not
// timed.
double jacobi_k1_ms(const cloth_samples::SceneConfig& config, float dt);

// max |L - l0| / l0 over the row and column neighbours of an n x n grid
// of 1 m sides (3 floats per particle): compression counts.
double grid_abs_strain(const std::vector<float>& x, uint32_t n);

// Root-mean-square distance between two position sets (same particle count).
double rms_distance(const std::vector<float>& a, const std::vector<float>& b);

const char* kind_name(cloth_solver_kind kind);

}  // namespace tradeoff
