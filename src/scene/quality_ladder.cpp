#include "scene/quality_ladder.h"

#include <algorithm>

#include "step/frame_decision.h"

namespace cloth {

uint32_t QualityLadder::fewest_substeps() const { return std::min(min_substeps, top.substeps); }

uint32_t QualityLadder::fewest_iterations() const { return std::min(min_iterations, top.iterations); }

uint32_t QualityLadder::floor() const { return ladder_floor(top.iterations, min_iterations); }

bool QualityLadder::at_or_below_floor(QualityRung rung) const {
    return rung.substeps == fewest_substeps() && rung.iterations <= floor();
}

bool QualityLadder::rate_is_next(QualityRung rung) const {
    return rung.substeps == fewest_substeps() && rung.iterations <= floor() && rung.rate < max_rate;
}

QualityRung QualityLadder::rung_of(uint32_t iterations, uint32_t substeps, uint32_t rate) const {
    QualityRung rung;
    rung.substeps = std::clamp(substeps, fewest_substeps(), top.substeps);
    const uint32_t fewest = rung.substeps > fewest_substeps() ? floor() : fewest_iterations();
    rung.iterations = std::clamp(iterations, fewest, top.iterations);
    rung.rate = rate;  // a rate the host set stays where the ladder does not move it
    return rung;
}

bool QualityLadder::down(QualityRung& rung) const {
    if (rung.substeps > fewest_substeps()) {
        if (rung.iterations > floor()) {
            --rung.iterations;
        } else {
            --rung.substeps;
            rung.iterations = top.iterations;
        }
        return true;
    }
    if (rung.iterations > floor()) {
        --rung.iterations;
        return true;
    }
    if (rate_is_next(rung)) {
        rung.rate *= 2;
        return true;
    }
    if (rung.iterations > fewest_iterations()) {
        --rung.iterations;
        return true;
    }
    return false;
}

bool QualityLadder::up(QualityRung& rung) const {
    // Below the floor the iterations come back first, then the rate.
    if (rung.substeps == fewest_substeps() && rung.iterations < floor()) {
        ++rung.iterations;
        return true;
    }
    if (max_rate > 1 && rung.rate > 1) {
        rung.rate /= 2;
        return true;
    }
    if (rung.iterations < top.iterations) {
        ++rung.iterations;
        return true;
    }
    if (rung.substeps < top.substeps) {
        ++rung.substeps;
        rung.iterations = floor();
        return true;
    }
    return false;
}

void QualityCosts::record(QualityRung rung, double cost_ns, uint64_t frame) {
    Entry* slot = nullptr;
    for (Entry& e : entries_) {
        if (e.used && e.rung == rung) {
            e.cost_ns += kWeight * (cost_ns - e.cost_ns);
            e.last_frame = frame;
            return;
        }
        // An empty entry, else the one run longest ago.
        if (!slot || (slot->used && (!e.used || e.last_frame < slot->last_frame))) slot = &e;
    }
    *slot = Entry{rung, cost_ns, frame, true};
}

double QualityCosts::cost_ns(QualityRung rung, uint64_t frame) const {
    for (const Entry& e : entries_) {
        if (e.used && e.rung == rung && frame - e.last_frame < kForgetFrames) return e.cost_ns;
    }
    return -1.0;
}

}  // namespace cloth
