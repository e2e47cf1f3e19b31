// The collision stage culls a particle range against a collider by the
// range's bounds before any shape query (range_is_clear). The culling must
// be exact: wherever it says a range is clear, the full per-particle stage
// changes no bit of that range and finds no contact. Checked on random
// ranges of a small cloth patch at heights from touching to well clear of
// a bumpy height field, a box, a capsule and a moving sphere, so that both
// answers occur; and on small ranges beside a long capsule and a box, where
// only the shapes' own distance culls.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "collide/colliders.h"
#include "test_support.h"

namespace cloth {
namespace {

using cloth::testing::heap;

struct Patch {
    Vec3Soa x{heap()}, v{heap()};
    std::vector<float> kinematic;
};

// 64 particles in an 8x8 patch of `size` m around `centre`, tilted and
// moving at random; one in eight kinematic.
Patch random_patch(std::mt19937& rng, const Vec3& centre, float size, float speed) {
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    Patch p;
    p.x.resize(64);
    p.v.resize(64);
    p.kinematic.assign(64, 0.0f);
    const Vec3 tilt(u(rng), u(rng), u(rng));
    for (uint32_t i = 0; i < 64; ++i) {
        const float a = size * (static_cast<float>(i % 8) / 7.0f - 0.5f);
        const float b = size * (static_cast<float>(i / 8) / 7.0f - 0.5f);
        p.x.set(i, centre + Vec3(a, 0.2f * a * tilt.x() + 0.2f * b * tilt.z(), b));
        p.v.set(i, Vec3(u(rng), u(rng), u(rng)) * speed);
        p.kinematic[i] = i % 8 == 3 ? 1.0f : 0.0f;
    }
    return p;
}

bool same_bits(const Vec3Soa& a, const Vec3Soa& b) {
    for (const auto& [p, q] : {std::pair{&a.x, &b.x}, std::pair{&a.y, &b.y}, std::pair{&a.z, &b.z}}) {
        if (std::memcmp(p->data(), q->data(), p->size() * sizeof(float)) != 0) return false;
    }
    return true;
}

TEST(CollisionCulling, WhereARangeIsCulledTheFullStageChangesNoBitOfIt) {
    // A 12 x 10 height field of 0.5 m cells with bumps of up to 0.4 m.
    std::vector<float> heights(12 * 10);
    for (uint32_t r = 0; r < 10; ++r) {
        for (uint32_t c = 0; c < 12; ++c)
            heights[r * 12 + c] = 0.2f * std::sin(1.3f * c) * std::cos(0.9f * r) + 0.2f;
    }
    Shape field(heap()), box(heap()), capsule(heap()), sphere(heap()), limb(heap());
    ASSERT_TRUE(build_heightfield(12, 10, 0.5f, 0.5f, heights.data(), field).ok());
    ASSERT_TRUE(build_box(Vec3(0.6f, 0.3f, 0.4f), box).ok());
    ASSERT_TRUE(build_capsule(0.05f, 0.8f, capsule).ok());
    ASSERT_TRUE(build_sphere(0.3f, sphere).ok());
    ASSERT_TRUE(build_tapered_capsule(0.25f, 0.1f, 0.5f, limb).ok());

    struct Case {
        const char* name;
        MovingCollider collider;
    };
    const Quat turned(Eigen::AngleAxisf(0.4f, Vec3(0.3f, 1.0f, 0.2f).normalized()));
    std::vector<Case> cases = {
        {"height field",
         {&field,
          {Vec3(0.1f, -0.05f, 0.2f), Quat::Identity()},
          {Vec3(0.1f, -0.05f, 0.2f), Quat::Identity()}}},
        {"box", {&box, {Vec3(2.5f, 1.0f, 2.0f), turned}, {Vec3(2.5f, 1.0f, 2.0f), turned}}},
        {"capsule",
         {&capsule, {Vec3(2.0f, 1.2f, 2.5f), Quat::Identity()}, {Vec3(2.0f, 1.2f, 2.5f), Quat::Identity()}}},
        {"moving sphere",
         {&sphere, {Vec3(2.0f, 1.0f, 2.0f), Quat::Identity()}, {Vec3(2.4f, 1.1f, 2.2f), turned}}},
        {"moving tapered capsule",
         {&limb, {Vec3(2.5f, 1.0f, 2.5f), turned}, {Vec3(2.2f, 1.2f, 2.8f), Quat::Identity()}}},
    };
    CollisionParams params;
    const float h = 1.0f / 120.0f;
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> where(0.0f, 5.0f), height(-0.2f, 2.5f), size(0.05f, 1.5f);
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        int culled = 0, run = 0;
        for (int trial = 0; trial < 400; ++trial) {
            Patch patch = random_patch(rng, Vec3(where(rng), height(rng), where(rng)), size(rng), 3.0f);
            const uint32_t begin = trial % 5, end = 64 - trial % 7;
            const bool clear = range_is_clear(
                c.collider, params, range_bounds(h, patch.kinematic.data(), begin, end, patch.x, patch.v));
            Patch full = patch;
            const uint32_t contacts =
                collide_particles(c.collider, params, h, full.kinematic.data(), begin, end, full.x, full.v);
            if (clear) {
                ++culled;
                ASSERT_EQ(contacts, 0u) << "trial " << trial;
                ASSERT_TRUE(same_bits(full.x, patch.x) && same_bits(full.v, patch.v)) << "trial " << trial;
            } else {
                ++run;
            }
        }
        // Both answers occur, so the check above is not vacuous.
        EXPECT_GT(culled, 20);
        EXPECT_GT(run, 20);
    }
}

// Small ranges (a chunk of the stage) beside a long capsule and a turned,
// moving box, all inside the shapes' bounding spheres, where only the
// shapes' own distance can cull: where it does, the full stage changes no
// bit and finds no contact, and it culls most ranges that pass clear.
TEST(CollisionCulling, BesideALongShapeARangeIsCulledByTheShapesDistance) {
    Shape capsule(heap()), box(heap());
    ASSERT_TRUE(build_capsule(0.04f, 1.2f, capsule).ok());
    ASSERT_TRUE(build_box(Vec3(1.0f, 0.3f, 0.6f), box).ok());
    const Quat turned(Eigen::AngleAxisf(0.3f, Vec3(0.2f, 1.0f, 0.1f).normalized()));
    const Quat turned_on(Eigen::AngleAxisf(0.35f, Vec3(0.2f, 1.0f, 0.1f).normalized()));
    struct Case {
        MovingCollider collider;
        Vec3 spread;  // ranges are centred within this of the shape's centre
    };
    const Case cases[] = {
        {{&capsule, {Vec3(0, 0, 0), Quat::Identity()}, {Vec3(0, 0, 0), Quat::Identity()}},
         Vec3(0.2f, 1.0f, 0.2f)},
        {{&box, {Vec3(0, 0, 0), turned}, {Vec3(0.05f, 0.01f, 0.02f), turned_on}}, Vec3(1.2f, 0.6f, 0.9f)},
    };
    CollisionParams params;
    const float h = 1.0f / 120.0f;
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> where(-1.0f, 1.0f), size(0.01f, 0.15f);
    for (const Case& c : cases) {
        const MovingCollider& collider = c.collider;
        SCOPED_TRACE(collider.shape == &capsule ? "capsule" : "box");
        int culled = 0, touched = 0, clear_but_run = 0;
        for (int trial = 0; trial < 400; ++trial) {
            const Vec3 centre = Vec3(where(rng), where(rng), where(rng)).cwiseProduct(c.spread);
            Patch patch = random_patch(rng, centre, size(rng), 0.5f);
            const uint32_t begin = 8 * (trial % 8), end = begin + 8;
            const bool clear = range_is_clear(
                collider, params, range_bounds(h, patch.kinematic.data(), begin, end, patch.x, patch.v));
            Patch full = patch;
            const uint32_t contacts =
                collide_particles(collider, params, h, full.kinematic.data(), begin, end, full.x, full.v);
            const bool unchanged = same_bits(full.x, patch.x) && same_bits(full.v, patch.v);
            if (clear) {
                ++culled;
                ASSERT_EQ(contacts, 0u) << "trial " << trial;
                ASSERT_TRUE(unchanged) << "trial " << trial;
            } else if (contacts > 0) {
                ++touched;
            } else {
                ++clear_but_run;
            }
        }
        EXPECT_GT(culled, 100);
        EXPECT_GT(touched, 5);
        EXPECT_LT(clear_but_run, culled);
    }
}

// A range carried along with a fast collider (a flag beside its pole at
// 30 m/s) sweeps 25 cm a substep in the world but hardly moves in the
// collider's frame: taking its start and end boxes into that frame
// separately, ranges a few centimetres clear of the pole are culled, and
// exactly (the full stage changes no bit where they are).
TEST(CollisionCulling, ARangeCarriedAlongWithAFastColliderIsCulledInItsFrame) {
    Shape capsule(heap());
    ASSERT_TRUE(build_capsule(0.035f, 0.75f, capsule).ok());
    const float h = 1.0f / 120.0f;
    const Vec3 velocity(30.0f, 0.0f, 0.0f);
    const MovingCollider pole(&capsule, {Vec3(0, 0, 0), Quat::Identity()}, {velocity * h, Quat::Identity()});
    CollisionParams params;
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f), distance(0.06f, 0.6f), angle(0.0f, 6.2832f);
    int far = 0, far_culled = 0;
    for (int trial = 0; trial < 400; ++trial) {
        // Eight particles in a row 8 cm long, its middle `d` from the
        // pole's axis, moving with the pole (give or take 0.5 m/s).
        const float d = distance(rng), a = angle(rng);
        const Vec3 middle = pole.end.position + Vec3(d * std::cos(a), 0.5f * u(rng), d * std::sin(a));
        const Vec3 along = Vec3(u(rng), 0.3f * u(rng), u(rng)).normalized();
        Patch patch;
        patch.x.resize(8);
        patch.v.resize(8);
        patch.kinematic.assign(8, 0.0f);
        for (uint32_t i = 0; i < 8; ++i) {
            patch.x.set(i, middle + along * (0.01f * (static_cast<float>(i) - 3.5f)));
            patch.v.set(i, velocity + 0.5f * Vec3(u(rng), u(rng), u(rng)));
        }
        const bool clear =
            range_is_clear(pole, params, range_bounds(h, patch.kinematic.data(), 0, 8, patch.x, patch.v));
        Patch full = patch;
        const uint32_t contacts =
            collide_particles(pole, params, h, full.kinematic.data(), 0, 8, full.x, full.v);
        if (clear) {
            ASSERT_EQ(contacts, 0u) << "trial " << trial;
            ASSERT_TRUE(same_bits(full.x, patch.x) && same_bits(full.v, patch.v)) << "trial " << trial;
        }
        if (d >= 0.12f) {
            ++far;
            far_culled += clear ? 1 : 0;
        }
    }
    ASSERT_GT(far, 200);
    EXPECT_GT(far_culled, far * 9 / 10)
        << "ranges 12 cm and more from the axis (8 cm and more clear of the pole)";
}

}  // namespace
}  // namespace cloth
