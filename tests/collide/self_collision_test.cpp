// Self-collision (self_collision.h): the contact search misses no pair
// closer than theta_c (against brute force, with and without regions),
// regions that fold stop being skipped, rest neighbours never repel, the
// response separates pairs and removes approach, results do not depend on
// how the ranges are split, and a cloth dropped into a pile keeps its
// non-neighbour particles theta_c apart after every step.
#include "collide/self_collision.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "test_support.h"

namespace cloth {
namespace {

// A grid folded like an accordion into layers 0.6 theta apart (folds run
// along the rows, so they cross regions), with noise.
Vec3Soa accordion(const Fabric& fabric, float period, float gap, float noise_amount, unsigned seed) {
    Vec3Soa x(testing::heap());
    x.resize(fabric.particle_count());
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> noise(-noise_amount, noise_amount);
    for (uint32_t i = 0; i < fabric.particle_count(); ++i) {
        const Vec3& p = fabric.rest_positions[i];
        const float layer = std::floor(p.x() / period), t = p.x() - layer * period;
        const float folded = static_cast<int>(layer) % 2 ? period - t : t;
        x.set(i, Vec3(folded + noise(rng), p.y() + noise(rng), layer * gap + noise(rng)));
    }
    return x;
}

bool in_contacts(const SelfCollision& c, uint32_t i, uint32_t j) {
    for (uint32_t k = 0; k < c.contact_count(i); ++k) {
        if (c.contact(i, k) == j) return true;
    }
    return false;
}

// Runs the detection stages on x, then checks every non-neighbour pair
// closer than theta_c: it is in both contact lists, or (only with regions)
// skipped as lying in one collision-free region. Returns how many pairs
// were skipped that way.
uint32_t check_against_brute_force(SelfCollision& c, const Vec3Soa& x, uint32_t min_close = 100) {
    const uint32_t n = c.particle_count();
    c.check_regions(x, 0, c.region_count());
    c.compute_keys(x, 0, n);
    c.sort_into_buckets(x);
    c.find_contacts(x, 0, n);
    EXPECT_EQ(c.stats().overflowed_particles, 0u) << "the scene must fit the contact slots";
    const float theta = c.settings().thickness;
    uint32_t close = 0, skipped = 0;
    for (uint32_t i = 0; i < n; ++i) {
        for (uint32_t j = i + 1; j < n; ++j) {
            if (!((x.get(i) - x.get(j)).norm() < theta) || c.is_rest_neighbour(i, j)) continue;
            ++close;
            if (c.skipped_by_region(i, j)) {
                ++skipped;
                continue;
            }
            EXPECT_TRUE(in_contacts(c, i, j) && in_contacts(c, j, i))
                << "pair " << i << ", " << j << " missed";
        }
    }
    EXPECT_GT(close, min_close) << "the scene must have close pairs to test";
    return skipped;
}

SelfCollisionSettings settings_for(const Fabric& fabric, float thickness_in_edges, bool regions) {
    SelfCollisionSettings s;
    s.thickness = thickness_in_edges * mean_rest_edge(fabric);
    s.use_regions = regions;
    return s;
}

TEST(SelfCollision, CrumpledClothContactsMatchBruteForceWithoutRegions) {
    auto fabric = testing::make_grid(32, 32);
    SelfCollision c(testing::heap(), *fabric, settings_for(*fabric, 0.9f, false));
    const float theta = c.settings().thickness;
    const Vec3Soa x = accordion(*fabric, 0.25f, 0.6f * theta, 0.15f * theta, 3);
    EXPECT_EQ(check_against_brute_force(c, x), 0u);
}

TEST(SelfCollision, CrumpledClothContactsMatchBruteForceWithRegions) {
    // Skipped pairs are only those in valid regions, and the accordion's
    // flat layers are the only regions that stay valid: none of their
    // non-neighbour pairs is within theta_c (the region criterion's promise).
    for (const bool mesh : {false, true}) {
        auto fabric = mesh ? testing::make_mesh_from_grid(32, 32) : testing::make_grid(32, 32);
        SelfCollision c(testing::heap(), *fabric, settings_for(*fabric, 0.9f, true));
        const float theta = c.settings().thickness;
        // Folds every 0.3 m: they cross the 8-column tiles of the grid.
        const Vec3Soa x = accordion(*fabric, 0.3f, 0.6f * theta, 0.15f * theta, 4);
        EXPECT_EQ(check_against_brute_force(c, x), 0u) << (mesh ? "mesh" : "grid");
        const SelfCollisionStats stats = c.stats();
        EXPECT_GT(stats.valid_regions, 0u) << "flat layers keep their regions";
        EXPECT_LT(stats.valid_regions, stats.regions) << "regions across a fold are not collision-free";
    }
}

TEST(SelfCollision, RandomCloudOfAClothMatchesBruteForce) {
    // Positions with no relation to the mesh: every region fails its test,
    // and the contact lists alone must hold every close pair.
    auto fabric = testing::make_grid(24, 24);
    SelfCollision c(testing::heap(), *fabric, settings_for(*fabric, 1.0f, true));
    Vec3Soa x(testing::heap());
    x.resize(fabric->particle_count());
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> uniform(0.0f, 0.6f);
    for (uint32_t i = 0; i < fabric->particle_count(); ++i)
        x.set(i, Vec3(uniform(rng), uniform(rng), uniform(rng)));
    check_against_brute_force(c, x);
}

TEST(SelfCollision, FoldThroughOneRegionGetsItsPairsTested) {
    // 16x16 grid = four 8x8 regions. Fold the columns >= 4 back over
    // columns <= 3 at height 0.6 theta: the crease runs through regions 0
    // and 2; column 5 lies over column 2 (three rings apart), and so on.
    auto fabric = testing::make_grid(16, 16);
    SelfCollision c(testing::heap(), *fabric, settings_for(*fabric, 0.9f, true));
    const float theta = c.settings().thickness, spacing = 1.0f / 15.0f, crease = 3.5f * spacing;
    Vec3Soa x(testing::heap());
    x.resize(256);
    for (uint32_t i = 0; i < 256; ++i) {
        const Vec3& p = fabric->rest_positions[i];
        x.set(i, p.x() < crease ? p : Vec3(2 * crease - p.x(), p.y(), 0.6f * theta));
    }
    c.check_regions(x, 0, c.region_count());
    EXPECT_FALSE(c.region_valid(c.region_of(0))) << "the region the fold crosses";
    EXPECT_FALSE(c.region_valid(c.region_of(8 * 16)));
    EXPECT_TRUE(c.region_valid(c.region_of(15))) << "a region wholly on the folded-over flap stays flat";
    check_against_brute_force(c, x, 30);
    const uint32_t over = 5, under = 2;  // row 0
    EXPECT_FALSE(c.is_rest_neighbour(over, under));
    EXPECT_TRUE(in_contacts(c, over, under));
}

TEST(SelfCollision, RestNeighboursNeverRepel) {
    // A flat cloth at rest with theta_c of 1.5 edges: every particle within
    // theta_c is a rest neighbour, so nothing moves.
    auto fabric = testing::make_mesh_from_grid(12, 12);
    SelfCollision c(testing::heap(), *fabric, settings_for(*fabric, 1.5f, false));
    Vec3Soa x(testing::heap()), v(testing::heap());
    x.resize(144);
    v.resize(144);
    for (uint32_t i = 0; i < 144; ++i) {
        x.set(i, fabric->rest_positions[i]);
        v.set(i, Vec3(0, 0, 0));
    }
    for (uint32_t s = 0; s < fabric->spring_count(); ++s) {
        EXPECT_TRUE(c.is_rest_neighbour(fabric->spring_first[s], fabric->spring_second[s]));
    }
    std::vector<float> mass(144, 0.01f), pinned(144, 0.0f);
    c.run_serially(x, v, mass.data(), pinned.data());
    for (uint32_t i = 0; i < 144; ++i) EXPECT_EQ(x.get(i), fabric->rest_positions[i]) << i;
    EXPECT_EQ(c.stats().contacts, 0u);
}

TEST(SelfCollision, ResponsePushesApartAndRemovesApproach) {
    // Two separate triangles, the second 0.3 theta above the first and
    // falling onto it at 2 m/s with a sideways slide: afterwards the pairs
    // are theta_c apart, no longer approach, momentum is conserved, and
    // friction slows the slide.
    const float positions[] = {0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0.03f, 0, 1, 0.03f, 0, 0, 0.03f, 1};
    const uint32_t triangles[] = {0, 1, 2, 3, 4, 5};
    for (const float friction : {0.0f, 0.5f}) {
        Fabric fabric(testing::heap());
        ASSERT_TRUE(build_mesh_fabric(positions, 6, triangles, 2, CLOTH_SPRING_ALL, fabric).ok());
        SelfCollisionSettings s;
        s.thickness = 0.1f;
        s.friction = friction;
        s.use_regions = false;
        s.passes = 8;
        SelfCollision c(testing::heap(), fabric, s);
        auto p = [&](uint32_t vertex) {
            return fabric.particle(vertex);
        };  // meshes store particles spatially sorted
        Vec3Soa x(testing::heap()), v(testing::heap());
        x.resize(6);
        v.resize(6);
        for (uint32_t i = 0; i < 6; ++i) {
            x.set(p(i), fabric.rest_positions[p(i)]);
            v.set(p(i), i < 3 ? Vec3(0, 0, 0) : Vec3(1.0f, -2.0f, 0));
        }
        std::vector<float> mass(6, 0.1f), pinned(6, 0.0f);
        c.run_serially(x, v, mass.data(), pinned.data());
        Vec3 momentum = Vec3::Zero();
        for (uint32_t i = 0; i < 3; ++i) {
            EXPECT_NEAR((x.get(p(i + 3)) - x.get(p(i))).norm(), 0.1f, 1e-3f);
            EXPECT_GE(v.get(p(i + 3)).y() - v.get(p(i)).y(), -1e-6f) << "still approaching";
        }
        for (uint32_t i = 0; i < 6; ++i) momentum += v.get(i) * 0.1f;
        EXPECT_NEAR(momentum.y(), 3 * 0.1f * -2.0f, 1e-5f);
        EXPECT_NEAR(momentum.x(), 3 * 0.1f * 1.0f, 1e-5f);
        const float slide = v.get(p(3)).x() - v.get(p(0)).x();
        if (friction == 0) {
            EXPECT_FLOAT_EQ(slide, 1.0f);
        } else {
            EXPECT_LT(slide, 1.0f);
            EXPECT_GE(slide, 0.0f) << "friction never reverses the slide";
        }
    }
}

TEST(SelfCollision, PinnedParticlesStayAndTheirPartnerTakesTheWholePush) {
    const float positions[] = {0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0.02f, 0, 1, 0.02f, 0, 0, 0.02f, 1};
    const uint32_t triangles[] = {0, 1, 2, 3, 4, 5};
    Fabric fabric(testing::heap());
    ASSERT_TRUE(build_mesh_fabric(positions, 6, triangles, 2, CLOTH_SPRING_ALL, fabric).ok());
    SelfCollisionSettings s;
    s.thickness = 0.1f;
    s.use_regions = false;
    SelfCollision c(testing::heap(), fabric, s);
    auto p = [&](uint32_t vertex) {
        return fabric.particle(vertex);
    };  // meshes store particles spatially sorted
    Vec3Soa x(testing::heap()), v(testing::heap());
    x.resize(6);
    v.resize(6);
    std::vector<float> mass(6, 0.1f), pinned(6, 0.0f);
    for (uint32_t i = 0; i < 6; ++i) {
        x.set(p(i), fabric.rest_positions[p(i)]);
        v.set(p(i), Vec3(0, i < 3 ? 0.0f : -1.0f, 0));
        pinned[p(i)] = i < 3 ? 1.0f : 0.0f;
    }
    c.run_serially(x, v, mass.data(), pinned.data());
    for (uint32_t i = 0; i < 3; ++i) {
        EXPECT_EQ(x.get(p(i)), fabric.rest_positions[p(i)]);
        EXPECT_NEAR(x.get(p(i + 3)).y(), 0.1f, 1e-4f);
        EXPECT_NEAR(v.get(p(i + 3)).y(), 0.0f, 1e-6f);
    }
}

TEST(SelfCollision, RangeSplitGivesIdenticalBits) {
    // The stages run on any split of their ranges (as a job system does)
    // give the bits of the serial run.
    auto fabric = testing::make_grid(24, 24);
    const SelfCollisionSettings s = settings_for(*fabric, 0.9f, true);
    const Vec3Soa start = accordion(*fabric, 0.2f, 0.4f * s.thickness, 0.2f * s.thickness, 8);
    std::vector<float> mass(576, 0.002f), pinned(576, 0.0f);
    pinned[0] = 1;
    Vec3Soa v0(testing::heap());
    v0.resize(576);
    for (uint32_t i = 0; i < 576; ++i) v0.set(i, Vec3(0.1f * (i % 7), -1.0f, 0.05f * (i % 3)));

    SelfCollision serial(testing::heap(), *fabric, s);
    Vec3Soa xs = start, vs = v0;
    serial.run_serially(xs, vs, mass.data(), pinned.data());

    SelfCollision split(testing::heap(), *fabric, s);
    Vec3Soa xp = start, vp = v0;
    const uint32_t n = 576, step = 97;
    auto each = [&](uint32_t count, auto body) {
        for (uint32_t b = 0; b < count; b += step) body(b, std::min(count, b + step));
    };
    each(split.region_count(), [&](uint32_t b, uint32_t e) { split.check_regions(xp, b, e); });
    each(n, [&](uint32_t b, uint32_t e) { split.compute_keys(xp, b, e); });
    split.sort_into_buckets(xp);
    each(n, [&](uint32_t b, uint32_t e) { split.find_contacts(xp, b, e); });
    each(n, [&](uint32_t b, uint32_t e) { split.compute_inverse_mass(mass.data(), pinned.data(), b, e); });
    for (uint32_t pass = 0; pass < s.passes; ++pass) {
        each(n, [&](uint32_t b, uint32_t e) { split.project(xp, b, e); });
        split.apply_positions(xp);
        if (!split.any_overlapping()) break;
    }
    each(n, [&](uint32_t b, uint32_t e) { split.respond_velocities(xp, vp, b, e); });
    split.apply_velocities(vp);
    EXPECT_GT(serial.stats().contacts, 100u);
    for (uint32_t i = 0; i < n; ++i) {
        ASSERT_EQ(xs.get(i), xp.get(i)) << i;
        ASSERT_EQ(vs.get(i), vp.get(i)) << i;
    }
}

}  // namespace
}  // namespace cloth

