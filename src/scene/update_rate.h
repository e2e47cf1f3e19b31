// A cloth's update rate: at rate N it steps every Nth world frame, N times
// the frame's dt at once, so it costs about 1/N of a cloth stepped every
// frame. Its state then runs ahead of the world: a step taken in frame f
// ends at the end of frame f + N - 1, and until then the cloth reports
// positions interpolated between its last two states at the world's
// current frame. A reader sees smooth motion; what the cloth follows
// (pins, skin, colliders) it reaches N - 1 frames late.
//
// The phase staggers cloths of one rate over the frames: a cloth's states
// fall on frames f with f % N == phase, so a world of rate-2 cloths with
// phases 0 and 1 pays half of them each frame. A step covers 1 to N frames
// (the first after a change of rate or phase is shorter, to land on the
// phase), and starts where the last one ended, so neither a change of rate
// nor of phase makes the reported positions jump.
//
// Frames count the world's steps: frame f is the f-th call of
// cloth_step, and "state at frame f" means at the end of that call.
#pragma once

#include <algorithm>
#include <cstdint>

namespace cloth {

class UpdateRate {
  public:
    static constexpr uint32_t kSlowest = 8;
    static bool valid(uint32_t rate) { return rate == 1 || rate == 2 || rate == 4 || rate == kSlowest; }

    // A cloth created after `frame` steps of its world, at rate 1.
    explicit UpdateRate(uint64_t frame = 0) : state_frame_(frame), previous_frame_(frame) {}

    uint32_t rate() const { return rate_; }
    uint32_t phase() const { return phase_; }
    // `rate` valid(), phase < rate.
    void set(uint32_t rate, uint32_t phase) {
        rate_ = rate;
        phase_ = phase % rate;
    }

    // Whether the cloth steps in world frame `frame`: its state ends before it.
    bool due(uint64_t frame) const { return frame > state_frame_; }
    // Starts the step of world frame `frame` (due): returns the frames it
    // covers. A cloth that fell behind (asleep, or not stepped) starts from
    // the frame before.
    uint32_t begin_step(uint64_t frame) {
        const uint64_t from = std::max(state_frame_, frame - 1);
        const uint32_t behind_phase = static_cast<uint32_t>((from + 1) % rate_);
        const uint32_t frames = (phase_ + rate_ - behind_phase) % rate_ + 1;
        previous_frame_ = from;
        state_frame_ = from + frames;
        stepped_frame_ = frame;
        return frames;
    }
    // Whether the cloth stepped in world frame `frame`.
    bool stepped_in(uint64_t frame) const { return stepped_frame_ == frame; }
    // The step failed and its start was put back: the state is at its start again.
    void undo_step() { state_frame_ = previous_frame_; }
    // The state was set from outside (positions, a snapshot): reports show it as it is.
    void settle() { previous_frame_ = state_frame_; }

    // How far the reported positions at world frame `frame` lie from the
    // previous state (0) to the current one (1).
    float fraction(uint64_t frame) const {
        if (frame >= state_frame_ || state_frame_ == previous_frame_) return 1.0f;
        if (frame <= previous_frame_) return 0.0f;
        return static_cast<float>(frame - previous_frame_) /
               static_cast<float>(state_frame_ - previous_frame_);
    }
    uint64_t state_frame() const { return state_frame_; }

  private:
    uint32_t rate_ = 1, phase_ = 0;
    uint64_t state_frame_, previous_frame_;
    uint64_t stepped_frame_ = UINT64_MAX;
};

}  // namespace cloth
