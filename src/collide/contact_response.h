// The velocity response of a particle-particle contact (paper eq. 13),
// shared by self-collision and contact between two cloths.
#pragma once

#include <algorithm>

#include "base/math.h"

namespace cloth {

// What particle i's velocity gains from one contact whose unit `normal`
// points towards i, with `relative` = v_i - v_j approaching along it
// (`approach` = relative . normal < 0): i's `share` of the approaching
// part removed (its inverse mass over the pair's), and Coulomb `friction`
// on the sliding part, at most stopping it.
inline Vec3 contact_velocity_change(const Vec3& relative, const Vec3& normal, float approach, float share,
                                    float friction) {
    Vec3 dv = normal * (-share * approach);
    if (friction > 0) {
        const Vec3 tangential = relative - normal * approach;
        const float speed = tangential.norm();
        if (speed > 0) dv -= tangential * (share * std::min(1.0f, -friction * approach / speed));
    }
    return dv;
}

}  // namespace cloth
