#include "springs.h"

#include "cloth_instance.h"

namespace cloth {
namespace {

Sym3 spring_jacobian(const Vec3& u, float length, float rest_length, float k, bool compression_safe) {
    if (compression_safe && length < rest_length) return Sym3::outer(u, k);
    const float ratio = rest_length / length;
    return Sym3::identity(k * (1.0f - ratio)) + Sym3::outer(u, k * ratio);
}

}  // namespace

SpringEval spring_force_and_jacobian(const Vec3& xi, const Vec3& xj, float rest_length, float stiffness,
                                     bool compression_safe) {
    const Vec3 d = xj - xi;
    const float length = d.norm();
    const Vec3 u = d / length;
    SpringEval out;
    out.force = u * (stiffness * (length - rest_length));
    out.jacobian = spring_jacobian(u, length, rest_length, stiffness, compression_safe);
    return out;
}

void evaluate_springs(const SpringPass& pass, uint32_t begin, uint32_t end, Vec3* force, Sym3* block) {
    const Fabric& f = *pass.fabric;
    const float h = pass.h;
    for (uint32_t s = begin; s < end; ++s) {
        const uint32_t i = f.spring_first[s], j = f.spring_second[s];
        const SpringParams& params = pass.params[f.spring_kind[s]];
        const Vec3 d = pass.x[j] - pass.x[i];
        const float length = d.norm();
        // Two particles on top of each other exert no force (direction undefined).
        if (!(length > 1e-9f)) {
            force[s].setZero();
            if (block) block[s] = Sym3{};
            continue;
        }
        const Vec3 u = d / length;
        const Vec3 relative_velocity = pass.v[j] - pass.v[i];
        const float k = params.stiffness, c = params.damping;
        Vec3 f_i = u * (k * (length - f.spring_rest_length[s]) + c * u.dot(relative_velocity));
        if (block) {
            const Sym3 jacobian = spring_jacobian(u, length, f.spring_rest_length[s], k, pass.compression_safe);
            f_i += (jacobian * relative_velocity) * h;
            block[s] = jacobian * (h * h) + Sym3::outer(u, h * c);
        }
        force[s] = f_i;
    }
}

}  // namespace cloth
