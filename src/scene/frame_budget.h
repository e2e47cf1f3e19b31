// A world's frame budget (cloth.h, "Frame budget"): the time a frame's
// step may take, the frames that took longer, the viewer whose distance
// scales each cloth's importance, and the policy (budget_policy.h) that
// moves the cloths along their quality ladders after each frame.
#pragma once

#include <cstdint>

#include "base/host_allocator.h"
#include "base/math.h"
#include "scene/budget_policy.h"
#include "scene/scene_cloth.h"

namespace cloth {

class FrameBudget {
  public:
    // Room for `max_cloths` cloths: a frame's decision allocates nothing.
    FrameBudget(const HostMemory* memory, uint32_t max_cloths);

    // Per-frame budget in milliseconds (0: none); with one, every frame
    // reports overrun and the policy adjusts policy-enabled cloths.
    void set_ms(double ms) { ms_ = ms; }
    double ms() const { return ms_; }
    uint64_t overrun_frames() const { return overrun_frames_; }

    // The viewer whose distance scales each cloth's importance (null:
    // none, every cloth counts by its importance).
    void set_viewer(const Vec3* position);
    // What a cloth counts for: its importance times, with a viewer, its
    // bounding sphere's radius over its distance (at most 1).
    float relevance(const SceneCloth& cloth) const;

    // After a frame whose step took `step_ms`: whether it ran over (and counted).
    bool count_frame(double step_ms);
    // The policy's decision over the frame's stepping cloths, each given
    // with its task time and the part of it in solve stages; then
    // cloths() lists them, for the rates the policy wants.
    void start_decision() { cloths_.clear(); }
    void add(SceneCloth* cloth, int64_t cost_ns, int64_t solve_ns) {
        cloths_.push_back(BudgetCloth{cloth, cost_ns, solve_ns, relevance(*cloth)});
    }
    void decide(double step_ms, uint64_t frame);
    const HostVector<BudgetCloth>& cloths() const { return cloths_; }

  private:
    double ms_ = 0;
    uint64_t overrun_frames_ = 0;
    bool has_viewer_ = false;
    Vec3 viewer_ = Vec3::Zero();
    BudgetPolicy policy_;
    HostVector<BudgetCloth> cloths_;
};

}  // namespace cloth
