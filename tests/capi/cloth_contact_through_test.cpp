// Contact between two cloths (cloth.h section "Contact between cloths")
// checked against brute force (support/sheet_side.h): with the pair's
// contact on, no particle of either cloth ends a frame more than half the
// contact thickness through the other, where wind blows one hanging sheet
// into another (2 to 8 m/s) and where a sheet dropped from a metre falls
// onto a trampoline; and that pair stepped on 1, 2 and 4 workers ends in
// the same bits.
#include <cloth/cloth.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "support/bits_hash.h"
#include "support/counting_allocator.h"
#include "support/sheet_side.h"

namespace {

constexpr uint32_t kSide = 32;  // particles along each edge of each sheet
constexpr uint32_t kParticles = kSide * kSide;
constexpr float kThickness = 0.02f;  // m
constexpr float kFrame = 1.0f / 60.0f;
#ifdef CLOTH_SANITIZED_BUILD
// Sanitized builds run the brute force 10-50x slower: there the check
// looks at every tenth frame (the steps are all taken), and the wind runs
// at the speeds where no particle goes round the other sheet's border (a
// side followed every tenth frame misses the swing round it).
constexpr int kCheckEvery = 10;
constexpr int kShorter = 3;  // and the scenes run a third of their frames
#define CLOTH_WIND_SPEEDS 2, 4
#else
constexpr int kCheckEvery = 1;
constexpr int kShorter = 1;
#define CLOTH_WIND_SPEEDS 2, 4, 6, 8
#endif

// Two cloths of one world with contact between them, and what the
// brute-force check found over the frames stepped.
struct Pair {
    cloth_test::CountingAllocator host;
    cloth_world_id world{};
    cloth_id a{}, b{};
    std::vector<uint32_t> triangles_a, triangles_b;
    // Each particle's side of the other cloth at the start.
    std::vector<float> side_a, side_b;
    // The worst frame: the most particles through, of a and of b.
    int worst_frame = -1;
    uint32_t worst_a = 0, worst_b = 0;
    int frames_through = 0;  // frames with any particle through
    float deepest = 0;       // m, the farthest any particle was on the other side

    explicit Pair(uint32_t workers) {
        cloth_world_desc wd = host.world_desc();
        wd.worker_count = workers;
        EXPECT_EQ(cloth_world_create(&wd, &world), CLOTH_OK);
    }
    ~Pair() { EXPECT_EQ(cloth_world_destroy(world), CLOTH_OK); }

