// The strain limit stage's rounds: the strain limiter's passes with the
// colliders run again between them as rounds of their own
// (Stage::kLimitCollisions), so a plan and a profile show them. They run
// after the limiter's last round, so the substep ends with every particle
// out of the colliders, and, where the collision stage found contacts,
// after every round that moved particles, so the next pass sees where the
// particles really are: limiting after the colliders alone pulls a spring
// that wraps a thin collider (the flag round its pole) through it; without
// contacts those runs would buy nothing and cost half the stage
// (docs/measurements.md, "Colliders between the strain limiter's rounds
// only after a contact"). A collider round touches only its own group's particles, so running it as
// a round of its own gives the bits of running it in the limiter's task.
#pragma once

#include "base/staged.h"
#include "solve/strain_limit.h"

namespace cloth {

class LimitRounds final : public StagedAlgorithm {
  public:
    // `collides`: the frame runs colliders at all; `touching` (read at each
    // round's end) whether this substep's collision stage found a contact.
    void begin(StrainLimiter* limiter, bool collides, const bool* touching) {
        limiter_ = limiter;
        collides_ = collides;
        touching_ = touching;
        colliding_ = false;
    }
    // The current round runs the colliders, not a strain-limit pass.
    bool colliding() const { return colliding_; }
    StrainLimiter& limiter() { return *limiter_; }

    bool done() const override { return !colliding_ && limiter_->done(); }
    bool single_task() const override { return !colliding_ && limiter_->single_task(); }
    bool last_round() const override {
        return colliding_ ? limiter_->done() : limiter_->last_round() && !collides_;
    }
    // The caller runs each task: the limiter's, or its colliders' (colliding()).
    void run(const GroupTask& task) override { limiter_->run(task); }
    void finish_round() override {
        if (colliding_) {
            colliding_ = false;
            return;
        }
        const bool last = limiter_->last_round(), moved = limiter_->applying();
        limiter_->finish_round();
        colliding_ = collides_ && (last || (moved && *touching_));
    }

  private:
    StrainLimiter* limiter_ = nullptr;
    const bool* touching_ = nullptr;
    bool collides_ = false, colliding_ = false;
};

}  // namespace cloth
