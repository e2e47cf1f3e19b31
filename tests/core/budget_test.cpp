// The frame-budget policy: with a budget well below what the cloths cost,
// their iterations go down and the share of frames over budget drops; with
// a loose budget they go back up to the policy's maximum; cloths without
// an enabled policy are never changed; an overrun is reported in the
// profile, never as a failed step.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

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

// Median step time over `frames` frames.
double median_step_ms(Scene& scene, int frames) {
    std::vector<double> ms;
    for (int i = 0; i < frames; ++i) {
        EXPECT_EQ(scene.step(kDt), CLOTH_OK);
        ms.push_back(profile_of(scene.world()).step_ms);
    }
    std::nth_element(ms.begin(), ms.begin() + ms.size() / 2, ms.end());
    return ms[ms.size() / 2];
}

// Frames over budget among the next `frames`, each a CLOTH_OK step.
int overruns(Scene& scene, int frames) {
    int count = 0;
    for (int i = 0; i < frames; ++i) {
        EXPECT_EQ(scene.step(kDt), CLOTH_OK) << "an overrun is not a failed step";
        count += profile_of(scene.world()).overrun ? 1 : 0;
    }
    return count;
}

TEST(Budget, ATightBudgetLowersIterationsAndOverrunsDropALooseOneRaisesThemAgain) {
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
    ASSERT_EQ(cloth_set_solver(fixed, &one_sweep), CLOTH_OK);  // cheap, so the others can meet the budget

    // 16 sweeps cost about (16 + 3) / (1 + 3) = 4.75 times one sweep per
    // substep; a budget of 40% of the measured cost lies between them.
    const double full_ms = median_step_ms(scene, 15);
    ASSERT_EQ(cloth_world_set_frame_budget(scene.world(), static_cast<float>(full_ms * 0.4)), CLOTH_OK);
    const int early = overruns(scene, 3);
    EXPECT_GE(early, 2) << "at full quality the frames overrun 40% of their cost";
    for (int i = 0; i < 60; ++i) ASSERT_EQ(scene.step(kDt), CLOTH_OK);
    const uint32_t lowered = iterations_of(scene.cloths()[0]);
    EXPECT_LT(lowered, 16u) << "iterations went down";
    EXPECT_GE(lowered, 1u);
    EXPECT_EQ(iterations_of(fixed), 1u) << "a cloth without a policy keeps its settings";
    const int late = overruns(scene, 30);
    EXPECT_LT(late / 30.0, early / 3.0) << "the overrun rate dropped (machine noise permitting)";
    EXPECT_GT(profile_of(scene.world()).overrun_frames, 0u);

    // A loose budget: the policy raises them back to the maximum.
    ASSERT_EQ(cloth_world_set_frame_budget(scene.world(), static_cast<float>(full_ms * 20.0)), CLOTH_OK);
    for (int i = 0; i < 200 && iterations_of(scene.cloths()[0]) < 16; ++i)
        ASSERT_EQ(scene.step(kDt), CLOTH_OK);
    EXPECT_EQ(iterations_of(scene.cloths()[0]), 16u) << "iterations went back up";
    EXPECT_EQ(overruns(scene, 5), 0);
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

}  // namespace
