// Self-collision is off and allocates nothing until enabled, and bad settings change nothing.
//
// (cloth.h section "Self-collision".) Freed when disabled; every bad input
// rejected with the checks of support/contract.h (its code, the last error,
// the log, the cloth's whole state and the world's memory unchanged), and a
// twin world stepped alongside stays bit-identical; results are the same
// bits for every worker count; the frame profile shows its stages.
#include <cloth/cloth.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "support/bits_hash.h"
#include "support/contract.h"
#include "support/contract_gtest.h"
#include "support/counting_allocator.h"

namespace {

// A world with one 16x16 cloth hanging from two corners, folding as it swings.
struct ClothWorld {
    cloth_test::CountingAllocator host;
    cloth_world_id world{};
    cloth_fabric_id fabric{};
    cloth_id cloth{};

    ClothWorld() {
        const cloth_world_desc wd = host.world_desc();
        EXPECT_EQ(cloth_world_create(&wd, &world), CLOTH_OK);
        cloth_grid_desc gd = cloth_default_grid_desc();
        gd.columns = gd.rows = 16;
        gd.v[1] = 0;
        gd.v[2] = 1;  // horizontal: it falls and folds about its pins
        EXPECT_EQ(cloth_fabric_create_grid(world, &gd, &fabric), CLOTH_OK);
        cloth_desc cd = cloth_default_desc();
        cd.fabric = fabric;
        cd.solver.substeps = 4;
        EXPECT_EQ(cloth_create(world, &cd, &cloth), CLOTH_OK);
        const uint32_t pins[] = {0, 15};
        EXPECT_EQ(cloth_pin(cloth, pins, 2), CLOTH_OK);
    }
    ~ClothWorld() {
        EXPECT_EQ(cloth_world_destroy(world), CLOTH_OK);
        cloth_test::ExpectAllReturned(host);
    }
    cloth_test::Watch watch() const { return {world, {cloth}, {}, &host, {}}; }
};

TEST(SelfCollisionApi, OffByDefaultAllocatesNothingUntilEnabledAndFreesWhenDisabled) {
    ClothWorld w;
    cloth_self_collision_desc d{};
    ASSERT_EQ(cloth_get_self_collision(w.cloth, &d), CLOTH_OK);
    EXPECT_FALSE(d.enabled) << "off by default";
    const size_t before = w.host.live_bytes();
    ASSERT_EQ(cloth_step(w.world, 1.0f / 60.0f), CLOTH_OK);
    EXPECT_EQ(w.host.live_bytes(), before) << "a cloth without self-collision allocates none of it";

    d = cloth_default_self_collision_desc();
    d.enabled = true;
    d.thickness = 0.05f;
    d.friction = 0.3f;
    ASSERT_EQ(cloth_set_self_collision(w.cloth, &d), CLOTH_OK);
    const size_t enabled = w.host.live_bytes();
    EXPECT_GT(enabled, before);
    for (int i = 0; i < 5; ++i) ASSERT_EQ(cloth_step(w.world, 1.0f / 60.0f), CLOTH_OK);
    EXPECT_EQ(w.host.live_bytes(), enabled) << "a step allocates nothing";
    cloth_self_collision_desc back{};
    ASSERT_EQ(cloth_get_self_collision(w.cloth, &back), CLOTH_OK);
    EXPECT_TRUE(back.enabled);
    EXPECT_EQ(back.thickness, 0.05f);
    EXPECT_EQ(back.friction, 0.3f);
    cloth_self_collision_stats stats{};
    stats.struct_size = sizeof stats;
    ASSERT_EQ(cloth_get_self_collision_stats(w.cloth, &stats), CLOTH_OK);
    EXPECT_EQ(stats.regions, 4u) << "a 16x16 grid has four 8x8 regions";
    EXPECT_GE(stats.passes, 1u);

    d.enabled = false;
    ASSERT_EQ(cloth_set_self_collision(w.cloth, &d), CLOTH_OK);
    EXPECT_EQ(w.host.live_bytes(), before) << "disabling frees it";
    ASSERT_EQ(cloth_get_self_collision_stats(w.cloth, &stats), CLOTH_OK);
    EXPECT_EQ(stats.regions, 0u);
}

TEST(SelfCollisionApi, BadInputIsRejectedWithItsCodeAndChangesNothing) {
    ClothWorld w, twin;
    cloth_self_collision_desc good = cloth_default_self_collision_desc();
    good.enabled = true;
    good.thickness = 0.04f;
    ASSERT_EQ(cloth_set_self_collision(w.cloth, &good), CLOTH_OK);
    ASSERT_EQ(cloth_set_self_collision(twin.cloth, &good), CLOTH_OK);
    cloth_self_collision_stats stats{};
    cloth_test::Watch watch = w.watch();
    watch.outputs = {{&stats, sizeof stats, "the stats"}};

    auto expect_rejected = [&](cloth_result expected, cloth_id id, const cloth_self_collision_desc* desc,
                               const char* what) {
        cloth_test::ExpectRejected(
            watch, w.host, expected, what, [&] { return cloth_set_self_collision(id, desc); },
            id.index1 == 0 ? cloth_test::Logged::kMaybe : cloth_test::Logged::kYes);
    };
    const float nan = std::numeric_limits<float>::quiet_NaN();
    cloth_self_collision_desc d = good;
    expect_rejected(CLOTH_ERROR_NULL_POINTER, w.cloth, nullptr, "null desc");
    expect_rejected(CLOTH_ERROR_INVALID_HANDLE, cloth_id{}, &good, "null cloth");
    d.internal_cookie = 0;
    expect_rejected(CLOTH_ERROR_INVALID_DESC, w.cloth, &d, "uninitialised desc");
    d = good;
    d.struct_size = 4;
    expect_rejected(CLOTH_ERROR_INVALID_DESC, w.cloth, &d, "wrong struct_size");
    d = good;
    d.thickness = nan;
    expect_rejected(CLOTH_ERROR_NOT_FINITE, w.cloth, &d, "NaN thickness");
    d.thickness = 0;
    expect_rejected(CLOTH_ERROR_INVALID_VALUE, w.cloth, &d, "zero thickness");
    d.thickness = -0.01f;
    expect_rejected(CLOTH_ERROR_INVALID_VALUE, w.cloth, &d, "negative thickness");
    d.thickness = 0.5f;  // the 16x16 grid's mean edge is about 0.076 m
    expect_rejected(CLOTH_ERROR_INVALID_VALUE, w.cloth, &d, "thickness beyond two rest edges");
    d = good;
    d.friction = -1;
    expect_rejected(CLOTH_ERROR_INVALID_VALUE, w.cloth, &d, "negative friction");
    d.friction = std::numeric_limits<float>::infinity();
    expect_rejected(CLOTH_ERROR_NOT_FINITE, w.cloth, &d, "infinite friction");
    d = good;
    d.passes = 0;
    expect_rejected(CLOTH_ERROR_INVALID_VALUE, w.cloth, &d, "zero passes");
    d.passes = 17;
    expect_rejected(CLOTH_ERROR_INVALID_VALUE, w.cloth, &d, "too many passes");

    cloth_test::ExpectRejected(watch, w.host, CLOTH_ERROR_NULL_POINTER, "cloth_get_self_collision(NULL)",
                               [&] { return cloth_get_self_collision(w.cloth, nullptr); });
    cloth_test::ExpectRejected(watch, w.host, CLOTH_ERROR_NULL_POINTER,
                               "cloth_get_self_collision_stats(NULL)",
                               [&] { return cloth_get_self_collision_stats(w.cloth, nullptr); });
    stats.struct_size = 3;
    cloth_test::ExpectRejected(watch, w.host, CLOTH_ERROR_INVALID_DESC, "stats of struct_size 3",
                               [&] { return cloth_get_self_collision_stats(w.cloth, &stats); });
    EXPECT_EQ(stats.contacts, 0u) << "nothing written";

    // Turning it off needs no valid values, only a valid desc.
    cloth_self_collision_desc off = cloth_default_self_collision_desc();
    off.thickness = nan;
    EXPECT_TRUE(cloth_test::SameFutureAsTwin(w.watch(), twin.watch(), 30))
        << "rejected calls left hidden state behind";
    EXPECT_EQ(cloth_set_self_collision(w.cloth, &off), CLOTH_OK);
}

}  // namespace

