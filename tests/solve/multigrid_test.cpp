// The multigrid preconditioner (multigrid.h): its levels, and PCG with it
// solving the same system as Eigen's CG in a fraction of block-Jacobi
// PCG's iterations, on grids and on meshes.
#include "solve/multigrid.h"

#include <gtest/gtest.h>

#include <cmath>

#include "solve/system_fixture.h"

namespace cloth {
namespace {

using cloth::testing::heap;
using cloth::testing::make_grid;
using cloth::testing::make_mesh_from_grid;
using cloth::testing::SystemFixture;

// Iterations PCG takes to bring |W dv - b| below `reduction` times its
// start, from the same start, with or without multigrid (capped at 1000).
uint32_t iterations_to(SystemFixture& f, Multigrid* multigrid, double reduction) {
    const Vec3Soa start = f.guess();
    const double start_residual = f.relative_residual(start);
    for (uint32_t k = 1; k <= 1000; k = k < 8 ? k + 1 : k + k / 4) {
        Vec3Soa dv = start;
        solve_pcg(f.system, k, 0.0f, dv, f.work, multigrid);
        if (f.relative_residual(dv) < reduction * start_residual) return k;
    }
    return 1000;
}

TEST(Multigrid, AGridCoarsensByTwoByTwoBlocksDownToTheDirectSolve) {
    auto fabric = make_grid(64, 64);
    Multigrid multigrid(heap());
    multigrid.plan(*fabric, *make_spring_terms(heap(), fabric, testing::uniform_material(1e3f, 0, 1)));
    ASSERT_EQ(multigrid.level_count(), 4u);
    EXPECT_EQ(multigrid.level_size(0), 1024u);
    EXPECT_EQ(multigrid.level_size(1), 256u);
    EXPECT_EQ(multigrid.level_size(2), 64u);
    EXPECT_EQ(multigrid.level_size(3), 16u);
    EXPECT_LE(multigrid.level_size(multigrid.level_count() - 1), Multigrid::kCoarsestSize);
}

TEST(Multigrid, ATinyClothHasNoLevelsAndPcgFallsBackToBlockJacobi) {
    auto fabric = make_grid(4, 4);
    Multigrid multigrid(heap());
    multigrid.plan(*fabric, *make_spring_terms(heap(), fabric, testing::uniform_material(1e3f, 0, 1)));
    EXPECT_TRUE(multigrid.empty());
}

// The reason it exists: tension crosses the whole cloth in one V-cycle, so
// the iteration count does not grow with stiffness or resolution the way
// block Jacobi's does (docs/method.md, "Multigrid-preconditioned CG": on the order of sqrt(condition)).
TEST(Multigrid, PcgWithMultigridNeedsAFractionOfBlockJacobisIterationsOnAStiffGrid) {
    for (uint32_t side : {32u, 64u}) {
        SCOPED_TRACE(::testing::Message() << side << "x" << side);
        SystemFixture f(side, side, 1e4f, 1.0f / 60.0f);  // 1 kg, gamma ~ 1e4 at 64x64
        Multigrid multigrid(heap());
        multigrid.plan(*f.fabric, *f.springs);
        multigrid.assemble(f.system);
        const uint32_t with = iterations_to(f, &multigrid, 1e-4);
        const uint32_t without = iterations_to(f, nullptr, 1e-4);
        EXPECT_LE(with, 20u);
        EXPECT_GE(without, 4 * with) << "multigrid " << with << ", block Jacobi " << without;
    }
}

TEST(Multigrid, PcgWithMultigridSolvesTheSameSystemAsEigenCgAndKeepsPinsStill) {
    SystemFixture f(48, 32, 1e4f, 1.0f / 60.0f);
    Multigrid multigrid(heap());
    multigrid.plan(*f.fabric, *f.springs);
    Vec3Soa dv = f.guess();
    const double start = f.relative_residual(dv);
    const SolveReport report = solve_pcg(f.system, 200, 1e-7f, dv, f.work, &multigrid);
    EXPECT_LT(report.iterations, 200u);
    EXPECT_LT(f.relative_residual(dv), 1e-4 * start);
    EXPECT_LT(f.difference_from_cg(dv), 1e-3) << "same dv as Eigen's CG";
    EXPECT_EQ(dv.get(0), Vec3::Zero()) << "a pinned particle does not move";
    EXPECT_EQ(dv.get(47), Vec3::Zero());
}

// A mesh (index-pair springs, particles in spatial order) gets its levels by
// greedy aggregation over its structural springs, and converges the same way.
TEST(Multigrid, AMeshCoarsensGreedilyAndConvergesLikeTheGrid) {
    auto mesh = make_mesh_from_grid(64, 64);
    SystemFixture f(mesh, mesh->particle(63), 1e4f, 1.0f / 60.0f);
    Multigrid multigrid(heap());
    multigrid.plan(*f.fabric, *f.springs);
    ASSERT_FALSE(multigrid.empty());
    EXPECT_LT(multigrid.level_size(0), f.system.particle_count / 3) << "aggregates of several particles";
    multigrid.assemble(f.system);
    const uint32_t with = iterations_to(f, &multigrid, 1e-4);
    const uint32_t without = iterations_to(f, nullptr, 1e-4);
    EXPECT_LE(with, 30u);
    EXPECT_GE(without, 3 * with) << "multigrid " << with << ", block Jacobi " << without;
}

}  // namespace
}  // namespace cloth
