// Frame profiling through the C API: the per-frame struct counts every
// task of every stage, the task records name the workers that ran them,
// the Chrome trace export is valid JSON with one event per stage used and
// one per task, and zone callbacks bracket every task and the step.
#include <gtest/gtest.h>

#include <atomic>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "scenes.h"

namespace {

using cloth_samples::Scene;
using cloth_samples::SceneConfig;
using cloth_samples::SceneKind;

// Three 32 x 32 flags (four groups of 256 particles each), JACOBI with two
// sweeps, on the built-in pool with two workers.
SceneConfig three_flags() {
    SceneConfig config;
    config.kind = SceneKind::kFlagInWind;
    config.resolution = 32;
    config.solver.kind = CLOTH_SOLVER_JACOBI;  // a fixed stage plan: two sweeps, one substep
    config.solver.iterations = 2;
    config.copies = 3;
    config.world.worker_count = 2;
    return config;
}

cloth_frame_profile profile_of(cloth_world_id world) {
    cloth_frame_profile p{};
    p.struct_size = sizeof p;
    EXPECT_EQ(cloth_world_get_frame_profile(world, &p), CLOTH_OK);
    return p;
}

TEST(Profile, EveryStageRunsOneTaskPerGroupPerCloth) {
    Scene scene(three_flags());
    ASSERT_TRUE(scene.ok()) << scene.error();
    ASSERT_EQ(cloth_world_set_profiling(scene.world(), 1000), CLOTH_OK);
    for (int i = 0; i < 4; ++i) ASSERT_EQ(scene.step(1.0f / 60.0f), CLOTH_OK);
    const cloth_frame_profile p = profile_of(scene.world());
    EXPECT_EQ(p.frame, 4u);
    EXPECT_EQ(p.worker_count, 2u);
    EXPECT_EQ(p.awake_cloths, 3u);
    const uint32_t groups = 3 * 4;
    EXPECT_EQ(p.stage_tasks[CLOTH_STAGE_AIR], groups);
    EXPECT_EQ(p.stage_tasks[CLOTH_STAGE_FORCES], groups);
    EXPECT_EQ(p.stage_tasks[CLOTH_STAGE_ASSEMBLE], groups);
    EXPECT_EQ(p.stage_tasks[CLOTH_STAGE_JACOBI_SWEEP], 2 * groups) << "two sweeps";
    EXPECT_EQ(p.stage_tasks[CLOTH_STAGE_INTEGRATE], groups);
    EXPECT_EQ(p.stage_tasks[CLOTH_STAGE_SERIAL_SOLVE], 0u);
    EXPECT_EQ(p.task_count, 6 * groups);
    EXPECT_EQ(p.tasks_dropped, 0u);
    EXPECT_GT(p.step_ms, 0.0);
    double busy = 0, stages = 0;
    for (uint32_t w = 0; w < p.worker_count; ++w) {
        busy += p.worker_busy_ms[w];
        EXPECT_NEAR(p.worker_idle_ms[w], p.step_ms - p.worker_busy_ms[w], 1e-9);
    }
    for (double ms : p.stage_ms) stages += ms;
    EXPECT_GT(busy, 0.0);
    EXPECT_LE(busy, 2 * p.step_ms) << "two workers cannot be busy longer than twice the step";
    // Three cloths on two workers: each worker runs whole cloths, and a
    // stage's time is the time of its tasks, summed over the workers.
    EXPECT_NEAR(stages, busy, 1e-6) << "every task's time counts once in its stage";
    EXPECT_FALSE(p.overrun) << "no budget, no overrun";

    std::vector<cloth_task_record> records(p.task_count);
    uint32_t count = 0;
    ASSERT_EQ(cloth_world_read_task_records(scene.world(), records.data(), p.task_count, &count), CLOTH_OK);
    ASSERT_EQ(count, p.task_count);
    for (const cloth_task_record& r : records) {
        EXPECT_LT(r.worker, p.worker_count);
        EXPECT_LT(r.group, 4u);
        EXPECT_LE(r.start_us, r.end_us);
        uint32_t particles = 0;
        EXPECT_EQ(cloth_get_particle_count(r.cloth, &particles), CLOTH_OK) << "the record names a live cloth";
    }
}

// With no more cloths than workers the world runs every cloth's stage as
// one round over the workers: the rounds' wall times add up within the
// step, and each stage runs one task per group per cloth as before.
TEST(Profile, RoundsOfTwoClothsOnTwoWorkersRunOneAfterAnotherInsideTheStep) {
    SceneConfig config = three_flags();
    config.copies = 2;
    Scene scene(config);
    ASSERT_TRUE(scene.ok()) << scene.error();
    ASSERT_EQ(cloth_world_set_profiling(scene.world(), 1000), CLOTH_OK);
    for (int i = 0; i < 4; ++i) ASSERT_EQ(scene.step(1.0f / 60.0f), CLOTH_OK);
    const cloth_frame_profile p = profile_of(scene.world());
    EXPECT_EQ(p.stage_tasks[CLOTH_STAGE_FORCES], 2u * 4u);
    EXPECT_EQ(p.task_count, 6u * 2u * 4u);
    double stages = 0;
    for (double ms : p.stage_ms) stages += ms;
    EXPECT_GT(stages, 0.0);
    EXPECT_LE(stages, p.step_ms) << "stages run one after another inside the step";
}

// The colliders run again inside the strain limit as a stage of their own:
// after the limiter's last pass when the cloth has colliders, and after
// every pass that moved particles while the substep touches one; never
// without colliders. One soft 32 x 32 cloth (4 groups), PCG with a strain
// limit of 2 passes, one substep, falling from its two pinned corners.
TEST(Profile, TheCollidersBetweenStrainLimitPassesAreTheirOwnStage) {
    struct Case {
        const char* name;
        bool collider;
        float depth;  // of a ball's top below the sheet, m
    };
    for (const Case& c :
         {Case{"no collider", false, 0.0f}, Case{"far below", true, 10.0f}, Case{"touching", true, 0.02f}}) {
        SCOPED_TRACE(c.name);
        cloth_world_desc world_desc = cloth_default_world_desc();
        cloth_world_id world{};
        ASSERT_EQ(cloth_world_create(&world_desc, &world), CLOTH_OK);
        cloth_grid_desc grid = cloth_default_grid_desc();
        grid.v[1] = 0.0f;  // a horizontal sheet at y = 0
        grid.v[2] = 1.0f;
        cloth_fabric_id fabric{};
        ASSERT_EQ(cloth_fabric_create_grid(world, &grid, &fabric), CLOTH_OK);
        cloth_desc desc = cloth_default_desc();
        desc.fabric = fabric;
        desc.solver.kind = CLOTH_SOLVER_PCG;
        desc.solver.iterations = 4;
        desc.structural.stiffness = desc.shear.stiffness = 10.0f;  // soft: the limiter has work
        cloth_id cloth{};
        ASSERT_EQ(cloth_create(world, &desc, &cloth), CLOTH_OK);
        cloth_strain_limit limit = cloth_default_strain_limit();
        limit.max_strain = 0.08f;
        limit.iterations = 2;
        ASSERT_EQ(cloth_set_strain_limit(cloth, &limit), CLOTH_OK);
        const uint32_t corners[] = {0, 31};
        ASSERT_EQ(cloth_pin(cloth, corners, 2), CLOTH_OK);
        if (c.collider) {  // a ball under the sheet's middle
            cloth_collider_desc collider = cloth_default_collider_desc();
            collider.local_position[0] = collider.local_position[2] = 0.5f;
            collider.local_position[1] = -0.25f - c.depth;
            cloth_collider_id ball{};
            ASSERT_EQ(cloth_collider_create_sphere(world, &collider, 0.25f, &ball), CLOTH_OK);
        }
        ASSERT_EQ(cloth_world_set_profiling(world, 1000), CLOTH_OK);
        for (int i = 0; i < 10; ++i) ASSERT_EQ(cloth_step(world, 1.0f / 60.0f), CLOTH_OK);
        const cloth_frame_profile p = profile_of(world);
        const uint32_t groups = 4, limiting = p.stage_tasks[CLOTH_STAGE_STRAIN_LIMIT];
        const uint32_t colliding = p.stage_tasks[CLOTH_STAGE_LIMIT_COLLISIONS];
        EXPECT_GE(limiting, groups) << "the strain limit ran";
        EXPECT_STREQ(cloth_stage_name(CLOTH_STAGE_LIMIT_COLLISIONS), "limit_collisions");
        if (!c.collider) {
            EXPECT_EQ(colliding, 0u);
        } else if (c.depth > 1.0f) {
            EXPECT_EQ(colliding, groups) << "once, after the last pass";
            EXPECT_GT(p.stage_tasks[CLOTH_STAGE_COLLISIONS], 0u);
        } else {
            EXPECT_GT(colliding, groups) << "after every pass that moved particles too";
        }
        cloth_world_destroy(world);
    }
}

TEST(Profile, TasksBeyondTheCapacityAreCountedAsDropped) {
    Scene scene(three_flags());
    ASSERT_TRUE(scene.ok());
    ASSERT_EQ(cloth_world_set_profiling(scene.world(), 10), CLOTH_OK);
    ASSERT_EQ(scene.step(1.0f / 60.0f), CLOTH_OK);
    const cloth_frame_profile p = profile_of(scene.world());
    EXPECT_EQ(p.task_count, 10u);
    EXPECT_EQ(p.tasks_dropped, 6u * 12u - 10u);
    ASSERT_EQ(cloth_world_set_profiling(scene.world(), 0), CLOTH_OK);
    ASSERT_EQ(scene.step(1.0f / 60.0f), CLOTH_OK);
    EXPECT_EQ(profile_of(scene.world()).task_count, 0u) << "recording is off";
}

TEST(Profile, ChromeTraceHasOneEventPerStageUsedAndOnePerTask) {
    Scene scene(three_flags());
    ASSERT_TRUE(scene.ok());
    ASSERT_EQ(cloth_world_set_profiling(scene.world(), 1000), CLOTH_OK);
    ASSERT_EQ(scene.step(1.0f / 60.0f), CLOTH_OK);
    size_t size = 0;
    ASSERT_EQ(cloth_world_write_trace_json(scene.world(), nullptr, 0, &size), CLOTH_OK);
    std::string text(size, '\0');
    EXPECT_EQ(cloth_world_write_trace_json(scene.world(), text.data(), size - 1, &size),
              CLOTH_ERROR_INVALID_COUNT)
        << "one byte short";
    ASSERT_EQ(cloth_world_write_trace_json(scene.world(), text.data(), size, &size), CLOTH_OK);
    text.resize(size - 1);  // drop the NUL

    const nlohmann::json trace = nlohmann::json::parse(text);  // throws (fails the test) if invalid
    const cloth_frame_profile p = profile_of(scene.world());
    int frames = 0, stages = 0, tasks = 0;
    std::vector<std::string> stage_names;
    for (const auto& event : trace.at("traceEvents")) {
        const std::string cat = event.value("cat", "");
        if (event.at("ph") == "M") continue;
        ASSERT_EQ(event.at("ph"), "X");
        EXPECT_GE(event.at("dur").get<double>(), 0.0);
        if (cat == "frame") ++frames;
        if (cat == "stage") {
            ++stages;
            stage_names.push_back(event.at("name"));
        }
        if (cat == "task") {
            ++tasks;
            EXPECT_LT(event.at("tid").get<uint32_t>(), p.worker_count);
        }
    }
    EXPECT_EQ(frames, 1);
    EXPECT_EQ(stage_names,
              (std::vector<std::string>{"air", "forces", "assemble", "jacobi_sweep", "integrate"}));
    EXPECT_EQ(stages, 5);
    EXPECT_EQ(tasks, static_cast<int>(p.task_count));
    EXPECT_EQ(tasks, 6 * 12);
}

struct ZoneCounter {
    std::atomic<int> begins{0}, ends{0}, steps{0};
    std::atomic<int> bad_worker{0};
};

void zone_begin(const char* name, uint32_t worker, void* user) {
    auto* z = static_cast<ZoneCounter*>(user);
    ++z->begins;
    if (std::string(name) == "cloth_step") ++z->steps;
    if (worker >= 2) ++z->bad_worker;
}
void zone_end(const char*, uint32_t, void* user) { ++static_cast<ZoneCounter*>(user)->ends; }

TEST(Profile, ZoneCallbacksBracketTheStepAndEveryTask) {
    Scene scene(three_flags());
    ASSERT_TRUE(scene.ok());
    ZoneCounter zones;
    EXPECT_EQ(cloth_world_set_zone_callbacks(scene.world(), zone_begin, nullptr, &zones),
              CLOTH_ERROR_INVALID_VALUE);
    ASSERT_EQ(cloth_world_set_zone_callbacks(scene.world(), zone_begin, zone_end, &zones), CLOTH_OK);
    ASSERT_EQ(scene.step(1.0f / 60.0f), CLOTH_OK);
    ASSERT_EQ(scene.step(1.0f / 60.0f), CLOTH_OK);
    EXPECT_EQ(zones.steps.load(), 2);
    EXPECT_EQ(zones.begins.load(), 2 * (1 + 6 * 12));
    EXPECT_EQ(zones.ends.load(), zones.begins.load());
    EXPECT_EQ(zones.bad_worker.load(), 0);
    ASSERT_EQ(cloth_world_set_zone_callbacks(scene.world(), nullptr, nullptr, nullptr), CLOTH_OK);
    ASSERT_EQ(scene.step(1.0f / 60.0f), CLOTH_OK);
    EXPECT_EQ(zones.begins.load(), 2 * (1 + 6 * 12)) << "removed";
}

}  // namespace
