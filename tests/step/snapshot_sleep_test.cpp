// Snapshots reproduce a run bit for bit; bad snapshots change nothing. A
// cloth at rest goes to sleep (and stays exactly where it is, skipped by
// the step) and wakes when its pins, wind or gravity change or cloth_wake
// is called.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "scenes.h"

namespace {

using cloth_samples::Scene;
using cloth_samples::SceneConfig;
using cloth_samples::SceneKind;

std::vector<float> state_of(cloth_id cloth, uint32_t n) {
    std::vector<float> state(6 * static_cast<size_t>(n));
    EXPECT_EQ(cloth_read_positions(cloth, state.data(), 3 * n), CLOTH_OK);
    EXPECT_EQ(cloth_read_velocities(cloth, state.data() + 3 * n, 3 * n), CLOTH_OK);
    return state;
}

bool same_bits(const std::vector<float>& a, const std::vector<float>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

SceneConfig flag() {
    SceneConfig config;
    config.kind = SceneKind::kFlagInWind;
    config.resolution = 24;
    config.solver.iterations = 2;
    config.world.worker_count = 2;
    return config;
}

TEST(Snapshot, RestoringAndSteppingAgainReproducesTheSameBits) {
    Scene scene(flag());
    ASSERT_TRUE(scene.ok()) << scene.error();
    const cloth_id cloth = scene.cloth();
    const uint32_t n = scene.particle_count();
    for (int i = 0; i < 30; ++i) ASSERT_EQ(scene.step(1.0f / 60.0f), CLOTH_OK);
    size_t size = 0;
    ASSERT_EQ(cloth_get_snapshot_size(cloth, &size), CLOTH_OK);
    std::vector<unsigned char> snapshot(size);
    ASSERT_EQ(cloth_save_snapshot(cloth, snapshot.data(), size), CLOTH_OK);
    const std::vector<float> saved = state_of(cloth, n);

    for (int i = 0; i < 100; ++i) ASSERT_EQ(scene.step(1.0f / 60.0f), CLOTH_OK);
    const std::vector<float> first = state_of(cloth, n);
    ASSERT_FALSE(same_bits(first, saved)) << "the flag moved";

    // Something a replay must undo: other wind and solver settings.
    const float calm[3] = {0.0f, 0.0f, 0.0f};
    ASSERT_EQ(cloth_set_wind(cloth, calm), CLOTH_OK);
    ASSERT_EQ(cloth_restore_snapshot(cloth, snapshot.data(), size), CLOTH_OK);
    EXPECT_TRUE(same_bits(state_of(cloth, n), saved));
    for (int i = 0; i < 100; ++i) ASSERT_EQ(scene.step(1.0f / 60.0f), CLOTH_OK);
    EXPECT_TRUE(same_bits(state_of(cloth, n), first)) << "the replay ends in the same bits";
}

// A default cloth of 32x32 pinned at two corners, in a world of its own.
struct PinnedDefaultCloth {
    PinnedDefaultCloth() {
        cloth_world_desc world_desc = cloth_default_world_desc();
        EXPECT_EQ(cloth_world_create(&world_desc, &world), CLOTH_OK);
        cloth_grid_desc grid = cloth_default_grid_desc();
        grid.columns = grid.rows = 32;
        cloth_fabric_id fabric{};
        EXPECT_EQ(cloth_fabric_create_grid(world, &grid, &fabric), CLOTH_OK);
        cloth_desc desc = cloth_default_desc();
        desc.fabric = fabric;
        EXPECT_EQ(cloth_create(world, &desc, &cloth), CLOTH_OK);
        EXPECT_EQ(cloth_pin(cloth, kPins, 2), CLOTH_OK);
    }
    ~PinnedDefaultCloth() { cloth_world_destroy(world); }
    void move_pins(float x) {
        const float targets[6] = {x, 0.0f, 0.0f, x + 1.0f, 0.0f, 0.0f};
        EXPECT_EQ(cloth_set_pin_targets(cloth, kPins, targets, 2), CLOTH_OK);
    }
    static constexpr uint32_t kPins[2] = {0, 31};
    static constexpr uint32_t kCount = 32 * 32;
    cloth_world_id world{};
    cloth_id cloth{};
};

// Right after a yank the default's strain limiter ends past its promise,
// so its next substep is backward Euler rather than its theta step
// (solver_default.h): the snapshot carries that, and a cloth that was
// never yanked steps a restored snapshot to the same bits as the original.
TEST(Snapshot, ARestoredYankedClothStepsAsTheOriginalDid) {
    PinnedDefaultCloth original;
    for (int i = 0; i < 60; ++i) ASSERT_EQ(cloth_step(original.world, 1.0f / 60.0f), CLOTH_OK);
    original.move_pins(10.0f);
    ASSERT_EQ(cloth_step(original.world, 1.0f / 60.0f), CLOTH_OK);
    original.move_pins(0.0f);
    size_t size = 0;
    ASSERT_EQ(cloth_get_snapshot_size(original.cloth, &size), CLOTH_OK);
    std::vector<unsigned char> snapshot(size);
    ASSERT_EQ(cloth_save_snapshot(original.cloth, snapshot.data(), size), CLOTH_OK);
    for (int i = 0; i < 3; ++i) ASSERT_EQ(cloth_step(original.world, 1.0f / 60.0f), CLOTH_OK);

    PinnedDefaultCloth fresh;
    for (int i = 0; i < 60; ++i) ASSERT_EQ(cloth_step(fresh.world, 1.0f / 60.0f), CLOTH_OK);
    ASSERT_EQ(cloth_restore_snapshot(fresh.cloth, snapshot.data(), size), CLOTH_OK);
    for (int i = 0; i < 3; ++i) ASSERT_EQ(cloth_step(fresh.world, 1.0f / 60.0f), CLOTH_OK);
    EXPECT_TRUE(same_bits(state_of(fresh.cloth, PinnedDefaultCloth::kCount),
                          state_of(original.cloth, PinnedDefaultCloth::kCount)));
}

TEST(Snapshot, ABadSnapshotIsRejectedAndChangesNothing) {
    Scene scene(flag());
    ASSERT_TRUE(scene.ok());
    const cloth_id cloth = scene.cloth();
    for (int i = 0; i < 10; ++i) ASSERT_EQ(scene.step(1.0f / 60.0f), CLOTH_OK);
    size_t size = 0;
    ASSERT_EQ(cloth_get_snapshot_size(cloth, &size), CLOTH_OK);
    std::vector<unsigned char> snapshot(size);
    EXPECT_EQ(cloth_save_snapshot(cloth, snapshot.data(), size - 1), CLOTH_ERROR_INVALID_COUNT);
    ASSERT_EQ(cloth_save_snapshot(cloth, snapshot.data(), size), CLOTH_OK);
    for (int i = 0; i < 10; ++i) ASSERT_EQ(scene.step(1.0f / 60.0f), CLOTH_OK);
    const std::vector<float> before = state_of(cloth, scene.particle_count());

    // Cut short, not a snapshot, a NaN or a pinned flag of 0.5 written in:
    // the checksum tells each from what was saved.
    EXPECT_EQ(cloth_restore_snapshot(cloth, snapshot.data(), size - 4), CLOTH_ERROR_CORRUPT_SNAPSHOT);
    EXPECT_EQ(cloth_restore_snapshot(cloth, nullptr, size), CLOTH_ERROR_NULL_POINTER);
    std::vector<unsigned char> broken = snapshot;
    broken[0] ^= 0xFF;
    EXPECT_EQ(cloth_restore_snapshot(cloth, broken.data(), size), CLOTH_ERROR_CORRUPT_SNAPSHOT)
        << "not a snapshot";
    broken = snapshot;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    std::memcpy(broken.data() + size - 40 * sizeof(float) * 10, &nan, sizeof nan);
    EXPECT_EQ(cloth_restore_snapshot(cloth, broken.data(), size), CLOTH_ERROR_CORRUPT_SNAPSHOT);
    broken = snapshot;
    const float half = 0.5f;
    std::memcpy(broken.data() + size - sizeof(float), &half, sizeof half);  // last pinned flag
    EXPECT_EQ(cloth_restore_snapshot(cloth, broken.data(), size), CLOTH_ERROR_CORRUPT_SNAPSHOT);
    EXPECT_TRUE(same_bits(state_of(cloth, scene.particle_count()), before)) << "nothing changed";
}

// A small, well-damped hanging cloth that settles quickly.
SceneConfig settling() {
    SceneConfig config;
    config.kind = SceneKind::kHanging;
    config.resolution = 8;
    config.damping = 2.0f;
    config.solver.iterations = 4;
    return config;
}

bool sleeping(cloth_id cloth) {
    bool s = false;
    EXPECT_EQ(cloth_is_sleeping(cloth, &s), CLOTH_OK);
    return s;
}

void step_until_asleep(Scene& scene) {
    cloth_sleep_params sleep = cloth_default_sleep_params();
    sleep.max_speed = 0.01f;
    sleep.frames = 10;
    ASSERT_EQ(cloth_set_sleep(scene.cloth(), &sleep), CLOTH_OK);
    for (int i = 0; i < 3000 && !sleeping(scene.cloth()); ++i) ASSERT_EQ(scene.step(1.0f / 60.0f), CLOTH_OK);
    ASSERT_TRUE(sleeping(scene.cloth())) << "the damped cloth came to rest";
}

TEST(Sleep, AClothAtRestSleepsStaysPutAndIsSkipped) {
    Scene scene(settling());
    ASSERT_TRUE(scene.ok());
    step_until_asleep(scene);
    const std::vector<float> rest = state_of(scene.cloth(), scene.particle_count());
    for (size_t i = 3 * scene.particle_count(); i < rest.size(); ++i)
        ASSERT_EQ(rest[i], 0.0f) << "no velocity";
    ASSERT_EQ(cloth_world_set_profiling(scene.world(), 100), CLOTH_OK);
    for (int i = 0; i < 5; ++i) ASSERT_EQ(scene.step(1.0f / 60.0f), CLOTH_OK);
    EXPECT_TRUE(same_bits(state_of(scene.cloth(), scene.particle_count()), rest));
    cloth_frame_profile p{};
    p.struct_size = sizeof p;
    ASSERT_EQ(cloth_world_get_frame_profile(scene.world(), &p), CLOTH_OK);
    EXPECT_EQ(p.sleeping_cloths, 1u);
    EXPECT_EQ(p.awake_cloths, 0u);
    EXPECT_EQ(p.task_count, 0u) << "a sleeping cloth runs no task";
}

TEST(Sleep, PinTargetsWindAndGravityWakeTheCloth) {
    Scene scene(settling());
    ASSERT_TRUE(scene.ok());
    const cloth_id cloth = scene.cloth();
    step_until_asleep(scene);
    const uint32_t corner = 0;
    std::vector<float> positions = state_of(cloth, scene.particle_count());
    const float target[3] = {positions[0] + 0.1f, positions[1], positions[2]};
    ASSERT_EQ(cloth_set_pin_targets(cloth, &corner, target, 1), CLOTH_OK);
    EXPECT_FALSE(sleeping(cloth)) << "a moved pin wakes it";
    const std::vector<float> before = state_of(cloth, scene.particle_count());
    ASSERT_EQ(scene.step(1.0f / 60.0f), CLOTH_OK);
    EXPECT_FALSE(same_bits(state_of(cloth, scene.particle_count()), before)) << "and it moves";

    step_until_asleep(scene);
    const float wind[3] = {3.0f, 0.0f, 1.0f};
    ASSERT_EQ(cloth_set_wind(cloth, wind), CLOTH_OK);
    EXPECT_FALSE(sleeping(cloth)) << "wind wakes it";

    const float calm[3] = {0.0f, 0.0f, 0.0f};
    ASSERT_EQ(cloth_set_wind(cloth, calm), CLOTH_OK);
    step_until_asleep(scene);
    const float sideways[3] = {2.0f, -9.81f, 0.0f};
    ASSERT_EQ(cloth_world_set_gravity(scene.world(), sideways), CLOTH_OK);
    EXPECT_FALSE(sleeping(cloth)) << "gravity wakes it";
    ASSERT_EQ(cloth_wake(cloth), CLOTH_OK);
}

// cloth_wake wakes a sleeping cloth: it "steps again from the next
// cloth_step" (cloth.h). A cloth sent to sleep mid-fall (any speed counts
// as rest here) hangs where sleep caught it, with no velocity, through
// steps that skip it; woken, it reports awake, the next step runs it (the
// frame profile counts it awake) and it falls on: from rest, a particle
// falls g h^2 = 2.7 mm in one step unless springs or air hold it (the
// farthest fall 1.6 mm measured; asleep, 0).
TEST(Sleep, CallingWakeOnASleepingClothLetsItsNextStepMoveIt) {
    SceneConfig config;
    config.kind = SceneKind::kFallingFlat;
    config.resolution = 8;
    Scene scene(config);
    ASSERT_TRUE(scene.ok()) << scene.error();
    const cloth_id cloth = scene.cloth();
    const uint32_t n = scene.particle_count();
    cloth_sleep_params sleep = cloth_default_sleep_params();
    sleep.max_speed = 1e3f;
    sleep.frames = 3;
    ASSERT_EQ(cloth_set_sleep(cloth, &sleep), CLOTH_OK);
    for (int i = 0; i < 3; ++i) ASSERT_EQ(scene.step(1.0f / 60.0f), CLOTH_OK);
    ASSERT_TRUE(sleeping(cloth)) << "asleep after 3 frames below 1e3 m/s";
    const std::vector<float> asleep = state_of(cloth, n);
    for (int i = 0; i < 5; ++i) ASSERT_EQ(scene.step(1.0f / 60.0f), CLOTH_OK);
    ASSERT_TRUE(same_bits(state_of(cloth, n), asleep)) << "asleep, it stays where sleep caught it";
    ASSERT_TRUE(sleeping(cloth));

    ASSERT_EQ(cloth_wake(cloth), CLOTH_OK);
    EXPECT_FALSE(sleeping(cloth)) << "cloth_wake wakes it";
    ASSERT_EQ(cloth_world_set_profiling(scene.world(), 100), CLOTH_OK);
    ASSERT_EQ(scene.step(1.0f / 60.0f), CLOTH_OK);
    cloth_frame_profile p{};
    p.struct_size = sizeof p;
    ASSERT_EQ(cloth_world_get_frame_profile(scene.world(), &p), CLOTH_OK);
    EXPECT_EQ(p.awake_cloths, 1u);
    EXPECT_EQ(p.sleeping_cloths, 0u);
    EXPECT_FALSE(sleeping(cloth)) << "one frame is not the 3 it takes to sleep again";
    const std::vector<float> woken = state_of(cloth, n);
    float drop = 0;
    for (uint32_t i = 0; i < n; ++i) drop = std::max(drop, asleep[3 * i + 1] - woken[3 * i + 1]);
    EXPECT_GT(drop, 1e-3f) << "the largest drop in the step after the wake (m)";
}

// Solver settings wake a cloth (cloth.h), the strain limit among them:
// it changes how the next step moves the cloth.
TEST(Sleep, SolverSettingsAndTheStrainLimitWakeTheCloth) {
    Scene scene(settling());
    ASSERT_TRUE(scene.ok());
    const cloth_id cloth = scene.cloth();
    step_until_asleep(scene);
    cloth_strain_limit limit = cloth_default_strain_limit();
    limit.max_strain = 0.05f;
    ASSERT_EQ(cloth_set_strain_limit(cloth, &limit), CLOTH_OK);
    EXPECT_FALSE(sleeping(cloth)) << "a new strain limit wakes it";
    step_until_asleep(scene);
    cloth_solver_settings solver{};
    ASSERT_EQ(cloth_get_solver(cloth, &solver), CLOTH_OK);
    ASSERT_EQ(cloth_set_solver(cloth, &solver), CLOTH_OK);
    EXPECT_FALSE(sleeping(cloth)) << "new solver settings wake it";
}

TEST(Sleep, ADisabledSleepNeverSleeps) {
    Scene scene(settling());
    ASSERT_TRUE(scene.ok());
    cloth_sleep_params sleep = cloth_default_sleep_params();
    sleep.enabled = false;
    sleep.max_speed = 1.0f;
    sleep.frames = 1;
    ASSERT_EQ(cloth_set_sleep(scene.cloth(), &sleep), CLOTH_OK);
    for (int i = 0; i < 50; ++i) ASSERT_EQ(scene.step(1.0f / 60.0f), CLOTH_OK);
    EXPECT_FALSE(sleeping(scene.cloth()));
    sleep.frames = 0;
    EXPECT_EQ(cloth_set_sleep(scene.cloth(), &sleep), CLOTH_ERROR_INVALID_VALUE);
    sleep.frames = 1;
    sleep.max_speed = -1.0f;
    EXPECT_EQ(cloth_set_sleep(scene.cloth(), &sleep), CLOTH_ERROR_INVALID_VALUE);
}

}  // namespace
