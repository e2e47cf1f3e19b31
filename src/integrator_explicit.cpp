#include "integrator_explicit.h"

namespace cloth {

void integrate_explicit(const Fabric& fabric, const Vec3* spring_force, const Vec3* external_force,
                        const float* mass, const uint8_t* pinned, float h, uint32_t begin, uint32_t end, Vec3* v,
                        Vec3* x) {
    for (uint32_t i = begin; i < end; ++i) {
        if (pinned[i]) continue;
        Vec3 force = external_force[i];
        for (uint32_t e = fabric.incidence_offset[i]; e < fabric.incidence_offset[i + 1]; ++e) {
            force += spring_force[fabric.incidence_spring[e]] * fabric.incidence_sign[e];
        }
        v[i] += force * (h / mass[i]);
        x[i] += v[i] * h;
    }
}

}  // namespace cloth
