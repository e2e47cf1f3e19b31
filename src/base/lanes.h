// Lanes: the same per-particle code run on one particle (float) or on eight
// consecutive particles at once (a GCC/Clang vector of eight floats), so a
// loop's vector body and its scalar edges are one source and sum in the
// same order: results do not depend on which particles went through which.
#pragma once

#include <cstdint>
#include <cstring>

#include "base/soa.h"

// Hot loops are compiled twice on x86-64, for AVX2 and for the baseline,
// and the loader picks one per machine. No FMA in either (-ffp-contract=off
// and no "fma" target), so both give the same bits.
// ThreadSanitizer instruments the loader's ifunc resolvers, which run
// before its runtime exists, so TSan builds keep the baseline only.
#if defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define CLOTH_TSAN 1
#endif
#endif
#if defined(__SANITIZE_THREAD__)
#define CLOTH_TSAN 1
#endif
// Clang (the fuzz build) refuses target_clones on a member function that
// was declared before its definition, so clang builds keep the baseline too.
#if defined(__x86_64__) && defined(__GNUC__) && defined(__ELF__) && !defined(CLOTH_TSAN) && \
    !defined(__clang__)
#define CLOTH_HOT_LOOP __attribute__((target_clones("avx2", "default")))
#else
#define CLOTH_HOT_LOOP
#endif

// Every function that takes or returns lanes by value is always inlined.
// An out-of-line copy would be a problem, not just slow: compiled for the
// baseline it takes eight-float vectors in memory, while an AVX2 caller
// passes them in ymm registers, so a non-inlining build (-O0/-O1) read
// garbage (fixed here; scripts/test builds the sanitizer trees at -O1 to
// keep it fixed).
#define CLOTH_LANES_INLINE __attribute__((always_inline)) inline
// The same for a lambda passed to a loop helper (for_each_block): out of
// line it is compiled for the baseline only, whatever its caller's clone.
#define CLOTH_LANES_INLINE_LAMBDA __attribute__((always_inline))

namespace cloth {

// A lanes type is a trait, named in the standard library's style: L::type and
// L::width (not Type and kWidth; .clang-tidy allows these two names).
struct ScalarLanes {
    using type = float;
    static constexpr uint32_t width = 1;
    CLOTH_LANES_INLINE static float load(const float* p) { return *p; }
    CLOTH_LANES_INLINE static void store(float* p, float v) { *p = v; }
};

struct VectorLanes {
    // Eight floats: one AVX register, or two SSE registers on the baseline.
    typedef float type __attribute__((vector_size(32)));
    static constexpr uint32_t width = 8;
    CLOTH_LANES_INLINE static type load(const float* p) {
        type v;
        std::memcpy(&v, p, sizeof v);
        return v;
    }
    // Stored as floats (a float vector with float alignment), not through
    // memcpy: a memcpy store may alias anything, so GCC would reload every
    // array pointer (read from a HostVector) after each store.
    typedef float Unaligned __attribute__((vector_size(32), aligned(4)));
    CLOTH_LANES_INLINE static void store(float* p, type v) { *reinterpret_cast<Unaligned*>(p) = v; }
};

// Calls body(lanes, p) over [begin, end): eight particles at a time where
// [p, p + 8) lies inside [vector_begin, vector_end), one at a time elsewhere.
// Always inlined with the body flattened into it, so a CLOTH_HOT_LOOP
// caller compiles the loop for its own target (AVX2) instead of calling an
// out-of-line baseline copy.
template <class Body>
__attribute__((always_inline, flatten)) inline void for_each_lane_group(uint32_t begin, uint32_t end,
                                                                        uint32_t vector_begin,
                                                                        uint32_t vector_end, Body body) {
    uint32_t p = begin;
    for (; p < end && p < vector_begin; ++p) body(ScalarLanes{}, p);
    for (; p + VectorLanes::width <= end && p + VectorLanes::width <= vector_end; p += VectorLanes::width) {
        body(VectorLanes{}, p);
    }
    for (; p < end; ++p) body(ScalarLanes{}, p);
}

// Whole entries of the structure-of-arrays types, lanes at a time.
template <class L>
struct Sym3Lanes {
    typename L::type xx, xy, xz, yy, yz, zz;
};

template <class L>
CLOTH_LANES_INLINE Sym3Lanes<L> load_sym3(const Sym3Soa& a, uint32_t i) {
    return {L::load(&a.xx[i]), L::load(&a.xy[i]), L::load(&a.xz[i]),
            L::load(&a.yy[i]), L::load(&a.yz[i]), L::load(&a.zz[i])};
}

template <class L>
CLOTH_LANES_INLINE void store_sym3(Sym3Soa& a, uint32_t i, const Sym3Lanes<L>& m) {
    L::store(&a.xx[i], m.xx);
    L::store(&a.xy[i], m.xy);
    L::store(&a.xz[i], m.xz);
    L::store(&a.yy[i], m.yy);
    L::store(&a.yz[i], m.yz);
    L::store(&a.zz[i], m.zz);
}

// (ox, oy, oz) = M_i (x, y, z) for the symmetric 3x3 blocks M.
template <class L>
CLOTH_LANES_INLINE void sym3_times(const Sym3Soa& m, uint32_t i, typename L::type x, typename L::type y,
                                   typename L::type z, typename L::type& ox, typename L::type& oy,
                                   typename L::type& oz) {
    using T = typename L::type;
    const T xy = L::load(&m.xy[i]), xz = L::load(&m.xz[i]), yz = L::load(&m.yz[i]);
    ox = L::load(&m.xx[i]) * x + xy * y + xz * z;
    oy = xy * x + L::load(&m.yy[i]) * y + yz * z;
    oz = xz * x + yz * y + L::load(&m.zz[i]) * z;
}

template <class L>
CLOTH_LANES_INLINE void store_vec3(Vec3Soa& a, uint32_t i, typename L::type x, typename L::type y,
                                   typename L::type z) {
    L::store(&a.x[i], x);
    L::store(&a.y[i], y);
    L::store(&a.z[i], z);
}

}  // namespace cloth
