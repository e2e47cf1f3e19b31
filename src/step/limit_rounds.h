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
// (Stage::kSelfProject) follows every pass, before the colliders, and the
// velocity response (Stage::kSelfRespond) follows the last projection:
// the passes take back the stretch the pushes made without pulling the
// layers they parted back together, where either stage alone after the
// other leaves one of the two, and the layers end the substep apart and
// not approaching (docs/measurements.md, "Self-collision projected between
// the strain limiter's passes").
#pragma once

#include "base/staged.h"
#include "collide/self_collision.h"
#include "solve/strain_limit.h"

namespace cloth {

class LimitRounds final : public StagedAlgorithm {
  public:
    enum class Round : uint8_t { kPass, kProject, kRespond, kColliders };

    // `collides`: the frame runs colliders at all; `touching` (read at each
    // round's end) whether this substep's collision stage found a contact;
    // `self` (or null) the self-collision whose contacts hold the cloth's
    // positions `x` apart between the passes, and whose response then
    // sets its velocities `v`.
    void begin(StrainLimiter* limiter, bool collides, const bool* touching, SelfCollision* self = nullptr,
               Vec3Soa* x = nullptr, Vec3Soa* v = nullptr) {
        limiter_ = limiter;
        collides_ = collides;
        touching_ = touching;
        self_ = self;
        x_ = x;
        v_ = v;
        round_ = Round::kPass;
        collide_next_ = false;
    }
    // What the current round runs: a strain-limit pass, or between passes
    // the self-collision's projection or response, or the colliders.
    Round round() const { return round_; }
    StrainLimiter& limiter() { return *limiter_; }

    bool done() const override { return round_ == Round::kPass && limiter_->done(); }
    bool single_task() const override { return round_ == Round::kPass && limiter_->single_task(); }
    bool last_round() const override {
        switch (round_) {
            case Round::kPass:
                return limiter_->last_round() && !collides_ && self_ == nullptr;
            case Round::kProject:
                return false;  // a pass, the colliders or the response follows
            case Round::kRespond:
                return !collide_next_;
            case Round::kColliders:
                return limiter_->done();
        }
        return false;
    }
    // The caller runs each task: the limiter's (round() is kPass), or the
    // self-collision's or the colliders' between its passes.
    void run(const GroupTask& task) override { limiter_->run(task); }
    void finish_round() override {
        switch (round_) {
            case Round::kPass: {
                const bool last = limiter_->last_round(), moved = limiter_->applying();
                limiter_->finish_round();
                collide_next_ = collides_ && (last || (moved && *touching_));
                round_ = self_ != nullptr && moved ? Round::kProject : next_after_self();
                return;
            }
            case Round::kProject:
                self_->apply_positions(*x_);
                round_ = limiter_->done() ? Round::kRespond : next_after_self();
                return;
            case Round::kRespond:
                self_->apply_velocities(*v_);
                round_ = next_after_self();
                return;
            case Round::kColliders:
                round_ = Round::kPass;
                return;
        }
    }

  private:
    Round next_after_self() const { return collide_next_ ? Round::kColliders : Round::kPass; }

    StrainLimiter* limiter_ = nullptr;
    const bool* touching_ = nullptr;
    SelfCollision* self_ = nullptr;
    Vec3Soa* x_ = nullptr;
    Vec3Soa* v_ = nullptr;
    Round round_ = Round::kPass;
    bool collides_ = false, collide_next_ = false;
};

}  // namespace cloth
