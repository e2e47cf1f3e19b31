#include "solve/integrate.h"

#include "base/lanes.h"

namespace cloth {

CLOTH_HOT_LOOP void integrate_implicit(const Vec3Soa& x, const Vec3Soa& v, const Vec3Soa& dv, float h,
                                       uint32_t begin, uint32_t end, Vec3Soa& x_out, Vec3Soa& v_out) {
    for_each_lane_group(begin, end, begin, end, [&](auto lanes, uint32_t i) {
        using L = decltype(lanes);
        const typename L::type vx = L::load(&v.x[i]) + L::load(&dv.x[i]);
        const typename L::type vy = L::load(&v.y[i]) + L::load(&dv.y[i]);
        const typename L::type vz = L::load(&v.z[i]) + L::load(&dv.z[i]);
        store_vec3<L>(x_out, i, L::load(&x.x[i]) + vx * h, L::load(&x.y[i]) + vy * h,
                      L::load(&x.z[i]) + vz * h);
        store_vec3<L>(v_out, i, vx, vy, vz);
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