namespace {

// A 24x24 curtain (three particle groups) lowered onto itself by its top
// row with self-collision on; hash of positions and velocities after 40
// steps, and the number of contacts seen.
uint64_t curtain_hash(uint32_t workers, uint32_t& contacts_seen) {
    cloth_world_desc wd = cloth_default_world_desc();
    wd.worker_count = workers;
    cloth_world_id world{};
    EXPECT_EQ(cloth_world_create(&wd, &world), CLOTH_OK);
    cloth_grid_desc gd = cloth_default_grid_desc();
    gd.columns = gd.rows = 24;
    gd.origin[1] = 1.0f;
    gd.origin[2] = 0.0f;
    cloth_fabric_id fabric{};
    EXPECT_EQ(cloth_fabric_create_grid(world, &gd, &fabric), CLOTH_OK);
    cloth_desc cd = cloth_default_desc();
    cd.fabric = fabric;
    cd.solver.kind = CLOTH_SOLVER_JACOBI;  // the soft fold this test was built on (the default holds strain)
    cd.solver.substeps = 4;
    cd.structural.stiffness = cd.shear.stiffness = 200.0f;
    std::vector<float> start(3 * 576);
    for (uint32_t i = 0; i < 576; ++i) {
        start[3 * i] = static_cast<float>(i % 24) / 23.0f;
        start[3 * i + 1] = 1.0f - static_cast<float>(i / 24) / 23.0f;
        start[3 * i + 2] = 0.04f * std::sin(static_cast<float>(i / 24));
    }
    cd.initial_positions = start.data();
    cloth_id cloth{};
    EXPECT_EQ(cloth_create(world, &cd, &cloth), CLOTH_OK);
    cloth_self_collision_desc sd = cloth_default_self_collision_desc();
    sd.enabled = true;
    sd.thickness = 0.035f;
    sd.friction = 0.2f;
    EXPECT_EQ(cloth_set_self_collision(cloth, &sd), CLOTH_OK);
    uint32_t top[24];
    for (uint32_t i = 0; i < 24; ++i) top[i] = i;
    EXPECT_EQ(cloth_pin(cloth, top, 24), CLOTH_OK);
    contacts_seen = 0;
    for (int step = 0; step < 40; ++step) {
        std::vector<float> targets(3 * 24);
        for (uint32_t i = 0; i < 24; ++i) {
            targets[3 * i] = start[3 * i];
            targets[3 * i + 1] = 1.0f - 0.02f * static_cast<float>(step + 1);
            targets[3 * i + 2] = start[3 * i + 2];
        }
        EXPECT_EQ(cloth_set_pin_targets(cloth, top, targets.data(), 24), CLOTH_OK);
        EXPECT_EQ(cloth_step(world, 1.0f / 60.0f), CLOTH_OK);
        cloth_self_collision_stats stats{};
        stats.struct_size = sizeof stats;
        EXPECT_EQ(cloth_get_self_collision_stats(cloth, &stats), CLOTH_OK);
        contacts_seen += stats.contacts;
    }
    uint64_t hash = cloth_test::kBitsHashStart;
    std::vector<float> values(3 * 576);
    EXPECT_EQ(cloth_read_positions(cloth, values.data(), 3 * 576), CLOTH_OK);
    hash = cloth_test::hash_bits(hash, values.data(), values.size() * sizeof(float));
    EXPECT_EQ(cloth_read_velocities(cloth, values.data(), 3 * 576), CLOTH_OK);
    hash = cloth_test::hash_bits(hash, values.data(), values.size() * sizeof(float));
    cloth_world_destroy(world);
    return hash;
}

TEST(SelfCollisionApi, ResultsAreBitIdenticalForEveryWorkerCount) {
    uint32_t contacts = 0;
    const uint64_t reference = curtain_hash(0, contacts);
    EXPECT_GT(contacts, 0u) << "the curtain must fold onto itself for the test to mean anything";
    for (uint32_t workers : {1u, 2u, 3u}) {
        uint32_t c = 0;
        EXPECT_EQ(curtain_hash(workers, c), reference) << workers << " workers";
        EXPECT_EQ(c, contacts);
    }
}

}  // namespace

