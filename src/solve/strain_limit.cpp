#include "solve/strain_limit.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "base/lanes.h"

namespace cloth {

// Fraction of each spring's excess one pass removes. Every particle moves
// at once (Jacobi), so a particle pulled by several springs would overshoot
// with the full share (docs/measurements.md, "The Provot passes'
// relaxation").
constexpr float kRelaxation = 0.5f;

// Particles a pass with StrainLimitPass::maybe_over tests at a time (one
// AVX register), and the squared length below which a spring is surely
// within the limit: at most kSurelyUnder times the squared allowed length,
// its rounded square root is within the allowed length, so the exact
// pass would correct nothing there and count nothing.
constexpr uint32_t kSkipRun = 8;
constexpr float kSurelyUnder = 1.0f - 1e-5f;

namespace {

// Calls exact(span_begin, span_end) for each span of consecutive runs of
// kSkipRun particles of [begin, end) with maybe[i] set for one of the
// run's particles.
template <class Exact>
void for_each_maybe_span(const uint8_t* maybe, uint32_t begin, uint32_t end, Exact exact) {
    uint32_t span = begin;  // the current span of runs with a flag set: [span, run)
    for (uint32_t run = begin; run < end; run += kSkipRun) {
        const uint32_t run_end = std::min(end, run + kSkipRun);
        uint64_t any = 0;
        if (run_end - run == kSkipRun) {
            static_assert(kSkipRun == sizeof any, "one run is one 64-bit word of flags");
            std::memcpy(&any, maybe + run, sizeof any);
        } else {
            for (uint32_t i = run; i < run_end; ++i) any |= maybe[i];
        }
        if (any != 0) continue;
        if (span < run) exact(span, run);
        span = run_end;
    }
    if (span < end) exact(span, end);
}

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

}  // namespace

StretchCount strain_limit_corrections(const StrainLimitPass& pass, const Vec3Soa& x, uint32_t begin,
                                      uint32_t end, Vec3Soa& correction) {
    const Fabric& f = *pass.fabric;
    const float stretch_limit = 1.0f + pass.max_strain;
    const float promise = stretch_limit + kStrainPromiseSlack, shortest = 1.0f - pass.max_strain;
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

GridStrainTerms::GridStrainTerms(const HostMemory* memory)
    : reach(HostAllocator<SpringFamily>(memory)),
      families(HostAllocator<const SpringFamily*>(memory)),
      weight(HostAllocator<float>(memory)),
      compresses(HostAllocator<uint8_t>(memory)),
      x(HostAllocator<float>(memory)),
      y(HostAllocator<float>(memory)),
      z(HostAllocator<float>(memory)),
      share(HostAllocator<float>(memory)),
      pull(HostAllocator<float>(memory)) {}

void GridStrainTerms::resize(const Fabric& fabric) {
    const uint32_t n = fabric.particle_count();
    reach.clear();
    families.clear();
    weight.clear();
    // A grid's columns: the offset of its structural springs along rows.
    uint32_t columns = 0;
    for (const SpringFamily& family : fabric.grid_families) {
        if (family.kind == kStructural) columns = std::max(columns, family.offset);
    }
    if (columns > 1) {
        for (const uint32_t offset : {kStrainReach, kStrainReach * columns}) {
            SpringFamily family(fabric.memory);
            family.offset = offset;
            family.mask.assign(n, 0.0f);
            family.rest_length.assign(n, 0.0f);
            bool any = false;
            for (uint32_t p = 0; p + offset < n; ++p) {
                if (offset < columns && p % columns + offset >= columns) continue;  // past the row's end
                family.mask[p] = 1.0f;
                family.rest_length[p] = (fabric.rest_positions[p + offset] - fabric.rest_positions[p]).norm();
                any = true;
            }
            if (any) reach.push_back(std::move(family));
        }
    }
    lead = 0;
    compresses.clear();
    for (const SpringFamily& family : fabric.grid_families) {
        if (family.kind == kBend) continue;
        families.push_back(&family);
        weight.push_back(1.0f);
        compresses.push_back(family.kind == kStructural ? 1 : 0);
        lead = std::max(lead, family.offset);
    }
    for (const SpringFamily& family : reach) {
        families.push_back(&family);
        weight.push_back(kStrainReachWeight);
        compresses.push_back(0);
        lead = std::max(lead, family.offset);
    }
    stride = lead + n;
    for (HostVector<float>* a : {&x, &y, &z, &share, &pull})
        a->assign(size_t{stride} * families.size(), 0.0f);
}

namespace {

// The loops of the grid path, every array a __restrict parameter so that GCC
// vectorizes them (as in spring_terms_grid.cpp).

// Each spring's first-end share w_p / (w_p + w_q), kept within
// [kLeastShare, 1 - kLeastShare] when both ends are free.
CLOTH_HOT_LOOP void family_shares_kernel(size_t begin, size_t last, size_t offset,
                                         const float* __restrict mass, const float* __restrict pinned,
                                         float* __restrict share) {
    for (size_t p = begin; p < last; ++p) {
        const size_t q = p + offset;
        const float wp = (1.0f - pinned[p]) / mass[p], wq = (1.0f - pinned[q]) / mass[q];
        const float sum = wp + wq;
        const float raw = sum > 0.0f ? wp / std::max(sum, 1e-30f) : 0.0f;
        share[p] = wp > 0.0f && wq > 0.0f ? std::min(std::max(raw, kLeastShare), 1.0f - kLeastShare) : raw;
    }
}

// The terms of springs [begin, last). Returns the springs over the limit
// and over `promise` (a stretch).
CLOTH_HOT_LOOP StretchCount family_terms_kernel(size_t begin, size_t last, size_t offset, float stretch_limit,
                                                float promise, float shortest, float weight,
                                                const float* __restrict mask, const float* __restrict rest,
                                                const float* __restrict px, const float* __restrict py,
                                                const float* __restrict pz, float* __restrict tx,
                                                float* __restrict ty, float* __restrict tz) {
    uint32_t over_limit = 0, over_promise = 0;
    for (size_t p = begin; p < last; ++p) {
        const size_t q = p + offset;
        const float dx = px[q] - px[p], dy = py[q] - py[p], dz = pz[q] - pz[p];
        const float length = std::sqrt(dx * dx + dy * dy + dz * dz);
        // Past the limit either way (shortest is 0 where compression is free).
        // At most one of the two is nonzero (shortest < stretch_limit).
        const float under = length - shortest * rest[p];
        const float excess = std::max(length - stretch_limit * rest[p], 0.0f) + std::min(under, 0.0f);
        // Zero within the limits (where the family has no spring, mask and
        // rest length are zero); a compressed term pushes the ends apart.
        const float c =
            excess != 0.0f ? weight * mask[p] * kRelaxation * excess / std::max(length, 1e-30f) : 0.0f;
        tx[p] = c * dx;
        ty[p] = c * dy;
        tz[p] = c * dz;
        over_limit += c != 0.0f;
        over_promise +=
            (mask[p] > 0.0f) & ((length > promise * rest[p]) | (under < -kStrainPromiseSlack * rest[p]));
    }
    return {over_limit, over_promise};
}

// The terms' weights in their ends' pull: `weight` where a term of
// [begin, last) is nonzero (its spring past the limits), else 0.
CLOTH_HOT_LOOP void term_pull_kernel(size_t begin, size_t last, float weight, const float* __restrict tx,
                                     const float* __restrict ty, const float* __restrict tz,
                                     float* __restrict tw) {
    for (size_t p = begin; p < last; ++p)
        tw[p] = ((tx[p] != 0.0f) | (ty[p] != 0.0f) | (tz[p] != 0.0f)) ? weight : 0.0f;
}

// Zero terms for springs [begin, last), and maybe[p] = 1 where spring p
// may be past the limits (shorter than `shortest` only kCompression).
template <bool kCompression>
CLOTH_HOT_LOOP void maybe_over_kernel(size_t begin, size_t last, size_t offset, float stretch_limit,
                                      float shortest, const float* __restrict mask,
                                      const float* __restrict rest, const float* __restrict px,
                                      const float* __restrict py, const float* __restrict pz,
                                      float* __restrict tx, float* __restrict ty, float* __restrict tz,
                                      float* __restrict tw, uint8_t* __restrict maybe) {
    for (size_t p = begin; p < last; ++p) {
        const size_t q = p + offset;
        const float dx = px[q] - px[p], dy = py[q] - py[p], dz = pz[q] - pz[p];
        const float allowed = stretch_limit * rest[p];
        const float squared = dx * dx + dy * dy + dz * dz, least = shortest * rest[p];
        const bool short_enough = kCompression && squared * kSurelyUnder <= least * least;
        maybe[p] = (mask[p] > 0.0f) & ((squared >= kSurelyUnder * (allowed * allowed)) | short_enough);
        tx[p] = 0.0f;
        ty[p] = 0.0f;
        tz[p] = 0.0f;
        tw[p] = 0.0f;
    }
}

// c_i += own share of t at i - (1 - their share) of t at i - offset
// (the back arrays are the same arrays, offset entries earlier), and the
// pull likewise from the terms' weights w; the first family assigns both
// instead of adding.
template <bool kFirst>
CLOTH_HOT_LOOP void family_corrections_kernel(size_t begin, size_t end, const float* __restrict tx,
                                              const float* __restrict ty, const float* __restrict tz,
                                              const float* __restrict share, const float* __restrict bx,
                                              const float* __restrict by, const float* __restrict bz,
                                              const float* __restrict back_share, const float* __restrict tw,
                                              const float* __restrict bw, float* __restrict cx,
                                              float* __restrict cy, float* __restrict cz,
                                              float* __restrict pull) {
    for (size_t i = begin; i < end; ++i) {
        const float mine = share[i], theirs = 1.0f - back_share[i];
        const float c[3] = {mine * tx[i] - theirs * bx[i], mine * ty[i] - theirs * by[i],
                            mine * tz[i] - theirs * bz[i]};
        const float p = mine * tw[i] + theirs * bw[i];
        // 0 + c, not c: a zero correction is +0 whatever the signs in its terms.
        cx[i] = (kFirst ? 0.0f : cx[i]) + c[0];
        cy[i] = (kFirst ? 0.0f : cy[i]) + c[1];
        cz[i] = (kFirst ? 0.0f : cz[i]) + c[2];
        pull[i] = (kFirst ? 0.0f : pull[i]) + p;
    }
}

}  // namespace

StretchCount strain_limit_grid_terms(const StrainLimitPass& pass, const Vec3Soa& x, uint32_t begin,
                                     uint32_t end, bool shares, GridStrainTerms& terms) {
    const Fabric& f = *pass.fabric;
    const uint32_t n = f.particle_count();
    const float stretch_limit = 1.0f + pass.max_strain, promise = stretch_limit + kStrainPromiseSlack;
    StretchCount count;
    for (size_t k = 0; k < terms.families.size(); ++k) {
        const SpringFamily& family = *terms.families[k];
        const float shortest = terms.compresses[k] != 0 ? 1.0f - pass.max_strain : 0.0f;
        const uint32_t last = std::min(end, n > family.offset ? n - family.offset : 0u);
        if (begin >= last) continue;
        const size_t base = k * terms.stride + terms.lead;
        float* tx = terms.x.data() + base;
        float* ty = terms.y.data() + base;
        float* tz = terms.z.data() + base;
        float* tw = terms.pull.data() + base;
        if (shares)
            family_shares_kernel(begin, last, family.offset, pass.mass, pass.pinned,
                                 terms.share.data() + base);
        const auto exact = [&](uint32_t run, uint32_t run_end) {
            const StretchCount found =
                family_terms_kernel(run, run_end, family.offset, stretch_limit, promise, shortest,
                                    terms.weight[k], family.mask.data(), family.rest_length.data(),
                                    x.x.data(), x.y.data(), x.z.data(), tx, ty, tz);
            term_pull_kernel(run, run_end, kRelaxation * terms.weight[k], tx, ty, tz, tw);
            count.over_limit += found.over_limit;
            count.over_promise += found.over_promise;
        };
        if (pass.maybe_over == nullptr) {
            exact(begin, last);
            continue;
        }
        (shortest > 0.0f ? maybe_over_kernel<true>
                         : maybe_over_kernel<false>)(begin, last, family.offset, stretch_limit, shortest,
                                                     family.mask.data(), family.rest_length.data(),
                                                     x.x.data(), x.y.data(), x.z.data(), tx, ty, tz, tw,
                                                     pass.maybe_over);
        for_each_maybe_span(pass.maybe_over, begin, last, exact);
    }
    return count;
}

void strain_limit_grid_corrections(const StrainLimitPass& pass, const GridStrainTerms& terms, uint32_t begin,
                                   uint32_t end, Vec3Soa& correction) {
    for (size_t k = 0; k < terms.families.size(); ++k) {  // a grid has structural families
        const size_t base = k * terms.stride + terms.lead;
        const size_t back = base - terms.families[k]->offset;  // >= k * stride: the lead
        (k == 0 ? family_corrections_kernel<true>
                : family_corrections_kernel<false>)(begin, end, terms.x.data() + base, terms.y.data() + base,
                                                    terms.z.data() + base, terms.share.data() + base,
                                                    terms.x.data() + back, terms.y.data() + back,
                                                    terms.z.data() + back, terms.share.data() + back,
                                                    terms.pull.data() + base, terms.pull.data() + back,
                                                    correction.x.data(), correction.y.data(),
                                                    correction.z.data(), pass.pull);
    }
    divide_by_pull(pass.pull, pass.pinned, begin, end, correction.x.data(), correction.y.data(),
                   correction.z.data());
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
    iterations_ = asked_ = iterations;
    past_promise_ = false;
    round_ = 0;
    h_ = h;
    x_ = &x;
    v_ = &v;
    correction_ = &correction;
    previous_ = &previous;
    omega_ = schedule_omega_ = 1.0f;
    accelerate_ = accelerate;
}

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
            if (pass + 1 == asked_) past_promise_ = over_promise > 0;
            if (over_limit == 0) {
                iterations_ = pass + 1;  // this pass applies nothing, nor would any after it
            } else if (over_promise > 0 && pass + 1 == iterations_ && iterations_ < max_iterations_) {
                ++iterations_;
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
