// Between the strain limiter's passes the colliders are tested only where
// the collision stage recorded that a particle can reach them
// (ClothContact::Pass). Checked against the full test (every collider for
// every particle in every round) on a cloth hanging against two capsule
// legs and over a sphere, with the default solver: where the legs sway,
// the record misses nothing, and both ways take the same bits every
// frame; where they kick through the cloth, the passes pull particles
// after the ones a leg pushed, past their records, and the round after the
// last pass (every collider) still ends every frame with no particle
// deeper in a leg or the sphere than 1 mm past the full test's deepest. And the stats say what the strain
// limiter's passes did.
#include <cloth/cloth.h>
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "api_call.h"
#include "scene/world.h"

namespace cloth {
namespace {

constexpr uint32_t kSide = 24;
constexpr float kFrame = 1.0f / 60.0f;

struct KickedCloth {
    cloth_world_id world{};
    cloth_id cloth{};
    cloth_body_id legs{};

    float amplitude, omega;  // the legs' swing along z: m, rad/s

    KickedCloth(bool record, float amplitude_m = 0.35f, float omega_rad_s = 9.4f)
        : amplitude(amplitude_m), omega(omega_rad_s) {
        cloth_world_desc wd = cloth_default_world_desc();
        EXPECT_EQ(cloth_world_create(&wd, &world), CLOTH_OK);
        cloth_grid_desc gd = cloth_default_grid_desc();
        gd.columns = gd.rows = kSide;
        cloth_fabric_id fabric{};
        EXPECT_EQ(cloth_fabric_create_grid(world, &gd, &fabric), CLOTH_OK);
        cloth_desc cd = cloth_default_desc();
        cd.fabric = fabric;
        EXPECT_EQ(cloth_create(world, &cd, &cloth), CLOTH_OK);
        std::vector<uint32_t> top;
        for (uint32_t c = 0; c < kSide; ++c) top.push_back(c);
        EXPECT_EQ(cloth_pin(cloth, top.data(), kSide), CLOTH_OK);
        // Two capsule legs on one body, just behind the hanging cloth, and a
        // static sphere under its lower edge.
        cloth_body_desc bd = cloth_default_body_desc();
        EXPECT_EQ(cloth_body_create(world, &bd, &legs), CLOTH_OK);
        for (float x : {0.3f, 0.7f}) {
            cloth_collider_desc d = cloth_default_collider_desc();
            d.body = legs;
            d.local_position[0] = x;
            d.local_position[1] = -0.6f;
            d.local_position[2] = -0.12f;
            cloth_collider_id id{};
            EXPECT_EQ(cloth_collider_create_capsule(world, &d, 0.08f, 0.3f, &id), CLOTH_OK);
        }
        cloth_collider_desc d = cloth_default_collider_desc();
        d.local_position[0] = 0.5f;
        d.local_position[1] = -1.1f;
        d.local_position[2] = 0.1f;
        cloth_collider_id id{};
        EXPECT_EQ(cloth_collider_create_sphere(world, &d, 0.25f, &id), CLOTH_OK);
        if (!record) api::find_world(world)->find_cloth(cloth)->contact().size_record(0);
    }
    ~KickedCloth() { EXPECT_EQ(cloth_world_destroy(world), CLOTH_OK); }
    // The legs swing forward and back.
    float swing(int frame) const {
        return amplitude * std::sin(omega * static_cast<float>(frame + 1) * kFrame);
    }
    void step(int frame) {
        const float position[3] = {0.0f, 0.0f, swing(frame)};
        const float rotation[4] = {0.0f, 0.0f, 0.0f, 1.0f};
        EXPECT_EQ(cloth_body_set_pose(legs, position, rotation), CLOTH_OK);
        EXPECT_EQ(cloth_step(world, kFrame), CLOTH_OK) << cloth_get_last_error();
    }
    std::vector<float> positions() const {
        std::vector<float> x(3 * kSide * kSide);
        EXPECT_EQ(cloth_read_positions(cloth, x.data(), static_cast<uint32_t>(x.size())), CLOTH_OK);
        return x;
    }
    // How far the deepest particle is inside a leg or the sphere after
    // `frame` (0: none is), by the shapes' own distances.
    float deepest(int frame) const {
        const std::vector<float> x = positions();
        const float z = -0.12f + swing(frame);
        float deepest = 0;
        for (size_t i = 0; i < x.size(); i += 3) {
            const Eigen::Vector3f p(x[i], x[i + 1], x[i + 2]);
            for (float leg : {0.3f, 0.7f}) {
                const float y = std::clamp(p.y(), -0.9f, -0.3f);  // the segment's nearest point
                deepest = std::max(deepest, 0.08f - (p - Eigen::Vector3f(leg, y, z)).norm());
            }
            deepest = std::max(deepest, 0.25f - (p - Eigen::Vector3f(0.5f, -1.1f, 0.1f)).norm());
        }
        return deepest;
    }
};

TEST(ColliderRecord, WhereTheLegsSwayTheRoundsTestingTheRecordTakeTheFullTestsBits) {
    KickedCloth recorded(true, 0.1f, 2.0f), full(false, 0.1f, 2.0f);
    uint32_t passes = 0;
    for (int frame = 0; frame < 240; ++frame) {
        recorded.step(frame);
        full.step(frame);
        const std::vector<float> a = recorded.positions(), b = full.positions();
        ASSERT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)), 0) << "frame " << frame;
        cloth_stats stats{};
        stats.struct_size = sizeof stats;
        ASSERT_EQ(cloth_get_stats(recorded.cloth, &stats), CLOTH_OK);
        passes = std::max(passes, stats.last_strain_passes);
    }
    // The scene runs rounds between passes at all: more passes than the
    // two a substep asks for.
    EXPECT_GT(passes, 4u);
}

