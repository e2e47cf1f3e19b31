// Update rates and importance through cloth.h (section "Importance and
// update rate"): a rate-N cloth steps every Nth call over N times its dt
// (the same bits as a rate-1 cloth stepped with N dt), reports the exact
// interpolation between its states in the calls between, is staggered
// across calls with its peers, shows no jump at a change of rate, gives
// the same bits for every worker count, and bad input changes nothing.
#include <cloth/cloth.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>
#include <vector>

#include "support/bits_hash.h"
#include "support/contract.h"
#include "support/contract_gtest.h"
#include "support/counting_allocator.h"
#include "support/flag_fabric.h"

namespace {

constexpr uint32_t kColumns = 16, kRows = 12, kParticles = kColumns * kRows;
constexpr float kFrame = 1.0f / 60.0f;

// Flags in wind, each 0.8 x 0.6 m, pinned along its left column.
struct Flags {
    cloth_test::CountingAllocator host;
    cloth_world_id world{};
    cloth_fabric_id fabric{};
    std::vector<cloth_id> flags;

    explicit Flags(uint32_t count, uint32_t workers = 0) {
        cloth_world_desc wd = host.world_desc();
        wd.worker_count = workers;
        EXPECT_EQ(cloth_world_create(&wd, &world), CLOTH_OK);
        fabric = cloth_test::flag_fabric(world, kColumns, kRows, 0.8f, 0.6f);
        for (uint32_t k = 0; k < count; ++k) flags.push_back(add());
    }
    ~Flags() {
        EXPECT_EQ(cloth_world_destroy(world), CLOTH_OK);
        cloth_test::ExpectAllReturned(host);
    }
    cloth_id add() {
        cloth_desc cd = cloth_default_desc();
        cd.fabric = fabric;
        cloth_id id{};
        EXPECT_EQ(cloth_create(world, &cd, &id), CLOTH_OK);
        std::vector<uint32_t> column;
        for (uint32_t r = 0; r < kRows; ++r) column.push_back(r * kColumns);
        EXPECT_EQ(cloth_pin(id, column.data(), kRows), CLOTH_OK);
        const float wind[3] = {6.0f, 0.0f, 1.5f};
        EXPECT_EQ(cloth_set_wind(id, wind), CLOTH_OK);
        cloth_sleep_params sleep = cloth_default_sleep_params();
        sleep.enabled = 0;
        EXPECT_EQ(cloth_set_sleep(id, &sleep), CLOTH_OK);
        return id;
    }
    void step(float dt = kFrame) { ASSERT_EQ(cloth_step(world, dt), CLOTH_OK); }
    static std::vector<float> positions(cloth_id c) {
        std::vector<float> x(3 * kParticles);
        EXPECT_EQ(cloth_read_positions(c, x.data(), 3 * kParticles), CLOTH_OK);
        return x;
    }
    uint32_t stepped_last_call() const {
        cloth_frame_profile p{};
        p.struct_size = sizeof p;
        EXPECT_EQ(cloth_world_get_frame_profile(world, &p), CLOTH_OK);
        return p.awake_cloths;
    }
};

// The largest distance any particle moved between two readings.
float largest_move(const std::vector<float>& a, const std::vector<float>& b) {
    float most = 0;
    for (size_t i = 0; i < a.size(); i += 3) {
        const float dx = a[i] - b[i], dy = a[i + 1] - b[i + 1], dz = a[i + 2] - b[i + 2];
        most = std::max(most, std::sqrt(dx * dx + dy * dy + dz * dz));
    }
    return most;
}

TEST(UpdateRate, ARateTwoClothStepsEveryOtherCallAsARateOneClothStepsTwiceTheDt) {
    Flags slow(1), reference(1);
    ASSERT_EQ(cloth_set_update_rate(slow.flags[0], 2), CLOTH_OK);
    uint32_t rate = 0, phase = 7;
    ASSERT_EQ(cloth_get_update_rate(slow.flags[0], &rate, &phase), CLOTH_OK);
    EXPECT_EQ(rate, 2u);
    EXPECT_EQ(phase, 0u) << "alone at its rate, the cloth takes phase 0";
    for (int k = 0; k < 30; ++k) {
        slow.step();
        EXPECT_EQ(slow.stepped_last_call(), 1u) << "call " << 2 * k + 1;
        slow.step();
        EXPECT_EQ(slow.stepped_last_call(), 0u);
        reference.step(2 * kFrame);
        EXPECT_EQ(Flags::positions(slow.flags[0]), Flags::positions(reference.flags[0]))
            << "after call " << 2 * (k + 1) << " the states differ";
    }
}

TEST(UpdateRate, BetweenItsStepsARateTwoClothReportsTheExactInterpolation) {
    Flags w(1);
    ASSERT_EQ(cloth_set_update_rate(w.flags[0], 2), CLOTH_OK);
    std::vector<std::vector<float>> reported;
    for (int call = 1; call <= 41; ++call) {
        w.step();
        reported.push_back(Flags::positions(w.flags[0]));
    }
    // Phase 0: the states fall on even calls (index odd), the odd calls
    // report half way from the state before to the one after.
    int checked = 0;
    for (size_t k = 2; k + 1 < reported.size(); k += 2) {
        const std::vector<float>&before = reported[k - 1], &after = reported[k + 1];
        for (size_t i = 0; i < before.size(); ++i) {
            const float expected = before[i] + 0.5f * (after[i] - before[i]);
            ASSERT_EQ(reported[k][i], expected) << "call " << k + 1 << ", coordinate " << i;
        }
        ++checked;
    }
    EXPECT_EQ(checked, 19);
    EXPECT_GT(largest_move(reported[1], reported.back()), 0.01f)
        << "the flag must move for this to mean anything";
}

TEST(UpdateRate, RateTwoClothsAreStaggeredSoEveryCallStepsHalfOfThem) {
    Flags w(8);
    for (cloth_id c : w.flags) ASSERT_EQ(cloth_set_update_rate(c, 2), CLOTH_OK);
    uint32_t phases[2] = {};
    for (cloth_id c : w.flags) {
        uint32_t phase = 9;
        ASSERT_EQ(cloth_get_update_rate(c, nullptr, &phase), CLOTH_OK);
        ASSERT_LT(phase, 2u);
        ++phases[phase];
    }
    EXPECT_EQ(phases[0], 4u);
    EXPECT_EQ(phases[1], 4u);
    w.step();  // the first call steps all: each starts where it was created
    for (int call = 0; call < 20; ++call) {
        w.step();
        EXPECT_EQ(w.stepped_last_call(), 4u) << "call " << call + 2;
    }
}

TEST(UpdateRate, AChangeOfRateMakesNoJumpInTheReportedPositions) {
    Flags w(1);
    const uint32_t rates[] = {1, 2, 4, 8, 2, 1, 8, 1};
    std::vector<std::vector<float>> reported{Flags::positions(w.flags[0])};
    std::vector<size_t> changes;
    for (uint32_t rate : rates) {
        ASSERT_EQ(cloth_set_update_rate(w.flags[0], rate), CLOTH_OK);
        changes.push_back(reported.size());
        for (int call = 0; call < 24; ++call) {
            w.step();
            reported.push_back(Flags::positions(w.flags[0]));
        }
    }
    // Each change's first call moves no particle more than twice what the
    // calls around it move (the flag in wind moves every call).
    for (size_t c = 1; c < changes.size(); ++c) {
        const size_t at = changes[c];
        const float move = largest_move(reported[at - 1], reported[at]);
        float around = 0;
        for (size_t k : {at - 2, at - 1, at + 1, at + 2}) {
            around = std::max(around, largest_move(reported[k - 1], reported[k]));
        }
        EXPECT_LE(move, 2.0f * around) << "to rate " << rates[c] << " from " << rates[c - 1];
        EXPECT_GT(around, 0.0f);
    }
}

TEST(UpdateRate, SettingPositionsBetweenStepsShowsAtOnce) {
    Flags w(1);
    ASSERT_EQ(cloth_set_update_rate(w.flags[0], 4), CLOTH_OK);
    w.step();
    const uint32_t corner = kParticles - 1;
    const float there[3] = {3.0f, -1.0f, 2.0f};
    ASSERT_EQ(cloth_set_positions(w.flags[0], &corner, there, 1), CLOTH_OK);
    const std::vector<float> x = Flags::positions(w.flags[0]);
    EXPECT_EQ(x[3 * corner], there[0]);
    EXPECT_EQ(x[3 * corner + 1], there[1]);
    EXPECT_EQ(x[3 * corner + 2], there[2]);
}

TEST(UpdateRate, ARateAboveOneAllocatesItsCopiesAndRateOneFreesThem) {
    Flags w(1);
    const size_t before = w.host.live_bytes();
    ASSERT_EQ(cloth_set_update_rate(w.flags[0], 4), CLOTH_OK);
    const size_t at_four = w.host.live_bytes();
    EXPECT_GE(at_four, before + 2 * 3 * sizeof(float) * kParticles);
    for (int call = 0; call < 9; ++call) {
        w.step();
        EXPECT_EQ(w.host.live_bytes(), at_four) << "a step allocates nothing";
    }
    ASSERT_EQ(cloth_set_update_rate(w.flags[0], 1), CLOTH_OK);
    for (int call = 0; call < 4; ++call) w.step();
    EXPECT_EQ(w.host.live_bytes(), before) << "back at rate 1 and caught up, the copies are freed";
}

uint64_t mixed_rates_hash(uint32_t workers) {
    Flags w(6, workers);
    const uint32_t rates[] = {1, 2, 2, 4, 8, 4};
    for (size_t k = 0; k < w.flags.size(); ++k)
        EXPECT_EQ(cloth_set_update_rate(w.flags[k], rates[k]), CLOTH_OK);
    uint64_t hash = cloth_test::kBitsHashStart;
    for (int call = 0; call < 40; ++call) {
        w.step();
        for (cloth_id c : w.flags) {
            const std::vector<float> x = Flags::positions(c);
            hash = cloth_test::hash_bits(hash, x.data(), x.size() * sizeof(float));
        }
    }
    return hash;
}

TEST(UpdateRate, MixedRatesGiveTheSameBitsForEveryWorkerCount) {
    const uint64_t reference = mixed_rates_hash(0);
    for (uint32_t workers : {1u, 2u, 3u}) EXPECT_EQ(mixed_rates_hash(workers), reference) << workers;
}

TEST(UpdateRate, AClothABodyCarriesStepsEveryCall) {
    Flags w(1);
    cloth_body_desc bd = cloth_default_body_desc();
    cloth_body_id body{};
    ASSERT_EQ(cloth_body_create(w.world, &bd, &body), CLOTH_OK);
    ASSERT_EQ(cloth_set_update_rate(w.flags[0], 4), CLOTH_OK);
    w.step();
    // Attached at rate 4: the next calls bring it back to rate 1.
    const uint32_t corner = 0;
    ASSERT_EQ(cloth_attach(w.flags[0], body, &corner, nullptr, 1), CLOTH_OK);
    for (int call = 0; call < 4; ++call) w.step();
    uint32_t rate = 0;
    ASSERT_EQ(cloth_get_update_rate(w.flags[0], &rate, nullptr), CLOTH_OK);
    EXPECT_EQ(rate, 1u);
    for (int call = 0; call < 3; ++call) {
        w.step();
        EXPECT_EQ(w.stepped_last_call(), 1u) << "it steps every call";
    }
    EXPECT_EQ(cloth_set_update_rate(w.flags[0], 2), CLOTH_ERROR_INVALID_VALUE);
    ASSERT_EQ(cloth_get_update_rate(w.flags[0], &rate, nullptr), CLOTH_OK);
    EXPECT_EQ(rate, 1u) << "refused, and nothing changed";
}

TEST(UpdateRate, AFrameBudgetSlowsTheRatesOfPoliciesThatAllowItAndAStepAllocatesNothing) {
    Flags w(8);
    cloth_quality_policy policy = cloth_default_quality_policy();
    EXPECT_EQ(policy.max_update_rate, 1u) << "the budget leaves rates alone by default";
    policy.enabled = 1;
    policy.max_update_rate = 8;
    for (cloth_id c : w.flags) ASSERT_EQ(cloth_set_quality_policy(c, &policy), CLOTH_OK);
    ASSERT_EQ(cloth_set_importance(w.flags[0], 10.0f), CLOTH_OK);
    // A budget no frame can meet: every flag comes down its ladder.
    cloth_world_set_frame_budget(w.world, 1e-4f);
    const size_t bytes = w.host.live_bytes();
    uint32_t slowest = 1;
    for (int call = 0; call < 120; ++call) {
        const cloth_result r = cloth_step(w.world, kFrame);
        ASSERT_TRUE(r == CLOTH_OK || r == CLOTH_ERROR_OVER_BUDGET) << cloth_result_name(r);
        EXPECT_EQ(w.host.live_bytes(), bytes) << "a step allocates nothing, rates included";
        for (cloth_id c : w.flags) {
            uint32_t rate = 0;
            ASSERT_EQ(cloth_get_update_rate(c, &rate, nullptr), CLOTH_OK);
            slowest = std::max(slowest, rate);
        }
    }
    EXPECT_EQ(slowest, 8u) << "the ladder continues with rates down to the policy's slowest";
    // Setting the policy again lifts its cuts: the rates go back to 1.
    for (cloth_id c : w.flags) {
        ASSERT_EQ(cloth_set_quality_policy(c, &policy), CLOTH_OK);
        uint32_t rate = 0;
        ASSERT_EQ(cloth_get_update_rate(c, &rate, nullptr), CLOTH_OK);
        EXPECT_EQ(rate, 1u);
    }
}

TEST(LevelOfDetailApi, BadInputIsRejectedWithItsCodeAndChangesNothing) {
    Flags w(2), twin(2);
    for (Flags* f : {&w, &twin}) {
        ASSERT_EQ(cloth_set_update_rate(f->flags[1], 2), CLOTH_OK);
        ASSERT_EQ(cloth_set_importance(f->flags[1], 0.5f), CLOTH_OK);
        for (int call = 0; call < 3; ++call) f->step();
    }
    cloth_test::Watch watch{w.world, w.flags, {}, &w.host, {}};
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const cloth_id flag = w.flags[0];
    auto rejected = [&](cloth_result code, const char* what, auto call) {
        cloth_test::ExpectRejected(watch, w.host, code, what, call);
    };
    rejected(CLOTH_ERROR_NOT_FINITE, "NaN importance", [&] { return cloth_set_importance(flag, nan); });
    rejected(CLOTH_ERROR_NOT_FINITE, "infinite importance",
             [&] { return cloth_set_importance(flag, std::numeric_limits<float>::infinity()); });
    rejected(CLOTH_ERROR_INVALID_VALUE, "negative importance",
             [&] { return cloth_set_importance(flag, -1.0f); });
    for (uint32_t rate : {0u, 3u, 5u, 16u, 0xffffffffu}) {
        rejected(CLOTH_ERROR_INVALID_VALUE, "a rate not 1, 2, 4 or 8",
                 [&] { return cloth_set_update_rate(flag, rate); });
    }
    cloth_quality_policy policy = cloth_default_quality_policy();
    policy.enabled = 1;
    for (uint32_t rate : {0u, 3u, 16u}) {
        policy.max_update_rate = rate;
        rejected(CLOTH_ERROR_INVALID_VALUE, "a max_update_rate not 1, 2, 4 or 8",
                 [&] { return cloth_set_quality_policy(flag, &policy); });
    }
    policy.struct_size = sizeof policy - 1;
    rejected(CLOTH_ERROR_INVALID_DESC, "a policy's struct_size neither 1.11's nor 1.10's",
             [&] { return cloth_set_quality_policy(flag, &policy); });
    rejected(CLOTH_ERROR_NULL_POINTER, "cloth_get_importance(NULL)",
             [&] { return cloth_get_importance(flag, nullptr); });
    rejected(CLOTH_ERROR_NULL_POINTER, "cloth_get_update_rate(NULL, NULL)",
             [&] { return cloth_get_update_rate(flag, nullptr, nullptr); });
    const float bad_viewer[3] = {0.0f, nan, 0.0f}, far_viewer[3] = {0.0f, 2.0f * CLOTH_MAX_COORDINATE, 0.0f};
    cloth_test::ExpectRejected(watch, w.host, CLOTH_ERROR_NOT_FINITE, "NaN viewer",
                               [&] { return cloth_world_set_viewer(w.world, bad_viewer); });
    cloth_test::ExpectRejected(watch, w.host, CLOTH_ERROR_INVALID_VALUE, "viewer beyond CLOTH_MAX_COORDINATE",
                               [&] { return cloth_world_set_viewer(w.world, far_viewer); });
    cloth_test::ExpectRejected(
        watch, w.host, CLOTH_ERROR_INVALID_HANDLE, "a null cloth",
        [&] { return cloth_set_update_rate(cloth_id{}, 2); }, cloth_test::Logged::kMaybe);

    // 1.10's policy, without max_update_rate, is accepted and reads as 1.
    cloth_quality_policy old_policy = cloth_default_quality_policy();
    old_policy.struct_size = offsetof(cloth_quality_policy, max_update_rate);
    old_policy.max_update_rate = 3;  // past 1.10's struct: never read
    for (Flags* f : {&w, &twin}) EXPECT_EQ(cloth_set_quality_policy(f->flags[0], &old_policy), CLOTH_OK);

    // A rate whose allocation fails changes nothing, at every count.
    bool done = false;
    int failures = 0;
    for (long allowed = 0; allowed < 20 && !done; ++allowed) {
        const cloth_test::Unchanged unchanged(watch);
        w.host.fail_after(allowed);
        const cloth_result r = cloth_set_update_rate(flag, 8);
        w.host.fail_after(-1);
        if (r == CLOTH_OK) {
            done = true;
            break;
        }
        ++failures;
        EXPECT_EQ(r, CLOTH_ERROR_OUT_OF_MEMORY);
        EXPECT_EQ(unchanged.what_changed(), "");
    }
    EXPECT_GE(failures, 1);
    ASSERT_TRUE(done);
    ASSERT_EQ(cloth_set_update_rate(twin.flags[0], 8), CLOTH_OK);
    cloth_test::Watch twin_watch{twin.world, twin.flags, {}, &twin.host, {}};
    EXPECT_TRUE(cloth_test::SameFutureAsTwin(watch, twin_watch, 30))
        << "rejected calls left hidden state behind";
}

}  // namespace

