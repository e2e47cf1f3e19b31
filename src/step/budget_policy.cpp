#include "step/budget_policy.h"

#include <algorithm>

namespace cloth {
namespace {

double units(uint32_t substeps, uint32_t iterations) {
    return static_cast<double>(substeps) * (static_cast<double>(iterations) + BudgetPolicy::kFixedStages);
}

// One notch down (iterations first) or up (substeps first, undoing the
// last cut); false at the bound.
bool lower(const QualityPolicy& q, SolverSettings& s) {
    if (s.iterations > q.min_iterations) {
        --s.iterations;
        return true;
    }
    if (s.substeps > q.min_substeps) {
        --s.substeps;
        return true;
    }
    return false;
}

bool raise(const QualityPolicy& q, SolverSettings& s) {
    if (s.substeps < q.max_substeps &&
        (s.iterations <= q.min_iterations || s.iterations >= q.max_iterations)) {
        ++s.substeps;
        return true;
    }
    if (s.iterations < q.max_iterations) {
        ++s.iterations;
        return true;
    }
    return false;
}

// Step time the frame would have taken with `after` instead of `before`
// for a cloth that had `share` of the step.
double predicted_change_ms(double step_ms, double share, const SolverSettings& before,
                           const SolverSettings& after) {
    return step_ms * share *
           (units(after.substeps, after.iterations) / units(before.substeps, before.iterations) - 1.0);
}

}  // namespace

void BudgetPolicy::after_frame(double budget_ms, double step_ms, BudgetCloth* cloths, uint32_t count) {
    if (budget_ms <= 0) return;
    int64_t total_ns = 0;
    for (uint32_t c = 0; c < count; ++c) total_ns += cloths[c].cost_ns;
    if (total_ns <= 0) return;
    // The most expensive first (ties by position: deterministic).
    std::stable_sort(cloths, cloths + count,
                     [](const BudgetCloth& a, const BudgetCloth& b) { return a.cost_ns > b.cost_ns; });
    double predicted = step_ms;
    if (step_ms > budget_ms) {
        calm_frames_ = 0;
        for (uint32_t c = 0; c < count && predicted > 0.9 * budget_ms; ++c) {
            ClothInstance& cloth = *cloths[c].cloth;
            if (!cloth.quality_policy().enabled) continue;
            const SolverSettings current = cloth.quality_settings();
            SolverSettings next = current;
            if (!lower(cloth.quality_policy(), next)) continue;
            predicted += predicted_change_ms(step_ms, static_cast<double>(cloths[c].cost_ns) / total_ns,
                                             current, next);
            cloth.set_quality_settings(next);
        }
        return;
    }
    if (step_ms >= 0.7 * budget_ms) {
        calm_frames_ = 0;
        return;
    }
    if (++calm_frames_ < kCalmFrames) return;
    calm_frames_ = 0;
    for (uint32_t c = count; c-- > 0;) {  // the cheapest first
        ClothInstance& cloth = *cloths[c].cloth;
        if (!cloth.quality_policy().enabled || !cloth.quality_can_rise()) continue;
        const SolverSettings current = cloth.quality_settings();
        SolverSettings next = current;
        if (!raise(cloth.quality_policy(), next)) continue;
        const double change =
            predicted_change_ms(step_ms, static_cast<double>(cloths[c].cost_ns) / total_ns, current, next);
        if (predicted + change > 0.85 * budget_ms) continue;
        predicted += change;
        cloth.set_quality_settings(next);
    }
}

}  // namespace cloth
