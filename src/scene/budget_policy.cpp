#include "scene/budget_policy.h"

#include <algorithm>

namespace cloth {

namespace {

// A cloth's ladder; one that bodies carry keeps rate 1 (ClothContact::rides_bodies).
QualityLadder ladder_of(const SceneCloth& cloth) {
    QualityLadder ladder = cloth.quality().ladder();
    if (cloth.cloth().contact().rides_bodies()) ladder.max_rate = 1;
    return ladder;
}

// Where a cloth stands on its ladder: its current settings' rung.
QualityRung current_rung(const QualityLadder& ladder, const SceneCloth& cloth) {
    const SolverSettings settings = cloth.quality().settings();
    return ladder.rung_of(settings.iterations, settings.substeps, cloth.quality().rate());
}

// A cloth's task time a frame at a rung: the average a step cost there
// lately (QualityCosts) or, at a rung it has not run, a model of the step
// just run scaled to its rung's average: a cost per substep (every stage
// but the solve) and per iteration and substep; over the rung's rate
// (its steps are staggered with its peers', update_rate.h).
class RungCost {
  public:
    RungCost(const BudgetCloth& c, uint64_t frame) : costs_(c.cloth->quality().costs()), frame_(frame) {
        const QualityRung ran = c.cloth->quality().ran_rung();
        const double substeps = std::max(ran.substeps, 1u), iterations = std::max(ran.iterations, 1u);
        const double cost = static_cast<double>(c.cost_ns);
        const double usual = costs_.cost_ns(ran, frame);
        const double scale = usual > 0 && cost > 0 ? usual / cost : 1.0;
        const double solve = static_cast<double>(std::clamp(c.solve_ns, int64_t{0}, c.cost_ns));
        per_substep_ = scale * (cost - solve) / substeps;
        per_iteration_ = scale * solve / (substeps * iterations);
    }
    double operator()(QualityRung rung) const {
        const double known = costs_.cost_ns(rung, frame_);
        const double step =
            known >= 0 ? known : rung.substeps * (per_substep_ + rung.iterations * per_iteration_);
        return step / rung.rate;
    }

