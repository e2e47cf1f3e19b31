// The frame-budget policy: after each frame of a world with a budget, lower
// or raise the iterations and substeps of the cloths whose quality policy
// is enabled, within their bounds, so the step stays inside the budget.
//
// Quality is a ladder of (iterations, substeps) rungs (quality_ladder.h):
// from the top (the policy's maximum, or what CLOTH_SOLVER_DEFAULT chooses
// by itself within that maximum) the iterations fall to half the top's,
// then a substep goes and the iterations come back, and so on: below about
// half its iterations a solve stops holding the strain limit, while a
// substep costs more than the iterations it would run (on the vehicle
// flag's course 1 iteration at 2 substeps costs more than 5 at 1 and holds
// less; docs/measurements.md, "The ladder").
//
// A rung's cost is what the cloth's frames cost there lately
// (QualityCosts), or at a rung it has not run a model of its last frame:
// its task time split into the solve stages (a cost per iteration and
// substep) and the rest (a cost per substep).
//
//   over budget          each cloth, the least relevant first (of equals
//                        the most expensive), goes down the ladder until the predicted step is at
//                        kLowerTo of the budget, predicted from its rung's
//                        usual cost (a spike moves it less than its own
//                        cost says); below the floor only after
//                        kLoadOverruns of the last kLoadWindow frames
//                        over budget (a load, not a spike),
//                        and one rung a frame
//   within budget        the most relevant cloth below its top rises a
//   (not calm)           rung if lowering less relevant cloths (to their
//                        floors, with their rates) pays for it within
//                        kRaiseTo of the budget: the most relevant cloth
//                        keeps its top as long as the others can pay
//   below kCalmBelow     for kCalmFrames frames in a row: each cloth, the
//                        most relevant first (of equals the cheapest),
//                        goes one rung up if the predicted
//                        step stays at or below kRaiseTo of the budget (a
//                        rung that ran over is remembered, and not tried
//                        again until forgotten)
//
// Below the floor a cloth's strain limit runs only the passes asked for
// (FrameDecision::below_floor): behind a solve that no longer
// holds the cloth the extra passes grow with every rung cut, which no
// prediction sees (docs/vehicle_flag.md). A CLOTH_SOLVER_DEFAULT cloth
// picks its own iterations and substeps every frame: the policy keeps its
// rung as caps on that choice, and raising ends when the caps reach it
// (ClothQuality::settings).
#pragma once

#include <cstdint>

#include "scene/scene_cloth.h"

namespace cloth {

struct BudgetCloth {
    SceneCloth* cloth;
    int64_t cost_ns;   // task time of the last frame
    int64_t solve_ns;  // the part of it in solve stages
    float relevance;   // World::relevance: the least relevant is lowered first
};

class BudgetPolicy {
  public:
    static constexpr uint32_t kCalmFrames = 5;
    static constexpr double kLowerTo = 0.75;
    static constexpr double kCalmBelow = 0.7;
    static constexpr double kRaiseTo = 0.7;
    // Below the floor the solve no longer holds the cloth: only this many
    // frames over budget among the last kLoadWindow (a load, not a spike)
    // take a cloth there.
    static constexpr uint32_t kLoadWindow = 30;
    static constexpr uint32_t kLoadOverruns = 24;

    // cloths: every awake cloth of the frame (policy or not), `count` of them.
    // `frame`: the world's frame count (the cost memory's clock).
    void after_frame(double budget_ms, double step_ms, uint64_t frame, BudgetCloth* cloths, uint32_t count);

  private:
    // Cloths that may pay for one raise of the most relevant.
    static constexpr uint32_t kMostRebalanced = 64;

    void decide(double budget_ms, double step_ms, uint64_t frame, int64_t total_ns, BudgetCloth* cloths,
                uint32_t count);
    // Within budget but not calm: the most relevant cloth below its top
    // rises one rung if lowering less relevant ones (to their floors, with
    // their rates) keeps the predicted step at kRaiseTo of the budget.
    void rebalance(double budget_ms, double predicted, uint64_t frame, double ms_per_ns, BudgetCloth* cloths,
                   uint32_t count);
    uint32_t calm_frames_ = 0;
    uint32_t recent_overruns_ = 0;  // bit k: the frame k frames ago overran
};

}  // namespace cloth
