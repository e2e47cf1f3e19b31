#include "solve/strain_limit.h"

#include <algorithm>
#include <cmath>

#include "base/lanes.h"
#include "solve/strain_limit_kernels.h"

namespace cloth {
namespace {

// One incidence slot of particles [begin, end) (slot of i at base + i):
// correction_i += the slot's spring's correction, counted in `count`.
// Branch-free over the fabric's padded slots of structural and shear
// springs (limited_slots), so GCC vectorizes it; padding has an infinite
// rest length and is never over. The same sums in the same order as a
// walk of each particle's incidence list (a spring under the limit adds a zero).
CLOTH_HOT_LOOP void slot_corrections_kernel(
    uint32_t begin, uint32_t end, int64_t base, float stretch_limit, float promise, float shortest,
    const uint32_t* __restrict other, const float* __restrict rest, const float* __restrict structural_rest,
    const float* __restrict mass, const float* __restrict pinned, const float* __restrict px,
    const float* __restrict py, const float* __restrict pz, float* __restrict cx, float* __restrict cy,
    float* __restrict cz, float* __restrict pull, uint32_t& over_limit, uint32_t& over_promise) {
    uint32_t limit_count = 0, promise_count = 0;
    for (uint32_t i = begin; i < end; ++i) {
        const int64_t k = base + i;
        const uint32_t j = other[k];
        const float dx = px[j] - px[i], dy = py[j] - py[i], dz = pz[j] - pz[i];
        const float length = std::sqrt(dx * dx + (dy * dy + dz * dz));  // summed as Eigen sums a Vec3
        const float allowed = stretch_limit * rest[k], least = shortest * structural_rest[k];
        const bool free = pinned[i] == 0.0f;
        const bool over = free & (length > allowed), under = free & (length < least);
        const float own = 1.0f / mass[i], other_inverse = 1.0f / mass[j];
        const float other_weight = pinned[j] != 0.0f ? 0.0f : other_inverse;
        // min and max rather than std::clamp, which GCC does not vectorize here.
        const float raw = own / (own + other_weight);
        const float share =
            other_weight > 0.0f ? std::min(std::max(raw, kLeastShare), 1.0f - kLeastShare) : raw;
        // At most one of the two is nonzero (least < allowed); min and max
        // rather than branches, so that GCC vectorizes the loop.
        const float excess = std::max(length - allowed, 0.0f) + std::min(length - least, 0.0f);
        const bool past = over | under;
        const float factor = past ? kRelaxation * share * excess / std::max(length, 1e-30f) : 0.0f;
        cx[i] += dx * factor;
        cy[i] += dy * factor;
        cz[i] += dz * factor;
        pull[i] += past ? kRelaxation * share : 0.0f;
        const bool past_promise = (over & (length > promise * rest[k])) |
                                  (under & (length < (shortest - kStrainPromiseSlack) * structural_rest[k]));
        limit_count += past ? 1u : 0u;
        promise_count += past_promise ? 1u : 0u;
    }
    over_limit += limit_count;
    over_promise += promise_count;
}

// maybe[i] = 1 where particle i's slot spring may be over the limit
// (padding, of infinite rest length, never is).
CLOTH_HOT_LOOP void slot_maybe_over_kernel(uint32_t begin, uint32_t end, int64_t base, float stretch_limit,
                                           float shortest, const uint32_t* __restrict other,
                                           const float* __restrict rest,
                                           const float* __restrict structural_rest,
                                           const float* __restrict px, const float* __restrict py,
                                           const float* __restrict pz, uint8_t* __restrict maybe) {
    for (uint32_t i = begin; i < end; ++i) {
        const int64_t k = base + i;
        const uint32_t j = other[k];
        const float dx = px[j] - px[i], dy = py[j] - py[i], dz = pz[j] - pz[i];
        const float allowed = stretch_limit * rest[k], least = shortest * structural_rest[k];
        const float squared = dx * dx + dy * dy + dz * dz;
        maybe[i] =
            (squared >= kSurelyUnder * (allowed * allowed)) | (squared * kSurelyUnder <= least * least);
    }
}

}  // namespace

// c_i /= max(1, pull_i), and zero where pinned (a null `pinned`: none is).
// Within the bound the factor is exactly 1: the same bits as no division.
CLOTH_HOT_LOOP void divide_by_pull(const float* __restrict pull, const float* __restrict pinned,
                                   uint32_t begin, uint32_t end, float* __restrict cx, float* __restrict cy,
                                   float* __restrict cz) {
    for (uint32_t i = begin; i < end; ++i) {
        const float free = pinned != nullptr ? 1.0f - pinned[i] : 1.0f;
        const float factor = free / std::max(pull[i], 1.0f);
        cx[i] *= factor;
        cy[i] *= factor;
        cz[i] *= factor;
    }
}

StretchCount strain_limit_corrections(const StrainLimitPass& pass, const Vec3Soa& x, uint32_t begin,
                                      uint32_t end, Vec3Soa& correction) {
    const Fabric& f = *pass.fabric;
    const float stretch_limit = 1.0f + pass.max_strain;
    const float promise = stretch_limit + kStrainPromiseSlack,
                shortest = pass.hold_compression ? 1.0f - pass.max_strain : 0.0f;
    for (HostVector<float>* a : {&correction.x, &correction.y, &correction.z})
        std::fill(a->begin() + begin, a->begin() + end, 0.0f);
    std::fill(pass.pull + begin, pass.pull + end, 0.0f);
    StretchCount count;
    f.limited_slots.for_each_slot(
        f.particle_count(), begin, end, [&](uint32_t lo, uint32_t hi, int64_t base, uint32_t) {
            // A skipped spring would add zero: each particle's sums are the same.
            const auto exact = [&](uint32_t run, uint32_t run_end) {
                slot_corrections_kernel(
                    run, run_end, base, stretch_limit, promise, shortest, f.limited_slots.other.data(),
                    f.limited_slot_rest.data(), f.limited_slot_structural_rest.data(), pass.mass, pass.pinned,
                    x.x.data(), x.y.data(), x.z.data(), correction.x.data(), correction.y.data(),
                    correction.z.data(), pass.pull, count.over_limit, count.over_promise);
            };
            if (pass.maybe_over == nullptr) return exact(lo, hi);
            slot_maybe_over_kernel(lo, hi, base, stretch_limit, shortest, f.limited_slots.other.data(),
                                   f.limited_slot_rest.data(), f.limited_slot_structural_rest.data(),
                                   x.x.data(), x.y.data(), x.z.data(), pass.maybe_over);
            for_each_maybe_span(pass.maybe_over, lo, hi, exact);
        });
    divide_by_pull(pass.pull, nullptr, begin, end, correction.x.data(), correction.y.data(),
                   correction.z.data());
    return count;
}

float strain_limit_next_omega(uint32_t pass, float omega) {
    const float rho_squared = kStrainLimitChebyshevRho * kStrainLimitChebyshevRho;
    return pass == 0 ? 2.0f / (2.0f - rho_squared) : 4.0f / (4.0f - rho_squared * omega);
}

namespace {

// One coordinate of strain_limit_apply; arrays as __restrict parameters so
// that GCC vectorizes the loop.
CLOTH_HOT_LOOP void apply_kernel(uint32_t begin, uint32_t end, float omega, float inverse_h,
                                 const float* __restrict correction, float* __restrict x, float* __restrict v,
                                 float* __restrict previous) {
    if (omega == 1.0f) {
        for (uint32_t i = begin; i < end; ++i) {
            previous[i] = x[i];
            x[i] += correction[i];
            v[i] += correction[i] * inverse_h;
        }
        return;
    }
    for (uint32_t i = begin; i < end; ++i) {
        const float now = x[i];
        const float next = omega * (now + correction[i] - previous[i]) + previous[i];
        previous[i] = now;
        x[i] = next;
        v[i] += (next - now) * inverse_h;
    }
}

}  // namespace

void strain_limit_apply(const Vec3Soa& correction, float h, float omega, uint32_t begin, uint32_t end,
                        Vec3Soa& x, Vec3Soa& v, Vec3Soa& previous) {
    const float inverse_h = 1.0f / h;
    apply_kernel(begin, end, omega, inverse_h, correction.x.data(), x.x.data(), v.x.data(),
                 previous.x.data());
    apply_kernel(begin, end, omega, inverse_h, correction.y.data(), x.y.data(), v.y.data(),
                 previous.y.data());
    apply_kernel(begin, end, omega, inverse_h, correction.z.data(), x.z.data(), v.z.data(),
                 previous.z.data());
}

void StrainLimiter::begin(const StrainLimitPass& pass, uint32_t iterations, float h, Vec3Soa& x, Vec3Soa& v,
                          Vec3Soa& correction, Vec3Soa& previous, bool accelerate, GridStrainTerms* grid,
                          const Tethers* tethers, StretchCount* counts, uint32_t max_iterations) {
    counts_ = counts;
    grid_ = grid != nullptr && !grid->empty() ? grid : nullptr;
    tethers_ = tethers != nullptr && !tethers->empty() ? tethers : nullptr;
    // Passes past those asked for only where tethers hold the cloth's
    // stretch as a whole: without them, many Jacobi passes on a cloth
    // dragged far in one step overshoot and diverge (docs/measurements.md,
    // "Strain-limit passes that follow what they find").
    max_iterations_ = tethers_ != nullptr ? std::max(iterations, max_iterations) : iterations;
    first_pass_round_ = tethers_ != nullptr ? 1 : 0;
    pass_ = pass;
    asked_strain_ = pass.max_strain;
    iterations_ = asked_ = iterations;
    past_promise_ = held_ = capped_ = false;
    round_ = 0;
    h_ = h;
    x_ = &x;
    v_ = &v;
    correction_ = &correction;
    previous_ = &previous;
    omega_ = schedule_omega_ = 1.0f;
    accelerate_ = accelerate;
}

void StrainLimiter::moved_between_passes(const Vec3Soa& from, const Vec3Soa& to, uint32_t begin,
                                         uint32_t end) {
    for (uint32_t i = begin; i < end; ++i)
        previous_->set(i, Vec3(previous_->get(i) + (to.get(i) - from.get(i))));
}

void StrainLimiter::hold_at_least(float demand) { pass_.max_strain = std::max(asked_strain_, demand); }

void StrainLimiter::run(const GroupTask& task) {
    if (tether_round()) {
        tethers_->clamp(pass_.max_strain, task.begin, task.end, *x_, *v_);
        return;
    }
    // Grid: the terms round, then the corrections and their application in
    // one round (they read only the terms). General: corrections, apply.
    if (grid_ != nullptr) {
        if (applying()) {
            strain_limit_grid_corrections(pass_, *grid_, task.begin, task.end, *correction_);
            strain_limit_apply(*correction_, h_, omega_, task.begin, task.end, *x_, *v_, *previous_);
            return;
        }
        const bool first_pass = round_ == first_pass_round_;
        const StretchCount count =
            strain_limit_grid_terms(pass_, *x_, task.begin, task.end, first_pass, *grid_);
        if (counts_) counts_[task.group] = count;
    } else if (applying()) {
        strain_limit_apply(*correction_, h_, omega_, task.begin, task.end, *x_, *v_, *previous_);
    } else {
        const StretchCount count = strain_limit_corrections(pass_, *x_, task.begin, task.end, *correction_);
        if (counts_) counts_[task.group] = count;
    }
}

void StrainLimiter::finish_round() {
    const uint32_t pass = (round_ - first_pass_round_) / 2;  // meaningless in the tether round
    if (applying()) {
        if (accelerate_) schedule_omega_ = strain_limit_next_omega(pass, schedule_omega_);
    } else if (!tether_round()) {
        // A corrections round: decide how many passes there are...
        if (counts_) {
            uint64_t over_limit = 0, over_promise = 0;
            const uint32_t groups = (pass_.fabric->particle_count() + kGroupSize - 1) / kGroupSize;
            for (uint32_t g = 0; g < groups; ++g) {
                over_limit += counts_[g].over_limit;
                over_promise += counts_[g].over_promise;
            }
            if (pass == 0) held_ = over_limit > 0;
            if (pass + 1 == asked_) past_promise_ = over_promise > 0;
            if (over_limit == 0) {
                iterations_ = pass + 1;  // this pass applies nothing, nor would any after it
            } else if (over_promise > 0 && pass + 1 == iterations_ && iterations_ < max_iterations_) {
                ++iterations_;
            } else if (over_promise > 0 && pass + 1 == iterations_) {
                capped_ = true;
            }
        }
        // ...and the weight its application round moves by. The last pass
        // applies its corrections as they are: an accelerated move past them
        // would leave springs it stretched (or, when nothing is left to
        // correct, move the cloth along the last passes for nothing).
        omega_ = pass + 1 == iterations_ ? 1.0f : schedule_omega_;
    }
    ++round_;
}

void limit_strain(const StrainLimitPass& pass, const StrainLimit& limit, float h, Vec3Soa& x, Vec3Soa& v,
                  Vec3Soa& correction, Vec3Soa& previous) {
    StrainLimiter limiter;
    limiter.begin(pass, limit.iterations, h, x, v, correction, previous, true);
    run_serially(limiter, pass.fabric->particle_count());
}

}  // namespace cloth
