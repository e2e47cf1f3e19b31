// What the garments' step costs beyond the budget table, printed after
// it: the cost per free particle at p50, the strain limiter's passes a
// frame and the frames they stopped at their cap, per garment, and the
// step standing still after the teleport against the idle start.
#pragma once

#include <cstdint>
#include <vector>

#include "skeleton.h"
#include "wardrobe.h"

namespace character_cloth {

class StepEffort {
  public:
    // Of `cape` and `skirt` (which outlive it).
    StepEffort(const Garment& cape, const Garment& skirt) : garments_{&cape, &skirt} {}

    // After the step of a frame in `phase`, which took `step_ms`.
    void observe(Phase phase, double step_ms);
    // `step_ms`: every frame's step; `free_particles`: the garments'
    // particles not sewn on; `frames`: the frames run.
    void print(const std::vector<double>& step_ms, uint32_t free_particles, int frames) const;

  private:
    const Garment* garments_[2];
    std::vector<double> strain_passes_[2], idle_ms_, still_ms_;
    int capped_frames_[2] = {0, 0};
};

}  // namespace character_cloth
