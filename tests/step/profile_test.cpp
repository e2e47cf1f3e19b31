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
    EXPECT_LE(stages, p.step_ms) << "stages run one after another inside the step";
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
