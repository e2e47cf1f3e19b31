#include "forces/springs.h"

namespace cloth {

SpringEval spring_force_and_jacobian(const Vec3& xi, const Vec3& xj, float rest_length, float stiffness,
                                     bool compression_safe) {
    // The step's own kernel with no velocity, no damping and h = 1: the
    // force is k (L - l0) u and the block h^2 J + h c u u^T is J.
    const Vec3 d = xj - xi;
    const SpringTerm t = spring_term(d.x(), d.y(), d.z(), 0.0f, 0.0f, 0.0f, rest_length, stiffness, 0.0f,
                                     1.0f, SpringModel::make(compression_safe));
    return SpringEval{Vec3(t.fx, t.fy, t.fz), Sym3{t.bxx, t.bxy, t.bxz, t.byy, t.byz, t.bzz}};
}

}  // namespace cloth