  private:
    const QualityCosts& costs_;
    uint64_t frame_;
    double per_substep_ = 0, per_iteration_ = 0;
};

void set_rung(SceneCloth& cloth, QualityRung rung) {
    SolverSettings next = cloth.quality().settings();
    next.iterations = rung.iterations;
    next.substeps = rung.substeps;
    cloth.quality().set_settings(next);
    cloth.quality().set_rate(rung.rate);
}

// Moves one cloth down its ladder until the predicted step (`predicted`,
// this cloth's share included) is at `target`, below its floor only if
// `below_floor`; returns the new prediction.
double lower(const BudgetCloth& c, uint64_t frame, double predicted, double target, double ms_per_ns,
             bool below_floor) {
    SceneCloth& cloth = *c.cloth;
    const QualityLadder ladder = ladder_of(cloth);
    const RungCost cost(c, frame);
    const double others = predicted - static_cast<double>(c.cost_ns) * ms_per_ns;
    QualityRung rung = current_rung(ladder, cloth);
    // From the rung's usual cost: a frame that cost more than that (a
    // spike) moves the cloth down less than its own cost says.
    predicted = others + cost(rung) * ms_per_ns;
    bool moved = false;
    while (predicted > target) {
        // Past the floor's last rung each rung gives up much of the hold:
        // only under a load, and one a decision. A slower rate keeps each
        // step's quality: it needs no load.
        if (ladder.at_or_below_floor(rung) && !ladder.rate_is_next(rung) && (!below_floor || moved)) break;
        if (!ladder.down(rung)) break;
        predicted = others + cost(rung) * ms_per_ns;
        moved = true;
    }
    if (moved) set_rung(cloth, rung);
    return predicted;
}

}  // namespace

void BudgetPolicy::after_frame(double budget_ms, double step_ms, uint64_t frame, BudgetCloth* cloths,
                               uint32_t count) {
    if (budget_ms <= 0) return;
    int64_t total_ns = 0;
    for (uint32_t c = 0; c < count; ++c) total_ns += cloths[c].cost_ns;
    if (total_ns <= 0) return;
    decide(budget_ms, step_ms, frame, total_ns, cloths, count);
    // The frame joins each cloth's memory after the decision: a spike is
    // judged against what the rung usually costs, not with itself in it.
    for (uint32_t c = 0; c < count; ++c) {
        SceneCloth& cloth = *cloths[c].cloth;
        if (!cloth.quality().policy().enabled) continue;
        const double cost = static_cast<double>(cloths[c].cost_ns);
        cloth.quality().costs().record(cloth.quality().ran_rung(), cost, frame);
        // Where more substeps ran than the rung has (frame_plan.cpp), the
        // rung the policy sees costs what ran.
        const QualityRung capped = cloth.quality().capped_rung();
        if (!(capped == cloth.quality().ran_rung())) cloth.quality().costs().record(capped, cost, frame);
    }
}

void BudgetPolicy::decide(double budget_ms, double step_ms, uint64_t frame, int64_t total_ns,
                          BudgetCloth* cloths, uint32_t count) {
    // Wall time per task nanosecond: a cloth's change of task time changes
    // the step by its share.
    const double ms_per_ns = step_ms / static_cast<double>(total_ns);
    // The order of lowering: the least relevant first, of equals the most
    // expensive (ties by position: deterministic). Raising runs it backwards.
    std::stable_sort(cloths, cloths + count, [](const BudgetCloth& a, const BudgetCloth& b) {
        if (a.relevance != b.relevance) return a.relevance < b.relevance;
        return a.cost_ns > b.cost_ns;
    });
    double predicted = step_ms;
    recent_overruns_ = (recent_overruns_ << 1) | (step_ms > budget_ms ? 1u : 0u);
    if (step_ms > budget_ms) {
        calm_frames_ = 0;
        const uint32_t window = (1u << kLoadWindow) - 1;
        const bool below_floor =
            static_cast<uint32_t>(__builtin_popcount(recent_overruns_ & window)) >= kLoadOverruns;
        for (uint32_t c = 0; c < count && predicted > kLowerTo * budget_ms; ++c) {
            if (!cloths[c].cloth->quality().policy().enabled) continue;
            predicted = lower(cloths[c], frame, predicted, kLowerTo * budget_ms, ms_per_ns, below_floor);
        }
        return;
    }
    if (step_ms >= kCalmBelow * budget_ms) {
        calm_frames_ = 0;
        rebalance(budget_ms, predicted, frame, ms_per_ns, cloths, count);
        return;
    }
    if (++calm_frames_ < kCalmFrames) return;
    calm_frames_ = 0;
    for (uint32_t c = count; c-- > 0;) {  // the most relevant first
        SceneCloth& cloth = *cloths[c].cloth;
        if (!cloth.quality().policy().enabled || !cloth.quality().can_rise()) continue;
        const QualityLadder ladder = ladder_of(cloth);
        const RungCost cost(cloths[c], frame);
        QualityRung rung = current_rung(ladder, cloth);
        if (!ladder.up(rung)) continue;
        // What it adds a frame now: its step over its rate.
        const double now = static_cast<double>(cloths[c].cost_ns) / cloth.quality().rate();
        const double change = (cost(rung) - now) * ms_per_ns;
        if (predicted + change > kRaiseTo * budget_ms) continue;
        predicted += change;
        set_rung(cloth, rung);
    }
}

void BudgetPolicy::rebalance(double budget_ms, double predicted, uint64_t frame, double ms_per_ns,
                             BudgetCloth* cloths, uint32_t count) {
    // The most relevant cloth that can rise, and what its next rung adds.
    uint32_t top = count;
    QualityRung raised{};
    double change = 0;
    for (uint32_t c = count; c-- > 0 && top == count;) {
        SceneCloth& cloth = *cloths[c].cloth;
        if (!cloth.quality().policy().enabled || !cloth.quality().can_rise()) continue;
        const QualityLadder ladder = ladder_of(cloth);
        raised = current_rung(ladder, cloth);
        if (!ladder.up(raised)) continue;
        top = c;
        const double now = static_cast<double>(cloths[c].cost_ns) / cloth.quality().rate();
        change = (RungCost(cloths[c], frame)(raised) - now) * ms_per_ns;
    }
    if (top == count) return;
    // Paid for by cloths strictly less relevant, the least first, each
    // down to its floor's last rung (with its rates: no load here).
    const double target = kRaiseTo * budget_ms;
    double after = predicted + change;
    QualityRung lowered[kMostRebalanced];
    uint32_t payers = 0;
    for (uint32_t c = 0; c < top && after > target && payers < kMostRebalanced; ++c) {
        SceneCloth& cloth = *cloths[c].cloth;
        if (!cloth.quality().policy().enabled || cloths[c].relevance >= cloths[top].relevance) continue;
        const QualityLadder ladder = ladder_of(cloth);
        const RungCost cost(cloths[c], frame);
        QualityRung rung = current_rung(ladder, cloth);
        const double before = cost(rung) * ms_per_ns;
        double now = before;
        while (after - before + now > target) {
            if (ladder.at_or_below_floor(rung) && !ladder.rate_is_next(rung)) break;
            if (!ladder.down(rung)) break;
            now = cost(rung) * ms_per_ns;
        }
        after += now - before;
        lowered[payers++] = rung;
    }
    if (after > target) return;  // the others cannot pay for it
    for (uint32_t p = 0, c = 0; p < payers; ++c) {
        if (!cloths[c].cloth->quality().policy().enabled || cloths[c].relevance >= cloths[top].relevance)
            continue;
        set_rung(*cloths[c].cloth, lowered[p++]);
    }
    set_rung(*cloths[top].cloth, raised);
}

}  // namespace cloth
