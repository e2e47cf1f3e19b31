// Chebyshev semi-iteration over block Jacobi (Saad, Iterative Methods for
// Sparse Linear Systems, Algorithm 12.1, with the block-diagonal
// preconditioner P = D^-1), then one exact line search (solvers.h). The
// eigenvalue interval comes from bounds that hold for every cloth
// (solvers.h), so nothing is estimated at run time and the iterations need
// no dot product: every pass is a loop over particles. The line search
// takes the only two, once per solve.
#include <algorithm>
#include <cmath>
#include <limits>

#include "base/lanes.h"
#include "solve/solvers.h"

namespace cloth {

float chebyshev_lower_bound(const LinearSystem& system, const AssemblyPass& pass, uint32_t begin,
                            uint32_t end) {
    const float mass_factor = 1.0f + pass.h * pass.linear_drag;
    const Sym3Soa& w = *system.diagonal;
    float bound = 1.0f;
    for (uint32_t i = begin; i < end; ++i) {
        if (system.pinned[i] != 0.0f) continue;
        const float m = pass.mass[i] * mass_factor;
        const float springs = w.xx[i] + w.yy[i] + w.zz[i] - 3.0f * m;  // sum of trace A_s >= lambda_max
        bound = std::min(bound, m / (m + springs));
    }
    return bound;
}

void chebyshev_start(const LinearSystem& system, const Vec3Soa& dv, float first_scale, uint32_t begin,
                     uint32_t end, SolverWorkspace& work) {
    multiply_system(system, dv, begin, end, work.q);
    const Vec3Soa& b = *system.rhs;
    const Sym3Soa& w = *system.diagonal_inverse;
    for (uint32_t i = begin; i < end; ++i) {
        // r = b - W dv; the inverse is zero on pinned rows, so p is too.
        const float x = b.x[i] - work.q.x[i], y = b.y[i] - work.q.y[i], z = b.z[i] - work.q.z[i];
        work.r.x[i] = x;
        work.r.y[i] = y;
        work.r.z[i] = z;
        work.p.x[i] = (w.xx[i] * x + w.xy[i] * y + w.xz[i] * z) * first_scale;
        work.p.y[i] = (w.xy[i] * x + w.yy[i] * y + w.yz[i] * z) * first_scale;
        work.p.z[i] = (w.xz[i] * x + w.yz[i] * y + w.zz[i] * z) * first_scale;
    }
}

CLOTH_HOT_LOOP void chebyshev_product(const LinearSystem& system, uint32_t begin, uint32_t end, Vec3Soa& dv,
                                      SolverWorkspace& work) {
    multiply_system(system, work.p, begin, end, work.q);
    for_each_lane_group(begin, end, begin, end, [&](auto lanes, uint32_t i) {
        using L = decltype(lanes);
        store_vec3<L>(dv, i, L::load(&dv.x[i]) + L::load(&work.p.x[i]),
                      L::load(&dv.y[i]) + L::load(&work.p.y[i]), L::load(&dv.z[i]) + L::load(&work.p.z[i]));
    });
}

CLOTH_HOT_LOOP void chebyshev_direction(const LinearSystem& system, float keep, float scale, uint32_t begin,
                                        uint32_t end, SolverWorkspace& work) {
    const Sym3Soa& w = *system.diagonal_inverse;
    for_each_lane_group(begin, end, begin, end, [&](auto lanes, uint32_t i) {
        using L = decltype(lanes);
        using T = typename L::type;
        const T x = L::load(&work.r.x[i]) - L::load(&work.q.x[i]);
        const T y = L::load(&work.r.y[i]) - L::load(&work.q.y[i]);
        const T z = L::load(&work.r.z[i]) - L::load(&work.q.z[i]);
        store_vec3<L>(work.r, i, x, y, z);
        const T xy = L::load(&w.xy[i]), xz = L::load(&w.xz[i]), yz = L::load(&w.yz[i]);
        const T zx = L::load(&w.xx[i]) * x + xy * y + xz * z;
        const T zy = xy * x + L::load(&w.yy[i]) * y + yz * z;
        const T zz = xz * x + yz * y + L::load(&w.zz[i]) * z;
        store_vec3<L>(work.p, i, L::load(&work.p.x[i]) * keep + zx * scale,
                      L::load(&work.p.y[i]) * keep + zy * scale, L::load(&work.p.z[i]) * keep + zz * scale);
    });
}

void chebyshev_energy(const LinearSystem& system, const Vec3Soa& dv, uint32_t begin, uint32_t end,
                      SolverWorkspace& work) {
    multiply_system(system, dv, begin, end, work.q);
    const Vec3Soa& b = *system.rhs;
    for_each_block(begin, end, [&](uint32_t block, uint32_t first, uint32_t last) CLOTH_LANES_INLINE_LAMBDA {
        double dwd = 0, bd = 0;
        for (uint32_t i = first; i < last; ++i) {
            dwd +=
                double(dv.x[i]) * work.q.x[i] + double(dv.y[i]) * work.q.y[i] + double(dv.z[i]) * work.q.z[i];
            bd += double(dv.x[i]) * b.x[i] + double(dv.y[i]) * b.y[i] + double(dv.z[i]) * b.z[i];
        }
        work.partial[block] = dwd;
        work.partial_second[block] = bd;
    });
}

double chebyshev_step_scale(const SolverWorkspace& work) {
    double dv_w_dv = 0, b_dv = 0;  // block order: the same sums for any split
    for (double partial : work.partial) dv_w_dv += partial;
    for (double partial : work.partial_second) b_dv += partial;
    // Not a positive finite curvature (an overflowed product, or W made
    // indefinite by compression_safe_jacobian off): keep dv as it is, and the
    // step's non-finite check sees what the iterations made of it.
    if (!(dv_w_dv > 0) || !std::isfinite(dv_w_dv) || !std::isfinite(b_dv)) return 1.0;
    // At most FLT_MAX: the scale is applied in float.
    return std::min(std::max(0.0, b_dv / dv_w_dv), double(std::numeric_limits<float>::max()));
}

void chebyshev_scale(float scale, uint32_t begin, uint32_t end, Vec3Soa& dv) {
    for (uint32_t i = begin; i < end; ++i) {
        dv.x[i] *= scale;
        dv.y[i] *= scale;
        dv.z[i] *= scale;
    }
}

}  // namespace cloth