// ---- Levels of detail (cloth.h, "Level of detail")

// The largest strain of the flag's row and column neighbours.
float largest_structural_strain(const std::vector<float>& x) {
    const float along = 0.8f / (kColumns - 1), down = 0.6f / (kRows - 1);
    float most = 0;
    auto strain = [&](uint32_t a, uint32_t b, float rest) {
        const float dx = x[3 * a] - x[3 * b], dy = x[3 * a + 1] - x[3 * b + 1],
                    dz = x[3 * a + 2] - x[3 * b + 2];
        most = std::max(most, std::sqrt(dx * dx + dy * dy + dz * dz) / rest - 1.0f);
    };
    for (uint32_t r = 0; r < kRows; ++r) {
        for (uint32_t c = 0; c < kColumns; ++c) {
            const uint32_t p = r * kColumns + c;
            if (c + 1 < kColumns) strain(p, p + 1, along);
            if (r + 1 < kRows) strain(p, p + kColumns, down);
        }
    }
    return most;
}

// Per particle, how far it moved between two readings.
std::vector<float> moves(const std::vector<float>& a, const std::vector<float>& b) {
    std::vector<float> out(a.size() / 3);
    for (size_t i = 0; i < out.size(); ++i) {
        const float dx = a[3 * i] - b[3 * i], dy = a[3 * i + 1] - b[3 * i + 1],
                    dz = a[3 * i + 2] - b[3 * i + 2];
        out[i] = std::sqrt(dx * dx + dy * dy + dz * dz);
    }
    return out;
}