namespace cloth {
namespace {

// Non-neighbour pairs closer than (1 - tolerance) theta_c, and the smallest
// such distance over theta_c.
struct Violations {
    uint32_t count = 0;
    float closest = 1e30f;
};

Violations count_violations(const ClothInstance& cloth, float tolerance) {
    const SelfCollision& c = *cloth.self_collision();
    const float theta = c.settings().thickness;
    const Vec3Soa& x = cloth.positions();
    Violations v;
    for (uint32_t i = 0; i < cloth.particle_count(); ++i) {
        for (uint32_t j = i + 1; j < cloth.particle_count(); ++j) {
            if (c.is_rest_neighbour(i, j)) continue;
            const float d = (x.get(i) - x.get(j)).norm() / theta;
            v.closest = std::min(v.closest, d);
            if (d < 1.0f - tolerance) ++v.count;
        }
    }
    return v;
}

TEST(SelfCollisionPile, DroppedClothKeepsNonNeighboursApartAfterEveryStep) {
    // A soft 20x20 curtain hanging just above the ground, with a wave along
    // its height, is lowered by its top row (pinned) to 6 cm above the
    // ground in one second: it folds into a pile under its top. The ground
    // is test-local: particles below y = 0 are put back on it with zero
    // velocity between steps.
    std::vector<Vec3> final_positions[2];
    for (const bool regions : {true, false}) {
        auto fabric = testing::make_grid(20, 20);
        SolverSettings solver;
        solver.substeps = 4;
        AeroParams air;
        air.linear_drag = 0.1f;
        ClothInstance cloth(testing::heap(), fabric, testing::uniform_material(200.0f, 0.05f, 0.2f), solver,
                            air);
        for (uint32_t i = 0; i < cloth.particle_count(); ++i) {
            const float wave = 0.04f * std::sin(2.0f * 3.14159265f * static_cast<float>(i / 20) / 6.0f);
            cloth.set_position(i, fabric->rest_positions[i] + Vec3(0.0f, 1.02f, wave));
        }
        for (uint32_t i = 0; i < 20; ++i) cloth.pin(i);
        SelfCollisionSettings s;
        s.thickness = 0.04f;
        s.use_regions = regions;
        s.friction = 0.2f;
        cloth.set_self_collision(&s);
        uint32_t total = 0, steps_with_contacts = 0;
        float closest = 1e30f;
        float lowest_top = 1e30f;
        for (int step = 0; step < 90; ++step) {
            const float top = std::max(0.06f, 1.02f - 0.96f * static_cast<float>(step + 1) / 60.0f);
            for (uint32_t i = 0; i < 20; ++i) {
                const Vec3 p = cloth.positions().get(i);
                cloth.set_pin_target(i, Vec3(p.x(), top, p.z()));
            }
            ASSERT_TRUE(cloth.step(1.0f / 60.0f, Vec3(0.0f, -9.81f, 0.0f)).ok());
            // Counted when the step returns (self-collision ran last); the
            // test's ground, applied next, may squash layers below y = 0.
            const Violations v = count_violations(cloth, 0.1f);
            for (uint32_t i = 0; i < cloth.particle_count(); ++i) {
                const Vec3 p = cloth.positions().get(i);
                if (p.y() < 0) cloth.set_position(i, Vec3(p.x(), 0.0f, p.z()));
            }
            total += v.count;
            closest = std::min(closest, v.closest);
            steps_with_contacts += cloth.self_collision()->stats().contacts > 0;
            lowest_top = std::min(lowest_top, cloth.positions().get(10 * 20).y());
        }
        std::printf(
            "pile (%s regions): %u violations beyond 10%% over 90 steps, closest %.3f theta_c, "
            "%u steps with contacts, middle row fell to %.3f m\n",
            regions ? "with" : "without", total, closest, steps_with_contacts, lowest_top);
        EXPECT_EQ(total, 0u);
        EXPECT_GT(steps_with_contacts, 30u) << "the cloth must pile up for the test to mean anything";
        EXPECT_LT(lowest_top, 0.2f) << "the middle row ended in the pile";
        final_positions[regions] = testing::positions_of(cloth);
    }
    // Regions only skip pairs that cannot touch, so here they change nothing.
    EXPECT_EQ(final_positions[0], final_positions[1]);
}

}  // namespace
}  // namespace cloth