namespace {

TEST(SelfCollisionApi, FrameProfileShowsTheSelfCollisionStagesOnlyWhenEnabled) {
    ClothWorld w;  // 16x16, 4 substeps, serial: one particle group
    ASSERT_EQ(cloth_world_set_profiling(w.world, 1024), CLOTH_OK);
    ASSERT_EQ(cloth_step(w.world, 1.0f / 60.0f), CLOTH_OK);
    cloth_frame_profile profile{};
    profile.struct_size = sizeof profile;
    ASSERT_EQ(cloth_world_get_frame_profile(w.world, &profile), CLOTH_OK);
    for (int stage = CLOTH_STAGE_SELF_COLLISION; stage <= CLOTH_STAGE_SELF_RESPOND; ++stage) {
        EXPECT_EQ(profile.stage_tasks[stage], 0u)
            << "off adds no pass: " << cloth_stage_name(cloth_stage(stage));
    }
    cloth_self_collision_desc d = cloth_default_self_collision_desc();
    d.enabled = true;
    d.thickness = 0.05f;
    ASSERT_EQ(cloth_set_self_collision(w.cloth, &d), CLOTH_OK);
    ASSERT_EQ(cloth_step(w.world, 1.0f / 60.0f), CLOTH_OK);
    ASSERT_EQ(cloth_world_get_frame_profile(w.world, &profile), CLOTH_OK);
    EXPECT_EQ(profile.stage_tasks[CLOTH_STAGE_SELF_COLLISION], 4u) << "one group, four substeps";
    EXPECT_EQ(profile.stage_tasks[CLOTH_STAGE_SELF_SORT], 4u);
    EXPECT_EQ(profile.stage_tasks[CLOTH_STAGE_SELF_CONTACTS], 4u);
    EXPECT_GE(profile.stage_tasks[CLOTH_STAGE_SELF_PROJECT], 4u);
    EXPECT_EQ(profile.stage_tasks[CLOTH_STAGE_SELF_RESPOND], 4u);
    EXPECT_STREQ(cloth_stage_name(CLOTH_STAGE_SELF_COLLISION), "self_collision");
    EXPECT_STREQ(cloth_stage_name(CLOTH_STAGE_SELF_SORT), "self_sort");
    EXPECT_STREQ(cloth_stage_name(CLOTH_STAGE_SELF_CONTACTS), "self_contacts");
    EXPECT_STREQ(cloth_stage_name(CLOTH_STAGE_SELF_PROJECT), "self_project");
    EXPECT_STREQ(cloth_stage_name(CLOTH_STAGE_SELF_RESPOND), "self_respond");
}

}  // namespace

