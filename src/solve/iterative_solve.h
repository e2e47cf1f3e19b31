// The iterative solvers of the substep system W dv = b as staged
// algorithms (base/staged.h): the paper's Jacobi sweeps (JACOBI),
// block-Jacobi-preconditioned conjugate gradient (PCG) and
// Chebyshev-accelerated Jacobi (CHEBYSHEV), each a sequence of per-group
// passes (solvers.h) with its scalars (step lengths, dot products) worked
// out serially after each barrier.
//
//   JACOBI:    `iterations` sweeps (at least one), alternating two buffers
//   PCG:       start (r = b - W dv, z = P r, p = z; r.z)
//              then per iteration: product (q = W p; p.q),
//              update (dv += a p, r -= a q, z = P r; r.z), direction (p = z + beta p)
//              until the budget or sqrt(r.z / r0.z0) < tolerance.
//              With multigrid, z = M r is three more rounds after the
//              start and each update: residual (then the coarse levels
//              on one thread), prolong, smooth (r.z).
//   CHEBYSHEV: bound (the eigenvalue interval), start, then per iteration
//              product and direction; then the line search: energy
//              (dv.W dv, b.dv), and scale (only when the length is not 1)
//
// Every sum is per reduction block (one per particle group), added in
// block order: the result does not depend on the workers. solve_pcg and
// solve_chebyshev run this same sequence on the calling thread.
#pragma once

#include <algorithm>

#include "base/staged.h"
#include "solve/multigrid.h"
#include "solve/solvers.h"

namespace cloth {

class IterativeSolve final : public StagedAlgorithm {
  public:
    // What the solve works on; the pointers outlive it.
    struct Problem {
        LinearSystem system;
        AssemblyPass assembly;  // CHEBYSHEV's eigenvalue bound reads it
        Vec3Soa* dv = nullptr;  // the start on entry; the solution on exit, but for JACOBI (solution())
        SolverWorkspace* work = nullptr;
        Vec3Soa* scratch = nullptr;  // JACOBI: the second iterate buffer
        // PCG: the multigrid preconditioner (planned for this cloth), or
        // null for block Jacobi.
        Multigrid* multigrid = nullptr;
    };

    // `kind` is CLOTH_SOLVER_JACOBI, CLOTH_SOLVER_PCG or
    // CLOTH_SOLVER_CHEBYSHEV; at most `max_iterations` iterations (PCG
    // stops earlier below `tolerance`, or once r.z is at most
    // `absolute_rz`, in r.z's own units: kg m^2/s^2).
    void begin(cloth_solver_kind kind, uint32_t max_iterations, double tolerance, const Problem& problem,
               double absolute_rz = 0);
    // Where the solution is once done: problem.dv, or for JACOBI whichever
    // of dv and scratch the last sweep wrote.
    Vec3Soa& solution() const { return *current_; }
    const SolveReport& report() const { return report_; }

    bool done() const override { return done_; }
    bool last_round() const override { return false; }
    void run(const GroupTask& task) override;
    void finish_round() override;

  private:
    enum class Round : uint8_t {
        kJacobiSweep,
        kPcgStart,
        kPcgProduct,
        kPcgUpdate,
        kPcgDirection,
        kMultigridResidual,  // t = r - W z
        kMultigridRestrict,  // the first level's right-hand side, then (one thread) the coarse levels
        kMultigridProlong,   // z += P e
        kMultigridSmooth,    // z = z + w W_ii^-1 (r - W z); r.z
        kChebyshevBound,
        kChebyshevStart,
        kChebyshevProduct,
        kChebyshevDirection,
        kChebyshevEnergy,
        kChebyshevScale
    };
    Problem problem_;
    Vec3Soa* current_ = nullptr;  // the iterate being read
    Vec3Soa* next_ = nullptr;     // JACOBI: the one being written
    cloth_solver_kind kind_ = CLOTH_SOLVER_PCG;
    uint32_t budget_ = 0;
    double tolerance_ = 0;
    double absolute_rz_ = 0;
    // PCG: whether r.z (= rz) still asks for another iteration.
    bool wants_more(double rz) const { return rz > std::max(tolerance_ * tolerance_ * rz0_, absolute_rz_); }
    Round round_ = Round::kPcgStart;
    bool done_ = true;
    uint32_t iteration_ = 0;
    double rz0_ = 0, rz_ = 0, alpha_ = 0, beta_ = 0;  // PCG
    bool starting_ = false;                           // PCG with multigrid: the first z = M r
    double sigma_ = 0, delta_ = 0, rho_ = 0;          // Chebyshev
    double step_scale_ = 1;                           // Chebyshev: the energy-minimising step length
    SolveReport report_;
};

}  // namespace cloth
