#include "solve/iterative_solve.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace cloth {

void IterativeSolve::begin(cloth_solver_kind kind, uint32_t max_iterations, double tolerance,
                           const Problem& problem, double absolute_rz) {
    problem_ = problem;
    kind_ = kind;
    budget_ = max_iterations;
    tolerance_ = tolerance;
    absolute_rz_ = absolute_rz;
    round_ = kind == CLOTH_SOLVER_JACOBI ? Round::kJacobiSweep
             : kind == CLOTH_SOLVER_PCG  ? Round::kPcgStart
                                         : Round::kChebyshevBound;
    current_ = problem.dv;
    next_ = problem.scratch;
    iteration_ = 0;
    done_ = false;
}

// One group of the current round. Groups are the reduction blocks
// (kGroupSize == kReductionBlock), so each writes its own partial sums.
void IterativeSolve::run(const GroupTask& task) {
    const LinearSystem& sys = problem_.system;
    Vec3Soa& dv = *problem_.dv;
    SolverWorkspace& work = *problem_.work;
    const uint32_t begin = task.begin, end = task.end;
    switch (round_) {
        case Round::kJacobiSweep:
            jacobi_sweep(sys, *current_, begin, end, *next_);
            break;
        case Round::kPcgStart:
            if (problem_.multigrid) {
                pcg_start_multigrid(sys, dv, begin, end, work);
                problem_.multigrid->assemble_top(sys, task);
            } else {
                pcg_start(sys, dv, begin, end, work);
            }
            break;
        case Round::kPcgProduct:
            pcg_product(sys, begin, end, work);
            break;
        case Round::kPcgUpdate:
            if (problem_.multigrid) {
                pcg_update_multigrid(sys, alpha_, begin, end, dv, work);
            } else {
                pcg_update(sys, alpha_, begin, end, dv, work);
            }
            break;
        case Round::kMultigridResidual:
            Multigrid::residual(sys, work.r, work.z, begin, end, work.q);
            break;
        case Round::kMultigridRestrict:
            problem_.multigrid->restrict_residual(work.q, task);
            break;
        case Round::kMultigridProlong:
            problem_.multigrid->prolong(sys.pinned, begin, end, work.z);
            break;
        case Round::kMultigridSmooth:
            pcg_smooth(sys, starting_, begin, end, work);
            break;
        case Round::kPcgDirection:
            pcg_direction(beta_, begin, end, work);
            break;
        case Round::kChebyshevBound:
            work.partial[task.group] = chebyshev_lower_bound(sys, problem_.assembly, begin, end);
            break;
        case Round::kChebyshevStart:
            chebyshev_start(sys, dv, static_cast<float>(1.0 / (sigma_ * delta_)), begin, end, work);
            break;
        case Round::kChebyshevProduct:
            chebyshev_product(sys, begin, end, dv, work);
            break;
        case Round::kChebyshevEnergy:
            chebyshev_energy(sys, dv, begin, end, work);
            break;
        case Round::kChebyshevScale:
            chebyshev_scale(static_cast<float>(step_scale_), begin, end, dv);
            break;
        case Round::kChebyshevDirection: {
            const double rho_next = 1.0 / (2.0 * sigma_ - rho_);
            chebyshev_direction(sys, static_cast<float>(rho_next * rho_),
                                static_cast<float>(2.0 * rho_next / delta_), begin, end, work);
            break;
        }
    }
}

