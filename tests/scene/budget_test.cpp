// The frame-budget policy against this machine's measured times, through
// the C API: under a budget no step meets, the cloths with an enabled
// policy go down their ladder (the default solver's iterations no lower
// than half while a substep can still go) and every step reports the
// overrun by its result code; under a budget every step meets they come
// back to the top; cloths without an enabled policy are never changed; a
// blow-out loses nothing. The assertions hold whatever the machine's
// speed and noise: how far the cloths go and how few frames run over once
// settled are exact facts of the policy, checked against a cost model in
// budget_policy_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "pinned_cloth.h"
#include "scene/budget_policy.h"
#include "scenes.h"

namespace {

using cloth_samples::Scene;
using cloth_samples::SceneConfig;
using cloth_samples::SceneKind;

constexpr float kDt = 1.0f / 60.0f;

SceneConfig four_flags(uint32_t iterations) {
    SceneConfig config;
    config.kind = SceneKind::kFlagInWind;
    config.resolution = 32;
    config.solver.kind = CLOTH_SOLVER_JACOBI;  // the policy tunes Jacobi sweeps
    config.solver.iterations = iterations;
    config.copies = 4;
    return config;
}

uint32_t iterations_of(cloth_id cloth) {
    cloth_solver_settings s{};
    s.struct_size = sizeof s;
    EXPECT_EQ(cloth_get_solver(cloth, &s), CLOTH_OK);
    return s.iterations;
}

cloth_frame_profile profile_of(cloth_world_id world) {
    cloth_frame_profile p{};
    p.struct_size = sizeof p;
    EXPECT_EQ(cloth_world_get_frame_profile(world, &p), CLOTH_OK);
    return p;
}

// Budgets no step meets and every step meets, on any machine.
constexpr float kNoStepMeets = 1e-6f, kEveryStepMeets = 1e6f;  // ms

// One step under a budget: a frame over it returns CLOTH_ERROR_OVER_BUDGET,
// one within it CLOTH_OK, and the profile agrees. Returns whether it overran.
bool step_under_budget(Scene& scene) {
    const cloth_result result = scene.step(kDt);
    const bool overrun = profile_of(scene.world()).overrun;
    EXPECT_EQ(result, overrun ? CLOTH_ERROR_OVER_BUDGET : CLOTH_OK) << "the result names the overrun";
    return overrun;
}

// Frames over budget among the next `frames`.
int overruns(Scene& scene, int frames) {
    int count = 0;
    for (int i = 0; i < frames; ++i) count += step_under_budget(scene) ? 1 : 0;
    return count;
}

TEST(Budget, ATightBudgetLowersIterationsAndReportsEveryOverrunALooseOneRaisesThemAgain) {
    Scene scene(four_flags(16));
    ASSERT_TRUE(scene.ok()) << scene.error();
    cloth_quality_policy policy = cloth_default_quality_policy();
    policy.enabled = true;
    policy.min_iterations = 1;
    policy.max_iterations = 16;
    policy.max_substeps = 1;
    // Three cloths follow the budget; the fourth has no policy and must keep its settings.
    for (size_t c = 0; c + 1 < scene.cloths().size(); ++c) {
        ASSERT_EQ(cloth_set_quality_policy(scene.cloths()[c], &policy), CLOTH_OK);
    }
    const cloth_id fixed = scene.cloths().back();
    cloth_solver_settings one_sweep = cloth_default_solver_settings();
    one_sweep.kind = CLOTH_SOLVER_JACOBI;
    ASSERT_EQ(cloth_set_solver(fixed, &one_sweep), CLOTH_OK);

    // Every frame over: down to the floor (8 sweeps) at once, and below it,
    // one sweep a frame, once kLoadOverruns frames have run over.
    ASSERT_EQ(cloth_world_set_frame_budget(scene.world(), kNoStepMeets), CLOTH_OK);
    for (int i = 0; i < 60; ++i) EXPECT_TRUE(step_under_budget(scene)) << "frame " << i;
    for (size_t c = 0; c + 1 < scene.cloths().size(); ++c) {
        EXPECT_EQ(iterations_of(scene.cloths()[c]), 1u) << "cloth " << c << " went down to its minimum";
    }
    EXPECT_EQ(iterations_of(fixed), 1u) << "a cloth without a policy keeps its settings";
    EXPECT_EQ(profile_of(scene.world()).overrun_frames, 60u);

    // Every frame within: back up to the maximum, and no frame over.
    ASSERT_EQ(cloth_world_set_frame_budget(scene.world(), kEveryStepMeets), CLOTH_OK);
    for (int i = 0; i < 200 && iterations_of(scene.cloths()[0]) < 16; ++i) step_under_budget(scene);
    EXPECT_EQ(iterations_of(scene.cloths()[0]), 16u) << "iterations went back up";
    EXPECT_EQ(overruns(scene, 5), 0);
}

uint32_t last_iterations(cloth_id cloth) {
    cloth_stats s{};
    s.struct_size = sizeof s;
    EXPECT_EQ(cloth_get_stats(cloth, &s), CLOTH_OK);
    return s.last_solver_iterations;
}

// Substeps the cloth's last step ran, from the task records (profiling on).
uint32_t last_substeps(cloth_world_id world, cloth_id cloth) {
    std::vector<cloth_task_record> records(1u << 16);
    uint32_t count = 0;
    EXPECT_EQ(
        cloth_world_read_task_records(world, records.data(), static_cast<uint32_t>(records.size()), &count),
        CLOTH_OK);
    uint32_t substeps = 0;
    for (uint32_t r = 0; r < count; ++r) {
        if (records[r].cloth.index1 == cloth.index1 && records[r].cloth.generation == cloth.generation)
            substeps = std::max(substeps, records[r].substep + 1);
    }
    return substeps;
}

// CLOTH_SOLVER_DEFAULT picks its own iterations and substeps every frame;
// the policy caps them under a tight budget (the iterations no lower than
// half their own while a substep can still go) and lifts the caps under a
// loose one.
TEST(Budget, TheDefaultSolverGivesUpQualityUnderATightBudgetAndTakesItBackUnderALooseOne) {
    SceneConfig config = four_flags(1);
    config.solver.kind = CLOTH_SOLVER_DEFAULT;
    Scene scene(config);
    ASSERT_TRUE(scene.ok()) << scene.error();
    cloth_quality_policy policy = cloth_default_quality_policy();
    policy.enabled = true;
    for (size_t c = 0; c + 1 < scene.cloths().size(); ++c) {
        ASSERT_EQ(cloth_set_quality_policy(scene.cloths()[c], &policy), CLOTH_OK);
    }
    const cloth_id capped = scene.cloths()[0], free_running = scene.cloths().back();
    const cloth_world_id world = scene.world();
    ASSERT_EQ(cloth_world_set_profiling(world, 1u << 16), CLOTH_OK);  // task records: substeps run

    // The fourth cloth keeps the default's own choice.
    for (int i = 0; i < 15; ++i) ASSERT_EQ(scene.step(kDt), CLOTH_OK);
    const uint32_t own = last_iterations(free_running), own_substeps = last_substeps(world, free_running);
    ASSERT_GT(own, 1u) << "the default iterates more than once here";
    ASSERT_GT(own_substeps, 1u) << "and runs more than one substep";
    ASSERT_EQ(last_iterations(capped), own) << "no budget, no cap";
    ASSERT_EQ(cloth_world_set_frame_budget(world, kNoStepMeets), CLOTH_OK);
    for (int i = 0; i < 60; ++i) {
        EXPECT_TRUE(step_under_budget(scene)) << "frame " << i;
        const uint32_t iterations = last_iterations(capped), substeps = last_substeps(world, capped);
        if (substeps > 1) {
            EXPECT_GE(2 * iterations, own) << "frame " << i << ": iterations at half their own or more while "
                                           << substeps << " substeps run";
        }
    }
    EXPECT_EQ(last_iterations(capped), 1u) << "the policy capped the default's quality down to its minimum";
    EXPECT_EQ(last_substeps(world, capped), 1u);
    EXPECT_EQ(last_iterations(free_running), own) << "a cloth without a policy keeps the default's choice";
    EXPECT_EQ(last_substeps(world, free_running), own_substeps);

    ASSERT_EQ(cloth_world_set_frame_budget(world, kEveryStepMeets), CLOTH_OK);
    const auto at_own = [&] {
        return last_iterations(capped) == own && last_substeps(world, capped) == own_substeps;
    };
    for (int i = 0; i < 300 && !at_own(); ++i) step_under_budget(scene);
    EXPECT_TRUE(at_own()) << "the caps came off";
    for (int i = 0; i < 30; ++i) EXPECT_FALSE(step_under_budget(scene));
    EXPECT_EQ(last_iterations(capped), own) << "and the policy raises nothing past the default's own choice";
    EXPECT_EQ(last_substeps(world, capped), own_substeps);
}

// Down its ladder a flag comes to step every 8th frame. At the floor's
// iterations the budget's cap of one substep would make that one substep
// of 8/60 s, which stretches a flag far past its limit, so the step runs
// two of 1/15 s; below the floor the budget wins: one substep.
TEST(Budget, ABudgetsCapsLeaveNoSubstepLongerThanAFifteenthOfASecondDownToTheFloor) {
    SceneConfig config = four_flags(1);
    config.solver.kind = CLOTH_SOLVER_DEFAULT;
    config.copies = 1;
    Scene scene(config);
    ASSERT_TRUE(scene.ok()) << scene.error();
    cloth_quality_policy policy = cloth_default_quality_policy();
    policy.enabled = true;
    policy.max_update_rate = 8;
    ASSERT_EQ(cloth_set_quality_policy(scene.cloth(), &policy), CLOTH_OK);
    for (int i = 0; i < 15; ++i) ASSERT_EQ(scene.step(kDt), CLOTH_OK);
    const uint32_t floor = (last_iterations(scene.cloth()) + 1) / 2;  // half the default's own, rounded up
    ASSERT_EQ(cloth_world_set_frame_budget(scene.world(), kNoStepMeets), CLOTH_OK);
    int at_floor = 0, below_floor = 0, frames_at_rate_8 = 0;
    for (int i = 0; i < 300; ++i) {
        step_under_budget(scene);
        uint32_t rate = 0, phase = 0;
        ASSERT_EQ(cloth_get_update_rate(scene.cloth(), &rate, &phase), CLOTH_OK);
        frames_at_rate_8 = rate == 8 ? frames_at_rate_8 + 1 : 0;
        if (frames_at_rate_8 <= 16) continue;  // its last step ran at rate 8
        cloth_stats stats{};
        stats.struct_size = sizeof stats;
        ASSERT_EQ(cloth_get_stats(scene.cloth(), &stats), CLOTH_OK);
        if (stats.last_max_iterations >= floor) {
            EXPECT_EQ(stats.last_substeps, 2u) << "frame " << i << ": 8/60 s in substeps of at most 1/15 s";
            ++at_floor;
        } else {
            EXPECT_EQ(stats.last_substeps, 1u) << "frame " << i << ": below the floor the budget wins";
            ++below_floor;
        }
    }
    EXPECT_GT(at_floor, 0) << "the flag stepped at rate 8 at its floor";
    EXPECT_GT(below_floor, 0) << "and went below it under a budget no step meets";
}

// The policy's maxima bound the default's own choice, budget or not: a
// host that gives a cloth one substep gets one substep.
TEST(Budget, APolicysMaximaBoundTheDefaultSolversOwnChoice) {
    SceneConfig config = four_flags(1);
    config.solver.kind = CLOTH_SOLVER_DEFAULT;
    Scene scene(config);
    ASSERT_TRUE(scene.ok()) << scene.error();
    const cloth_id bounded = scene.cloths()[0], free_running = scene.cloths().back();
    const cloth_world_id world = scene.world();
    ASSERT_EQ(cloth_world_set_profiling(world, 1u << 16), CLOTH_OK);
    for (int i = 0; i < 5; ++i) ASSERT_EQ(scene.step(kDt), CLOTH_OK);
    const uint32_t own = last_iterations(free_running), own_substeps = last_substeps(world, free_running);
    ASSERT_GT(own, 2u) << "the default iterates more than twice here";
    ASSERT_GT(own_substeps, 1u) << "and runs more than one substep";

    cloth_quality_policy policy = cloth_default_quality_policy();
    policy.enabled = true;
    policy.max_iterations = 2;
    policy.max_substeps = 1;
    ASSERT_EQ(cloth_set_quality_policy(bounded, &policy), CLOTH_OK);
    for (int i = 0; i < 5; ++i) {
        ASSERT_EQ(scene.step(kDt), CLOTH_OK);
        EXPECT_EQ(last_iterations(bounded), 2u) << "frame " << i;
        EXPECT_EQ(last_substeps(world, bounded), 1u) << "frame " << i;
        EXPECT_EQ(last_iterations(free_running), own)
            << "a cloth without a policy keeps the default's choice";
        EXPECT_EQ(last_substeps(world, free_running), own_substeps);
    }

    policy.enabled = false;
    ASSERT_EQ(cloth_set_quality_policy(bounded, &policy), CLOTH_OK);
    ASSERT_EQ(scene.step(kDt), CLOTH_OK);
    EXPECT_EQ(last_iterations(bounded), own) << "a disabled policy bounds nothing";
    EXPECT_EQ(last_substeps(world, bounded), own_substeps);
}

TEST(Budget, PolicyBoundsAreValidatedAndEnablingClampsTheSolver) {
    Scene scene(four_flags(20));
    ASSERT_TRUE(scene.ok());
    const cloth_id cloth = scene.cloth();
    cloth_quality_policy policy = cloth_default_quality_policy();
    EXPECT_FALSE(policy.enabled) << "off by default";
    policy.min_iterations = 0;
    EXPECT_EQ(cloth_set_quality_policy(cloth, &policy), CLOTH_ERROR_INVALID_VALUE);
    policy = cloth_default_quality_policy();
    policy.min_substeps = 5;
    policy.max_substeps = 4;
    EXPECT_EQ(cloth_set_quality_policy(cloth, &policy), CLOTH_ERROR_INVALID_VALUE);
    EXPECT_EQ(cloth_world_set_frame_budget(scene.world(), -1.0f), CLOTH_ERROR_INVALID_VALUE);
    EXPECT_EQ(iterations_of(cloth), 20u) << "rejected calls changed nothing";
    policy = cloth_default_quality_policy();
    policy.enabled = true;
    policy.max_iterations = 8;
    ASSERT_EQ(cloth_set_quality_policy(cloth, &policy), CLOTH_OK);
    EXPECT_EQ(iterations_of(cloth), 8u);
}

// A cloth whose strain limiter needs more passes than it was asked for (1 kg
// per particle hanging from two corners: springs stay past the limit) runs
// them while it has time, and only the passes asked for once the policy has
// taken it below its floor: behind a solve that no longer holds the cloth,
// those passes, and not the frame, must not be the thing that grows.
TEST(Budget, AClothBelowItsFloorRunsOnlyTheStrainLimitPassesAskedFor) {
    const cloth::testing::PinnedCloth pinned(1.0f);  // 1 kg per particle
    const cloth_world_id world = pinned.world;
    const cloth_id cloth = pinned.cloth;
    cloth_strain_limit limit = cloth_default_strain_limit();
    limit.max_strain = 0.08f;
    ASSERT_EQ(cloth_set_strain_limit(cloth, &limit), CLOTH_OK);
    cloth_quality_policy policy = cloth_default_quality_policy();
    policy.enabled = true;
    ASSERT_EQ(cloth_set_quality_policy(cloth, &policy), CLOTH_OK);
    ASSERT_EQ(cloth_world_set_profiling(world, 1u << 16), CLOTH_OK);  // stage task counts
    // Rounds of the strain limiter per substep: its tasks over the force
    // stage's (one task per group and substep each).
    const auto strain_rounds = [&] {
        const cloth_frame_profile p = profile_of(world);
        return static_cast<double>(p.stage_tasks[CLOTH_STAGE_STRAIN_LIMIT]) /
               p.stage_tasks[CLOTH_STAGE_FORCES];
    };
    // A tether round and two rounds (corrections, moves) per pass.
    const double asked = 1.0 + 2.0 * limit.iterations;
    double most = 0;
    for (int i = 0; i < 30; ++i) {
        ASSERT_EQ(cloth_step(world, kDt), CLOTH_OK);
        most = std::max(most, strain_rounds());
    }
    EXPECT_GT(most, asked) << "with time to spare it runs more passes than asked for";
    ASSERT_EQ(cloth_world_set_frame_budget(world, 1e-6f), CLOTH_OK);  // no step meets it: always lowered
    // Down to the floor's last rung in one frame; below it once
    // kLoadOverruns frames have run over budget.
    const int below = static_cast<int>(cloth::BudgetPolicy::kLoadOverruns) + 1;
    for (int i = 0; i < below + 10; ++i) {
        ASSERT_EQ(cloth_step(world, kDt), CLOTH_ERROR_OVER_BUDGET);
        if (i > 0 && i < below - 1) {
            EXPECT_GT(strain_rounds(), asked) << "frame " << i << ": at the floor it keeps its extra passes";
        }
        if (i >= below) {
            EXPECT_LE(strain_rounds(), asked) << "frame " << i;
        }
    }
}

// Recovery from a budget blow-out: a budget no step can meet makes every
// step return CLOTH_ERROR_OVER_BUDGET and log a warning with that code, yet
// the cloths end in the same bits as in a world without a budget, and once
// the budget is lifted steps return CLOTH_OK again.
TEST(Budget, ABlowOutIsReportedWithItsOwnCodeAndLosesNothing) {
    struct Log {
        int warnings = 0;
        cloth_result last = CLOTH_OK;
    } log;
    SceneConfig config = four_flags(4);
    config.world.log = [](cloth_log_level level, cloth_result code, const char*, void* user) {
        auto* l = static_cast<Log*>(user);
        if (level == CLOTH_LOG_WARNING) ++l->warnings;
        l->last = code;
    };
    config.world.user = &log;
    Scene budgeted(config);
    Scene reference(four_flags(4));
    ASSERT_TRUE(budgeted.ok() && reference.ok());
    ASSERT_EQ(cloth_world_set_frame_budget(budgeted.world(), 1e-6f), CLOTH_OK);
    for (int i = 0; i < 20; ++i) {
        ASSERT_EQ(budgeted.step(kDt), CLOTH_ERROR_OVER_BUDGET) << "frame " << i;
        ASSERT_EQ(reference.step(kDt), CLOTH_OK);
    }
    EXPECT_EQ(log.warnings, 20);
    EXPECT_EQ(log.last, CLOTH_ERROR_OVER_BUDGET);
    EXPECT_NE(std::string(cloth_get_last_error()).find("over the frame budget"), std::string::npos);
    EXPECT_EQ(profile_of(budgeted.world()).overrun_frames, 20u);
    for (size_t c = 0; c < budgeted.cloths().size(); ++c) {
        std::vector<float> a(3 * static_cast<size_t>(budgeted.particle_count()));
        std::vector<float> b(a.size());
        ASSERT_EQ(cloth_read_positions(budgeted.cloths()[c], a.data(), static_cast<uint32_t>(a.size())),
                  CLOTH_OK);
        ASSERT_EQ(cloth_read_positions(reference.cloths()[c], b.data(), static_cast<uint32_t>(b.size())),
                  CLOTH_OK);
        EXPECT_EQ(a, b) << "cloth " << c << " advanced exactly as without a budget";
    }
    ASSERT_EQ(cloth_world_set_frame_budget(budgeted.world(), 0.0f), CLOTH_OK);
    EXPECT_EQ(budgeted.step(kDt), CLOTH_OK) << "no budget, no overrun";
}

}  // namespace
