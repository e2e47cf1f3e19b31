// Spring forces and their Jacobians (paper eqs. 11-12; algorithm.md 1-2).
#pragma once

#include "fabric.h"
#include "math.h"
#include "soa.h"

namespace cloth {

// Force on the first particle i of a spring (i, j) and the Jacobian block
// J_ij = df_i/dx_j (symmetric; df_i/dx_i = -J_ij). With d = x_j - x_i,
// L = |d|, u = d / L:
//   f_i  = k (L - l0) u
//   J_ij = k [ (1 - l0/L) I + (l0/L) u u^T ]          stretched (or compression_safe off)
//   J_ij = k u u^T                                    compressed, compression_safe on (eq. 12)
struct SpringEval {
    Vec3 force;
    Sym3 jacobian;
};
SpringEval spring_force_and_jacobian(const Vec3& xi, const Vec3& xj, float rest_length, float stiffness,
                                     bool compression_safe);

// Inputs of the per-spring stage.
struct SpringPass {
    const Fabric* fabric;
    const float* stiffness;  // per spring, N/m
    const float* damping;    // per spring, N s/m
    const Vec3Soa* x;
    const Vec3Soa* v;
    float h;                 // substep; used only when blocks are wanted
    bool compression_safe;
};

// Stage 1 (per spring, independent): for springs [begin, end)
//   force[s] = spring force + damping force on i, plus h J_ij (v_j - v_i)
//              when `block` is given (the viscous right-hand side, eq. 4);
//   block[s] = h^2 J_ij + h D_ij, D_ij = c u u^T the damping's velocity
//              Jacobian, so that W_ij = -block[s] and W_ii = m_i I + sum block.
// Pass block = nullptr for the explicit integrator (forces only).
// Written without branches over plain arrays so that it vectorizes.
void evaluate_springs(const SpringPass& pass, uint32_t begin, uint32_t end, Vec3Soa& force, Sym3Soa* block);

}  // namespace cloth
