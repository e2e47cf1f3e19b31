// The external-force guess every iterative solver starts from (solvers.h).
#include "base/lanes.h"
#include "solve/solvers.h"

namespace cloth {

CLOTH_HOT_LOOP void external_force_guess(const AssemblyPass& pass, uint32_t begin, uint32_t end,
                                         Vec3Soa& dv) {
    const Vec3Soa& f = *pass.external_force;
    const float mass_factor = 1.0f + pass.h * pass.linear_drag;
    for_each_lane_group(begin, end, begin, end, [&](auto lanes, uint32_t i) {
        using L = decltype(lanes);
        using T = typename L::type;
        // h / (m (1 + h c)) on free particles, 0 on pinned ones.
        const T scale = (1.0f - L::load(&pass.pinned[i])) * pass.h / (L::load(&pass.mass[i]) * mass_factor);
        store_vec3<L>(dv, i, L::load(&f.x[i]) * scale, L::load(&f.y[i]) * scale, L::load(&f.z[i]) * scale);
    });
}

}  // namespace cloth
