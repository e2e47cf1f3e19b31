// Solvers for the substep system W dv = b (linear_system.h). Each takes the
// same system view, writes dv (zero for pinned particles) and reports what
// it did. Solver kinds that hold at high stiffness slot in here as further
// functions of this shape.
#pragma once

#include "linear_system.h"
#include "settings.h"

namespace cloth {

// Jacobi (algorithm.md 3; paper eqs. 8-10 for iterations = 1):
//   dv^(0) = p = W_ii^-1 b_i  (given in `dv` on entry)
//   dv^(k+1)_i = p_i + W_ii^-1 sum_s A_s dv^(k)_other
// Per iteration one per-particle gather; no global solve. `scratch` holds
// particle_count vectors; it and dv may trade buffers.
SolveReport solve_jacobi(const LinearSystem& system, uint32_t iterations, Vec3Soa& dv, Vec3Soa& scratch);

// Conjugate gradient on the same system with Eigen's sparse solver
// (Baraff-Witkin), in double precision, to a relative residual of
// `tolerance`: the accuracy reference. It builds an Eigen sparse matrix
// every call, so it allocates from the C++ heap, not the host allocator.
SolveReport solve_cg(const LinearSystem& system, float tolerance, uint32_t max_iterations, Vec3Soa& dv);

}  // namespace cloth
