// Reference solver: the substep system assembled into an Eigen sparse
// matrix (double) and solved by Eigen's ConjugateGradient with a diagonal
// preconditioner. Serial, allocating, exact to a tolerance: it is the
// yardstick the fast solvers are measured against, not a fast path.
// W is symmetric positive definite when every A_s is positive
// semi-definite, which the compression-safe Jacobian guarantees.
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCore>
#include <vector>

#include "solve/solvers.h"

namespace cloth {

SolveReport solve_cg(const LinearSystem& system, float tolerance, uint32_t max_iterations, Vec3Soa& dv) {
    const uint32_t n = system.particle_count;
    std::vector<Eigen::Triplet<double>> triplets;
    triplets.reserve(9 * 13 * static_cast<size_t>(n));

    auto add_block = [&](uint32_t row, uint32_t col, const Sym3& block, double sign) {
        const Mat3 m = block.to_matrix();
        for (int r = 0; r < 3; ++r) {
            for (int c = 0; c < 3; ++c) triplets.emplace_back(3 * row + r, 3 * col + c, sign * m(r, c));
        }
    };
    for (uint32_t i = 0; i < n; ++i) {
        add_block(i, i, system.pinned[i] ? Sym3::identity(1.0f) : system.diagonal->get(i), 1.0);
    }
    system.springs->for_each_block([&](uint32_t i, uint32_t j, const Sym3& block) {
        if (system.pinned[i] || system.pinned[j]) return;
        add_block(i, j, block, -1.0);
        add_block(j, i, block, -1.0);
    });
    Eigen::SparseMatrix<double> w(3 * n, 3 * n);
    w.setFromTriplets(triplets.begin(), triplets.end());

    Eigen::VectorXd b(3 * n);
    for (uint32_t i = 0; i < n; ++i) {
        const Vec3 rhs = system.rhs->get(i);
        for (int c = 0; c < 3; ++c) b[3 * i + c] = system.pinned[i] ? 0.0 : static_cast<double>(rhs[c]);
    }

    Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper> cg;
    cg.setTolerance(tolerance);
    cg.setMaxIterations(static_cast<Eigen::Index>(max_iterations));
    cg.compute(w);
    const Eigen::VectorXd x = cg.solve(b);

    for (uint32_t i = 0; i < n; ++i) {
        dv.set(i, system.pinned[i] ? Vec3::Zero()
                                   : Vec3(static_cast<float>(x[3 * i]), static_cast<float>(x[3 * i + 1]),
                                          static_cast<float>(x[3 * i + 2])));
    }
    SolveReport report;
    report.iterations = static_cast<uint32_t>(cg.iterations());
    report.residual = static_cast<float>(cg.error());
    report.converged = cg.info() == Eigen::Success;
    return report;
}

}  // namespace cloth
