// Block-Jacobi-preconditioned conjugate gradient on the library's own
// passes: the product W p is the per-particle gather of multiply_system,
// the preconditioner is the W_ii^-1 the assembly stage already stored, and
// the two dot products per iteration are summed per fixed block of
// particles and then in block order (deterministic for any thread count).
// Written by hand rather than with Eigen's CG because it must run as range
// passes over the SoA buffers, allocate nothing and split across workers.
#include <algorithm>
#include <cmath>

#include "base/lanes.h"
#include "solve/multigrid.h"
#include "solve/solvers.h"

namespace cloth {
namespace {

// Lane-wise accumulator of one block's dot product: float lanes over a
// block (their grouping is fixed by the block's start, so the sum is the
// same for any split), then added lane by lane in double.
struct BlockSum {
    float lanes[VectorLanes::width] = {};
    template <class L>
    CLOTH_LANES_INLINE void add(uint32_t offset, typename L::type value) {
        if constexpr (L::width == 1) {
            lanes[offset % VectorLanes::width] += value;
        } else {
            L::store(lanes, L::load(lanes) + value);
        }
    }
    double total() const {
        double sum = 0;
        for (float lane : lanes) sum += lane;
        return sum;
    }
};

// z_i = W_ii^-1 r_i (zero for pinned particles), lanes at a time.
template <class L>
CLOTH_LANES_INLINE void precondition(const Sym3Soa& w, const Vec3Soa& r, uint32_t i, Vec3Soa& z) {
    typename L::type ox, oy, oz;
    sym3_times<L>(w, i, L::load(&r.x[i]), L::load(&r.y[i]), L::load(&r.z[i]), ox, oy, oz);
    store_vec3<L>(z, i, ox, oy, oz);
}

template <class L>
CLOTH_LANES_INLINE typename L::type dot(const Vec3Soa& a, const Vec3Soa& b, uint32_t i) {
    return L::load(&a.x[i]) * L::load(&b.x[i]) + L::load(&a.y[i]) * L::load(&b.y[i]) +
           L::load(&a.z[i]) * L::load(&b.z[i]);
}

// r = (b - q) (free), dv += a p and r -= a q: lanes at a time.
template <class L>
CLOTH_LANES_INLINE void start_residual(const LinearSystem& system, uint32_t i, SolverWorkspace& work) {
    using T = typename L::type;
    const Vec3Soa& b = *system.rhs;
    const T free = 1.0f - L::load(&system.pinned[i]);
    store_vec3<L>(work.r, i, (L::load(&b.x[i]) - L::load(&work.q.x[i])) * free,
                  (L::load(&b.y[i]) - L::load(&work.q.y[i])) * free,
                  (L::load(&b.z[i]) - L::load(&work.q.z[i])) * free);
}

template <class L>
CLOTH_LANES_INLINE void step_along(float a, uint32_t i, Vec3Soa& dv, SolverWorkspace& work) {
    store_vec3<L>(dv, i, L::load(&dv.x[i]) + L::load(&work.p.x[i]) * a,
                  L::load(&dv.y[i]) + L::load(&work.p.y[i]) * a,
                  L::load(&dv.z[i]) + L::load(&work.p.z[i]) * a);
    store_vec3<L>(work.r, i, L::load(&work.r.x[i]) - L::load(&work.q.x[i]) * a,
                  L::load(&work.r.y[i]) - L::load(&work.q.y[i]) * a,
                  L::load(&work.r.z[i]) - L::load(&work.q.z[i]) * a);
}

}  // namespace

double sum_partials(const SolverWorkspace& work) {
    double sum = 0;
    for (double partial : work.partial) sum += partial;
    return sum;
}

CLOTH_HOT_LOOP void pcg_start(const LinearSystem& system, const Vec3Soa& dv, uint32_t begin, uint32_t end,
                              SolverWorkspace& work) {
    multiply_system(system, dv, begin, end, work.q);
    for_each_block(begin, end, [&](uint32_t block, uint32_t first, uint32_t last) CLOTH_LANES_INLINE_LAMBDA {
        BlockSum sum;
        for_each_lane_group(first, last, first, last, [&](auto lanes, uint32_t i) {
            using L = decltype(lanes);
            start_residual<L>(system, i, work);
            precondition<L>(*system.diagonal_inverse, work.r, i, work.z);
            store_vec3<L>(work.p, i, L::load(&work.z.x[i]), L::load(&work.z.y[i]), L::load(&work.z.z[i]));
            sum.add<L>(i - first, dot<L>(work.r, work.z, i));
        });
        work.partial[block] = sum.total();
    });
}

CLOTH_HOT_LOOP void pcg_product(const LinearSystem& system, uint32_t begin, uint32_t end,
                                SolverWorkspace& work) {
    multiply_system(system, work.p, begin, end, work.q);
    for_each_block(begin, end, [&](uint32_t block, uint32_t first, uint32_t last) CLOTH_LANES_INLINE_LAMBDA {
        BlockSum sum;
        for_each_lane_group(first, last, first, last, [&](auto lanes, uint32_t i) {
            using L = decltype(lanes);
            sum.add<L>(i - first, dot<L>(work.p, work.q, i));
        });
        work.partial[block] = sum.total();
    });
}

CLOTH_HOT_LOOP void pcg_update(const LinearSystem& system, double alpha, uint32_t begin, uint32_t end,
                               Vec3Soa& dv, SolverWorkspace& work) {
    const float a = static_cast<float>(alpha);
    for_each_block(begin, end, [&](uint32_t block, uint32_t first, uint32_t last) CLOTH_LANES_INLINE_LAMBDA {
        BlockSum sum;
        for_each_lane_group(first, last, first, last, [&](auto lanes, uint32_t i) {
            using L = decltype(lanes);
            step_along<L>(a, i, dv, work);
            precondition<L>(*system.diagonal_inverse, work.r, i, work.z);
            sum.add<L>(i - first, dot<L>(work.r, work.z, i));
        });
        work.partial[block] = sum.total();
    });
}

// With the multigrid preconditioner (multigrid.h): the same passes, but
// z = M r is a V-cycle, so the start and the update only begin it (the
// first smoothing sweep) and pcg_smooth ends it with the dot product.

CLOTH_HOT_LOOP void pcg_start_multigrid(const LinearSystem& system, const Vec3Soa& dv, uint32_t begin,
                                        uint32_t end, SolverWorkspace& work) {
    multiply_system(system, dv, begin, end, work.q);
    for_each_lane_group(begin, end, begin, end,
                        [&](auto lanes, uint32_t i) { start_residual<decltype(lanes)>(system, i, work); });
    Multigrid::smooth_from_zero(system, work.r, begin, end, work.z);
}

CLOTH_HOT_LOOP void pcg_update_multigrid(const LinearSystem& system, double alpha, uint32_t begin,
                                         uint32_t end, Vec3Soa& dv, SolverWorkspace& work) {
    const float a = static_cast<float>(alpha);
    for_each_lane_group(begin, end, begin, end,
                        [&](auto lanes, uint32_t i) { step_along<decltype(lanes)>(a, i, dv, work); });
    Multigrid::smooth_from_zero(system, work.r, begin, end, work.z);
}

CLOTH_HOT_LOOP void pcg_smooth(const LinearSystem& system, bool first, uint32_t begin, uint32_t end,
                               SolverWorkspace& work) {
    multiply_system(system, work.z, begin, end, work.q);
    const Sym3Soa& w = *system.diagonal_inverse;
    const float weight = Multigrid::kSmootherWeight;
    for_each_block(
        begin, end, [&](uint32_t block, uint32_t first_particle, uint32_t last) CLOTH_LANES_INLINE_LAMBDA {
            BlockSum sum;
            for_each_lane_group(first_particle, last, first_particle, last, [&](auto lanes, uint32_t i) {
                using L = decltype(lanes);
                using T = typename L::type;
                const T x = (L::load(&work.r.x[i]) - L::load(&work.q.x[i])) * weight;
                const T y = (L::load(&work.r.y[i]) - L::load(&work.q.y[i])) * weight;
                const T z = (L::load(&work.r.z[i]) - L::load(&work.q.z[i])) * weight;
                const T xy = L::load(&w.xy[i]), xz = L::load(&w.xz[i]), yz = L::load(&w.yz[i]);
                store_vec3<L>(work.q, i, L::load(&work.z.x[i]) + L::load(&w.xx[i]) * x + xy * y + xz * z,
                              L::load(&work.z.y[i]) + xy * x + L::load(&w.yy[i]) * y + yz * z,
                              L::load(&work.z.z[i]) + xz * x + yz * y + L::load(&w.zz[i]) * z);
                if (first)
                    store_vec3<L>(work.p, i, L::load(&work.q.x[i]), L::load(&work.q.y[i]),
                                  L::load(&work.q.z[i]));
                sum.add<L>(i - first_particle, dot<L>(work.r, work.q, i));
            });
            work.partial[block] = sum.total();
        });
}

CLOTH_HOT_LOOP void pcg_direction(double beta, uint32_t begin, uint32_t end, SolverWorkspace& work) {
    const float bt = static_cast<float>(beta);
    for_each_lane_group(begin, end, begin, end, [&](auto lanes, uint32_t i) {
        using L = decltype(lanes);
        store_vec3<L>(work.p, i, L::load(&work.z.x[i]) + L::load(&work.p.x[i]) * bt,
                      L::load(&work.z.y[i]) + L::load(&work.p.y[i]) * bt,
                      L::load(&work.z.z[i]) + L::load(&work.p.z[i]) * bt);
    });
}

}  // namespace cloth
