// The parallel solvers (PCG, Chebyshev) solve the same system as the
// Eigen CG reference, on the library's own passes.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "solve/system_fixture.h"

namespace cloth {
namespace {

using cloth::testing::heap;
using cloth::testing::SystemFixture;

TEST(ParallelSolvers, PcgResidualFallsToTheToleranceAndMatchesEigenCg) {
    SystemFixture f(20, 20, 1e4f, 1.0f / 60.0f);
    Vec3Soa dv = f.guess();
    const double start = f.relative_residual(dv);
    const SolveReport report = solve_pcg(f.system, 2000, 1e-6f, dv, f.work);
    EXPECT_LT(report.iterations, 2000u);
    EXPECT_LT(f.relative_residual(dv), 1e-3 * start) << "PCG converges on the matrix-free system";
    EXPECT_LT(f.difference_from_cg(dv), 1e-3) << "same dv as Eigen's CG";
}

// Chebyshev's guarantee is on the error in the energy norm |e|_W =
// sqrt(e^T W e): over the eigenvalue interval [a, 2] the iteration
// polynomial stays below 1 / T_k(sigma) <= 1, so no iteration count ends
// with more error than it started with (plain Jacobi's error can grow at
// high gamma), and the bound falls quickly once gamma is moderate.
double chebyshev_energy_error(SystemFixture& f, uint32_t iterations) {
    const uint32_t n = f.system.particle_count;
    Vec3Soa reference(f.guess());
    solve_cg(f.system, 1e-9f, 100000, reference);
    Vec3Soa dv = f.guess();
    if (iterations > 0) solve_chebyshev(f.system, f.assembly, iterations, dv, f.work);
    Vec3Soa e(heap()), we(heap());
    e.resize(n);
    we.resize(n);
    for (uint32_t i = 0; i < n; ++i) e.set(i, dv.get(i) - reference.get(i));
    multiply_system(f.system, e, 0, n, we);
    double sum = 0;
    for (uint32_t i = 0; i < n; ++i) sum += double(e.get(i).dot(we.get(i)));
    return std::sqrt(sum);
}

TEST(ParallelSolvers, ChebyshevNeverEndsWithMoreEnergyNormErrorThanItStartedWith) {
    SystemFixture f(20, 20, 1e4f, 1.0f / 60.0f);  // gamma ~ 1100
    const double start = chebyshev_energy_error(f, 0);
    for (uint32_t k : {1u, 2u, 3u, 4u, 8u, 16u, 64u}) {
        SCOPED_TRACE(::testing::Message() << "k = " << k);
        EXPECT_LT(chebyshev_energy_error(f, k), start);
    }
}

// ... and the error after k iterations is within the Chebyshev bound
// |e_k| <= |e_0| / T_k(sigma), sigma = (2 + a) / (2 - a), which falls
// geometrically once gamma is moderate.
TEST(ParallelSolvers, ChebyshevErrorIsWithinTheChebyshevBound) {
    SystemFixture f(20, 20, 1e3f, 1.0f / 600.0f);
    const double a = chebyshev_lower_bound(f.system, f.assembly, 0, f.system.particle_count);
    const double sigma = (2.0 + a) / (2.0 - a);
    const double start = chebyshev_energy_error(f, 0);
    for (uint32_t k : {4u, 16u, 32u}) {
        const double bound = start / std::cosh(k * std::acosh(sigma));
        SCOPED_TRACE(::testing::Message() << "k = " << k << ", bound = " << bound);
        EXPECT_LT(chebyshev_energy_error(f, k), bound);
    }
    EXPECT_LT(chebyshev_energy_error(f, 32), 1e-2 * start);
}

// The line search that ends solve_chebyshev (solvers.h): dv comes out at
// the length that minimises phi(a dv) = a^2/2 dv.W dv - a b.dv along its
// own direction, so a step 5 % longer or shorter has no lower phi. At
// gamma ~1100 the unscaled Chebyshev step is off that length (the swing
// the search is there to take out), so the test sees it act.
TEST(ParallelSolvers, ChebyshevStepHasTheEnergyMinimisingLengthAlongItsDirection) {
    SystemFixture f(20, 20, 1e4f, 1.0f / 60.0f);  // gamma ~ 1100
    const uint32_t n = f.system.particle_count;
    Vec3Soa dv = f.guess(), product(heap());
    product.resize(n);
    solve_chebyshev(f.system, f.assembly, 16, dv, f.work);
    auto phi = [&](double a) {
        multiply_system(f.system, dv, 0, n, product);
        double dwd = 0, bd = 0;
        for (uint32_t i = 0; i < n; ++i) {
            dwd += double(dv.get(i).dot(product.get(i)));
            bd += double(dv.get(i).dot(f.rhs.get(i)));
        }
        return 0.5 * a * a * dwd - a * bd;
    };
    EXPECT_LT(phi(1.0), 0.0) << "the step lowers the energy";
    EXPECT_LE(phi(1.0), phi(0.95));
    EXPECT_LE(phi(1.0), phi(1.05));
}

// The line search only rescales dv along a positive, finite curvature: an
// overflowed product or an indefinite W (compression_safe_jacobian off)
// leaves dv as the iterations made it (scale 1) instead of zeroing it or
// blowing it up, and the scale always fits the float it is applied in.
TEST(ParallelSolvers, ChebyshevLineSearchKeepsTheStepWhenItsCurvatureIsNotPositiveAndFinite) {
    SolverWorkspace work(heap());
    work.resize(2 * kReductionBlock);
    auto scale = [&](double dv_w_dv, double b_dv) {
        work.partial = {dv_w_dv, 0.0};
        work.partial_second = {0.0, b_dv};
        return chebyshev_step_scale(work);
    };
    EXPECT_EQ(scale(2.0, 1.0), 0.5) << "the minimiser of a^2/2 dv.W dv - a b.dv";
    EXPECT_EQ(scale(2.0, -1.0), 0.0) << "a direction that raises the energy is not taken";
    const double inf = std::numeric_limits<double>::infinity();
    EXPECT_EQ(scale(inf, 1.0), 1.0) << "an overflowed W dv";
    EXPECT_EQ(scale(1.0, inf), 1.0);
    EXPECT_EQ(scale(std::nan(""), 1.0), 1.0);
    EXPECT_EQ(scale(0.0, 1.0), 1.0);
    EXPECT_EQ(scale(-1.0, 1.0), 1.0) << "indefinite W";
    EXPECT_EQ(scale(1e-300, 1.0), double(std::numeric_limits<float>::max()));
}

}  // namespace
}  // namespace cloth