TEST(ColliderRecord, WhereTheLegsKickNoFrameEndsWithAParticleDeeperInAColliderThanTheFullTestLeaves) {
    KickedCloth recorded(true), full(false);
    float deepest = 0, deepest_full = 0;
    for (int frame = 0; frame < 240; ++frame) {
        recorded.step(frame);
        full.step(frame);
        deepest = std::max(deepest, recorded.deepest(frame));
        deepest_full = std::max(deepest_full, full.deepest(frame));
    }
    // The record's course differs from the full test's, but no deeper in a collider.
    EXPECT_LE(deepest, deepest_full + 1e-3f) << "m inside a leg or the sphere at a frame's end";
}

TEST(StrainPassStats, AHangingClothRunsThePassesAskedForAndAStruckOneHitsTheCap) {
    KickedCloth cloth(true);
    cloth_stats stats{};
    stats.struct_size = sizeof stats;
    bool capped = false;
    for (int frame = 0; frame < 240; ++frame) {
        cloth.step(frame);
        ASSERT_EQ(cloth_get_stats(cloth.cloth, &stats), CLOTH_OK);
        ASSERT_GE(stats.last_strain_passes, stats.last_substeps) << "at least a pass a substep";
        capped = capped || stats.last_strain_pass_cap_hit == 1;
    }
    // The legs stopped: the passes hold it within their cap.
    for (int frame = 0; frame < 240; ++frame) EXPECT_EQ(cloth_step(cloth.world, kFrame), CLOTH_OK);
    ASSERT_EQ(cloth_get_stats(cloth.cloth, &stats), CLOTH_OK);
    EXPECT_EQ(stats.last_strain_pass_cap_hit, 0u) << stats.last_strain_passes << " passes";
    // Unpinned, it falls onto the sphere and its rim is flung round it.
    ASSERT_EQ(cloth_unpin(cloth.cloth, std::vector<uint32_t>{0}.data(), 1), CLOTH_OK);
    std::vector<uint32_t> top;
    for (uint32_t c = 0; c < kSide; ++c) top.push_back(c);
    ASSERT_EQ(cloth_unpin(cloth.cloth, top.data(), kSide), CLOTH_OK);
    for (int frame = 0; frame < 120; ++frame) {
        cloth.step(frame);
        ASSERT_EQ(cloth_get_stats(cloth.cloth, &stats), CLOTH_OK);
        capped = capped || stats.last_strain_pass_cap_hit == 1;
    }
    EXPECT_TRUE(capped) << "kicked or struck, some substep's passes stop at their cap";
    // A caller of 1.12 gets its fields and nothing past them.
    cloth_stats old{};
    std::memset(&old, 0xAB, sizeof old);
    old.struct_size = offsetof(cloth_stats, last_strain_passes);
    ASSERT_EQ(cloth_get_stats(cloth.cloth, &old), CLOTH_OK);
    EXPECT_EQ(old.last_strain_passes, 0xABABABABu) << "untouched past 1.12's size";
}

}  // namespace
}  // namespace cloth
