// How a cloth's substep system is solved: the solver kind and its budget,
// the strain limit, and what a solve reports.
#pragma once

#include <cloth/cloth.h>

#include <cstdint>

namespace cloth {

// Provot-style strain limiting after each substep (strain_limit.h): off
// unless max_strain > 0.
struct StrainLimit {
    // (L - l0) / l0 allowed: the implicit solvers' strain cable (springs.h)
    // holds it on every spring, bend included; the projection passes on
    // structural and shear springs.
    float max_strain = 0;
    uint32_t iterations = 4;  // Jacobi-style projection passes per substep
    // Set by the host (cloth_set_strain_limit): the default solver then
    // keeps it, a max_strain of 0 (off) included, instead of its own.
    bool chosen = false;
};

struct SolverSettings {
    // The core's own default is the paper's method, which internal tests
    // build on; the public default (cloth_default_solver_settings) is
    // CLOTH_SOLVER_DEFAULT, resolved per frame (solver_default.h).
    cloth_solver_kind kind = CLOTH_SOLVER_JACOBI;
    uint32_t iterations = 1;
    uint32_t substeps = 1;
    float cg_tolerance = 1e-6f;
    // PCG also stops once sqrt(r.z / lightest free mass) is below this
    // (m/s): no particle's velocity change is off by more than it (r.z is
    // about the error's W-norm, which bounds sum m_i |e_i|^2). 0: off.
    // CLOTH_SOLVER_DEFAULT sets kDefaultVelocityTolerance.
    float velocity_tolerance = 0;
    uint32_t cg_max_iterations = 1000;
    bool compression_safe_jacobian = true;
    // How implicit a substep is (the theta step, integrate.h): 1 is the
    // paper's backward Euler; below 1 the forces are taken part way
    // through the substep, which damps less.
    float theta = 1.0f;
    // PCG preconditioned by multigrid (multigrid.h) rather than block
    // Jacobi: what CLOTH_SOLVER_DEFAULT resolves to.
    bool multigrid = false;
    StrainLimit strain_limit;  // set with cloth_set_strain_limit, kept by cloth_set_solver
};

// What the last solve reported (for stats and tests).
struct SolveReport {
    uint32_t iterations = 0;
    float residual = 0;
    bool converged = true;
};

}  // namespace cloth
