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
//
// With self-collision, whose stage ran before the limiter and found the
// substep's contacts, one projection pass over those contacts
// (Stage::kSelfProject) follows every round that moved particles, before
// the colliders: the passes then take back the stretch the pushes made
// without pulling the layers they parted back together, where either
// stage alone after the other leaves one of the two (docs/measurements.md,
// "Self-collision projected between the strain limiter's passes").
#pragma once

#include "base/staged.h"
#include "collide/self_collision.h"
#include "solve/strain_limit.h"

namespace cloth {

class LimitRounds final : public StagedAlgorithm {
  public:
    // `collides`: the frame runs colliders at all; `touching` (read at each
    // round's end) whether this substep's collision stage found a contact;
    // `self` (or null) the self-collision whose contacts hold the positions
    // `x` apart between the passes.
    void begin(StrainLimiter* limiter, bool collides, const bool* touching, SelfCollision* self = nullptr,
               Vec3Soa* x = nullptr) {
        limiter_ = limiter;
        collides_ = collides;
        touching_ = touching;
        self_ = self;
        x_ = x;
        colliding_ = projecting_ = collide_next_ = false;
    }
    // The current round runs the colliders, not a strain-limit pass.
    bool colliding() const { return colliding_; }
    // The current round projects the self-collision's contacts.
    bool projecting() const { return projecting_; }
    StrainLimiter& limiter() { return *limiter_; }

    bool done() const override { return !colliding_ && !projecting_ && limiter_->done(); }
    bool single_task() const override { return !colliding_ && !projecting_ && limiter_->single_task(); }
    bool last_round() const override {
        if (projecting_) return limiter_->done() && !collide_next_;
        if (colliding_) return limiter_->done();
        return limiter_->last_round() && !collides_ && self_ == nullptr;
    }
    // The caller runs each task: the limiter's, its colliders' (colliding())
    // or the self-collision's projection (projecting()).
    void run(const GroupTask& task) override { limiter_->run(task); }
    void finish_round() override {
        if (projecting_) {
            self_->apply_positions(*x_);
            projecting_ = false;
            colliding_ = collide_next_;
            return;
        }
        if (colliding_) {
            colliding_ = false;
            return;
        }
        const bool last = limiter_->last_round(), moved = limiter_->applying();
        limiter_->finish_round();
        const bool collide = collides_ && (last || (moved && *touching_));
        projecting_ = self_ != nullptr && moved;
        collide_next_ = projecting_ && collide;
        colliding_ = !projecting_ && collide;
    }

  private:
    StrainLimiter* limiter_ = nullptr;
    const bool* touching_ = nullptr;
    SelfCollision* self_ = nullptr;
    Vec3Soa* x_ = nullptr;
    bool collides_ = false, colliding_ = false, projecting_ = false, collide_next_ = false;
};

}  // namespace cloth
