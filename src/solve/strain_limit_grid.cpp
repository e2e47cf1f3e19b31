// The strain limiter's grid path (strain_limit.h): the long-range families
// and the per-family terms and corrections, every loop contiguous.
#include <algorithm>
#include <cmath>

#include "base/lanes.h"
#include "solve/strain_limit.h"
#include "solve/strain_limit_kernels.h"

namespace cloth {

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
        const float shortest =
            terms.compresses[k] != 0 && pass.hold_compression ? 1.0f - pass.max_strain : 0.0f;
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

}  // namespace cloth