// After a round's barrier: its sums, and the round that follows.
void IterativeSolve::finish_round() {
    SolverWorkspace& work = *problem_.work;
    Multigrid* multigrid = problem_.multigrid;
    bool go_on = true;
    switch (round_) {
        case Round::kJacobiSweep:
            std::swap(current_, next_);
            ++iteration_;
            go_on = iteration_ < budget_;
            break;
        case Round::kPcgStart:
            if (multigrid) {
                multigrid->assemble_coarse();
                starting_ = true;
                go_on = budget_ > 0;
                round_ = Round::kMultigridResidual;
                break;
            }
            rz0_ = rz_ = sum_partials(work);
            go_on = budget_ > 0 && rz_ > 0 && wants_more(rz_);
            round_ = Round::kPcgProduct;
            break;
        case Round::kPcgProduct: {
            const double pq = sum_partials(work);
            go_on = pq > 0;  // W is positive definite; pq <= 0 only from round-off at convergence
            if (go_on) alpha_ = rz_ / pq;
            round_ = Round::kPcgUpdate;
            break;
        }
        case Round::kPcgUpdate: {
            if (multigrid) {
                ++iteration_;
                go_on = iteration_ < budget_;
                round_ = Round::kMultigridResidual;
                break;
            }
            const double rz_next = sum_partials(work);
            ++iteration_;
            go_on = iteration_ < budget_ && wants_more(rz_next);
            beta_ = rz_next / rz_;
            rz_ = rz_next;
            round_ = Round::kPcgDirection;
            break;
        }
        case Round::kPcgDirection:
            round_ = Round::kPcgProduct;
            break;
        case Round::kMultigridResidual:
            round_ = Round::kMultigridRestrict;
            break;
        case Round::kMultigridRestrict:
            multigrid->correct_coarse();
            round_ = Round::kMultigridProlong;
            break;
        case Round::kMultigridProlong:
            round_ = Round::kMultigridSmooth;
            break;
        case Round::kMultigridSmooth: {
            work.z.swap_buffers(work.q);  // pcg_smooth left the new z in q
            const double rz_next = sum_partials(work);
            if (starting_) {
                starting_ = false;
                rz0_ = rz_ = rz_next;
                go_on = rz_ > 0 && rz_ > absolute_rz_;
                round_ = Round::kPcgProduct;
                break;
            }
            go_on = wants_more(rz_next);
            beta_ = rz_next / rz_;
            rz_ = rz_next;
            round_ = Round::kPcgDirection;
            break;
        }
        case Round::kChebyshevBound: {
            double a = 1.0;
            for (double partial : work.partial) a = std::min(a, partial);
            const double theta = 0.5 * (2.0 + a);
            delta_ = 0.5 * (2.0 - a);
            sigma_ = theta / delta_;
            rho_ = 1.0 / sigma_;
            round_ = Round::kChebyshevStart;
            break;
        }
        case Round::kChebyshevStart:
            round_ = Round::kChebyshevProduct;
            break;
        case Round::kChebyshevProduct:
            ++iteration_;
            if (iteration_ < budget_) {
                // Another iteration.
                if (iteration_ > 1) rho_ = 1.0 / (2.0 * sigma_ - rho_);
                round_ = Round::kChebyshevDirection;
            } else {
                round_ = Round::kChebyshevEnergy;  // the line search (solvers.h)
            }
            break;
        case Round::kChebyshevDirection:
            round_ = Round::kChebyshevProduct;
            break;
        case Round::kChebyshevEnergy:
            step_scale_ = chebyshev_step_scale(work);
            go_on = step_scale_ != 1.0;
            round_ = Round::kChebyshevScale;
            break;
        case Round::kChebyshevScale:
            go_on = false;
            break;
    }
    if (go_on) return;
    done_ = true;
    report_ = SolveReport{};
    report_.iterations = kind_ == CLOTH_SOLVER_JACOBI ? budget_ : iteration_;
    if (kind_ == CLOTH_SOLVER_PCG && rz0_ > 0) {
        report_.residual = static_cast<float>(std::sqrt(std::max(rz_, 0.0) / rz0_));
    }
}

// The serial forms: the same rounds on this thread.

SolveReport solve_pcg(const LinearSystem& system, uint32_t max_iterations, float tolerance, Vec3Soa& dv,
                      SolverWorkspace& work, Multigrid* multigrid) {
    IterativeSolve solve;
    solve.begin(CLOTH_SOLVER_PCG, max_iterations, tolerance,
                {system, AssemblyPass{}, &dv, &work, nullptr, multigrid});
    run_serially(solve, system.particle_count);
    return solve.report();
}

SolveReport solve_chebyshev(const LinearSystem& system, const AssemblyPass& pass, uint32_t iterations,
                            Vec3Soa& dv, SolverWorkspace& work) {
    IterativeSolve solve;
    solve.begin(CLOTH_SOLVER_CHEBYSHEV, iterations, 0.0, {system, pass, &dv, &work});
    run_serially(solve, system.particle_count);
    return solve.report();
}

}  // namespace cloth
