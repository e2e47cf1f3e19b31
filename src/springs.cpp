#include "springs.h"

#include <algorithm>
#include <limits>

namespace cloth {
namespace {

// J = a I + b u u^T with a = k (1 - l0/L), b = k l0/L. Compression-safe
// (eq. 12) clamps a >= 0 and b <= k, which is exactly k u u^T when L < l0
// and leaves stretched springs untouched. These bounds turn the clamp on.
struct JacobianClamp {
    float a_min, ratio_max;
};

JacobianClamp clamp_for(bool compression_safe) {
    const float inf = std::numeric_limits<float>::infinity();
    return compression_safe ? JacobianClamp{0.0f, 1.0f} : JacobianClamp{-inf, inf};
}

}  // namespace

SpringEval spring_force_and_jacobian(const Vec3& xi, const Vec3& xj, float rest_length, float stiffness,
                                     bool compression_safe) {
    const JacobianClamp clamp = clamp_for(compression_safe);
    const Vec3 d = xj - xi;
    const float length = d.norm();
    const Vec3 u = d / length;
    const float ratio = rest_length / length;
    const float a = stiffness * std::max(clamp.a_min, 1.0f - ratio);
    const float b = stiffness * std::min(clamp.ratio_max, ratio);
    return SpringEval{u * (stiffness * (length - rest_length)), Sym3::identity(a) + Sym3::outer(u, b)};
}

namespace {

// The kernels take every array as a __restrict parameter: GCC trusts
// restrict on parameters (not on locals) and only then vectorizes the
// indexed loads of particle data.
void spring_forces_kernel(uint32_t begin, uint32_t end, const uint32_t* __restrict first,
                          const uint32_t* __restrict second, const float* __restrict rest,
                          const float* __restrict stiffness, const float* __restrict damping,
                          const float* __restrict px, const float* __restrict py, const float* __restrict pz,
                          const float* __restrict vx, const float* __restrict vy, const float* __restrict vz,
                          float* __restrict fx, float* __restrict fy, float* __restrict fz) {
    for (uint32_t s = begin; s < end; ++s) {
        const uint32_t i = first[s], j = second[s];
        const float dx = px[j] - px[i], dy = py[j] - py[i], dz = pz[j] - pz[i];
        // Two coincident particles exert no force: the length is floored so u = 0.
        const float length = std::max(std::sqrt(dx * dx + dy * dy + dz * dz), 1e-9f);
        const float inv = 1.0f / length;
        const float ux = dx * inv, uy = dy * inv, uz = dz * inv;
        const float rvx = vx[j] - vx[i], rvy = vy[j] - vy[i], rvz = vz[j] - vz[i];
        const float magnitude = stiffness[s] * (length - rest[s]) + damping[s] * (ux * rvx + uy * rvy + uz * rvz);
        fx[s] = ux * magnitude;
        fy[s] = uy * magnitude;
        fz[s] = uz * magnitude;
    }
}

void spring_system_kernel(uint32_t begin, uint32_t end, JacobianClamp clamp, float h,
                          const uint32_t* __restrict first, const uint32_t* __restrict second,
                          const float* __restrict rest, const float* __restrict stiffness,
                          const float* __restrict damping, const float* __restrict px, const float* __restrict py,
                          const float* __restrict pz, const float* __restrict vx, const float* __restrict vy,
                          const float* __restrict vz, float* __restrict fx, float* __restrict fy,
                          float* __restrict fz, float* __restrict bxx, float* __restrict bxy, float* __restrict bxz,
                          float* __restrict byy, float* __restrict byz, float* __restrict bzz) {
    for (uint32_t s = begin; s < end; ++s) {
        const uint32_t i = first[s], j = second[s];
        const float dx = px[j] - px[i], dy = py[j] - py[i], dz = pz[j] - pz[i];
        const float length = std::max(std::sqrt(dx * dx + dy * dy + dz * dz), 1e-9f);
        const float inv = 1.0f / length;
        const float ux = dx * inv, uy = dy * inv, uz = dz * inv;
        const float rvx = vx[j] - vx[i], rvy = vy[j] - vy[i], rvz = vz[j] - vz[i];
        const float k = stiffness[s], c = damping[s];
        const float ratio = rest[s] * inv;
        // J = a I + b u u^T (eq. 11, clamped per eq. 12).
        const float a = k * std::max(clamp.a_min, 1.0f - ratio);
        const float b = k * std::min(clamp.ratio_max, ratio);
        const float u_dot_rv = ux * rvx + uy * rvy + uz * rvz;
        // f~ on i: k (L - l0) u + c (u . rv) u + h J rv, with J rv = a rv + b (u . rv) u.
        const float along = k * (length - rest[s]) + c * u_dot_rv + h * b * u_dot_rv;
        const float across = h * a;
        fx[s] = ux * along + rvx * across;
        fy[s] = uy * along + rvy * across;
        fz[s] = uz * along + rvz * across;
        // A_s = h^2 J + h c u u^T = alpha I + beta u u^T.
        const float alpha = h * h * a, beta = h * h * b + h * c;
        bxx[s] = alpha + beta * ux * ux;
        bxy[s] = beta * ux * uy;
        bxz[s] = beta * ux * uz;
        byy[s] = alpha + beta * uy * uy;
        byz[s] = beta * uy * uz;
        bzz[s] = alpha + beta * uz * uz;
    }
}

}  // namespace

void evaluate_springs(const SpringPass& pass, uint32_t begin, uint32_t end, Vec3Soa& force, Sym3Soa* block) {
    const Fabric& f = *pass.fabric;
    const Vec3Soa& x = *pass.x;
    const Vec3Soa& v = *pass.v;
    if (!block) {  // explicit: forces only
        spring_forces_kernel(begin, end, f.spring_first.data(), f.spring_second.data(), f.spring_rest_length.data(),
                             pass.stiffness, pass.damping, x.x.data(), x.y.data(), x.z.data(), v.x.data(),
                             v.y.data(), v.z.data(), force.x.data(), force.y.data(), force.z.data());
        return;
    }
    spring_system_kernel(begin, end, clamp_for(pass.compression_safe), pass.h, f.spring_first.data(),
                         f.spring_second.data(), f.spring_rest_length.data(), pass.stiffness, pass.damping,
                         x.x.data(), x.y.data(), x.z.data(), v.x.data(), v.y.data(), v.z.data(), force.x.data(),
                         force.y.data(), force.z.data(), block->xx.data(), block->xy.data(), block->xz.data(),
                         block->yy.data(), block->yz.data(), block->zz.data());
}

}  // namespace cloth
