// Two cloths in contact step together: the rounds of their contact
// (collide/cloth_pair_contact.h) run once a substep at the same place of
// both frames, while both wait there. Each cloth plans the pair's stage
// (Stage::kClothContact) after its colliders and self-collision, before
// its strain limiter; the first to reach it runs no task until the other
// arrives; then the pair's rounds run as
// tasks of the first side's cloth (tasks over both cloths' particles,
// split over the workers as any stage's) while the other side's cloth runs
// none, and both go on when the rounds are done. The rest of each frame
// runs at each cloth's own pace.
//
// Both cloths run the same number of substeps (the world shares them,
// fewer), and every cloth plans its pairs in the world's pair order, so
// two cloths never wait for each other at two different pairs. A cloth
// that does not step this frame (asleep) is the pair's read-only side: it
// never arrives, and the other waits for nobody.
#pragma once

#include <cassert>
#include <cstdint>

#include "base/staged.h"
#include "collide/cloth_pair_contact.h"

namespace cloth {

class PairRounds {
  public:
    // The pair's stage as one cloth's plan sees it (base/staged.h): no
    // task until both sides arrived, then side 0 (side 1 while side 0
    // sleeps) runs the pair's rounds.
    class Side final : public StagedAlgorithm {
      public:
        void bind(PairRounds* pair, uint32_t side) { pair_ = pair, side_ = side; }
        PairRounds& pair() const { return *pair_; }
        uint32_t side() const { return side_; }
        // The cloth, whose substeps are `h` long, reached the pair's stage
        // (serial, before the round).
        void arrive(float h) {
            done_ = false;
            pair_->arrive(side_, h);
        }
        uint32_t task_count() const { return pair_->task_count(side_); }
        bool done() const override { return done_; }
        bool single_task() const override { return false; }
        // A contact stage is never a frame's last: a response follows it.
        bool last_round() const override { return false; }
        void run(const GroupTask& task) override { pair_->contact().run(task); }
        void finish_round() override { done_ = pair_->finish_round(side_); }

      private:
        PairRounds* pair_ = nullptr;
        uint32_t side_ = 0;
        bool done_ = false;
    };

    explicit PairRounds(ClothPairContact* contact) : contact_(contact) {
        sides_[0].bind(this, 0);
        sides_[1].bind(this, 1);
    }
    ClothPairContact& contact() { return *contact_; }
    Side& side(uint32_t s) { return sides_[s]; }

    // The frame's views of both cloths (World::step, before the rounds):
    // a side whose view does not step never arrives.
    void begin_frame(const ParticleView& a, const ParticleView& b) {
        a_ = a;
        b_ = b;
        arrived_[0] = !a.steps;
        arrived_[1] = !b.steps;
        left_[0] = left_[1] = false;
        running_ = false;
    }

  private:
    void arrive(uint32_t side, float h) {
        assert(!running_);  // the other side left the pair's last stage
        arrived_[side] = true;
        if (arrived_[0] && arrived_[1]) {
            contact_->begin(a_, b_, h);  // the two cloths' substeps are alike
            running_ = true;
        }
    }
    // The tasks `side`'s cloth runs in this round.
    uint32_t task_count(uint32_t side) const {
        return running_ && side == runner() ? contact_->task_count() : 0;
    }
    // The side whose cloth runs the rounds: 0, or 1 when 0 does not step.
    uint32_t runner() const { return a_.steps ? 0 : 1; }
    // After a round's barrier, from each waiting side; whether `side` is done.
    bool finish_round(uint32_t side) {
        if (!running_) return false;
        if (side == runner() && !contact_->done()) contact_->finish_round();
        if (!contact_->done()) return false;
        left_[side] = true;
        const bool other_left = left_[1 - side] || !(side == 0 ? b_.steps : a_.steps);
        if (other_left) {  // both through: the next substep's arrivals start anew
            arrived_[0] = !a_.steps;
            arrived_[1] = !b_.steps;
            left_[0] = left_[1] = false;
            running_ = false;
        }
        return true;
    }

    ClothPairContact* contact_;
    ParticleView a_, b_;
    Side sides_[2];
    bool arrived_[2] = {false, false};
    bool left_[2] = {false, false};
    bool running_ = false;
};

}  // namespace cloth