void set_strain_limit(cloth_id c, float max_strain) {
    cloth_strain_limit limit = cloth_default_strain_limit();
    limit.max_strain = max_strain;
    ASSERT_EQ(cloth_set_strain_limit(c, &limit), CLOTH_OK);
}

TEST(LodLevel, AGridFlagHasThreeLevelsAndStartsAtTheFullGrid) {
    Flags w(1);
    uint32_t level = 7, count = 0;
    ASSERT_EQ(cloth_get_lod_level(w.flags[0], &level, &count), CLOTH_OK);
    EXPECT_EQ(level, 0u);
    EXPECT_EQ(count, 3u) << "16 x 12, 8 x 6 and 4 x 3";
    ASSERT_EQ(cloth_set_lod_level(w.flags[0], 2), CLOTH_OK);
    ASSERT_EQ(cloth_get_lod_level(w.flags[0], &level, nullptr), CLOTH_OK);
    EXPECT_EQ(level, 2u);
}

TEST(LodLevel, ACoarseFlagReadsEveryParticleOfTheFullGridWithItsPinsOnTheirTargets) {
    Flags w(1);
    const std::vector<float> rest = Flags::positions(w.flags[0]);
    ASSERT_EQ(cloth_set_lod_level(w.flags[0], 1), CLOTH_OK);
    for (int call = 0; call < 60; ++call) w.step();
    const std::vector<float> x = Flags::positions(w.flags[0]);
    std::vector<float> normals(3 * kParticles);
    ASSERT_EQ(cloth_read_normals(w.flags[0], normals.data(), 3 * kParticles), CLOTH_OK);
    float moved = 0;
    for (uint32_t i = 0; i < kParticles; ++i) {
        for (int a = 0; a < 3; ++a) ASSERT_TRUE(std::isfinite(x[3 * i + a])) << i;
        const float length =
            std::sqrt(normals[3 * i] * normals[3 * i] + normals[3 * i + 1] * normals[3 * i + 1] +
                      normals[3 * i + 2] * normals[3 * i + 2]);
        EXPECT_NEAR(length, 1.0f, 1e-4f) << "normal " << i;
        if (i % kColumns == 0) {
            for (int a = 0; a < 3; ++a) EXPECT_EQ(x[3 * i + a], rest[3 * i + a]) << "pinned " << i;
        }
        moved = std::max(moved, std::abs(x[3 * i + 2] - rest[3 * i + 2]));
    }
    EXPECT_GT(moved, 0.05f) << "the wind blows the coarse flag along z";
    EXPECT_LT(largest_structural_strain(x), 0.3f) << "the interpolated mesh holds together";
}

