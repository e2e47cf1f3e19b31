// Solvers for the substep system W dv = b (linear_system.h). Each takes the
// same system view, writes dv (zero for pinned particles) and reports what
// it did.
//
// The fast ones are built from range passes over particles (begin, end), so
// a job system can split every pass; a barrier separates passes. Sums over
// all particles (the dot products of PCG) are formed per fixed block of
// kReductionBlock particles, then added in block order in double: the
// result does not depend on how many workers ran the passes, as long as
// every range of a reducing pass starts on a block boundary.
#pragma once

#include <cassert>

#include "forces/material.h"
#include "solve/linear_system.h"
#include "solve/solver_settings.h"

namespace cloth {

class Multigrid;

constexpr uint32_t kReductionBlock = 256;
inline uint32_t reduction_block_count(uint32_t particle_count) {
    return (particle_count + kReductionBlock - 1) / kReductionBlock;
}

// Calls body(block, first, last) for each reduction block met by [begin, end).
// Always inlined with its body (flatten), like for_each_lane_group: out of
// line, the body is a separate function compiled for the baseline only, so
// the AVX2 clone of a CLOTH_HOT_LOOP caller would run it on SSE with its
// block sum spilled to the stack (docs/measurements.md, "The block loops
// inlined into their AVX2 clones").
template <class Body>
__attribute__((always_inline, flatten)) inline void for_each_block(uint32_t begin, uint32_t end, Body body) {
    assert(begin % kReductionBlock == 0 && "reducing passes start on a block boundary");
    for (uint32_t first = begin; first < end; first += kReductionBlock) {
        const uint32_t last = first + kReductionBlock < end ? first + kReductionBlock : end;
        body(first / kReductionBlock, first, last);
    }
}

// Scratch of the iterative solvers, sized once per cloth (no allocation per
// step): four particle vectors and one partial sum per reduction block.
struct SolverWorkspace {
    explicit SolverWorkspace(const HostMemory* memory)
        : r(memory),
          z(memory),
          p(memory),
          q(memory),
          partial(HostAllocator<double>(memory)),
          partial_second(HostAllocator<double>(memory)) {}
    void resize(uint32_t particle_count) {
        for (Vec3Soa* a : {&r, &z, &p, &q}) a->resize(particle_count);
        partial.assign(reduction_block_count(particle_count), 0.0);
        partial_second.assign(reduction_block_count(particle_count), 0.0);
    }
    Vec3Soa r, z, p, q;
    HostVector<double> partial, partial_second;
};

// Sum of the per-block partials in block order (deterministic).
double sum_partials(const SolverWorkspace& work);

// A start, per particle: dv0_i = h f_ext_i / (m_i (1 + h c)), zero for
// pinned particles: the exact answer when the springs do not resist the
// motion (rigid translation under gravity). The step starts from
// p = W_ii^-1 b, not from this: near equilibrium it is a smooth error the
// few iterations cannot remove (docs/measurements.md, "Starting vectors and
// warm starts"); tests use it as a far-from-answer start.
void external_force_guess(const AssemblyPass& pass, uint32_t begin, uint32_t end, Vec3Soa& dv);

// Conjugate gradient on the same system with Eigen's sparse solver
// (Baraff-Witkin), in double precision, to a relative residual of
// `tolerance`: the accuracy reference. It builds an Eigen sparse matrix
// every call, so it allocates from the C++ heap, not the host allocator.
SolveReport solve_cg(const LinearSystem& system, float tolerance, uint32_t max_iterations, Vec3Soa& dv);

// Block-Jacobi-preconditioned conjugate gradient on the library's own
// passes (preconditioner: the stored W_ii^-1), from the dv given on entry.
// At most `max_iterations` iterations; stops earlier once the preconditioned
// residual sqrt(r.z / r0.z0) is below `tolerance`. A budgeted solver: it
// never reports failure. Each iteration: one W p gather, two dot products.
// With `multigrid` (planned for the system's fabric) the preconditioner is
// its V-cycle instead (multigrid.h): two more gathers per iteration.
SolveReport solve_pcg(const LinearSystem& system, uint32_t max_iterations, float tolerance, Vec3Soa& dv,
                      SolverWorkspace& work, Multigrid* multigrid = nullptr);

// The passes solve_pcg runs (r, z, p, q live in `work`). Reducing passes
// write work.partial for the blocks their range covers.
void pcg_start(const LinearSystem& system, const Vec3Soa& dv, uint32_t begin, uint32_t end,
               SolverWorkspace& work);  // r = b - W dv, z = P r, p = z; partial r.z
void pcg_product(const LinearSystem& system, uint32_t begin, uint32_t end,
                 SolverWorkspace& work);  // q = W p; partial p.q
void pcg_update(const LinearSystem& system, double alpha, uint32_t begin, uint32_t end, Vec3Soa& dv,
                SolverWorkspace& work);  // dv += a p, r -= a q, z = P r; partial r.z
void pcg_direction(double beta, uint32_t begin, uint32_t end, SolverWorkspace& work);  // p = z + beta p
// With the multigrid preconditioner (multigrid.h), z = M r is a V-cycle
// that the start and the update begin (z = w W_ii^-1 r, no dot product) and
// pcg_smooth ends: q = z + w W_ii^-1 (r - W z), the new z (the caller swaps
// z and q), with partial r.q, and on the first application p = q.
void pcg_start_multigrid(const LinearSystem& system, const Vec3Soa& dv, uint32_t begin, uint32_t end,
                         SolverWorkspace& work);
void pcg_update_multigrid(const LinearSystem& system, double alpha, uint32_t begin, uint32_t end, Vec3Soa& dv,
                          SolverWorkspace& work);
void pcg_smooth(const LinearSystem& system, bool first, uint32_t begin, uint32_t end, SolverWorkspace& work);

// Chebyshev-accelerated block Jacobi (the Chebyshev semi-iteration of
// Golub-Varga, as used for cloth by Wang 2015) over the interval [a, 2]
// that provably holds the eigenvalues of D^-1 W (D = block diagonal):
// W <= 2D - M because every A_s is positive semi-definite, and
// a = min_i m_i' / (trace W_ii - 2 m_i') with m_i' = m_i (1 + h c).
// `iterations` iterations from the dv given on entry, no dot products; the
// error never grows in any eigen-direction (unlike plain Jacobi, whose
// error alternates in sign near eigenvalue -1).
//
// Then one exact line search: dv is scaled to the length that minimises
// phi(a dv) = a^2/2 dv.W dv - a b.dv, the energy whose minimum the solve
// seeks (two dot products and one product with W). Why: at high gamma the
// Chebyshev polynomial swings between +-1/T_k(sigma), which is close to 1,
// so from the start p = D^-1 b some modes of dv come out up to twice too
// large; as a time stepper that blew up in 56 of the stability map's 210
// cells. Scaled to the energy minimum along its own direction, the step
// never has more W-norm error than dv, and none of those cells blows up.
SolveReport solve_chebyshev(const LinearSystem& system, const AssemblyPass& pass, uint32_t iterations,
                            Vec3Soa& dv, SolverWorkspace& work);

// The step length that minimises the system's energy along dv,
// phi(a dv) = a^2/2 dv.W dv - a b.dv: partials of dv.W dv (work.partial)
// and b.dv (work.partial_second) per reduction block, with q = W dv.
void chebyshev_energy(const LinearSystem& system, const Vec3Soa& dv, uint32_t begin, uint32_t end,
                      SolverWorkspace& work);
// The line search's length b.dv / dv.W dv from chebyshev_energy's partials
// (in [0, FLT_MAX]; 1, dv kept, when dv.W dv is not positive and finite).
double chebyshev_step_scale(const SolverWorkspace& work);
// dv *= scale.
void chebyshev_scale(float scale, uint32_t begin, uint32_t end, Vec3Soa& dv);

// Its passes. chebyshev_lower_bound returns the block-range minimum of a
// (exact whatever the split: min does not round).
float chebyshev_lower_bound(const LinearSystem& system, const AssemblyPass& pass, uint32_t begin,
                            uint32_t end);
// r = b - W dv, p = P r * first_scale.
void chebyshev_start(const LinearSystem& system, const Vec3Soa& dv, float first_scale, uint32_t begin,
                     uint32_t end, SolverWorkspace& work);
// q = W p and dv += p.
void chebyshev_product(const LinearSystem& system, uint32_t begin, uint32_t end, Vec3Soa& dv,
                       SolverWorkspace& work);
// r -= q, p = keep * p + scale * P r.
void chebyshev_direction(const LinearSystem& system, float keep, float scale, uint32_t begin, uint32_t end,
                         SolverWorkspace& work);

}  // namespace cloth
