// A bad dt changes nothing, a cloth that goes non-finite is restored, a step allocates nothing.
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "bad_input/fixture.h"

namespace cloth_bad_input {
namespace {

TEST_F(BadInput, StepWithDtNotInZeroToOneReturnsInvalidValueAndAdvancesNothing) {
    for (float dt : {0.0f, -0.0f, -kFrame, -1.0f, std::nextafter(1.0f, 2.0f), 2.0f, 1e30f}) {
        SCOPED_TRACE("dt = " + std::to_string(dt));
        EXPECT_REJECTED(CLOTH_ERROR_INVALID_VALUE, cloth_step(a_.world, dt));
    }
}

// A dt inside (0, 1] but below CLOTH_MIN_DT (denormals among them) is the
// caller's range error, refused before any cloth moves, for every solver.
TEST_F(BadInput, StepWithDtBelowTheMinimumReturnsInvalidValueForEverySolverAndAdvancesNothing) {
    const float tiny[] = {
        std::numeric_limits<float>::denorm_min(), 1e-40f, std::numeric_limits<float>::min(), 1e-30f, 1e-7f,
        std::nextafter(CLOTH_MIN_DT, 0.0f)};
    for (cloth_solver_kind kind : {CLOTH_SOLVER_DEFAULT, CLOTH_SOLVER_JACOBI, CLOTH_SOLVER_CG,
                                   CLOTH_SOLVER_EXPLICIT, CLOTH_SOLVER_PCG, CLOTH_SOLVER_CHEBYSHEV}) {
        cloth_solver_settings solver = cloth_default_solver_settings();
        solver.kind = kind;
        solver.substeps = 4;
        for (const Scene* s : {&a_, &b_}) {
            ASSERT_EQ(cloth_set_solver(s->cloth, &solver), CLOTH_OK);
            ASSERT_EQ(cloth_set_solver(s->other, &solver), CLOTH_OK);
        }
        for (float dt : tiny) {
            SCOPED_TRACE("solver " + std::to_string(kind) + ", dt = " + std::to_string(dt));
            EXPECT_REJECTED(CLOTH_ERROR_INVALID_VALUE, cloth_step(a_.world, dt));
        }
    }
}

// The smallest dt steps every solver kind, with the most substeps, pins
// moving and a carrier, to a finite state.
TEST_F(BadInput, StepWithTheMinimumDtAdvancesEverySolverFinitely) {
    check_twin_ = false;
    const uint32_t corner[] = {0};
    const float target[3] = {1e-6f, 0.0f, 0.0f};  // 1 m/s over one step
    for (cloth_solver_kind kind : {CLOTH_SOLVER_DEFAULT, CLOTH_SOLVER_JACOBI, CLOTH_SOLVER_CG,
                                   CLOTH_SOLVER_EXPLICIT, CLOTH_SOLVER_PCG, CLOTH_SOLVER_CHEBYSHEV}) {
        SCOPED_TRACE("solver " + std::to_string(kind));
        cloth_solver_settings solver = cloth_default_solver_settings();
        solver.kind = kind;
        solver.substeps = CLOTH_MAX_SUBSTEPS;
        ASSERT_EQ(cloth_set_solver(a_.cloth, &solver), CLOTH_OK);
        ASSERT_EQ(cloth_set_pin_targets(a_.cloth, corner, target, 1), CLOTH_OK);
        for (int frame = 0; frame < 3; ++frame) {
            EXPECT_EQ(cloth_step(a_.world, CLOTH_MIN_DT), CLOTH_OK) << cloth_get_last_error();
        }
        const ClothState state = ReadState(a_.cloth);
        EXPECT_TRUE(AllFinite(state.positions));
        EXPECT_TRUE(AllFinite(state.velocities));
    }
}

TEST_F(BadInput, StepWithNonFiniteDtReturnsNotFiniteAndAdvancesNothing) {
    for (float dt : {kNaN, kInf, -kInf}) {
        SCOPED_TRACE("dt = " + std::to_string(dt));
        EXPECT_REJECTED(CLOTH_ERROR_NOT_FINITE, cloth_step(a_.world, dt));
    }
}

TEST_F(BadInput, StepThatGoesNonFiniteRestoresThatClothAndStillAdvancesTheOthers) {
    check_twin_ = false;
    // Explicit integration of springs a million times too stiff for the step.
    cloth_solver_settings explicit_solver = cloth_default_solver_settings();
    explicit_solver.kind = CLOTH_SOLVER_EXPLICIT;
    explicit_solver.substeps = 64;
    ASSERT_EQ(cloth_set_solver(a_.cloth, &explicit_solver), CLOTH_OK);
    ASSERT_EQ(cloth_set_spring_params(a_.cloth, CLOTH_SPRING_ALL, cloth_spring_params{1e9f, 0.0f}), CLOTH_OK);
    const ClothState bad_before = ReadState(a_.cloth);
    const ClothState other_before = ReadState(a_.other);
    const size_t logs_before = a_.host.logs().size();

    ++cloth_test::bad_inputs();
    const cloth_test::CallOutcome o =
        cloth_test::call_on_fresh_thread([&] { return cloth_step(a_.world, 0.1f); });
    ASSERT_EQ(o.result, CLOTH_ERROR_NONFINITE_STATE) << result_name(o.result) << ": " << o.error_after;
    EXPECT_NE(o.error_after, "") << "cloth_step failed but cloth_get_last_error() is empty";
    bool logged = false;
    for (size_t i = logs_before; i < a_.host.logs().size(); ++i) {
        logged |= a_.host.logs()[i].level == CLOTH_LOG_ERROR &&
                  a_.host.logs()[i].code == CLOTH_ERROR_NONFINITE_STATE;
    }
    EXPECT_TRUE(logged) << "the log callback did not receive CLOTH_ERROR_NONFINITE_STATE";

    // The exploded cloth is back to its state before the call, bit for bit.
    const ClothState bad_after = ReadState(a_.cloth);
    EXPECT_TRUE(SameFloats("position", bad_before.positions, bad_after.positions));
    EXPECT_TRUE(SameFloats("velocity", bad_before.velocities, bad_after.velocities));
    EXPECT_TRUE(SameState(bad_before, bad_after, cloth_test::Compare{/*step_diagnostics=*/false}));
    EXPECT_EQ(bad_after.stats.last_step_result, CLOTH_ERROR_NONFINITE_STATE)
        << result_name(bad_after.stats.last_step_result);

    // The healthy cloth advanced in the same call, exactly as it does in the
    // twin world where nothing blew up.
    const ClothState other_after = ReadState(a_.other);
    EXPECT_FALSE(SameFloats("position", other_before.positions, other_after.positions))
        << "the healthy cloth did not advance";
    EXPECT_TRUE(AllFinite(other_after.positions));
    EXPECT_TRUE(AllFinite(other_after.velocities));
    EXPECT_EQ(other_after.stats.last_step_result, CLOTH_OK)
        << result_name(other_after.stats.last_step_result);
    ASSERT_EQ(cloth_step(b_.world, 0.1f), CLOTH_OK) << cloth_get_last_error();
    EXPECT_TRUE(SameState(ReadState(b_.other), other_after))
        << "the healthy cloth did not advance as it does in an identical world without the blow-up";

    // With sane settings the restored cloth steps again and reports OK.
    const cloth_desc defaults = cloth_default_desc();
    ASSERT_EQ(cloth_set_solver(a_.cloth, &defaults.solver), CLOTH_OK);
    ASSERT_EQ(cloth_set_spring_params(a_.cloth, CLOTH_SPRING_STRUCTURAL, defaults.structural), CLOTH_OK);
    ASSERT_EQ(cloth_set_spring_params(a_.cloth, CLOTH_SPRING_SHEAR, defaults.shear), CLOTH_OK);
    ASSERT_EQ(cloth_set_spring_params(a_.cloth, CLOTH_SPRING_BEND, defaults.bend), CLOTH_OK);
    EXPECT_EQ(cloth_step(a_.world, kFrame), CLOTH_OK) << cloth_get_last_error();
    const ClothState recovered = ReadState(a_.cloth);
    EXPECT_TRUE(AllFinite(recovered.positions));
    EXPECT_EQ(recovered.stats.last_step_result, CLOTH_OK) << result_name(recovered.stats.last_step_result);
}

TEST_F(BadInput, StepAndPinAllocateNothingSoTheySucceedWhileTheAllocatorFails) {
    check_twin_ = false;
    const ClothState before = ReadState(a_.cloth);
    const size_t live_before = a_.host.live_bytes();
    a_.host.fail_after(0);
    const cloth_test::CallOutcome o =
        cloth_test::call_on_fresh_thread([&] { return cloth_step(a_.world, kFrame); });
    EXPECT_EQ(o.result, CLOTH_OK) << result_name(o.result) << " " << o.error_after;
    EXPECT_FALSE(SameFloats("position", before.positions, ReadState(a_.cloth).positions))
        << "the step advanced";
    std::vector<uint32_t> all(kParticles);
    for (uint32_t i = 0; i < kParticles; ++i) all[i] = i;
    EXPECT_EQ(cloth_pin(a_.cloth, all.data(), kParticles), CLOTH_OK) << cloth_get_last_error();
    EXPECT_EQ(cloth_unpin(a_.cloth, all.data(), kParticles), CLOTH_OK) << cloth_get_last_error();
    a_.host.fail_after(-1);
    EXPECT_EQ(a_.host.live_bytes(), live_before) << "no host memory taken or released";
}

}  // namespace
}  // namespace cloth_bad_input
