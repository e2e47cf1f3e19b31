#include "springs.h"

namespace cloth {

SpringEval spring_force_and_jacobian(const Vec3& xi, const Vec3& xj, float rest_length, float stiffness,
                                     bool compression_safe) {
    const JacobianClamp clamp = JacobianClamp::make(compression_safe);
    const Vec3 d = xj - xi;
    const float length = d.norm();
    const Vec3 u = d / length;
    const float ratio = rest_length / length;
    const float a = stiffness * std::max(clamp.a_min, 1.0f - ratio);
    const float b = stiffness * std::min(clamp.ratio_max, ratio);
    return SpringEval{u * (stiffness * (length - rest_length)), Sym3::identity(a) + Sym3::outer(u, b)};
}

}  // namespace cloth
