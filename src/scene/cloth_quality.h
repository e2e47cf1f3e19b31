// One cloth under a world's frame budget (budget_policy.h): its quality
// policy, the policy's memory of what each rung cost, and where the budget
// put the cloth: caps on CLOTH_SOLVER_DEFAULT's own choice, or the
// iterations and substeps another kind runs. It reads the cloth's settings
// and its last frame's decision and writes nothing of the cloth's: the
// frame's decision reads bounds() (step/frame_decision.h).
#pragma once

#include <cstdint>
#include <utility>

#include "scene/quality_ladder.h"
#include "scene/update_rate.h"
#include "step/cloth_instance.h"

namespace cloth {

// Bounds within which a world's frame budget may change a cloth's solver
// iterations and substeps. Off by default.
struct QualityPolicy {
    bool enabled = false;
    uint32_t min_iterations = 1, max_iterations = 8;
    uint32_t min_substeps = 1, max_substeps = 4;
    uint32_t max_update_rate = 1;  // update_rate.h; 1: the budget never changes the rate
};

class ClothQuality {
  public:
    // `cloth` and `rate` are the scene record's, which outlives this.
    ClothQuality(const ClothInstance& cloth, const UpdateRate& rate) : cloth_(cloth), rate_(rate) {}
    ClothQuality(const ClothQuality&) = delete;
    ClothQuality& operator=(const ClothQuality&) = delete;

    const QualityPolicy& policy() const { return policy_; }
    // Enabling clamps the settings the cloth runs into the bounds; either
    // way the default's caps and the cost memory go.
    void set_policy(const QualityPolicy& policy);
    // The host set new solver settings: the budget starts from them.
    void host_set_solver();
    // What the frame's decision reads.
    BudgetBounds bounds() const;
    QualityCosts& costs() { return costs_; }
    const QualityCosts& costs() const { return costs_; }

    // The iterations and substeps the policy steps from: the budget's, the
    // host's or, for CLOTH_SOLVER_DEFAULT, its caps or what its last frame
    // ran when it has none. Setting them sets the budget's rung, or the
    // default's caps (removed once they reach what the default chooses by
    // itself).
    SolverSettings settings() const;
    void set_settings(const SolverSettings& settings);
    // The ladder the policy moves the cloth along: from the policy's top,
    // or the default's own choice of the last frame, down to the policy's
    // minimum. And the rung the last frame ran, and the rung of the
    // ladder that put it there (fewer substeps where a budget's cap would
    // have made a substep too long: frame_decision.cpp).
    QualityLadder ladder() const;
    QualityRung ran_rung() const {
        const FrameDecision& d = cloth_.last_frame_decision();
        return {d.solver.iterations, d.solver.substeps, rate_.rate()};
    }
    QualityRung capped_rung() const {
        const FrameDecision& d = cloth_.last_frame_decision();
        return {d.solver.iterations, d.capped_substeps, rate_.rate()};
    }
    // The update rate the policy wants (set_rate), or the cloth's own.
    // The world applies a wanted rate after the policy's decision
    // (take_wanted_rate: 0 when there is none), since a rate's phase is
    // the world's choice.
    uint32_t rate() const { return wanted_rate_ > 0 ? wanted_rate_ : rate_.rate(); }
    void set_rate(uint32_t rate) {
        wanted_rate_ = rate == rate_.rate() ? 0 : rate;
        if (rate > 1) rate_cut_ = true;
    }
    uint32_t take_wanted_rate() { return std::exchange(wanted_rate_, 0u); }
    // Whether the policy has slowed the cloth's rate since it was set:
    // setting a policy again puts the rate back to 1.
    bool rate_cut() const { return rate_cut_; }
    // Whether the policy may raise it: not a default running its own choice.
    bool can_rise() const;

  private:
    bool by_default() const { return cloth_.solver().kind == CLOTH_SOLVER_DEFAULT; }

    const ClothInstance& cloth_;
    const UpdateRate& rate_;
    uint32_t wanted_rate_ = 0;
    bool rate_cut_ = false;
    QualityPolicy policy_;
    QualityCosts costs_;
    // Where the budget put the cloth (0: nowhere): caps on the default's
    // own choice, or what another kind runs instead of the host's settings.
    uint32_t iterations_ = 0, substeps_ = 0;
};

}  // namespace cloth