TEST(LodLevel, ChangingLevelMakesNoJumpAndGoingUpKeepsTheStrainLimit) {
    Flags w(1);
    constexpr float kLimit = 0.08f;
    set_strain_limit(w.flags[0], kLimit);
    const uint32_t levels[] = {0, 1, 2, 1, 0};  // one level at a time
    std::vector<std::vector<float>> reported{Flags::positions(w.flags[0])};
    std::vector<size_t> changes;
    for (uint32_t level : levels) {
        ASSERT_EQ(cloth_set_lod_level(w.flags[0], level), CLOTH_OK);
        changes.push_back(reported.size());
        for (int call = 0; call < 45; ++call) {
            w.step();
            reported.push_back(Flags::positions(w.flags[0]));
            if (level == 0 && changes.size() > 1) {
                EXPECT_LE(largest_structural_strain(reported.back()), kLimit + 0.02f)
                    << "call " << call << " after going up from level " << levels[changes.size() - 2];
            }
        }
    }
    // Each change's first call moves no particle more than 1.3 times the
    // most it moved in the calls just before and after it, plus 12 mm: the
    // first frames at a new level still settle the pole's side and the
    // border by up to about a centimetre (docs/measurements.md, "Levels of
    // detail: the jump at a change of level").
    for (size_t c = 1; c < changes.size(); ++c) {
        const size_t at = changes[c];
        const std::vector<float> move = moves(reported[at - 1], reported[at]);
        const std::vector<float> before = moves(reported[at - 2], reported[at - 1]);
        const std::vector<float> after = moves(reported[at], reported[at + 1]);
        float worst = 0;
        uint32_t worst_particle = 0;
        for (uint32_t i = 0; i < kParticles; ++i) {
            const float excess = move[i] - 1.3f * std::max(before[i], after[i]);
            if (excess > worst) worst = excess, worst_particle = i;
        }
        EXPECT_LE(worst, 0.012f) << "level " << levels[c - 1] << " to " << levels[c] << ": particle "
                                 << worst_particle << " moved " << move[worst_particle] << " m, around it "
                                 << before[worst_particle] << " and " << after[worst_particle];
    }
}

