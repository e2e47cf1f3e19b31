#include "integrator_explicit.h"

namespace cloth {

void integrate_explicit(const Fabric& fabric, const Vec3Soa& spring_force, const Vec3Soa& external_force,
                        const float* mass, const uint8_t* pinned, float h, uint32_t begin, uint32_t end, Vec3Soa& v,
                        Vec3Soa& x) {
    for (uint32_t i = begin; i < end; ++i) {
        if (pinned[i]) continue;
        Vec3 force = external_force.get(i);
        for (uint32_t e = fabric.incidence_offset[i]; e < fabric.incidence_offset[i + 1]; ++e) {
            force += spring_force.get(fabric.incidence_spring[e]) * fabric.incidence_sign[e];
        }
        const Vec3 velocity = v.get(i) + force * (h / mass[i]);
        v.set(i, velocity);
        x.set(i, x.get(i) + velocity * h);
    }
}

}  // namespace cloth
