#include "solve/linear_system.h"

#include "base/lanes.h"

namespace cloth {

CLOTH_HOT_LOOP void assemble_particles(const AssemblyPass& pass, uint32_t begin, uint32_t end,
                                       Sym3Soa& diagonal, Sym3Soa& diagonal_inverse, Vec3Soa& rhs,
                                       Vec3Soa& p) {
    const Vec3Soa& external = *pass.external_force;
    const float mass_factor = 1.0f + pass.theta * pass.h * pass.linear_drag;
    // rhs starts as the external force, diagonal as m (1 + h c) I; the
    // springs add theirs.
    for_each_lane_group(begin, end, begin, end, [&](auto lanes, uint32_t i) {
        using L = decltype(lanes);
        const typename L::type zero{}, m = L::load(&pass.mass[i]) * mass_factor;
        store_vec3<L>(rhs, i, L::load(&external.x[i]), L::load(&external.y[i]), L::load(&external.z[i]));
        store_sym3(diagonal, i, Sym3Lanes<L>{m, zero, zero, m, zero, m});
    });
    pass.springs->gather(begin, end, rhs, &diagonal);
    // b = h f~, W^-1 by cofactors (zero for pinned particles), p = W^-1 b.
    for_each_lane_group(begin, end, begin, end, [&](auto lanes, uint32_t i) {
        using L = decltype(lanes);
        using T = typename L::type;
        const Sym3Lanes<L> w = load_sym3<L>(diagonal, i);
        T inverse[6];
        invert_symmetric(w.xx, w.xy, w.xz, w.yy, w.yz, w.zz, 1.0f - L::load(&pass.pinned[i]), inverse);
        const Sym3Lanes<L> iw{inverse[0], inverse[1], inverse[2], inverse[3], inverse[4], inverse[5]};
        store_sym3(diagonal_inverse, i, iw);
        const T bx = L::load(&rhs.x[i]) * pass.h, by = L::load(&rhs.y[i]) * pass.h,
                bz = L::load(&rhs.z[i]) * pass.h;
        store_vec3<L>(rhs, i, bx, by, bz);
        store_vec3<L>(p, i, iw.xx * bx + iw.xy * by + iw.xz * bz, iw.xy * bx + iw.yy * by + iw.yz * bz,
                      iw.xz * bx + iw.yz * by + iw.zz * bz);
    });
}

CLOTH_HOT_LOOP void jacobi_sweep(const LinearSystem& system, const Vec3Soa& current, uint32_t begin,
                                 uint32_t end, Vec3Soa& next) {
    system.springs->neighbour_sums(current, begin, end, next);
    const Sym3Soa& w = *system.diagonal_inverse;
    const Vec3Soa& b = *system.rhs;
    for_each_lane_group(begin, end, begin, end, [&](auto lanes, uint32_t i) {
        using L = decltype(lanes);
        using T = typename L::type;
        const T x = L::load(&b.x[i]) + L::load(&next.x[i]);
        const T y = L::load(&b.y[i]) + L::load(&next.y[i]);
        const T z = L::load(&b.z[i]) + L::load(&next.z[i]);
        const T xy = L::load(&w.xy[i]), xz = L::load(&w.xz[i]), yz = L::load(&w.yz[i]);
        L::store(&next.x[i], L::load(&w.xx[i]) * x + xy * y + xz * z);
        L::store(&next.y[i], xy * x + L::load(&w.yy[i]) * y + yz * z);
        L::store(&next.z[i], xz * x + yz * y + L::load(&w.zz[i]) * z);
    });
}

CLOTH_HOT_LOOP void multiply_system(const LinearSystem& system, const Vec3Soa& x, uint32_t begin,
                                    uint32_t end, Vec3Soa& y) {
    system.springs->neighbour_sums(x, begin, end, y);
    const Sym3Soa& w = *system.diagonal;
    for_each_lane_group(begin, end, begin, end, [&](auto lanes, uint32_t i) {
        using L = decltype(lanes);
        using T = typename L::type;
        const T free = 1.0f - L::load(&system.pinned[i]);
        const T px = L::load(&x.x[i]), py = L::load(&x.y[i]), pz = L::load(&x.z[i]);
        const T xy = L::load(&w.xy[i]), xz = L::load(&w.xz[i]), yz = L::load(&w.yz[i]);
        store_vec3<L>(y, i, (L::load(&w.xx[i]) * px + xy * py + xz * pz - L::load(&y.x[i])) * free,
                      (xy * px + L::load(&w.yy[i]) * py + yz * pz - L::load(&y.y[i])) * free,
                      (xz * px + yz * py + L::load(&w.zz[i]) * pz - L::load(&y.z[i])) * free);
    });
}

}  // namespace cloth