    // A kSide x kSide sheet from `origin` along `u` (columns) and `v` (rows).
    cloth_id sheet(const float origin[3], const float u[3], const float v[3],
                   std::vector<uint32_t>* triangles) {
        cloth_grid_desc gd = cloth_default_grid_desc();
        gd.columns = gd.rows = kSide;
        for (int k = 0; k < 3; ++k) gd.origin[k] = origin[k], gd.u[k] = u[k], gd.v[k] = v[k];
        cloth_fabric_id fabric{};
        EXPECT_EQ(cloth_fabric_create_grid(world, &gd, &fabric), CLOTH_OK) << cloth_get_last_error();
        uint32_t count = 0;
        EXPECT_EQ(cloth_fabric_get_triangle_count(fabric, &count), CLOTH_OK);
        triangles->resize(3 * count);
        EXPECT_EQ(cloth_fabric_read_triangles(fabric, triangles->data(), 3 * count), CLOTH_OK);
        cloth_desc cd = cloth_default_desc();
        cd.fabric = fabric;
        cloth_id id{};
        EXPECT_EQ(cloth_create(world, &cd, &id), CLOTH_OK) << cloth_get_last_error();
        return id;
    }
    void contact(bool on) {
        cloth_cloth_contact_desc d = cloth_default_cloth_contact_desc();
        d.enabled = on;
        d.thickness = kThickness;
        EXPECT_EQ(cloth_set_cloth_contact(a, b, &d), CLOTH_OK) << cloth_get_last_error();
    }
    static std::vector<float> positions(cloth_id c) {
        std::vector<float> x(3 * kParticles);
        EXPECT_EQ(cloth_read_positions(c, x.data(), 3 * kParticles), CLOTH_OK);
        return x;
    }
    // Each particle's side of the other sheet, before the first step.
    void take_sides() {
        const std::vector<float> x = positions(a), y = positions(b);
        side_a = cloth_test::sides_of_sheet(cloth_test::signed_distances_to_sheet(x, y, triangles_b));
        side_b = cloth_test::sides_of_sheet(cloth_test::signed_distances_to_sheet(y, x, triangles_a));
    }
    // The particles of each sheet more than half the thickness through the
    // other at the end of `frame`.
    void check(int frame) {
        const std::vector<float> x = positions(a), y = positions(b);
        const std::vector<float> to_b = cloth_test::signed_distances_to_sheet(x, y, triangles_b);
        const std::vector<float> to_a = cloth_test::signed_distances_to_sheet(y, x, triangles_a);
        const cloth_test::Through through_a = cloth_test::count_through(to_b, side_a, 0.5f * kThickness);
        const cloth_test::Through through_b = cloth_test::count_through(to_a, side_b, 0.5f * kThickness);
        // A particle that went round the other sheet's border is on its new side.
        cloth_test::follow_sides_round_the_border(to_b, side_a);
        cloth_test::follow_sides_round_the_border(to_a, side_b);
        deepest = std::max({deepest, through_a.deepest, through_b.deepest});
        frames_through += through_a.count + through_b.count > 0;
        if (through_a.count + through_b.count > worst_a + worst_b) {
            worst_frame = frame;
            worst_a = through_a.count;
            worst_b = through_b.count;
        }
    }
    // Steps `frames` frames, checking the ends of every kCheckEvery-th.
    void run(int frames) {
        take_sides();
        for (int frame = 0; frame < frames; ++frame) {
            ASSERT_EQ(cloth_step(world, kFrame), CLOTH_OK) << cloth_get_last_error();
            if ((frame + 1) % kCheckEvery == 0) check(frame);
        }
    }
    std::string report() const {
        char line[256];
        std::snprintf(
            line, sizeof line,
            "worst frame %d: %u of %u and %u of %u particles more than %.3g m through the other sheet; "
            "frames with any: %d; deepest %.3g m",
            worst_frame, worst_a, kParticles, worst_b, kParticles, 0.5f * kThickness, frames_through,
            deepest);
        return line;
    }
};

// Two 1 m x 1 m sheets hanging from their pinned top rows, parallel, one
// contact thickness apart along z; the wind (along +z) blows on the front
// one (`a`) only, the back one (`b`) in its lee, so that the front one is
// driven into the back one (with the same wind on both they move together,
// and no particle crosses at any of the speeds).
struct HangingPair : Pair {
    HangingPair(float wind_speed, uint32_t workers) : Pair(workers) {
        const float u[3] = {1.0f, 0.0f, 0.0f}, v[3] = {0.0f, -1.0f, 0.0f};
        const float front[3] = {0.0f, 1.0f, 0.0f}, back[3] = {0.0f, 1.0f, kThickness};
        a = sheet(front, u, v, &triangles_a);
        b = sheet(back, u, v, &triangles_b);
        std::vector<uint32_t> top(kSide);
        for (uint32_t c = 0; c < kSide; ++c) top[c] = c;
        EXPECT_EQ(cloth_pin(a, top.data(), kSide), CLOTH_OK);
        EXPECT_EQ(cloth_pin(b, top.data(), kSide), CLOTH_OK);
        const float wind[3] = {0.0f, 0.0f, wind_speed};
        EXPECT_EQ(cloth_set_wind(a, wind), CLOTH_OK);
        contact(true);
    }
};

// A free 0.5 m x 0.5 m sheet (`a`), level, 1 m above a 1 m x 1 m
// trampoline (`b`, its border pinned) and turned 30 degrees about the
// vertical to it, falls onto it: at 4.4 m/s, 7 cm a frame, more than three
// thicknesses.
struct DroppedPair : Pair {
    DroppedPair(bool with_contact, uint32_t workers) : Pair(workers) {
        const float c30 = 0.8660254f, s30 = 0.5f;
        const float u[3] = {0.5f * c30, 0.0f, 0.5f * s30}, v[3] = {-0.5f * s30, 0.0f, 0.5f * c30};
        // Centred over the trampoline's middle, (0.5, 0, 0.5).
        const float over[3] = {0.5f - 0.5f * (u[0] + v[0]), 1.0f, 0.5f - 0.5f * (u[2] + v[2])};
        const float uu[3] = {1.0f, 0.0f, 0.0f}, vv[3] = {0.0f, 0.0f, 1.0f}, corner[3] = {0.0f, 0.0f, 0.0f};
        a = sheet(over, u, v, &triangles_a);
        b = sheet(corner, uu, vv, &triangles_b);
        std::vector<uint32_t> border;
        for (uint32_t i = 0; i < kParticles; ++i) {
            const uint32_t r = i / kSide, c = i % kSide;
            if (r == 0 || c == 0 || r == kSide - 1 || c == kSide - 1) border.push_back(i);
        }
        EXPECT_EQ(cloth_pin(b, border.data(), static_cast<uint32_t>(border.size())), CLOTH_OK);
        contact(with_contact);
    }
};

class ClothContactInWind : public ::testing::TestWithParam<int> {};

// Wind of 2, 4, 6 and 8 m/s for 300 frames at 60 Hz (sanitized: 2 and 4
// m/s for 100 frames; 10 m/s:
// docs/measurements.md, "Contact between cloths inside the substeps").
TEST_P(ClothContactInWind, NoParticleEndsAFrameMoreThanHalfTheThicknessThroughTheOtherSheet) {
    HangingPair pair(static_cast<float>(GetParam()), 1);
    pair.run(300 / kShorter);
    std::printf("wind %d m/s: %s\n", GetParam(), pair.report().c_str());
    EXPECT_EQ(pair.worst_a + pair.worst_b, 0u) << "wind " << GetParam() << " m/s: " << pair.report();
}

INSTANTIATE_TEST_SUITE_P(WindSpeeds, ClothContactInWind, ::testing::Values(CLOTH_WIND_SPEEDS),
                         [](const ::testing::TestParamInfo<int>& info) {
                             return "wind_" + std::to_string(info.param) + "_m_s";
                         });

// The drop for 120 frames (2 s): with the contact no particle ends a frame
// through; without it the sheet falls through the trampoline, which the
// check sees (so it can fail).
TEST(ClothContactCrossing, ADroppedSheetEndsNoFrameThroughTheTrampolineItFallsOnto) {
    DroppedPair with(true, 1), without(false, 1);
    with.run(120);
    without.run(120);
    std::printf("dropped, contact on: %s\ndropped, contact off: %s\n", with.report().c_str(),
                without.report().c_str());
    EXPECT_EQ(with.worst_a + with.worst_b, 0u) << with.report();
    EXPECT_GT(without.worst_a, kParticles / 2)
        << "without the contact the sheet falls through: " << without.report();
}

// Positions and velocities of both cloths after `frames` frames.
uint64_t end_state_hash(Pair& pair, int frames) {
    for (int frame = 0; frame < frames; ++frame) EXPECT_EQ(cloth_step(pair.world, kFrame), CLOTH_OK);
    uint64_t hash = cloth_test::kBitsHashStart;
    std::vector<float> values(3 * kParticles);
    for (cloth_id c : {pair.a, pair.b}) {
        EXPECT_EQ(cloth_read_positions(c, values.data(), 3 * kParticles), CLOTH_OK);
        hash = cloth_test::hash_bits(hash, values.data(), values.size() * sizeof(float));
        EXPECT_EQ(cloth_read_velocities(c, values.data(), 3 * kParticles), CLOTH_OK);
        hash = cloth_test::hash_bits(hash, values.data(), values.size() * sizeof(float));
    }
    return hash;
}

// The drop (90 frames: through the impact) and the sheets in 8 m/s wind
// (120 frames) end in the same bits on 1, 2 and 4 workers.
TEST(ClothContactCrossing, ThePairEndsInTheSameBitsOnOneTwoAndFourWorkers) {
    uint64_t dropped[3], hanging[3];
    const uint32_t workers[3] = {1, 2, 4};
    for (int k = 0; k < 3; ++k) {
        DroppedPair drop(true, workers[k]);
        dropped[k] = end_state_hash(drop, 90 / kShorter);
        HangingPair wind(8.0f, workers[k]);
        hanging[k] = end_state_hash(wind, 120 / kShorter);
    }
    for (int k = 1; k < 3; ++k) {
        EXPECT_EQ(dropped[k], dropped[0]) << "the drop on " << workers[k] << " workers";
        EXPECT_EQ(hanging[k], hanging[0]) << "the sheets in wind on " << workers[k] << " workers";
    }
}

// The brute force itself, on a sheet whose signs are known: a flat sheet
// (normal +y) and the same sheet folded 90 degrees along its middle row.
TEST(SheetSide, SignedDistancesAreTheOffsetAlongTheSheetsNormalWithItsSign) {
    constexpr uint32_t n = 5;  // 5 x 5 vertices over 1 m x 1 m in the x-z plane, y = 0
    std::vector<float> flat;
    std::vector<uint32_t> triangles;
    for (uint32_t r = 0; r < n; ++r) {
        for (uint32_t c = 0; c < n; ++c) flat.insert(flat.end(), {0.25f * c, 0.0f, 0.25f * r});
    }
    for (uint32_t r = 0; r + 1 < n; ++r) {
        for (uint32_t c = 0; c + 1 < n; ++c) {
            const uint32_t i = r * n + c;  // wound so that the normals face +y
            triangles.insert(triangles.end(), {i, i + n, i + 1, i + 1, i + n, i + n + 1});
        }
    }
    const std::vector<float> points = {
        0.4f, 0.3f,   0.6f,   // above the inside: +0.3
        0.4f, -0.2f,  0.6f,   // below: -0.2
        0.5f, 0.1f,   0.5f,   // above a vertex: +0.1
        0.6f, -0.05f, 0.25f,  // below an edge: -0.05
        1.5f, 0.0f,   0.5f,   // beside the sheet in its plane: 0
        1.3f, 0.2f,   0.5f,   // above, beyond its border, leaning out 56 degrees: beside it, 0
        1.1f, 0.3f,   0.5f,   // above, beyond its border, leaning out 18 degrees: +0.3
        1.1f, -0.3f,  0.5f,   // the same below: -0.3
    };
    const std::vector<float> flat_distances = cloth_test::signed_distances_to_sheet(points, flat, triangles);
    const float expected[] = {0.3f, -0.2f, 0.1f, -0.05f, 0.0f, 0.0f, 0.3f, -0.3f};
    for (int k = 0; k < 8; ++k) EXPECT_NEAR(flat_distances[k], expected[k], 1e-6f) << "point " << k;
    const cloth_test::Through through =
        cloth_test::count_through(flat_distances, std::vector<float>(8, 1.0f), 0.1f);
    EXPECT_EQ(through.count, 2u) << "only the points 0.2 and 0.3 m below are more than 0.1 m through";
    EXPECT_NEAR(through.deepest, 0.3f, 1e-6f);
    // A point that goes round the border takes the side it comes back on;
    // one that crosses the inside keeps the side it started on.
    std::vector<float> sides(2, 1.0f);
    cloth_test::follow_sides_round_the_border({0.0f, -0.2f}, sides);  // beside it; through the inside
    EXPECT_EQ(sides, (std::vector<float>{0.0f, 1.0f}));
    cloth_test::follow_sides_round_the_border({-0.3f, -0.2f}, sides);  // back below it; still through
    EXPECT_EQ(sides, (std::vector<float>{-1.0f, 1.0f}));
    EXPECT_EQ(cloth_test::count_through({-0.3f, -0.2f}, sides, 0.1f).count, 1u)
        << "only the one through the inside";

    // Folded: the rows beyond z = 0.5 stood up along +y from the middle
    // row, so that half's normal faces -z.
    std::vector<float> folded = flat;
    for (uint32_t r = 3; r < n; ++r) {
        for (uint32_t c = 0; c < n; ++c) {
            folded[3 * (r * n + c) + 1] = 0.25f * (r - 2);
            folded[3 * (r * n + c) + 2] = 0.5f;
        }
    }
    // Inside the fold's corner, nearest to the fold line (z = 0.5, y = 0):
    // on the side of both halves' normals (+y and -z); outside it, on neither.
    const std::vector<float> corner = {0.5f, 0.05f, 0.45f, 0.5f, -0.05f, 0.55f};
    const std::vector<float> fold_distances =
        cloth_test::signed_distances_to_sheet(corner, folded, triangles);
    EXPECT_GT(fold_distances[0], 0.0f);
    EXPECT_LT(fold_distances[1], 0.0f);
}

}  // namespace