namespace {

// Max distance and backstop are promises after every step, self-collision
// or not: a 16x16 sheet whose host skin is folded in two, the upper layer
// 6 mm above the lower, self-collision at 1 cm (so it pushes the layers
// apart) and every particle at most 1 mm from its skinned position. After
// every step each particle is within it; with the self-collision after
// the skin's constraints it ended 2 mm out.
TEST(SelfCollisionApi, ASkinnedClothWithSelfCollisionStillKeepsItsMaxDistances) {
    ClothWorld w;
    const uint32_t none[] = {0, 15};
    ASSERT_EQ(cloth_unpin(w.cloth, none, 2), CLOTH_OK);
    constexpr uint32_t kSide = 16, kCount = kSide * kSide;
    std::vector<float> skinned(3 * kCount), normals(3 * kCount, 0.0f), reach(kCount, 0.001f);
    for (uint32_t i = 0; i < kCount; ++i) {
        const uint32_t r = i / kSide, c = i % kSide;
        const uint32_t folded =
            r < kSide / 2 ? r : kSide - 1 - r;  // rows past the middle lie back over the first
        skinned[3 * i] = static_cast<float>(c) / (kSide - 1);
        skinned[3 * i + 1] = r < kSide / 2 ? 0.0f : 0.006f;
        skinned[3 * i + 2] = static_cast<float>(folded) / (kSide - 1);
        normals[3 * i + 1] = 1.0f;
    }
    ASSERT_EQ(cloth_set_skinned_positions(w.cloth, skinned.data(), normals.data(), kCount), CLOTH_OK);
    ASSERT_EQ(cloth_set_max_distances(w.cloth, reach.data(), kCount), CLOTH_OK);
    std::vector<uint32_t> all(kCount);
    for (uint32_t i = 0; i < kCount; ++i) all[i] = i;
    ASSERT_EQ(cloth_set_positions(w.cloth, all.data(), skinned.data(), kCount), CLOTH_OK);
    cloth_self_collision_desc d = cloth_default_self_collision_desc();
    d.enabled = true;
    d.thickness = 0.01f;
    ASSERT_EQ(cloth_set_self_collision(w.cloth, &d), CLOTH_OK);
    uint32_t contacts = 0;
    float worst = 0.0f;
    for (int frame = 0; frame < 10; ++frame) {
        ASSERT_EQ(cloth_set_skinned_positions(w.cloth, skinned.data(), normals.data(), kCount), CLOTH_OK);
        ASSERT_EQ(cloth_step(w.world, 1.0f / 60.0f), CLOTH_OK) << cloth_get_last_error();
        cloth_self_collision_stats stats{};
        stats.struct_size = sizeof stats;
        ASSERT_EQ(cloth_get_self_collision_stats(w.cloth, &stats), CLOTH_OK);
        contacts += stats.contacts;
        std::vector<float> x(3 * kCount), s(3 * kCount);
        ASSERT_EQ(cloth_read_positions(w.cloth, x.data(), 3 * kCount), CLOTH_OK);
        ASSERT_EQ(cloth_read_skinned_positions(w.cloth, s.data(), nullptr, 3 * kCount), CLOTH_OK);
        for (uint32_t i = 0; i < kCount; ++i) {
            const float dx = x[3 * i] - s[3 * i], dy = x[3 * i + 1] - s[3 * i + 1],
                        dz = x[3 * i + 2] - s[3 * i + 2];
            worst = std::max(worst, std::sqrt(dx * dx + dy * dy + dz * dz) - reach[i]);
        }
    }
    EXPECT_GT(contacts, 0u) << "the layers must touch for the test to mean anything";
    EXPECT_LE(worst, 1e-5f) << "a particle ended a step past its max distance";
}

}  // namespace