uint64_t levels_hash(uint32_t workers) {
    Flags w(4, workers);
    const uint32_t levels[] = {0, 1, 2, 1};
    for (size_t k = 0; k < w.flags.size(); ++k)
        EXPECT_EQ(cloth_set_lod_level(w.flags[k], levels[k]), CLOTH_OK);
    EXPECT_EQ(cloth_set_update_rate(w.flags[3], 2), CLOTH_OK);
    uint64_t hash = cloth_test::kBitsHashStart;
    for (int call = 0; call < 40; ++call) {
        if (call == 20) {
            for (size_t k = 0; k < w.flags.size(); ++k)
                EXPECT_EQ(cloth_set_lod_level(w.flags[k], levels[(k + 1) % 4]), CLOTH_OK);
        }
        w.step();
        for (cloth_id c : w.flags) {
            const std::vector<float> x = Flags::positions(c);
            hash = cloth_test::hash_bits(hash, x.data(), x.size() * sizeof(float));
        }
    }
    return hash;
}

TEST(LodLevel, LevelsAndTheirChangesGiveTheSameBitsForEveryWorkerCount) {
    const uint64_t reference = levels_hash(1);
    for (uint32_t workers : {2u, 4u}) EXPECT_EQ(levels_hash(workers), reference) << workers;
}

