#include "solve/integrate.h"

#include "base/lanes.h"

namespace cloth {

CLOTH_HOT_LOOP void integrate_implicit(const Vec3Soa& x, const Vec3Soa& v, const Vec3Soa& dv, float h,
                                       float theta, uint32_t begin, uint32_t end, Vec3Soa& x_out,
                                       Vec3Soa& v_out) {
    for_each_lane_group(begin, end, begin, end, [&](auto lanes, uint32_t i) {
        using L = decltype(lanes);
        using T = typename L::type;
        const T vx = L::load(&v.x[i]), vy = L::load(&v.y[i]), vz = L::load(&v.z[i]);
        const T dvx = L::load(&dv.x[i]), dvy = L::load(&dv.y[i]), dvz = L::load(&dv.z[i]);
        // theta = 1: v + dv, the same bits as backward Euler's v'.
        store_vec3<L>(x_out, i, L::load(&x.x[i]) + (vx + dvx * theta) * h,
                      L::load(&x.y[i]) + (vy + dvy * theta) * h, L::load(&x.z[i]) + (vz + dvz * theta) * h);
        store_vec3<L>(v_out, i, vx + dvx, vy + dvy, vz + dvz);
    });
}

void integrate_explicit(const Vec3Soa& force, const float* mass, const float* pinned, float h, uint32_t begin,
                        uint32_t end, Vec3Soa& v, Vec3Soa& x) {
    for (uint32_t i = begin; i < end; ++i) {
        if (pinned[i]) continue;
        const Vec3 velocity = v.get(i) + force.get(i) * (h / mass[i]);
        v.set(i, velocity);
        x.set(i, x.get(i) + velocity * h);
    }
}

}  // namespace cloth
