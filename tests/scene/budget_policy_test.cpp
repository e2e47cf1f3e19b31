// The frame-budget policy against a model of what frames cost: each frame
// of a rung costs exactly `per_substep + iterations * per_iteration` a
// substep, so every decision is reproducible and the facts the policy
// promises are checked exactly, not through this machine's timing (the
// same policy against measured times: budget_test.cpp).
//
//   - under a budget the top rung cannot meet, a cloth comes down its
//     ladder and, once settled, no frame runs over;
//   - it stops at the floor (half its top's iterations) until a load keeps
//     the frames over budget (BudgetPolicy::kLoadOverruns of the last
//     kLoadWindow), and goes below it one rung a frame;
//   - a spike (one costly frame) moves it as far as its rung's usual cost
//     says, not its own;
//   - the default solver's iterations stay at half its own choice or more
//     while more than one substep runs, and its caps come off under a
//     loose budget, never past its own choice;
//   - a cloth without an enabled policy is never changed;
//   - the least important cloth is lowered first and the most important
//     raised first;
//   - a flapping flag the budget moves to its floor at rate 8 stays within
//     the samples' 12 % (the substeps' length grows step by step, and with
//     the flag's speed), and substeps a cap takes past the default's
//     substep gamma run backward Euler.
//
// And the ladder and the cost memory the policy reads, alone.
#include "scene/budget_policy.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <utility>
#include <vector>

#include "solve/solver_default.h"
#include "step/cloth_measure.h"
#include "test_support.h"

namespace cloth {
namespace {

using cloth::testing::make_grid;
using cloth::testing::uniform_material;

constexpr float kDt = 1.0f / 60.0f;
const Vec3 kGravity(0.0f, -9.81f, 0.0f);

// What a frame costs at the rung it ran, in task nanoseconds.
struct CostModel {
    double per_substep_ns = 100e3;
    double per_iteration_ns = 40e3;  // a solve iteration, each substep
    int64_t cost_ns(QualityRung ran) const {
        return static_cast<int64_t>(ran.substeps * (per_substep_ns + ran.iterations * per_iteration_ns));
    }
    int64_t solve_ns(QualityRung ran) const {
        return static_cast<int64_t>(ran.substeps * ran.iterations * per_iteration_ns);
    }
};

// Cloths stepped for real (their default solver chooses from their state)
// on one thread, each frame costed by the model and handed to the policy
// as World::step does.
class ModelWorld {
  public:
    SceneCloth& add(const SolverSettings& solver, float stiffness) {
        auto scene = std::make_unique<SceneCloth>(cloth::testing::heap(), make_grid(8, 8),
                                                  uniform_material(stiffness, 0.2f, 0.2f), solver,
                                                  cloth::testing::still_air());
        ClothInstance& cloth = scene->cloth();
        cloth.pin(0);
        cloth.pin(7);
        SleepSettings awake;
        awake.enabled = false;  // every cloth runs every frame, as the policy expects of its list
        cloth.set_sleep(awake);
        corners_.push_back(cloth.positions().get(7));
        cloths_.push_back(std::move(scene));
        return *cloths_.back();
    }
    // Every frame from now on moves each cloth's pinned corner 7 around a
    // 2 cm circle once a second, so no cloth comes to rest (a quiet
    // default cloth runs fewer substeps: solver_default.h).
    void keep_moving() { moving_ = true; }
    // One frame; returns whether it ran over `budget_ms`. `spike` multiplies
    // this frame's cost. As in World::step, a cloth at update rate N steps
    // only in the frames it is due, over N frames, and a rate the policy
    // chose takes the phase with the fewest cloths of that rate.
    bool frame(double budget_ms, double spike = 1.0) {
        std::vector<BudgetCloth> costs;
        int64_t total_ns = 0;
        ++frame_;
        if (moving_) {
            const float angle = 2.0f * 3.14159265f * kDt * static_cast<float>(frame_);
            for (size_t c = 0; c < cloths_.size(); ++c)
                cloths_[c]->cloth().set_pin_target(
                    7, corners_[c] + 0.02f * Vec3(std::cos(angle), 0, std::sin(angle)));
        }
        for (auto& cloth : cloths_) {
            if (!cloth->update_rate().due(frame_)) continue;
            const uint32_t frames = cloth->begin_rate_step(frame_);
            EXPECT_TRUE(
                cloth->cloth()
                    .step(kDt * static_cast<float>(frames), kGravity, nullptr, cloth->quality().bounds())
                    .ok());
            const QualityRung ran = cloth->quality().ran_rung();
            const int64_t cost = static_cast<int64_t>(spike * static_cast<double>(model.cost_ns(ran)));
            costs.push_back(
                {cloth.get(), cost, static_cast<int64_t>(spike * model.solve_ns(ran)), cloth->importance()});
            total_ns += cost;
        }
        const double step_ms = static_cast<double>(total_ns) * 1e-6;
        policy_.after_frame(budget_ms, step_ms, frame_, costs.data(), static_cast<uint32_t>(costs.size()));
        for (auto& cloth : cloths_) {
            const uint32_t rate = cloth->quality().take_wanted_rate();
            if (rate == 0) continue;
            uint32_t load[UpdateRate::kSlowest] = {};
            for (const auto& other : cloths_) {
                if (other != cloth && other->update_rate().rate() == rate)
                    ++load[other->update_rate().phase()];
            }
            cloth->set_update_rate(rate, static_cast<uint32_t>(std::min_element(load, load + rate) - load));
        }
        return step_ms > budget_ms;
    }
    int overruns(double budget_ms, int frames) {
        int count = 0;
        for (int i = 0; i < frames; ++i) count += frame(budget_ms) ? 1 : 0;
        return count;
    }
    // The step's cost at every cloth's current rung (the last frame's).
    double step_ms() const {
        double ns = 0;
        for (const auto& cloth : cloths_) {
            const QualityRung ran = cloth->quality().ran_rung();
            ns += static_cast<double>(model.cost_ns(ran)) / ran.rate;
        }
        return ns * 1e-6;
    }
    CostModel model;

