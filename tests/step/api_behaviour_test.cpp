// What a host sees through the C API when it uses it correctly: pins follow
// their targets, fabrics are shared, run-time changes take effect, the
// renderer's read-outs are sane, and the same calls give the same bits.
#include <cloth/cloth.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "scenes.h"

namespace {

using cloth_samples::Scene;
using cloth_samples::SceneConfig;
using cloth_samples::SceneKind;

TEST(ApiBehaviour, PinnedParticlesLandExactlyOnTheirMovingTargets) {
    SceneConfig config;
    config.resolution = 12;
    Scene scene(config);
    ASSERT_TRUE(scene.ok()) << scene.error();
    const uint32_t pins[] = {0, 11};
    for (int frame = 1; frame <= 120; ++frame) {
        const float t = static_cast<float>(frame) / 60.0f;
        const float targets[] = {0.3f * std::sin(t),        1.5f, 0.2f * t,
                                 1.0f + 0.3f * std::sin(t), 1.5f, 0.2f * t};
        ASSERT_EQ(cloth_set_pin_targets(scene.cloth(), pins, targets, 2), CLOTH_OK);
        ASSERT_EQ(scene.step(1.0f / 60.0f), CLOTH_OK);
        const std::vector<float> x = scene.positions();
        for (int k = 0; k < 2; ++k) {
            for (int c = 0; c < 3; ++c)
                ASSERT_EQ(x[3 * pins[k] + c], targets[3 * k + c]) << "frame " << frame;
        }
    }
}

TEST(ApiBehaviour, UnpinnedParticleFallsAndPinReportsState) {
    SceneConfig config;
    config.resolution = 8;
    config.solver.kind = CLOTH_SOLVER_CG;  // one Jacobi sweep lets stiff cloth fall in slow motion
    Scene scene(config);
    const uint32_t corner = 7;
    bool pinned = false;
    ASSERT_EQ(cloth_is_pinned(scene.cloth(), corner, &pinned), CLOTH_OK);
    EXPECT_TRUE(pinned);
    ASSERT_EQ(cloth_unpin(scene.cloth(), &corner, 1), CLOTH_OK);
    ASSERT_EQ(cloth_is_pinned(scene.cloth(), corner, &pinned), CLOTH_OK);
    EXPECT_FALSE(pinned);
    const float y0 = scene.positions()[3 * corner + 1];
    for (int i = 0; i < 30; ++i) scene.step(1.0f / 60.0f);
    EXPECT_LT(scene.positions()[3 * corner + 1], y0 - 0.1f) << "released corner drops";
}

TEST(ApiBehaviour, TwoClothsShareOneFabricAndDestroyingTheFabricHandleKeepsThemAlive) {
    cloth_world_desc world_desc = cloth_default_world_desc();
    cloth_world_id world;
    ASSERT_EQ(cloth_world_create(&world_desc, &world), CLOTH_OK);
    cloth_grid_desc grid = cloth_default_grid_desc();
    grid.columns = grid.rows = 8;
    cloth_fabric_id fabric;
    ASSERT_EQ(cloth_fabric_create_grid(world, &grid, &fabric), CLOTH_OK);
    cloth_desc desc = cloth_default_desc();
    desc.fabric = fabric;
    cloth_id a, b;
    ASSERT_EQ(cloth_create(world, &desc, &a), CLOTH_OK);
    desc.solver.kind = CLOTH_SOLVER_CG;
    ASSERT_EQ(cloth_create(world, &desc, &b), CLOTH_OK);
    ASSERT_EQ(cloth_fabric_destroy(fabric), CLOTH_OK);
    uint32_t count = 0;
    EXPECT_EQ(cloth_fabric_get_particle_count(fabric, &count), CLOTH_ERROR_INVALID_HANDLE);
    for (int i = 0; i < 10; ++i) ASSERT_EQ(cloth_step(world, 1.0f / 60.0f), CLOTH_OK);
    std::vector<float> xa(3 * 64), xb(3 * 64);
    ASSERT_EQ(cloth_read_positions(a, xa.data(), 3 * 64), CLOTH_OK);
    ASSERT_EQ(cloth_read_positions(b, xb.data(), 3 * 64), CLOTH_OK);
    // Backward Euler free fall after n steps: h^2 g n (n + 1) / 2 = 0.1499 m for n = 10 at 60 Hz.
    // CG gets it; one Jacobi sweep lets stiff cloth fall in slow motion.
    EXPECT_NEAR(xb[1], -0.1499f, 0.002f) << "the CG cloth falls freely";
    EXPECT_LT(xa[1], 0.0f) << "the JACOBI cloth falls too";
    EXPECT_NE(std::memcmp(xa.data(), xb.data(), xa.size() * sizeof(float)), 0)
        << "different solvers, own state";
    ASSERT_EQ(cloth_world_destroy(world), CLOTH_OK);
}

TEST(ApiBehaviour, RunTimeChangesOfSolverStiffnessAndWindTakeEffect) {
    SceneConfig config;
    config.resolution = 10;
    Scene scene(config);
    cloth_solver_settings solver = cloth_default_solver_settings();
    solver.kind = CLOTH_SOLVER_CG;
    solver.substeps = 3;
    ASSERT_EQ(cloth_set_solver(scene.cloth(), &solver), CLOTH_OK);
    cloth_solver_settings read{};
    ASSERT_EQ(cloth_get_solver(scene.cloth(), &read), CLOTH_OK);
    EXPECT_EQ(read.kind, CLOTH_SOLVER_CG);
    EXPECT_EQ(read.substeps, 3u);

    for (int i = 0; i < 120; ++i) scene.step(1.0f / 60.0f);
    const float stiff_strain = scene.stats().max_strain;
    ASSERT_EQ(cloth_set_spring_params(scene.cloth(), CLOTH_SPRING_ALL, cloth_spring_params{50.0f, 0.5f}),
              CLOTH_OK);
    for (int i = 0; i < 240; ++i) scene.step(1.0f / 60.0f);
    EXPECT_GT(scene.stats().max_strain, 2 * stiff_strain)
        << "softer springs stretch more under the same weight";

    const float before = scene.positions()[3 * 55 + 2];
    const float wind[] = {0.0f, 0.0f, 8.0f};
    ASSERT_EQ(cloth_set_wind(scene.cloth(), wind), CLOTH_OK);
    for (int i = 0; i < 60; ++i) scene.step(1.0f / 60.0f);
    EXPECT_GT(scene.positions()[3 * 55 + 2], before + 0.05f) << "wind across the cloth pushes it downwind";
}

TEST(ApiBehaviour, FlagFlapsInWind) {
    SceneConfig config;
    config.kind = SceneKind::kFlagInWind;
    config.resolution = 16;
    Scene scene(config);
    ASSERT_TRUE(scene.ok()) << scene.error();
    for (int i = 0; i < 120; ++i) ASSERT_EQ(scene.step(1.0f / 60.0f), CLOTH_OK);
    // Over the next two seconds the free edge keeps moving across the wind.
    const uint32_t tip = 8 * 16 + 15;
    float z_min = 1e9f, z_max = -1e9f, speed_sum = 0;
    for (int i = 0; i < 120; ++i) {
        ASSERT_EQ(scene.step(1.0f / 60.0f), CLOTH_OK);
        const float z = scene.positions()[3 * tip + 2];
        z_min = std::min(z_min, z);
        z_max = std::max(z_max, z);
        speed_sum += scene.stats().max_speed;
    }
    EXPECT_GT(z_max - z_min, 0.05f) << "the tip swings across the wind";
    EXPECT_GT(speed_sum / 120, 0.2f) << "the flag does not come to rest";
    EXPECT_GT(scene.positions()[3 * tip], 0.7f) << "the flag streams downwind of its pole";
}

TEST(ApiBehaviour, NormalsAreUnitLength) {
    SceneConfig config;
    config.kind = SceneKind::kFlagInWind;
    config.resolution = 9;
    Scene scene(config);
    for (int i = 0; i < 30; ++i) scene.step(1.0f / 60.0f);
    std::vector<float> n(3 * 81);
    ASSERT_EQ(cloth_read_normals(scene.cloth(), n.data(), 3 * 81), CLOTH_OK);
    for (int i = 0; i < 81; ++i) {
        EXPECT_NEAR(
            std::sqrt(n[3 * i] * n[3 * i] + n[3 * i + 1] * n[3 * i + 1] + n[3 * i + 2] * n[3 * i + 2]), 1.0f,
            1e-5f);
    }
}

// Two worlds given the same calls end with the same bits. Compared only
// once both scenes were built and every one of their steps returned
// CLOTH_OK (two empty read-outs compare equal too), after the flag has
// flown far from where it started; and one step more gives other bits, so
// the comparison sees a difference where there is one.
TEST(ApiBehaviour, SameCallsGiveBitIdenticalResults) {
    auto run = [](int steps, std::vector<float>& start, std::vector<float>& end) {
        SceneConfig config;
        config.kind = SceneKind::kFlagInWind;
        config.resolution = 12;
        Scene scene(config);
        ASSERT_TRUE(scene.ok()) << scene.error();
        ASSERT_EQ(scene.particle_count(), 144u);
        start.assign(3 * 144, NAN);
        end.assign(3 * 144, NAN);
        ASSERT_EQ(cloth_read_positions(scene.cloth(), start.data(), 3 * 144), CLOTH_OK);
        for (int i = 0; i < steps; ++i) ASSERT_EQ(scene.step(1.0f / 60.0f), CLOTH_OK) << "step " << i;
        ASSERT_EQ(cloth_read_positions(scene.cloth(), end.data(), 3 * 144), CLOTH_OK);
    };
    std::vector<float> start_a, a, start_b, b, start_c, c;
    ASSERT_NO_FATAL_FAILURE(run(200, start_a, a));
    ASSERT_NO_FATAL_FAILURE(run(200, start_b, b));
    ASSERT_NO_FATAL_FAILURE(run(201, start_c, c));
    float moved = 0;
    for (size_t i = 0; i < a.size(); i += 3) {
        ASSERT_TRUE(std::isfinite(a[i]) && std::isfinite(a[i + 1]) && std::isfinite(a[i + 2]));
        moved = std::max(moved,
                         std::hypot(a[i] - start_a[i], a[i + 1] - start_a[i + 1], a[i + 2] - start_a[i + 2]));
    }
    EXPECT_GT(moved, 0.1f) << "the flag flew: its farthest particle moved this far (m)";
    ASSERT_EQ(a.size(), b.size());
    EXPECT_EQ(std::memcmp(start_a.data(), start_b.data(), a.size() * sizeof(float)), 0);
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)), 0) << "the same 200 steps";
    EXPECT_NE(std::memcmp(a.data(), c.data(), a.size() * sizeof(float)), 0) << "201 steps against 200";
}