namespace {

// Pairs of particles more than 3 grid steps apart on a side x side grid
// closer than `distance`.
uint32_t far_pairs_within(const std::vector<float>& x, uint32_t side, float distance) {
    uint32_t close = 0;
    for (uint32_t i = 0; i < side * side; ++i) {
        for (uint32_t j = i + 1; j < side * side; ++j) {
            const int dc = std::abs(static_cast<int>(i % side) - static_cast<int>(j % side));
            const int dr = std::abs(static_cast<int>(i / side) - static_cast<int>(j / side));
            if (std::max(dc, dr) <= 3) continue;
            const float dx = x[3 * i] - x[3 * j], dy = x[3 * i + 1] - x[3 * j + 1],
                        dz = x[3 * i + 2] - x[3 * j + 2];
            close += dx * dx + dy * dy + dz * dz < distance * distance;
        }
    }
    return close;
}

// Self-collision's pushes part a cloth's layers by stretching the springs
// beside them; the strain limiter's passes take that stretch back, and
// the contacts are projected again after each pass so that the passes do
// not pull the layers together. A 24x24, 1 m default curtain hanging from
// its top corners, which close to a third of its width over two seconds
// while gusts blow into it, folds onto itself (self_collision --scene
// wind). Over 240 steps its max strain stays within 0.3 and no two
// particles more than 3 grid steps apart end a step within half the
// thickness. Self-collision after the limiter's passes reached 0.57
// strain; before them without the projections between, such a pair
// ended 4 of the steps.
TEST(SelfCollisionApi, AFoldingCurtainKeepsItsLayersApartWithoutStretching) {
    constexpr uint32_t kSide = 24, kCount = kSide * kSide;
    cloth_world_desc wd = cloth_default_world_desc();
    cloth_world_id world{};
    ASSERT_EQ(cloth_world_create(&wd, &world), CLOTH_OK);
    cloth_grid_desc gd = cloth_default_grid_desc();
    gd.columns = gd.rows = kSide;
    gd.origin[1] = 1.6f;
    cloth_fabric_id fabric{};
    ASSERT_EQ(cloth_fabric_create_grid(world, &gd, &fabric), CLOTH_OK);
    cloth_desc cd = cloth_default_desc();
    cd.fabric = fabric;
    cd.structural = {300.0f, 0.1f};
    cd.shear = {60.0f, 0.05f};
    cd.bend = {2.0f, 0.01f};
    cd.solver.substeps = 4;
    cloth_id cloth{};
    ASSERT_EQ(cloth_create(world, &cd, &cloth), CLOTH_OK);
    const float thickness = 0.8f / static_cast<float>(kSide - 1);
    cloth_self_collision_desc sd = cloth_default_self_collision_desc();
    sd.enabled = true;
    sd.thickness = thickness;
    sd.friction = 0.3f;
    ASSERT_EQ(cloth_set_self_collision(cloth, &sd), CLOTH_OK);
    const uint32_t corners[2] = {0, kSide - 1};
    ASSERT_EQ(cloth_pin(cloth, corners, 2), CLOTH_OK);
    float worst = 0.0f;
    uint32_t contacts = 0, frames_close = 0, most_close = 0;
    for (int frame = 0; frame < 240; ++frame) {
        const float t = static_cast<float>(frame) / 60.0f;
        const float closing = std::min(1.0f, t / 2.0f) * 0.33f;
        const float targets[6] = {closing, 1.6f, 0.0f, 1.0f - closing, 1.6f, 0.0f};
        ASSERT_EQ(cloth_set_pin_targets(cloth, corners, targets, 2), CLOTH_OK);
        const float gust = 6.0f + 3.0f * std::sin(1.3f * t) + 2.0f * std::sin(3.1f * t);
        const float air[3] = {1.5f * std::sin(0.9f * t), 0.0f, -gust};
        ASSERT_EQ(cloth_set_wind(cloth, air), CLOTH_OK);
        ASSERT_EQ(cloth_step(world, 1.0f / 60.0f), CLOTH_OK) << cloth_get_last_error();
        cloth_stats stats{};
        stats.struct_size = sizeof stats;
        ASSERT_EQ(cloth_get_stats(cloth, &stats), CLOTH_OK);
        worst = std::max(worst, stats.max_strain);
        cloth_self_collision_stats self{};
        self.struct_size = sizeof self;
        ASSERT_EQ(cloth_get_self_collision_stats(cloth, &self), CLOTH_OK);
        contacts += self.contacts;
        std::vector<float> x(3 * kCount);
        ASSERT_EQ(cloth_read_positions(cloth, x.data(), 3 * kCount), CLOTH_OK);
        const uint32_t close = far_pairs_within(x, kSide, 0.5f * thickness);
        frames_close += close > 0;
        most_close = std::max(most_close, close);
    }
    EXPECT_GT(contacts, 0u) << "the curtain must fold onto itself for the test to mean anything";
    EXPECT_LE(worst, 0.3f) << "the pushes that part the layers stretched the curtain";
    EXPECT_EQ(frames_close, 0u) << "steps ended with far-apart particles within half the thickness, up to "
                                << most_close << " pairs";
    cloth_world_destroy(world);
}

}  // namespace
