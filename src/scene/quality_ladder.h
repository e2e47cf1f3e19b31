// A cloth's quality ladder under a frame budget: (iterations, substeps,
// update rate) rungs from the top down. The iterations fall to half the
// top's (rounded up), then a substep goes and the iterations come back to
// the top's, and so on; at the fewest substeps and half the iterations
// the update rate doubles up to the policy's slowest, and then the
// iterations fall to the minimum. budget_policy.h says why in that order.
#pragma once

#include <cstdint>

namespace cloth {

struct QualityRung {
    uint32_t iterations, substeps;
    uint32_t rate = 1;  // update_rate.h: a step every `rate` frames
};

struct QualityLadder {
    QualityRung top;
    uint32_t min_iterations, min_substeps;
    uint32_t max_rate = 1;  // 1: the ladder leaves the rate alone

    // The ends (bounds above the top count as the top).
    uint32_t fewest_substeps() const;
    uint32_t fewest_iterations() const;
    // The fewest iterations a rung above the fewest substeps runs.
    uint32_t floor() const;
    // Whether `rung` is the floor's last rung (the fewest substeps at the
    // floor's iterations) or below it.
    bool at_or_below_floor(QualityRung rung) const;
    // Whether the rung below `rung` is a slower update rate at the same
    // iterations and substeps (each step keeps its quality).
    bool rate_is_next(QualityRung rung) const;
    // The rung nearest to these settings (settings made outside the ladder
    // may lie between rungs or past its ends).
    QualityRung rung_of(uint32_t iterations, uint32_t substeps, uint32_t rate = 1) const;
    // The rung below or above `rung`, in place; false at the ends.
    bool down(QualityRung& rung) const;
    bool up(QualityRung& rung) const;
};

inline bool operator==(QualityRung a, QualityRung b) {
    return a.iterations == b.iterations && a.substeps == b.substeps && a.rate == b.rate;
}

// What a cloth's frames cost at the rungs it ran lately: a moving average
// of its task time per rung, for the few rungs a budget moves it between.
// A rung not run for kForgetFrames frames is forgotten, so a rung that was
// too expensive once is tried again later.
class QualityCosts {
  public:
    static constexpr uint32_t kRungs = 8;
    static constexpr uint64_t kForgetFrames = 600;
    static constexpr double kWeight = 0.25;  // of the newest frame

    void record(QualityRung rung, double cost_ns, uint64_t frame);
    // The average cost at `rung`, or a negative value if not known.
    double cost_ns(QualityRung rung, uint64_t frame) const;
    void clear() { *this = QualityCosts{}; }

  private:
    struct Entry {
        QualityRung rung{0, 0};
        double cost_ns = 0;
        uint64_t last_frame = 0;
        bool used = false;
    };
    Entry entries_[kRungs];
};

}  // namespace cloth