TEST(LodLevel, PositionsSetAtACoarseLevelReachItAtTheNextStep) {
    Flags w(1);
    ASSERT_EQ(cloth_set_lod_level(w.flags[0], 1), CLOTH_OK);
    for (int call = 0; call < 10; ++call) w.step();
    std::vector<float> x = Flags::positions(w.flags[0]);
    std::vector<uint32_t> all(kParticles);
    for (uint32_t i = 0; i < kParticles; ++i) {
        all[i] = i;
        x[3 * i + 1] += 5.0f;  // everything 5 m up, the pins with it
    }
    ASSERT_EQ(cloth_set_positions(w.flags[0], all.data(), x.data(), kParticles), CLOTH_OK);
    w.step();
    const std::vector<float> after = Flags::positions(w.flags[0]);
    for (uint32_t i = 0; i < kParticles; ++i) EXPECT_GT(after[3 * i + 1], 4.0f) << "particle " << i;
}

TEST(LodLevel, WhatACoarseLevelCannotFollowKeepsTheClothAtTheFullGrid) {
    Flags w(1);
    const cloth_id flag = w.flags[0];
    ASSERT_EQ(cloth_set_lod_level(flag, 1), CLOTH_OK);
    w.step();
    cloth_self_collision_desc self = cloth_default_self_collision_desc();
    self.enabled = 1;
    ASSERT_EQ(cloth_set_self_collision(flag, &self), CLOTH_OK);
    w.step();
    uint32_t level = 9;
    ASSERT_EQ(cloth_get_lod_level(flag, &level, nullptr), CLOTH_OK);
    EXPECT_EQ(level, 0u) << "self-collision took it back to the full grid";
    EXPECT_EQ(cloth_set_lod_level(flag, 1), CLOTH_ERROR_INVALID_VALUE);
    ASSERT_EQ(cloth_get_lod_level(flag, &level, nullptr), CLOTH_OK);
    EXPECT_EQ(level, 0u);
}

