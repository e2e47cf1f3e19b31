#include "solve/integrate.h"

namespace cloth {

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
