// A hanging chain reaches the analytic static stretch: the spring below
// particle r carries the weight of every particle beneath it.
#include <gtest/gtest.h>

#include "test_support.h"

namespace cloth {
namespace {

// A 2-column ladder of structural springs only: each column is a chain of
// `rows` particles of mass m, rungs stay at rest length by symmetry.
TEST(Chain, HangingChainReachesTheAnalyticStaticStretch) {
    const uint32_t rows = 12;
    const float m = 0.05f, k = 200.0f, g = 9.81f;
    auto fabric = cloth::testing::make_grid(2, rows, CLOTH_SPRING_STRUCTURAL);
    const float rest = 1.0f / static_cast<float>(rows - 1);

    for (cloth_solver_kind kind : {CLOTH_SOLVER_JACOBI, CLOTH_SOLVER_CG}) {
        SCOPED_TRACE(kind == CLOTH_SOLVER_JACOBI ? "JACOBI" : "CG");
        Material material = cloth::testing::uniform_material(k, 0.5f, 1.0f);
        material.particle_mass = m;
        SolverSettings solver;
        solver.kind = kind;
        solver.cg_tolerance = 1e-8f;
        AeroParams air = cloth::testing::still_air();
        air.linear_drag = 0.5f;  // settle quickly; drag vanishes at rest
        ClothInstance chain(cloth::testing::heap(), fabric, material, solver, air);
        chain.pin(0);
        chain.pin(1);
        for (int s = 0; s < 3000; ++s) ASSERT_TRUE(chain.step(1.0f / 60.0f, Vec3(0, -g, 0)).ok());

        for (uint32_t r = 0; r + 1 < rows; ++r) {
            const float expected = rest + static_cast<float>(rows - 1 - r) * m * g / k;
            for (uint32_t c = 0; c < 2; ++c) {
                const float length =
                    (chain.positions().get((r + 1) * 2 + c) - chain.positions().get(r * 2 + c)).norm();
                EXPECT_NEAR(length, expected, 1e-4f * expected)
                    << "spring below row " << r << ", column " << c;
            }
        }
        EXPECT_LT(chain.velocities().get(2 * rows - 1).norm(), 1e-4f) << "at rest";
    }
}

}  // namespace
}  // namespace cloth
