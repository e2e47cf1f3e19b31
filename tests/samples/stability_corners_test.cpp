// The corners of the stability map (docs/stability.md): for each solver
// kind, the lowest- and highest-gamma cells the map documents as holding
// (docs/data/stability.csv, 16x16, falling flat) still hold: finite, no
// energy gain beyond 1 % of m g x 1 m, max structural strain under 10 %.
// Each cell runs as `tradeoff stability` runs it (run_scene, 0.5 s but 20
// to 120 frames, the same thresholds as its classify()).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "run_scene.h"

namespace {

struct Cell {
    cloth_solver_kind kind;
    uint32_t iterations;
    float stiffness;      // N/m
    float dt;             // s
    float particle_mass;  // kg
};

std::string describe(const Cell& c) {
    return std::string(tradeoff::kind_name(c.kind)) + " k=" + std::to_string(c.iterations) + ", stiffness " +
           std::to_string(c.stiffness) + " N/m, dt " + std::to_string(c.dt) + " s, mass " +
           std::to_string(c.particle_mass) + " kg, gamma " +
           std::to_string(double(c.dt) * c.dt * c.stiffness / c.particle_mass);
}

TEST(StabilityMap, TheLowestAndHighestGammaCellsDocumentedAsHoldingHold) {
    const Cell cells[] = {
        {CLOTH_SOLVER_EXPLICIT, 1, 1e2f, 1e-3f, 1e-2f},
        {CLOTH_SOLVER_EXPLICIT, 1, 1e5f, 1e-3f, 1.0f},
        {CLOTH_SOLVER_JACOBI, 1, 1e2f, 1e-3f, 1e-2f},
        {CLOTH_SOLVER_JACOBI, 1, 1e7f, 1e-3f, 1e-4f},
        {CLOTH_SOLVER_CHEBYSHEV, 16, 1e2f, 1e-3f, 1e-2f},
        {CLOTH_SOLVER_CHEBYSHEV, 16, 1e7f, 1.0f / 300, 1e-4f},
        {CLOTH_SOLVER_PCG, 16, 1e2f, 1e-3f, 1e-2f},
        {CLOTH_SOLVER_PCG, 16, 1e7f, 1.0f / 300, 1e-4f},
        {CLOTH_SOLVER_DEFAULT, 1, 1e1f, 1e-3f, 1.0f},
        {CLOTH_SOLVER_DEFAULT, 1, 1e7f, 0.1f, 1e-4f},
    };
    for (const Cell& c : cells) {
        SCOPED_TRACE(describe(c));
        cloth_samples::SceneConfig config;
        config.kind = cloth_samples::SceneKind::kFallingFlat;
        config.resolution = 16;
        config.total_mass = c.particle_mass * 16 * 16;
        config.stiffness = c.stiffness;
        config.solver.kind = c.kind;
        config.solver.iterations = c.iterations;
        const uint32_t frames =
            std::clamp<uint32_t>(static_cast<uint32_t>(std::lround(0.5f / c.dt)), 20, 120);
        const tradeoff::RunResult r = tradeoff::run_scene(config, c.dt, frames);
        ASSERT_TRUE(r.ok) << r.error;
        EXPECT_LE(r.energy_gain, 1e-2 * config.total_mass * 9.81) << "gained energy";
        EXPECT_LT(r.max_strain, 0.1) << "over-stretched";
    }
}

}  // namespace

// The default at the stiff end: 1 kg cloths of 1e7 N/m springs at a tenth
// of a second a step, where its sixteen substeps cannot bring a substep's
// gamma within the theta step's measured range, falling flat and hanging
// for 50 frames: no energy gained beyond 1e-3 J (the theta step gained
// 0.06 J falling flat at 32x32 and 41 J at 128x128, which tradeoff probe
// measures; here 32x32, for the test's time).
TEST(StabilityMap, TheDefaultPastItsSubstepCapGainsNoEnergy) {
    for (const auto kind : {cloth_samples::SceneKind::kFallingFlat, cloth_samples::SceneKind::kHanging}) {
        SCOPED_TRACE(cloth_samples::scene_name(kind));
        cloth_samples::SceneConfig config;
        config.kind = kind;
        config.resolution = 32;
        config.stiffness = 1e7f;
        const tradeoff::RunResult r = tradeoff::run_scene(config, 0.1f, 50);
        ASSERT_TRUE(r.ok) << r.error;
        EXPECT_LE(r.energy_gain, 1e-3) << "gained energy";
        EXPECT_LT(r.max_strain, 0.1) << "over-stretched";
    }
}
