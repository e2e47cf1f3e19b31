// Contact between two cloths of one world (cloth.h section "Contact between
// cloths"): a sheet dropped onto another stays on it, and without the
// contact falls through; off costs nothing; results are the same bits for
// every worker count; a destroyed cloth takes its pairs with it; bad input
// is rejected with its code and changes nothing (support/contract.h).
#include <cloth/cloth.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "support/bits_hash.h"
#include "support/contract.h"
#include "support/contract_gtest.h"
#include "support/counting_allocator.h"

namespace {

constexpr uint32_t kSide = 24;
constexpr uint32_t kParticles = kSide * kSide;
constexpr float kSize = 0.75f;  // m: a mean rest edge of 0.75 / 23 = 0.033 m
constexpr float kThickness = 0.03f;
constexpr float kFrame = 1.0f / 60.0f;

// Two horizontal sheets: `lower`, its border pinned (a trampoline), and
// `upper`, free, 6 cm above it and shifted half a cell in x and z, so
// that its particles fall between the lower sheet's.
struct TwoSheets {
    cloth_test::CountingAllocator host;
    cloth_world_id world{};
    cloth_fabric_id fabric{};
    cloth_id lower{}, upper{};

    explicit TwoSheets(uint32_t workers = 0) {
        cloth_world_desc wd = host.world_desc();
        wd.worker_count = workers;
        EXPECT_EQ(cloth_world_create(&wd, &world), CLOTH_OK);
        cloth_grid_desc gd = cloth_default_grid_desc();
        gd.columns = gd.rows = kSide;
        gd.u[0] = kSize;
        gd.v[1] = 0;
        gd.v[2] = kSize;
        EXPECT_EQ(cloth_fabric_create_grid(world, &gd, &fabric), CLOTH_OK);
        lower = create(0.0f, 0.0f);
        const float half_cell = 0.5f * kSize / static_cast<float>(kSide - 1);
        upper = create(0.06f, half_cell);
        std::vector<uint32_t> border;
        for (uint32_t i = 0; i < kParticles; ++i) {
            const uint32_t r = i / kSide, c = i % kSide;
            if (r == 0 || c == 0 || r == kSide - 1 || c == kSide - 1) border.push_back(i);
        }
        EXPECT_EQ(cloth_pin(lower, border.data(), static_cast<uint32_t>(border.size())), CLOTH_OK);
    }
    ~TwoSheets() {
        EXPECT_EQ(cloth_world_destroy(world), CLOTH_OK);
        cloth_test::ExpectAllReturned(host);
    }
    cloth_id create(float height, float shift) {
        std::vector<float> start(3 * kParticles);
        for (uint32_t i = 0; i < kParticles; ++i) {
            start[3 * i] = shift + kSize * static_cast<float>(i % kSide) / (kSide - 1);
            start[3 * i + 1] = height;
            start[3 * i + 2] = shift + kSize * static_cast<float>(i / kSide) / (kSide - 1);
        }
        cloth_desc cd = cloth_default_desc();
        cd.fabric = fabric;
        cd.initial_positions = start.data();
        cloth_id id{};
        EXPECT_EQ(cloth_create(world, &cd, &id), CLOTH_OK);
        return id;
    }
    bool set_contact(bool on) {
        cloth_cloth_contact_desc d = cloth_default_cloth_contact_desc();
        d.enabled = on;
        d.thickness = kThickness;
        d.friction = 0.3f;
        return cloth_set_cloth_contact(lower, upper, &d) == CLOTH_OK;
    }
    static std::vector<float> positions(cloth_id c) {
        std::vector<float> x(3 * kParticles);
        EXPECT_EQ(cloth_read_positions(c, x.data(), 3 * kParticles), CLOTH_OK);
        return x;
    }
    // The least distance between a particle of one sheet and one of the other.
    float closest() const {
        const std::vector<float> a = positions(lower), b = positions(upper);
        float least = std::numeric_limits<float>::infinity();
        for (uint32_t i = 0; i < kParticles; ++i) {
            for (uint32_t j = 0; j < kParticles; ++j) {
                const float dx = a[3 * i] - b[3 * j], dy = a[3 * i + 1] - b[3 * j + 1],
                            dz = a[3 * i + 2] - b[3 * j + 2];
                least = std::min(least, std::sqrt(dx * dx + dy * dy + dz * dz));
            }
        }
        return least;
    }
    // The upper sheet's mean height over the lower's.
    float height_above() const {
        const std::vector<float> a = positions(lower), b = positions(upper);
        double sum = 0;
        for (uint32_t i = 0; i < kParticles; ++i) sum += b[3 * i + 1] - a[3 * i + 1];
        return static_cast<float>(sum / kParticles);
    }
};

TEST(ClothContactApi, ASheetDroppedOnAnotherStaysOnItAndFallsThroughWithoutTheContact) {
    TwoSheets on, off;
    ASSERT_TRUE(on.set_contact(true));
    float least = std::numeric_limits<float>::infinity();
    uint32_t contacts_seen = 0;
    for (int frame = 0; frame < 90; ++frame) {
        ASSERT_EQ(cloth_step(on.world, kFrame), CLOTH_OK) << cloth_get_last_error();
        ASSERT_EQ(cloth_step(off.world, kFrame), CLOTH_OK) << cloth_get_last_error();
        least = std::min(least, on.closest());
        uint32_t contacts = 0, passes = 0;
        ASSERT_EQ(cloth_get_cloth_contact_count(on.upper, on.lower, &contacts, &passes), CLOTH_OK);
        contacts_seen += contacts;
        if (contacts > 0) {
            EXPECT_GE(passes, 1u);
        }
    }
    EXPECT_GT(contacts_seen, 0u) << "the sheets must meet for the test to mean anything";
    // After every frame no two particles of the sheets are within half the thickness.
    EXPECT_GE(least, 0.5f * kThickness);
    EXPECT_GT(on.height_above(), 0.5f * kThickness) << "the upper sheet rests on the lower";
    EXPECT_LT(off.height_above(), -0.05f) << "without the contact it falls through";
}

TEST(ClothContactApi, OffByDefaultAndApartTheSheetsStepAsWithoutItAndPinnedParticlesNeverMove) {
    TwoSheets plain, paired;
    cloth_cloth_contact_desc d{};
    ASSERT_EQ(cloth_get_cloth_contact(paired.lower, paired.upper, &d), CLOTH_OK);
    EXPECT_EQ(d.enabled, 0) << "off by default";
    const size_t before = paired.host.live_bytes();
    ASSERT_TRUE(paired.set_contact(true));
    EXPECT_GT(paired.host.live_bytes(), before) << "turning a pair on allocates";
    ASSERT_EQ(cloth_get_cloth_contact(paired.upper, paired.lower, &d), CLOTH_OK);
    EXPECT_EQ(d.enabled, 1) << "either order names the pair";
    EXPECT_EQ(d.thickness, kThickness);
    EXPECT_EQ(d.friction, 0.3f);
    const size_t on = paired.host.live_bytes();
    // While the sheets are more than the thickness apart (the first frames
    // of the drop) they move as they do without the pair.
    for (int frame = 0; frame < 3; ++frame) {
        ASSERT_EQ(cloth_step(plain.world, kFrame), CLOTH_OK);
        ASSERT_EQ(cloth_step(paired.world, kFrame), CLOTH_OK);
        ASSERT_GT(paired.closest(), kThickness);
        EXPECT_EQ(TwoSheets::positions(plain.upper), TwoSheets::positions(paired.upper));
        EXPECT_EQ(TwoSheets::positions(plain.lower), TwoSheets::positions(paired.lower));
    }
    EXPECT_EQ(paired.host.live_bytes(), on) << "a step allocates nothing";
    const std::vector<float> start = TwoSheets::positions(paired.lower);
    for (int frame = 0; frame < 60; ++frame) ASSERT_EQ(cloth_step(paired.world, kFrame), CLOTH_OK);
    const std::vector<float> end = TwoSheets::positions(paired.lower);
    for (uint32_t i : {0u, kSide - 1, kParticles / 2 - kSide / 2 - 12, kParticles - 1}) {
        const bool pinned = i < kSide || i % kSide == 0 || i % kSide == kSide - 1 || i >= kParticles - kSide;
        if (!pinned) continue;
        EXPECT_EQ(start[3 * i + 1], end[3 * i + 1]) << "pinned particle " << i << " moved";
    }
    cloth_cloth_contact_desc off = cloth_default_cloth_contact_desc();
    ASSERT_EQ(cloth_set_cloth_contact(paired.lower, paired.upper, &off), CLOTH_OK);
    const size_t after_off = paired.host.live_bytes();
    EXPECT_LT(after_off - before, (on - before) / 100)
        << "turning it off frees its buffers (the list keeps its room)";
    ASSERT_TRUE(paired.set_contact(true));
    ASSERT_EQ(cloth_set_cloth_contact(paired.lower, paired.upper, &off), CLOTH_OK);
    EXPECT_EQ(paired.host.live_bytes(), after_off) << "on and off again leaves nothing behind";
}

// The skin still wins: the lower sheet skinned to one joint at rest with a
// max distance of 1 cm everywhere (0 on its border), the upper one dropped
// on it; after every frame each lower particle is within its max distance
// of its skinned position, and the upper sheet rests on the lower.
TEST(ClothContactApi, AContactThatPushesASkinnedClothLeavesItWithinItsMaxDistances) {
    TwoSheets s;
    std::vector<uint32_t> joints(kParticles, 0u);
    cloth_skin_desc skin = cloth_default_skin_desc();
    skin.particle_count = kParticles;
    skin.joint_count = 1;
    skin.joints = joints.data();
    ASSERT_EQ(cloth_set_skin(s.lower, &skin), CLOTH_OK) << cloth_get_last_error();
    std::vector<float> reach(kParticles, 0.01f);
    for (uint32_t i = 0; i < kParticles; ++i) {
        const uint32_t r = i / kSide, c = i % kSide;
        if (r == 0 || c == 0 || r == kSide - 1 || c == kSide - 1) reach[i] = 0.0f;
    }
    ASSERT_EQ(cloth_set_max_distances(s.lower, reach.data(), kParticles), CLOTH_OK);
    ASSERT_TRUE(s.set_contact(true));
    uint32_t contacts_seen = 0;
    float worst = 0.0f;
    for (int frame = 0; frame < 60; ++frame) {
        ASSERT_EQ(cloth_step(s.world, kFrame), CLOTH_OK) << cloth_get_last_error();
        uint32_t contacts = 0, passes = 0;
        ASSERT_EQ(cloth_get_cloth_contact_count(s.lower, s.upper, &contacts, &passes), CLOTH_OK);
        contacts_seen += contacts;
        std::vector<float> skinned(3 * kParticles);
        ASSERT_EQ(cloth_read_skinned_positions(s.lower, skinned.data(), nullptr, 3 * kParticles), CLOTH_OK);
        const std::vector<float> x = TwoSheets::positions(s.lower);
        for (uint32_t i = 0; i < kParticles; ++i) {
            const float dx = x[3 * i] - skinned[3 * i], dy = x[3 * i + 1] - skinned[3 * i + 1],
                        dz = x[3 * i + 2] - skinned[3 * i + 2];
            worst = std::max(worst, std::sqrt(dx * dx + dy * dy + dz * dz) - reach[i]);
        }
    }
    EXPECT_GT(contacts_seen, 0u) << "the sheets must meet for the test to mean anything";
    EXPECT_LE(worst, 1e-5f) << "a particle of the skinned sheet ended a frame past its max distance";
    EXPECT_GT(s.height_above(), 0.5f * kThickness) << "the upper sheet rests on the lower";
}

uint64_t dropped_sheets_hash(uint32_t workers) {
    TwoSheets s(workers);
    EXPECT_TRUE(s.set_contact(true));
    for (int frame = 0; frame < 40; ++frame) EXPECT_EQ(cloth_step(s.world, kFrame), CLOTH_OK);
    uint64_t hash = cloth_test::kBitsHashStart;
    std::vector<float> values(3 * kParticles);
    for (cloth_id c : {s.lower, s.upper}) {
        EXPECT_EQ(cloth_read_positions(c, values.data(), 3 * kParticles), CLOTH_OK);
        hash = cloth_test::hash_bits(hash, values.data(), values.size() * sizeof(float));
        EXPECT_EQ(cloth_read_velocities(c, values.data(), 3 * kParticles), CLOTH_OK);
        hash = cloth_test::hash_bits(hash, values.data(), values.size() * sizeof(float));
    }
    return hash;
}

TEST(ClothContactApi, ResultsAreBitIdenticalForEveryWorkerCount) {
    const uint64_t reference = dropped_sheets_hash(0);
    for (uint32_t workers : {1u, 2u, 3u}) EXPECT_EQ(dropped_sheets_hash(workers), reference) << workers;
}

TEST(ClothContactApi, DestroyingEitherClothTurnsThePairOff) {
    TwoSheets s;
    ASSERT_TRUE(s.set_contact(true));
    const size_t on = s.host.live_bytes();
    ASSERT_EQ(cloth_destroy(s.upper), CLOTH_OK);
    EXPECT_LT(s.host.live_bytes(), on);
    // A new cloth in the freed slot is not in contact with the lower one.
    const cloth_id again = s.create(0.06f, 0.0f);
    ASSERT_EQ(again.index1, s.upper.index1) << "the slot is re-used";
    cloth_cloth_contact_desc d{};
    ASSERT_EQ(cloth_get_cloth_contact(s.lower, again, &d), CLOTH_OK);
    EXPECT_EQ(d.enabled, 0);
    uint32_t contacts = 7, passes = 7;
    ASSERT_EQ(cloth_get_cloth_contact_count(s.lower, again, &contacts, &passes), CLOTH_OK);
    EXPECT_EQ(contacts, 0u);
    EXPECT_EQ(passes, 0u);
    s.upper = again;
}

TEST(ClothContactApi, BadInputIsRejectedWithItsCodeAndChangesNothing) {
    TwoSheets w, twin, other_world;
    ASSERT_TRUE(w.set_contact(true));
    ASSERT_TRUE(twin.set_contact(true));
    cloth_test::Watch watch{w.world, {w.lower, w.upper}, {}, &w.host, {}};
    cloth_cloth_contact_desc good = cloth_default_cloth_contact_desc();
    good.enabled = 1;
    good.thickness = 0.02f;
    auto expect_rejected = [&](cloth_result expected, cloth_id a, cloth_id b,
                               const cloth_cloth_contact_desc* d, const char* what) {
        cloth_test::ExpectRejected(
            watch, w.host, expected, what, [&] { return cloth_set_cloth_contact(a, b, d); },
            a.index1 == 0 ? cloth_test::Logged::kMaybe : cloth_test::Logged::kYes);
    };
    const float nan = std::numeric_limits<float>::quiet_NaN();
    cloth_cloth_contact_desc d = good;
    expect_rejected(CLOTH_ERROR_NULL_POINTER, w.lower, w.upper, nullptr, "null desc");
    expect_rejected(CLOTH_ERROR_INVALID_HANDLE, cloth_id{}, w.upper, &good, "null cloth a");
    expect_rejected(CLOTH_ERROR_INVALID_HANDLE, w.lower, cloth_id{}, &good, "null cloth b");
    expect_rejected(CLOTH_ERROR_INVALID_HANDLE, w.lower, other_world.upper, &good,
                    "a cloth of another world");
    expect_rejected(CLOTH_ERROR_INVALID_VALUE, w.lower, w.lower, &good, "a cloth and itself");
    d.internal_cookie = 0;
    expect_rejected(CLOTH_ERROR_INVALID_DESC, w.lower, w.upper, &d, "uninitialised desc");
    d = good;
    d.struct_size = 4;
    expect_rejected(CLOTH_ERROR_INVALID_DESC, w.lower, w.upper, &d, "wrong struct_size");
    d = good;
    d.thickness = nan;
    expect_rejected(CLOTH_ERROR_NOT_FINITE, w.lower, w.upper, &d, "NaN thickness");
    d.thickness = 0;
    expect_rejected(CLOTH_ERROR_INVALID_VALUE, w.lower, w.upper, &d, "zero thickness");
    d.thickness = -0.01f;
    expect_rejected(CLOTH_ERROR_INVALID_VALUE, w.lower, w.upper, &d, "negative thickness");
    d.thickness = 0.2f;  // the mean rest edge is 0.033 m
    expect_rejected(CLOTH_ERROR_INVALID_VALUE, w.lower, w.upper, &d, "thickness beyond two rest edges");
    d = good;
    d.friction = -1;
    expect_rejected(CLOTH_ERROR_INVALID_VALUE, w.lower, w.upper, &d, "negative friction");
    d.friction = std::numeric_limits<float>::infinity();
    expect_rejected(CLOTH_ERROR_NOT_FINITE, w.lower, w.upper, &d, "infinite friction");
    d = good;
    d.passes = 0;
    expect_rejected(CLOTH_ERROR_INVALID_VALUE, w.lower, w.upper, &d, "zero passes");
    d.passes = CLOTH_MAX_SELF_COLLISION_PASSES + 1;
    expect_rejected(CLOTH_ERROR_INVALID_VALUE, w.lower, w.upper, &d, "too many passes");

    uint32_t contacts = 0, passes = 0;
    cloth_test::ExpectRejected(watch, w.host, CLOTH_ERROR_NULL_POINTER, "cloth_get_cloth_contact(NULL)",
                               [&] { return cloth_get_cloth_contact(w.lower, w.upper, nullptr); });
    cloth_test::ExpectRejected(watch, w.host, CLOTH_ERROR_NULL_POINTER, "count without out_contacts", [&] {
        return cloth_get_cloth_contact_count(w.lower, w.upper, nullptr, &passes);
    });
    cloth_test::ExpectRejected(watch, w.host, CLOTH_ERROR_NULL_POINTER, "count without out_passes", [&] {
        return cloth_get_cloth_contact_count(w.lower, w.upper, &contacts, nullptr);
    });

    // A pair whose allocation fails changes nothing: a fresh pair in the
    // twin, with every allocation count until it succeeds.
    cloth_cloth_contact_desc off = cloth_default_cloth_contact_desc();
    ASSERT_EQ(cloth_set_cloth_contact(w.lower, w.upper, &off), CLOTH_OK);
    ASSERT_EQ(cloth_set_cloth_contact(twin.lower, twin.upper, &off), CLOTH_OK);
    bool done = false;
    int failures = 0;
    for (long allowed = 0; allowed < 100 && !done; ++allowed) {
        const cloth_test::Unchanged unchanged(watch);
        w.host.fail_after(allowed);
        const cloth_result r = cloth_set_cloth_contact(w.lower, w.upper, &good);
        w.host.fail_after(-1);
        if (r == CLOTH_OK) {
            done = true;
            break;
        }
        ++failures;
        EXPECT_EQ(r, CLOTH_ERROR_OUT_OF_MEMORY);
        EXPECT_EQ(unchanged.what_changed(), "");
        cloth_cloth_contact_desc back{};
        ASSERT_EQ(cloth_get_cloth_contact(w.lower, w.upper, &back), CLOTH_OK);
        EXPECT_EQ(back.enabled, 0) << "a failed call turned the pair on";
    }
    EXPECT_GE(failures, 1);
    ASSERT_TRUE(done);
    ASSERT_EQ(cloth_set_cloth_contact(twin.lower, twin.upper, &good), CLOTH_OK);

    // Turning it off needs no valid values, only a valid desc.
    off.thickness = nan;
    cloth_test::Watch twin_watch{twin.world, {twin.lower, twin.upper}, {}, &twin.host, {}};
    EXPECT_TRUE(cloth_test::SameFutureAsTwin(watch, twin_watch, 30))
        << "rejected calls left hidden state behind";
    EXPECT_EQ(cloth_set_cloth_contact(w.lower, w.upper, &off), CLOTH_OK);
}

}  // namespace