// Masses a host sets are read back in vertex order (a mesh keeps its own
// particle order inside), stay through new spring parameters, and weigh:
// a hanging cloth whose bottom row weighs ten times more sags lower.
TEST(ApiBehaviour, ParticleMassesAreReadBackKeptThroughSpringChangesAndWeighTheCloth) {
    SceneConfig config;
    config.kind = SceneKind::kHanging;
    config.resolution = 16;
    config.mesh = true;
    Scene heavy_hem(config), plain(config);
    ASSERT_TRUE(heavy_hem.ok() && plain.ok()) << heavy_hem.error();
    const uint32_t n = heavy_hem.particle_count();
    std::vector<float> masses(n);
    ASSERT_EQ(cloth_read_particle_masses(heavy_hem.cloth(), masses.data(), n), CLOTH_OK);
    float total = 0;
    for (float m : masses) total += m;
    EXPECT_NEAR(total, config.total_mass, 1e-4f) << "the material's masses, read back";
    // The bottom row (the grid's last 16 vertices) ten times heavier.
    std::vector<uint32_t> hem;
    std::vector<float> hem_masses;
    for (uint32_t v = n - 16; v < n; ++v) {
        hem.push_back(v);
        hem_masses.push_back(10.0f * masses[v]);
    }
    ASSERT_EQ(cloth_set_particle_masses(heavy_hem.cloth(), hem.data(), hem_masses.data(), 16), CLOTH_OK);
    ASSERT_EQ(cloth_set_spring_params(heavy_hem.cloth(), CLOTH_SPRING_ALL, {1000.0f, 0.0f}), CLOTH_OK);
    ASSERT_EQ(cloth_set_spring_params(plain.cloth(), CLOTH_SPRING_ALL, {1000.0f, 0.0f}), CLOTH_OK);
    std::vector<float> after(n);
    ASSERT_EQ(cloth_read_particle_masses(heavy_hem.cloth(), after.data(), n), CLOTH_OK);
    for (uint32_t v = 0; v < n; ++v) {
        EXPECT_EQ(after[v], v >= n - 16 ? 10.0f * masses[v] : masses[v]) << "vertex " << v;
    }
    for (int frame = 0; frame < 120; ++frame) {
        ASSERT_EQ(heavy_hem.step(1.0f / 60.0f), CLOTH_OK);
        ASSERT_EQ(plain.step(1.0f / 60.0f), CLOTH_OK);
    }
    const std::vector<float> x = heavy_hem.positions(), y = plain.positions();
    float hem_height = 0, plain_height = 0;
    for (uint32_t v = n - 16; v < n; ++v) {
        hem_height += x[3 * v + 1] / 16;
        plain_height += y[3 * v + 1] / 16;
    }
    EXPECT_LT(hem_height, plain_height - 1e-3f) << "the heavier hem hangs lower";
}

TEST(ApiBehaviour, VersionMatchesTheHeader) {
    const cloth_version v = cloth_get_version();
    EXPECT_EQ(v.major, CLOTH_VERSION_MAJOR);
    EXPECT_EQ(v.minor, CLOTH_VERSION_MINOR);
    EXPECT_EQ(v.patch, CLOTH_VERSION_PATCH);
}

}  // namespace