  private:
    std::vector<std::unique_ptr<SceneCloth>> cloths_;
    std::vector<Vec3> corners_;  // each cloth's corner 7 where it was pinned
    bool moving_ = false;
    BudgetPolicy policy_;
    uint64_t frame_ = 0;
};

SolverSettings jacobi(uint32_t iterations) {
    SolverSettings s;
    s.kind = CLOTH_SOLVER_JACOBI;
    s.iterations = iterations;
    s.substeps = 1;
    return s;
}

SolverSettings automatic() {
    SolverSettings s;
    s.kind = CLOTH_SOLVER_DEFAULT;
    return s;
}

QualityPolicy policy_on() {
    QualityPolicy policy;
    policy.enabled = true;
    return policy;
}

QualityPolicy sweeps_policy() {
    QualityPolicy p = policy_on();
    p.min_iterations = 1;
    p.max_iterations = 16;
    p.max_substeps = 1;
    return p;
}

TEST(BudgetPolicyModel, ATightBudgetSettlesWithNoFrameOverAndALooseOneRestoresTheTop) {
    ModelWorld world;
    std::vector<SceneCloth*> follow;
    for (int c = 0; c < 3; ++c) {
        SceneCloth& cloth = world.add(jacobi(16), 300.0f);
        cloth.set_quality_policy(sweeps_policy());
        follow.push_back(&cloth);
    }
    SceneCloth& fixed = world.add(jacobi(1), 300.0f);  // no policy

    world.frame(1e9);
    const double full_ms = world.step_ms();
    // 40% of the top: below what even the floor (8 sweeps) costs, so the
    // cloths must go below it, which takes a load of kLoadOverruns frames.
    const double budget = 0.4 * full_ms;
    int first_frames_over = 0;
    for (uint32_t i = 0; i < BudgetPolicy::kLoadWindow; ++i) first_frames_over += world.frame(budget) ? 1 : 0;
    EXPECT_GE(first_frames_over, static_cast<int>(BudgetPolicy::kLoadOverruns))
        << "the floor alone cannot meet this budget";
    for (int i = 0; i < 60; ++i) world.frame(budget);
    EXPECT_EQ(world.overruns(budget, 60), 0) << "settled: no frame over budget";
    for (SceneCloth* cloth : follow) {
        EXPECT_LT(cloth->quality().settings().iterations, 8u) << "below the floor, under a load";
        EXPECT_GE(cloth->quality().settings().iterations, 1u);
    }
    EXPECT_EQ(fixed.quality().settings().iterations, 1u) << "a cloth without a policy keeps its settings";
    EXPECT_LE(world.step_ms(), budget);

    for (int i = 0; i < 300; ++i) world.frame(100 * full_ms);
    for (SceneCloth* cloth : follow)
        EXPECT_EQ(cloth->quality().settings().iterations, 16u) << "back to the top";
    EXPECT_EQ(world.overruns(100 * full_ms, 5), 0);
}

TEST(BudgetPolicyModel, AtTheFloorOnlyALoadTakesAClothLowerAndThenOneRungAFrame) {
    ModelWorld world;
    SceneCloth& cloth = world.add(jacobi(16), 300.0f);
    cloth.set_quality_policy(sweeps_policy());
    const QualityLadder ladder = cloth.quality().ladder();
    ASSERT_EQ(ladder.floor(), 8u);

    // A budget nothing meets: the first frame takes the cloth to the
    // floor, and it stays there until kLoadOverruns frames have run over.
    for (uint32_t i = 1; i < BudgetPolicy::kLoadOverruns; ++i) {
        EXPECT_TRUE(world.frame(1e-9));
        EXPECT_EQ(cloth.quality().settings().iterations, 8u) << "frame " << i << ": at the floor";
    }
    uint32_t last = cloth.quality().settings().iterations;
    for (int i = 0; i < 10; ++i) {
        EXPECT_TRUE(world.frame(1e-9));
        const uint32_t now = cloth.quality().settings().iterations;
        EXPECT_EQ(now, last > 1 ? last - 1 : 1u) << "below the floor: one rung a frame";
        last = now;
    }
}

TEST(BudgetPolicyModel, ASpikeMovesAClothOnlyAsFarAsItsRungsUsualCostSays) {
    ModelWorld world;
    SceneCloth& cloth = world.add(jacobi(16), 300.0f);
    cloth.set_quality_policy(sweeps_policy());
    world.frame(1e9);
    const double budget = 1.2 * world.step_ms();
    for (int i = 0; i < 20; ++i) EXPECT_FALSE(world.frame(budget));
    EXPECT_EQ(cloth.quality().settings().iterations, 16u) << "within budget: at the top";
    EXPECT_TRUE(world.frame(budget, 10.0)) << "a frame ten times its usual cost";
    // Judged by the usual cost, 16 sweeps (740 us) are just over kLowerTo of
    // the budget (0.75 * 1.2 * 740 = 666 us): 14 sweeps (660 us) meet it.
    // Judged by the spike, nothing above the floor (8 sweeps) would.
    EXPECT_EQ(cloth.quality().settings().iterations, 14u);
}

TEST(BudgetPolicyModel, TheLeastImportantClothsAreLoweredFirstAndTheMostImportantRaisedFirst) {
    ModelWorld world;
    SceneCloth& near = world.add(jacobi(16), 300.0f);
    SceneCloth& mid = world.add(jacobi(16), 300.0f);
    SceneCloth& far = world.add(jacobi(16), 300.0f);
    near.set_importance(4.0f);
    far.set_importance(0.25f);
    for (SceneCloth* c : {&near, &mid, &far}) c->set_quality_policy(sweeps_policy());
    world.frame(1e9);
    const double full_ms = world.step_ms();
    // Each costs 740 us at 16 sweeps and 420 us at its floor (8): with the
    // two others at their floor the step (1580 us) is within kLowerTo of
    // this budget, so the most important cloth stays at its top.
    const double budget = 0.96 * full_ms;
    for (int i = 0; i < 60; ++i) world.frame(budget);
    EXPECT_EQ(near.quality().settings().iterations, 16u) << "the most important keeps its top";
    EXPECT_EQ(far.quality().settings().iterations, 8u) << "the least important pays first";
    EXPECT_EQ(mid.quality().settings().iterations, 8u);
    EXPECT_EQ(world.overruns(budget, 30), 0);

    // A budget whose calm leaves room for five more sweeps (200 us below
    // kRaiseTo of it): the calm raises both, and then the more important
    // takes the least important's sweeps (it goes back to its floor): all
    // five go to it, the step within kRaiseTo of the budget.
    const double looser = (1580e3 + 200e3) * 1e-6 / BudgetPolicy::kRaiseTo;
    for (int i = 0; i < 300; ++i) world.frame(looser);
    EXPECT_EQ(near.quality().settings().iterations, 16u);
    EXPECT_EQ(mid.quality().settings().iterations, 13u)
        << "the more important rises first, paid for by the less";
    EXPECT_EQ(far.quality().settings().iterations, 8u);
    EXPECT_LE(world.step_ms(), BudgetPolicy::kRaiseTo * looser * (1 + 1e-9));
    EXPECT_EQ(world.overruns(looser, 30), 0);
}

TEST(BudgetPolicyModel, AtTheFloorASlowerRateComesBeforeFewerIterationsAndGoesFirstOnTheWayUp) {
    ModelWorld world;
    QualityPolicy policy = sweeps_policy();
    policy.max_update_rate = 4;
    std::vector<SceneCloth*> cloths;
    for (int c = 0; c < 4; ++c) {
        cloths.push_back(&world.add(jacobi(16), 300.0f));
        cloths.back()->set_quality_policy(policy);
    }
    world.frame(1e9);
    const double full_ms = world.step_ms();
    // At the floor (8 sweeps) a step costs 0.57 of the top's: within
    // kLowerTo of this budget the cloths must step at rates 2 and 4.
    const double budget = 0.3 * full_ms;
    for (int i = 0; i < 30; ++i) world.frame(budget);
    for (SceneCloth* cloth : cloths) {
        EXPECT_GE(cloth->update_rate().rate(), 2u) << "no load needed: each step keeps its quality";
        EXPECT_EQ(cloth->quality().settings().iterations, 8u) << "at the floor, not below it";
    }
    EXPECT_LE(world.step_ms(), BudgetPolicy::kLowerTo * budget);
    EXPECT_EQ(world.overruns(budget, 40), 0) << "staggered: the frames share the steps";
    // Raising: a cloth's rate comes back to 1 before its sweeps return.
    bool sweeps_before_rate = false;
    for (int i = 0; i < 400; ++i) {
        world.frame(100 * full_ms);
        for (SceneCloth* cloth : cloths)
            sweeps_before_rate |=
                cloth->update_rate().rate() > 1 && cloth->quality().settings().iterations > 8;
    }
    EXPECT_FALSE(sweeps_before_rate);
    for (SceneCloth* cloth : cloths) {
        EXPECT_EQ(cloth->update_rate().rate(), 1u);
        EXPECT_EQ(cloth->quality().settings().iterations, 16u) << "back to the top";
    }
    // Without max_update_rate the same budget takes them below the floor
    // instead, under a load.
    ModelWorld fixed_rate;
    std::vector<SceneCloth*> others;
    for (int c = 0; c < 4; ++c) {
        others.push_back(&fixed_rate.add(jacobi(16), 300.0f));
        others.back()->set_quality_policy(sweeps_policy());
    }
    for (int i = 0; i < 60; ++i) fixed_rate.frame(budget);
    for (SceneCloth* cloth : others) {
        EXPECT_EQ(cloth->update_rate().rate(), 1u);
        EXPECT_LT(cloth->quality().settings().iterations, 8u);
    }
}

// A quiet default cloth runs one substep, but its ladder's top stays the
// moving cloth's choice: a rung the budget picks while it rests is one of
// the moving cloth's ladder, not one counted down from the quiet frame.
TEST(BudgetPolicyModel, AQuietDefaultClothKeepsTheMovingClothsLadder) {
    ModelWorld world;
    SceneCloth& resting = world.add(automatic(), 20000.0f);
    resting.set_quality_policy(policy_on());
    world.frame(1e9);
    const QualityRung moving = resting.quality().ran_rung();
    ASSERT_GT(moving.substeps, 1u) << "released from rest, it runs the moving cloth's substeps";
    for (int i = 0; i < 600 && resting.quality().ran_rung().substeps != 1; ++i) world.frame(1e9);
    ASSERT_EQ(resting.quality().ran_rung().substeps, 1u) << "quiet within 10 s";
    EXPECT_EQ(resting.quality().ladder().top.substeps, moving.substeps);
    EXPECT_EQ(resting.quality().ladder().top.iterations, moving.iterations);
}

// A stiff cloth at 60 Hz: the default solver chooses several iterations
// and substeps by itself.
TEST(BudgetPolicyModel, TheDefaultKeepsHalfItsIterationsWhileSubstepsCanGoAndGetsItsOwnChoiceBack) {
    ModelWorld world;
    SceneCloth& capped = world.add(automatic(), 20000.0f);
    SceneCloth& free_running = world.add(automatic(), 20000.0f);  // no policy
    world.keep_moving();  // the default's own choice stays what it is in the first frame
    capped.set_quality_policy(policy_on());

    world.frame(1e9);
    const QualityRung own = free_running.quality().ran_rung();
    ASSERT_GT(own.iterations, 1u) << "the default iterates more than once here";
    ASSERT_GT(own.substeps, 1u) << "and runs more than one substep";
    ASSERT_EQ(capped.quality().ran_rung().iterations, own.iterations) << "no budget, no cap";

    // The free-running cloth alone costs half the step: at 80% of it the
    // capped one must come down to its fewest substeps.
    const double budget = 0.8 * world.step_ms();
    bool capped_below_own = false;
    for (int i = 0; i < 60; ++i) {
        world.frame(budget);
        const QualityRung ran = capped.quality().ran_rung();
        if (ran.substeps > 1) {
            EXPECT_GE(2 * ran.iterations, own.iterations)
                << "frame " << i << ": iterations at half their own or more while " << ran.substeps
                << " substeps run";
        }
        capped_below_own |= ran.substeps < own.substeps;
    }
    EXPECT_TRUE(capped_below_own) << "the policy took substeps away";
    EXPECT_EQ(free_running.quality().ran_rung().iterations, own.iterations)
        << "a cloth without a policy keeps the default's choice";
    EXPECT_EQ(free_running.quality().ran_rung().substeps, own.substeps);
    EXPECT_EQ(world.overruns(budget, 30), 0) << "settled: no frame over budget";

    const double loose = 100 * budget;
    for (int i = 0; i < 300; ++i) world.frame(loose);
    EXPECT_EQ(capped.quality().ran_rung().iterations, own.iterations) << "the caps came off";
    EXPECT_EQ(capped.quality().ran_rung().substeps, own.substeps);
    EXPECT_FALSE(capped.quality().can_rise()) << "and nothing is raised past the default's own choice";
}

// A 1 m flag of the field sample's fabric (40x40, 0.25 kg/m^2, the
// default springs) pinned along one edge, flapping in gusts at full
// quality for two seconds; then the budget's floor at rate 8 (half the
// default's iterations, one substep asked), steps of 8 frames at once.
// Returns the largest strain after any of those steps.
float worst_strain_at_rate_8_after_flapping() {
    Material material;
    material.area_density = 0.25f;
    AeroParams air;
    SceneCloth scene(cloth::testing::heap(), make_grid(40, 40), material, automatic(), air);
    ClothInstance& flag = scene.cloth();
    for (uint32_t r = 0; r < 40; ++r) flag.pin(r * 40);
    SleepSettings awake;
    awake.enabled = false;
    flag.set_sleep(awake);
    QualityPolicy policy = policy_on();
    policy.max_substeps = 16;
    policy.max_update_rate = 8;
    scene.set_quality_policy(policy);
    auto gust = [&](uint64_t frame) {
        const float t = kDt * static_cast<float>(frame);
        flag.aero().wind = Vec3(8.0f + 2.0f * std::sin(0.9f * t), 0.0f, 1.0f + 1.5f * std::sin(1.9f * t));
    };
    uint64_t frame = 0;
    while (++frame <= 120) {
        gust(frame);
        EXPECT_TRUE(flag.step(kDt, kGravity, nullptr, scene.quality().bounds()).ok());
    }
    SolverSettings floor = scene.quality().settings();
    floor.iterations = (floor.iterations + 1) / 2;
    floor.substeps = 1;
    scene.quality().set_settings(floor);
    scene.set_update_rate(8, 0);
    float worst = 0;
    for (; frame <= 120 + 8 * 30; ++frame) {
        if (!scene.update_rate().due(frame)) continue;
        gust(frame);
        const uint32_t frames = scene.begin_rate_step(frame);
        EXPECT_TRUE(
            flag.step(kDt * static_cast<float>(frames), kGravity, nullptr, scene.quality().bounds()).ok());
        worst = std::max(worst, measure(flag, kGravity).max_strain);
    }
    return worst;
}

TEST(CappedSubsteps, AFlappingFlagTheBudgetStepsEightFramesAtOnceStaysWithinTwelvePercent) {
    // The samples' check on the default's 8 % limit. Without the bounds on
    // a capped substep its first slow step reaches 0.147.
    EXPECT_LE(worst_strain_at_rate_8_after_flapping(), 0.12f);
}

// A stiff 16x16 cloth (k / m past the default's substep gamma in one
// substep of 1/60 s) hanging from two corners: the theta the frame ran.
float theta_of_a_frame(const QualityPolicy& policy, uint32_t budget_substep_cap) {
    SceneCloth scene(cloth::testing::heap(), make_grid(16, 16), uniform_material(3e4f, 0.0f, 0.1f),
                     automatic(), cloth::testing::still_air());
    ClothInstance& cloth = scene.cloth();
    cloth.pin(0);
    cloth.pin(15);
    scene.set_quality_policy(policy);
    EXPECT_TRUE(cloth.step(kDt, kGravity, nullptr, scene.quality().bounds()).ok());
    if (budget_substep_cap > 0) {  // as BudgetPolicy sets it, below the last frame's own choice
        SolverSettings caps = scene.quality().settings();
        caps.substeps = budget_substep_cap;
        scene.quality().set_settings(caps);
        EXPECT_TRUE(cloth.step(kDt, kGravity, nullptr, scene.quality().bounds()).ok());
        EXPECT_EQ(cloth.last_frame_solver().substeps, budget_substep_cap);
    }
    return cloth.last_frame_solver().theta;
}

TEST(CappedSubsteps, PastTheSubstepGammaRunBackwardEulerWhoeverChoseThem) {
    EXPECT_EQ(theta_of_a_frame(QualityPolicy{}, 0), kDefaultTheta) << "the default's own substeps";
    QualityPolicy one = policy_on();
    one.max_substeps = 1;
    EXPECT_EQ(theta_of_a_frame(one, 0), 1.0f) << "a policy's bound of one substep, no budget";
    EXPECT_EQ(theta_of_a_frame(policy_on(), 1), 1.0f) << "a budget's cap of one substep";
}

TEST(CappedSubsteps, GrowStepByStepAndWithTheSpeedNeverBelowTheFloor) {
    const float edge = 0.025f;
    EXPECT_EQ(longest_capped_substep(0.0f, 0.0f, edge), kLongestCappedSubstep) << "a still cloth, no history";
    EXPECT_FLOAT_EQ(longest_capped_substep(1.0f / 60.0f, 0.0f, edge), kCappedSubstepGrowth / 60.0f);
    EXPECT_FLOAT_EQ(longest_capped_substep(0.0f, 2.0f, edge), kCappedSubstepEdges * edge / 2.0f)
        << "three rest edges at the fastest particle's speed";
    EXPECT_EQ(longest_capped_substep(1.0f / 240.0f, 20.0f, edge), kCappedSubstepBoundFloor)
        << "never below the floor: at 60 Hz the budget keeps its one-substep rungs";
    EXPECT_EQ(longest_capped_substep(1.0f, 0.01f, 0.0f), kLongestCappedSubstep) << "no edges: no speed bound";
}

// The ladder: iterations down to half the top's, then a substep with the
// iterations back at the top's, ...; at the fewest substeps down to the
// minimum; up retraces it rung by rung.
TEST(QualityLadder, GivesUpIterationsToHalfBeforeEachSubstepAndRetracesItsStepsUp) {
    const QualityLadder ladder{{5, 3}, 1, 1};
    EXPECT_EQ(ladder.floor(), 3u);
    const std::vector<std::pair<uint32_t, uint32_t>> expected = {
        {5, 3}, {4, 3}, {3, 3}, {5, 2}, {4, 2}, {3, 2}, {5, 1}, {4, 1}, {3, 1}, {2, 1}, {1, 1}};
    QualityRung rung = ladder.top;
    std::vector<std::pair<uint32_t, uint32_t>> down = {{rung.iterations, rung.substeps}};
    while (ladder.down(rung)) down.emplace_back(rung.iterations, rung.substeps);
    EXPECT_EQ(down, expected);
    std::vector<std::pair<uint32_t, uint32_t>> up = {{rung.iterations, rung.substeps}};
    while (ladder.up(rung)) up.emplace_back(rung.iterations, rung.substeps);
    const std::vector<std::pair<uint32_t, uint32_t>> reversed(expected.rbegin(), expected.rend());
    EXPECT_EQ(up, reversed);
    // Settings made outside the ladder are read as its nearest rung.
    const QualityRung between = ladder.rung_of(1, 3), past = ladder.rung_of(9, 9);
    EXPECT_EQ(std::make_pair(between.iterations, between.substeps), std::make_pair(3u, 3u));
    EXPECT_EQ(std::make_pair(past.iterations, past.substeps), std::make_pair(5u, 3u));
    // The floor's last rung and those below it.
    EXPECT_TRUE(ladder.at_or_below_floor({3, 1}));
    EXPECT_TRUE(ladder.at_or_below_floor({1, 1}));
    EXPECT_FALSE(ladder.at_or_below_floor({4, 1}));
    EXPECT_FALSE(ladder.at_or_below_floor({3, 2}));
    // With rates, they come at the floor's last rung, before the rungs below it.
    const QualityLadder rates{{5, 2}, 1, 1, 4};
    std::vector<std::vector<uint32_t>> walk;
    QualityRung r = rates.top;
    walk.push_back({r.iterations, r.substeps, r.rate});
    while (rates.down(r)) walk.push_back({r.iterations, r.substeps, r.rate});
    const std::vector<std::vector<uint32_t>> expected_walk = {{5, 2, 1}, {4, 2, 1}, {3, 2, 1}, {5, 1, 1},
                                                              {4, 1, 1}, {3, 1, 1}, {3, 1, 2}, {3, 1, 4},
                                                              {2, 1, 4}, {1, 1, 4}};
    EXPECT_EQ(walk, expected_walk);
    std::vector<std::vector<uint32_t>> back = {{r.iterations, r.substeps, r.rate}};
    while (rates.up(r)) back.push_back({r.iterations, r.substeps, r.rate});
    EXPECT_EQ(back, std::vector<std::vector<uint32_t>>(expected_walk.rbegin(), expected_walk.rend()));
    EXPECT_TRUE(rates.rate_is_next({3, 1, 1}));
    EXPECT_FALSE(rates.rate_is_next({3, 1, 4}));
    EXPECT_FALSE(ladder.rate_is_next({3, 1})) << "a ladder without rates";
    // Bounds above the top (a policy minimum over the default's own choice)
    // leave one rung.
    const QualityLadder tight{{2, 1}, 4, 2};
    QualityRung only = tight.top;
    EXPECT_FALSE(tight.down(only));
    EXPECT_FALSE(tight.up(only));
}

// The cost memory: a moving average per rung, forgotten after a while.
TEST(QualityCosts, AveragesWhatARungCostAndForgetsRungsNotRunForLong) {
    QualityCosts costs;
    const QualityRung a{5, 2}, b{3, 1};
    EXPECT_LT(costs.cost_ns(a, 0), 0.0) << "unknown";
    costs.record(a, 1000.0, 1);
    costs.record(a, 2000.0, 2);
    EXPECT_DOUBLE_EQ(costs.cost_ns(a, 2), 1000.0 + QualityCosts::kWeight * 1000.0);
    costs.record(b, 500.0, 3);
    EXPECT_DOUBLE_EQ(costs.cost_ns(b, 3), 500.0);
    EXPECT_LT(costs.cost_ns(a, 2 + QualityCosts::kForgetFrames), 0.0) << "forgotten";
    // More rungs than it keeps: the one run longest ago goes.
    for (uint32_t i = 0; i < QualityCosts::kRungs; ++i) costs.record({10 + i, 1}, 1.0, 10 + i);
    EXPECT_LT(costs.cost_ns(a, 20), 0.0);
}

}  // namespace
}  // namespace cloth
