// The frame-budget policy: after each frame of a world with a budget, lower
// or raise the Jacobi iterations and substeps of the cloths whose quality
// policy is enabled, within their bounds, so the step stays inside the
// budget. It works from the measured cost of the frame just run: the step's
// wall time and each cloth's share of the task time, with a cloth's cost
// taken as proportional to substeps * (iterations + kFixedStages).
//
//   over budget          lower cloths one notch each, the most expensive
//                        first, until the predicted step is at 90% of it
//   below 70% of budget  for kCalmFrames frames in a row: raise cloths one
//                        notch each while the predicted step stays at or
//                        below 85% of it
//
// Lowering takes iterations first, then substeps; raising undoes it in the
// reverse order. The hysteresis band (70%..100%) keeps it from oscillating.
// A lowered cloth also runs only the strain-limit passes asked for
// (ClothInstance::quality_lowered): the extra passes would grow as the
// substeps shrink, which the cost model above cannot see.
// A CLOTH_SOLVER_DEFAULT cloth picks its own iterations and substeps every
// frame: the policy lowers from what it ran and keeps the result as caps on
// that choice, and raising ends when the caps reach it
// (ClothInstance::quality_settings).
#pragma once

#include <cstdint>

#include "step/cloth_instance.h"

namespace cloth {

struct BudgetCloth {
    ClothInstance* cloth;
    int64_t cost_ns;  // task time of the last frame
};

class BudgetPolicy {
  public:
    static constexpr uint32_t kCalmFrames = 5;
    static constexpr double kFixedStages = 3.0;  // air, forces + assembly, integration, in sweep units

    // cloths: every awake cloth of the frame (policy or not), `count` of them.
    void after_frame(double budget_ms, double step_ms, BudgetCloth* cloths, uint32_t count);

  private:
    uint32_t calm_frames_ = 0;
};

}  // namespace cloth
