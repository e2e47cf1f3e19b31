// What the strain limiter's two paths share (strain_limit.cpp for meshes,
// strain_limit_grid.cpp for grid families): the pass's constants, the walk
// over the runs that may be over the limit, and the division by the pull.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstring>

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

// c_i /= max(1, pull_i), and zero where pinned (a null `pinned`: none is).
// Within the bound the factor is exactly 1: the same bits as no division.
void divide_by_pull(const float* pull, const float* pinned, uint32_t begin, uint32_t end, float* cx,
                    float* cy, float* cz);

}  // namespace cloth