TEST(LodLevel, BadInputIsRejectedWithItsCodeAndChangesNothing) {
    Flags w(1);
    for (int call = 0; call < 3; ++call) w.step();
    const cloth_id flag = w.flags[0];
    const float quad[12] = {0, 0, 0, 1, 0, 0, 1, 0, 1, 0, 0, 1};
    const uint32_t triangles[6] = {0, 1, 2, 0, 2, 3};
    cloth_mesh_desc md = cloth_default_mesh_desc();
    md.positions = quad;
    md.vertex_count = 4;
    md.indices = triangles;
    md.triangle_count = 2;
    cloth_fabric_id mesh_fabric{};
    ASSERT_EQ(cloth_fabric_create_mesh(w.world, &md, &mesh_fabric), CLOTH_OK);
    cloth_desc cd = cloth_default_desc();
    cd.fabric = mesh_fabric;
    cloth_id mesh{};
    ASSERT_EQ(cloth_create(w.world, &cd, &mesh), CLOTH_OK);
    cloth_test::Watch watch{w.world, {flag, mesh}, {}, &w.host, {}};
    auto rejected = [&](cloth_result code, const char* what, auto call) {
        cloth_test::ExpectRejected(watch, w.host, code, what, call);
    };
    for (uint32_t level : {3u, 4u, 0xffffffffu}) {
        rejected(CLOTH_ERROR_INDEX_OUT_OF_RANGE, "a level past the fabric's",
                 [&] { return cloth_set_lod_level(flag, level); });
    }
    rejected(CLOTH_ERROR_INVALID_VALUE, "a level above 0 on a mesh",
             [&] { return cloth_set_lod_level(mesh, 1); });
    rejected(CLOTH_ERROR_NULL_POINTER, "cloth_get_lod_level(NULL, NULL)",
             [&] { return cloth_get_lod_level(flag, nullptr, nullptr); });
    uint32_t level = 5, count = 0;
    ASSERT_EQ(cloth_get_lod_level(mesh, &level, &count), CLOTH_OK);
    EXPECT_EQ(level, 0u);
    EXPECT_EQ(count, 1u);
    EXPECT_EQ(cloth_set_lod_level(mesh, 0), CLOTH_OK) << "level 0 is every fabric's";
}
