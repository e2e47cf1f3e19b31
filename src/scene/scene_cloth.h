// One cloth in a world's scene: the cloth (step/cloth_instance.h), which
// steps a frame, and what the scene decides for it across frames, which
// the cloth never reads: how much it matters (importance), when it steps
// (its update rate and phase), what a reader sees between its steps (the
// interpolation of its last two states) and its side of the frame budget.
#pragma once

#include <memory>

#include "base/host_allocator.h"
#include "base/soa.h"
#include "scene/cloth_levels.h"
#include "scene/cloth_quality.h"
#include "scene/update_rate.h"
#include "step/cloth_instance.h"

namespace cloth {

class SceneCloth {
  public:
    SceneCloth(const HostMemory* memory, std::shared_ptr<const Fabric> fabric, const Material& material,
               const SolverSettings& solver, const AeroParams& aero);
    SceneCloth(const SceneCloth&) = delete;
    SceneCloth& operator=(const SceneCloth&) = delete;

    ClothInstance& cloth() { return cloth_; }
    const ClothInstance& cloth() const { return cloth_; }

    // How much the cloth matters to the host (>= 0, default 1): under a
    // frame budget the least important cloths are lowered first.
    float importance() const { return importance_; }
    void set_importance(float importance) { importance_ = importance; }

    // Update rate (update_rate.h): World::step steps the cloth only when
    // it is due, over begin_rate_step's frames. A rate above 1 allocates
    // the previous state and the reported positions (an allocation failure
    // changes nothing); back at rate 1 they go once the reports caught up
    // (here, or at the next step).
    const UpdateRate& update_rate() const { return rate_; }
    void set_update_rate(uint32_t rate, uint32_t phase);
    // Whether the quality policy may change the rate (its copies stay).
    bool rates_by_budget() const;
    // Starts the step of world frame `frame`; returns the frames it covers.
    uint32_t begin_rate_step(uint64_t frame);
    // The step failed and the cloth went back to its start.
    void undo_rate_step() { rate_.undo_step(); }
    // The state was set from outside (positions, a snapshot): reports show it at once.
    void settle() { rate_.settle(); }
    // The world's current frame, which the reported positions are at.
    void set_world_frame(uint64_t frame) { world_frame_ = frame; }
    // The positions a reader sees: the state, or between steps the
    // interpolation between the last two states at the world's frame; and
    // their unit area-weighted vertex normals.
    const Vec3Soa& reported_positions() const;
    const Vec3Soa& reported_normals() const { return cloth_.normals(reported_positions()); }

    // The cloth under a world's frame budget (cloth_quality.h). A new
    // quality policy wakes the cloth; one that may slow the update rate
    // allocates what a rate above 1 needs (a failure changes nothing), so
    // the budget's changes of rate allocate nothing; a rate the last
    // policy slowed goes back to 1.
    void set_quality_policy(const QualityPolicy& policy);
    ClothQuality& quality() { return quality_; }
    const ClothQuality& quality() const { return quality_; }
    // New solver settings from the host: the budget's caps and its memory
    // of what each rung cost go with the old ones. A new strain limit
    // keeps the budget's rung and clears only its memory.
    void set_solver(const SolverSettings& settings);
    void set_strain_limit(const StrainLimit& limit);

    // The level of detail it steps at (cloth_levels.h) and the cloth the
    // world steps: the full cloth at level 0, else the level's coarse one.
    ClothLevels& levels() { return levels_; }
    const ClothLevels& levels() const { return levels_; }
    ClothInstance& stepped() {
        ClothInstance* coarse = levels_.stepped();
        return coarse ? *coarse : cloth_;
    }

    // Origin rebasing: the cloth's positions and the previous state.
    bool can_shift_origin(const Vec3& shift) const;
    void shift_origin(const Vec3& shift);

  private:
    // The previous state and the reported positions, sized aside (an
    // allocation failure changes nothing), or freed.
    void size_interpolation();
    void free_interpolation();

    ClothInstance cloth_;
    float importance_ = 1.0f;
    UpdateRate rate_;
    uint64_t world_frame_ = 0;
    Vec3Soa previous_x_;          // the state before the last step, while the rate is above 1
    mutable Vec3Soa reported_x_;  // filled by reported_positions() between steps
    ClothQuality quality_{cloth_, rate_};
    ClothLevels levels_;
};

}  // namespace cloth
