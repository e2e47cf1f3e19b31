// Spring forces and their Jacobians (paper eqs. 11-12; docs/method.md,
// "The linear system").
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "base/math.h"

namespace cloth {

// Force on the first particle i of a spring (i, j) and the Jacobian block
// J_ij = df_i/dx_j (symmetric; df_i/dx_i = -J_ij). With d = x_j - x_i,
// L = |d|, u = d / L:
//   f_i  = k (L - l0) u
//   J_ij = k [ (1 - l0/L) I + (l0/L) u u^T ]          stretched (or compression_safe off)
//   J_ij = k u u^T                                    compressed, compression_safe on (eq. 12)
// Computed by the step's kernel, spring_term below (tests check it).
struct SpringEval {
    Vec3 force;
    Sym3 jacobian;
};
SpringEval spring_force_and_jacobian(const Vec3& xi, const Vec3& xj, float rest_length, float stiffness,
                                     bool compression_safe);

// How spring_term shapes a spring.
//
// J = a I + b u u^T with a = k (1 - l0/L), b = k l0/L. Compression-safe
// (eq. 12) clamps a >= 0 and b <= k, which is exactly k u u^T when L < l0
// and leaves stretched springs untouched.
//
// The strain cable holds a strain limit inside the implicit solve: past
// cable_stretch * l0 a second, one-sided spring of stiffness
// cable_factor * k and rest length cable_stretch * l0 joins in (force,
// Jacobian and energy: a cable that only pulls). Why: projection passes
// after the solve fix one spring length per pass, while the solve itself
// spreads a stiff spring's pull over the whole cloth in the same substep;
// passes alone leave a pinned 128 x 128 cloth at 1e3 N/m up to 34 %
// stretched at its pins (docs/measurements.md, "The strain cable").
//
// cable_approach > 0 puts the cable's stiffness in the Jacobian from
// (cable_stretch - cable_approach) l0, before it pulls. Without it a spring
// that the load holds just past cable_stretch * l0 never rests: a substep
// that starts slack does not see the cable and overshoots into it, the
// next one starts taut and pulls back past the kink, and so on; with it
// the step approaches the kink as a stiff spring would and stops on the
// cable (docs/measurements.md, "A cloth held at its limit rests on the
// cable").
struct SpringModel {
    float a_min, ratio_max;
    float cable_stretch = 1.0f, cable_factor = 0.0f;  // cable off: factor 0
    float cable_approach = 0.0f;

    static SpringModel make(bool compression_safe) {
        const float inf = std::numeric_limits<float>::infinity();
        return compression_safe ? SpringModel{0.0f, 1.0f} : SpringModel{-inf, inf};
    }
};

// What one spring contributes to the substep system (docs/method.md,
// "The linear system"):
//   force = k (L - l0) u + c (u . rv) u + h J rv   on i (f~, eq. 4; -force on j;
//           plus the strain cable's pull when it is taut)
//   block = A_s = h^2 J + h c u u^T                 (W_ij = -A_s)
// from d = x_j - x_i and rv = v_j - v_i. Branch-free, so the loops that
// call it vectorize. Coincident particles (L = 0) exert no force. With
// h = 0 it is the plain spring + damping force (the explicit integrator),
// and with h = 1, c = 0, rv = 0 the block is J itself.
struct SpringTerm {
    float fx, fy, fz;
    float bxx, bxy, bxz, byy, byz, bzz;
};

// kCable = false leaves the strain cable out at compile time (the kernels
// pick it when model.cable_factor is 0: same result, fewer instructions).
template <bool kCable = true>
inline SpringTerm spring_term(float dx, float dy, float dz, float rvx, float rvy, float rvz, float rest,
                              float k, float c, float h, SpringModel model) {
    const float true_length = std::sqrt(dx * dx + dy * dy + dz * dz);
    const float length = std::max(true_length, 1e-9f);
    // Coincident ends: no direction, so no force (k = c = 0 zeroes the term).
    k = true_length > 1e-9f ? k : 0.0f;
    c = true_length > 1e-9f ? c : 0.0f;
    const float inv = 1.0f / length;
    const float ux = dx * inv, uy = dy * inv, uz = dz * inv;
    const float ratio = rest * inv;
    float a = k * std::max(model.a_min, 1.0f - ratio);
    float b = k * std::min(model.ratio_max, ratio);
    float pull = k * (length - rest);
    if constexpr (kCable) {
        // The cable: a stretched spring of rest length cable_rest when taut,
        // its stiffness from `near` on. A cable not near adds exact zeros:
        // its ratio and stretch are not even formed, since a huge accepted
        // limit makes them inf, and 0 * inf is NaN. Near but slack, 1 - ratio
        // is negative: the across term stays the spring's own.
        const float cable_rest = model.cable_stretch * rest;
        const bool taut = length > cable_rest;
        const bool near = length > (model.cable_stretch - model.cable_approach) * rest;
        const float cable = near ? k * model.cable_factor : 0.0f;
        const float cable_ratio = near ? cable_rest * inv : 0.0f;
        const float cable_stretch = taut ? length - cable_rest : 0.0f;
        a += cable * std::max(0.0f, 1.0f - cable_ratio);
        b += cable * cable_ratio;
        pull += cable * cable_stretch;
    }
    const float u_dot_rv = ux * rvx + uy * rvy + uz * rvz;
    // J rv = a rv + b (u . rv) u
    const float along = pull + c * u_dot_rv + h * b * u_dot_rv;
    const float across = h * a;
    const float alpha = h * h * a, beta = h * h * b + h * c;
    return SpringTerm{ux * along + rvx * across,
                      uy * along + rvy * across,
                      uz * along + rvz * across,
                      alpha + beta * ux * ux,
                      beta * ux * uy,
                      beta * ux * uz,
                      alpha + beta * uy * uy,
                      beta * uy * uz,
                      alpha + beta * uz * uz};
}

}  // namespace cloth
