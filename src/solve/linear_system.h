// The linearized backward-Euler system of one substep (docs/method.md,
// "The linear system"; Baraff-Witkin eq. 6, paper eq. 3):
//
//     W dv = b,   W = M - h dF/dv - h^2 dF/dx,   b = h (f + h dF/dx v)
//
// stored the way the paper's stages produce it: per spring the block
// A_s = h^2 J_s + h D_s (W_ij = -A_s, held by SpringTerms), per particle
// W_ii, W_ii^-1 and b_i. Pinned (kinematic) particles have dv = 0: their
// W_ii^-1 is zero and their rows and columns are left out of the system.
//
// Every solver takes this view and writes dv; a new solver kind is one
// more function of this shape (see solvers.h).
#pragma once

#include "base/math.h"
#include "base/soa.h"
#include "fabric/fabric.h"
#include "forces/spring_terms.h"

namespace cloth {

struct LinearSystem {
    const SpringTerms* springs;  // A_s
    uint32_t particle_count;
    const Sym3Soa* diagonal;          // W_ii, per particle
    const Sym3Soa* diagonal_inverse;  // W_ii^-1, zero for pinned particles
    const Vec3Soa* rhs;               // b_i = h f~_i
    const float* pinned;              // 1 for pinned particles, 0 for free ones
};

// Inputs of the per-particle assembly stage.
struct AssemblyPass {
    const SpringTerms* springs;     // evaluated for this substep
    const Vec3Soa* external_force;  // per particle
    const float* mass;
    const float* pinned;  // 1 for pinned particles, 0 for free ones
    float h;
    float linear_drag;   // c: force -c m v, implicit on the diagonal
    float theta = 1.0f;  // the theta step's (integrate.h): the drag is taken at theta h
};

// Stage 2 (per particle, independent): f~_i = external + incident springs,
// W_ii = m_i (1 + h c) I + sum A_s, then W_ii^-1, b_i = h f~_i and the
// paper's p_i = W_ii^-1 b_i (eq. 8).
void assemble_particles(const AssemblyPass& pass, uint32_t begin, uint32_t end, Sym3Soa& diagonal,
                        Sym3Soa& diagonal_inverse, Vec3Soa& rhs, Vec3Soa& p);

// One Jacobi sweep for particles [begin, end) (paper eqs. 9-10 with h^2
// folded into A_s):  next_i = W_ii^-1 (b_i + sum_s A_s current_other).
void jacobi_sweep(const LinearSystem& system, const Vec3Soa& current, uint32_t begin, uint32_t end,
                  Vec3Soa& next);

// y_i = (W x)_i = W_ii x_i - sum A_s x_other for particles [begin, end);
// pinned rows give y_i = 0 (they are not unknowns). x must be zero on
// pinned particles.
void multiply_system(const LinearSystem& system, const Vec3Soa& x, uint32_t begin, uint32_t end, Vec3Soa& y);

}  // namespace cloth
