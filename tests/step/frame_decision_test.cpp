// The frame's decision (step/frame_decision.h), rule by rule: each row
// gives what the host set, the budget's bounds, the last frame's record
// and the motion, and what the frame must run.
#include "step/frame_decision.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "solve/solver_default.h"

namespace cloth {
namespace {

constexpr float kFrame = 1.0f / 60.0f;
constexpr float kSoft = 1e4f;   // k / m, 1/s^2: gamma 2.8 at 60 Hz
constexpr float kStiff = 4e8f;  // gamma 1.1e5: three substeps for multigrid's 2e4

FrameInputs the_default(float stiffness_per_mass = kSoft, float dt = kFrame) {
    FrameInputs in;
    in.host.kind = CLOTH_SOLVER_DEFAULT;
    in.dt = dt;
    in.stiffness_per_mass = stiffness_per_mass;
    in.multigrid = true;
    return in;
}

BudgetBounds policy(uint32_t max_iterations, uint32_t max_substeps, uint32_t iterations = 0,
                    uint32_t substeps = 0) {
    BudgetBounds b;
    b.enabled = true;
    b.min_iterations = 1;
    b.max_iterations = max_iterations;
    b.max_substeps = max_substeps;
    b.iterations = iterations;
    b.substeps = substeps;
    return b;
}

struct Row {
    std::string rule;
    FrameInputs in;
    uint32_t iterations, substeps;
    float theta;
    uint32_t own_iterations, own_substeps, capped_substeps;
    bool below_floor;
    uint32_t strain_passes_cap;
};

std::vector<Row> rows() {
    std::vector<Row> r;
    {
        FrameInputs in;
        in.host.kind = CLOTH_SOLVER_JACOBI;
        in.host.iterations = 3;
        in.host.substeps = 2;
        in.host.strain_limit = StrainLimit{0.1f, 5};
        in.dt = kFrame;
        in.stiffness_per_mass = kStiff;
        r.push_back({"a kind the host chose runs as set, with four times its strain passes at most", in, 3, 2,
                     1.0f, 3, 2, 2, false, 20});
        in.budget = policy(8, 4, 6, 3);
        r.push_back({"a kind the host chose runs the budget's rung, above the host's settings too", in, 6, 3,
                     1.0f, 6, 3, 3, false, 20});
        in.budget = policy(8, 4, 3, 1);
        r.push_back({"a kind the host chose, below the floor of the policy's maxima", in, 3, 1, 1.0f, 3, 1, 1,
                     true, 5});
    }
    r.push_back(
        {"the default's substep rule: substeps of at most 1/120 s, multigrid's 5 iterations, theta 0.7",
         the_default(), 5, 2, kDefaultTheta, 5, 2, 2, false, 4 * kDefaultStrainLimitPasses});
    r.push_back({"the default's substep rule: a substep gamma of at most 2e4 (multigrid's)",
                 the_default(kStiff), 5, 3, kDefaultTheta, 5, 3, 3, false, 4 * kDefaultStrainLimitPasses});
    {
        FrameInputs in = the_default();
        in.host.substeps = 4;
        r.push_back({"the default's substep rule: the host's substeps are a lower bound", in, 5, 4,
                     kDefaultTheta, 5, 4, 4, false, 4 * kDefaultStrainLimitPasses});
    }
    {
        FrameInputs in = the_default(kStiff);
        in.budget = policy(3, 1);
        r.push_back(
            {"a policy's maxima bound the default's own choice; one substep past the gamma runs "
             "backward Euler",
             in, 3, 1, 1.0f, 3, 1, 1, false, 4 * kDefaultStrainLimitPasses});
    }
    {
        FrameInputs in = the_default();
        in.budget = policy(8, 4, 3);
        r.push_back({"a budget's iteration cap at the ladder's floor (half the top's, rounded up)", in, 3, 2,
                     kDefaultTheta, 5, 2, 2, false, 4 * kDefaultStrainLimitPasses});
        in.budget = policy(8, 4, 2);
        r.push_back(
            {"a budget's iteration cap below the floor: the strain limiter runs only the passes asked", in, 2,
             2, kDefaultTheta, 5, 2, 2, true, kDefaultStrainLimitPasses});
    }
    {
        FrameInputs in = the_default(kSoft, 4 * kFrame);  // a step of four frames (update rate 4)
        in.budget = policy(8, 16, 0, 1);
        in.last.decision.h = kFrame;
        r.push_back({"a budget's substep cap: the substep at most twice the last one (1/30 s)", in, 5, 2,
                     kDefaultTheta, 5, 8, 1, false, 4 * kDefaultStrainLimitPasses});
        in.last.decision.h = kFrame * 2;
        r.push_back({"a budget's substep cap: the substep grows to 1/15 s at most", in, 5, 1, kDefaultTheta,
                     5, 8, 1, false, 4 * kDefaultStrainLimitPasses});
        in.last.decision.h = kFrame * 2;
        in.fastest_free_speed = 3.0f;
        in.mean_rest_length = 0.02f;
        r.push_back(
            {"a budget's substep cap: a fast particle crosses at most three edges (1/50 s, never below "
             "1/60 s)",
             in, 5, 4, kDefaultTheta, 5, 8, 1, false, 4 * kDefaultStrainLimitPasses});
        in.budget = policy(8, 16, 1, 1);
        r.push_back({"a budget's substep cap below the floor: the substep is as long as the cap makes it", in,
                     1, 1, kDefaultTheta, 5, 8, 1, true, kDefaultStrainLimitPasses});
    }
    {
        FrameInputs in = the_default();
        in.last.quiet = in.starts_slow = in.pins_slow = true;
        r.push_back({"a quiet cloth takes substeps of up to 1/60 s (its own choice is a moving cloth's)", in,
                     5, 1, kDefaultTheta, 5, 2, 1, false, 4 * kDefaultStrainLimitPasses});
        in.pins_slow = false;
        r.push_back({"not quiet where a pin moves", in, 5, 2, kDefaultTheta, 5, 2, 2, false,
                     4 * kDefaultStrainLimitPasses});
    }
    return r;
}

TEST(FrameDecision, EveryRuleGivesTheSettingsItsRowAsksFor) {
    for (const Row& row : rows()) {
        const FrameDecision d = decide_frame(row.in);
        EXPECT_EQ(d.solver.iterations, row.iterations) << row.rule;
        EXPECT_EQ(d.solver.substeps, row.substeps) << row.rule;
        EXPECT_EQ(d.solver.theta, row.theta) << row.rule;
        EXPECT_EQ(d.own_iterations, row.own_iterations) << row.rule;
        EXPECT_EQ(d.own_substeps, row.own_substeps) << row.rule;
        EXPECT_EQ(d.capped_substeps, row.capped_substeps) << row.rule;
        EXPECT_EQ(d.below_floor, row.below_floor) << row.rule;
        EXPECT_EQ(d.strain_passes_cap, row.strain_passes_cap) << row.rule;
        EXPECT_EQ(d.h, row.in.dt / static_cast<float>(row.substeps)) << row.rule;
    }
}

TEST(FrameDecision, TheDefaultResolvesToMultigridPcgWithTheDefaultStrainLimit) {
    const FrameDecision d = decide_frame(the_default());
    EXPECT_EQ(d.solver.kind, CLOTH_SOLVER_PCG);
    EXPECT_TRUE(d.solver.multigrid);
    EXPECT_EQ(d.solver.strain_limit.max_strain, kDefaultStrainLimit);
    EXPECT_FALSE(d.started_slow);
    FrameInputs slow = the_default();
    slow.starts_slow = true;
    EXPECT_TRUE(decide_frame(slow).started_slow) << "the next frame's record: it started slow";
}

TEST(FrameDecision, AClothInContactSharesTheMoreSubstepsAndNeverFewer) {
    FrameInputs in = the_default(kStiff);
    in.budget = policy(3, 1);
    const FrameDecision one = decide_frame(in);
    ASSERT_EQ(one.solver.substeps, 1u);
    const FrameDecision shared = share_substeps(one, 3, in);
    EXPECT_EQ(shared.solver.substeps, 3u);
    EXPECT_EQ(shared.h, in.dt / 3.0f);
    EXPECT_EQ(shared.solver.theta, 1.0f) << "theta never rises back within a frame's decision";
    EXPECT_EQ(shared.capped_substeps, 1u) << "the rung the budget put it on";
    const FrameDecision fewer = share_substeps(decide_frame(the_default()), 1, the_default());
    EXPECT_EQ(fewer.solver.substeps, 2u);

    // Raised past the default's own theta switch: a cloth whose own two
    // substeps are within the gamma keeps theta 0.7 at three.
    const FrameDecision own = decide_frame(the_default());
    EXPECT_EQ(share_substeps(own, 3, the_default()).solver.theta, kDefaultTheta);
}

TEST(FrameDecision, TheLadderFloorIsHalfTheTopRoundedUpAndAtLeastThePolicysLeast) {
    EXPECT_EQ(ladder_floor(5, 1), 3u);
    EXPECT_EQ(ladder_floor(8, 1), 4u);
    EXPECT_EQ(ladder_floor(8, 6), 6u);
    EXPECT_EQ(ladder_floor(4, 9), 4u) << "never above the top";
    EXPECT_EQ(ladder_floor(1, 1), 1u);
}

}  // namespace
}  // namespace cloth