namespace {

TEST(ClothContactApi, AFifthPairForOneClothIsRefusedAndChangesNothing) {
    TwoSheets sheets;
    // Four more cloths of the same fabric, each paired with `lower`.
    std::vector<cloth_id> others;
    for (int k = 0; k < 4; ++k) others.push_back(sheets.create(0.2f * static_cast<float>(k + 1), 0.0f));
    cloth_cloth_contact_desc d = cloth_default_cloth_contact_desc();
    d.enabled = 1;
    d.thickness = kThickness;
    ASSERT_EQ(cloth_set_cloth_contact(sheets.lower, sheets.upper, &d), CLOTH_OK);
    for (int k = 0; k < 3; ++k) ASSERT_EQ(cloth_set_cloth_contact(sheets.lower, others[k], &d), CLOTH_OK);
    EXPECT_EQ(cloth_set_cloth_contact(sheets.lower, others[3], &d), CLOTH_ERROR_CAPACITY)
        << "a cloth is in contact with at most four others";
    cloth_cloth_contact_desc out = cloth_default_cloth_contact_desc();
    ASSERT_EQ(cloth_get_cloth_contact(sheets.lower, others[3], &out), CLOTH_OK);
    EXPECT_EQ(out.enabled, 0) << "the refused pair stays off";
    // Changing a pair it has is no new pair; the other cloth has room.
    d.friction = 0.5f;
    EXPECT_EQ(cloth_set_cloth_contact(sheets.lower, others[0], &d), CLOTH_OK);
    EXPECT_EQ(cloth_set_cloth_contact(sheets.upper, others[3], &d), CLOTH_OK);
    for (int f = 0; f < 30; ++f) ASSERT_EQ(cloth_step(sheets.world, kFrame), CLOTH_OK);
}

}  // namespace
