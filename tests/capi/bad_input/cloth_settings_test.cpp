// Bad solver, spring, aerodynamic and wind settings are rejected and the old settings stay.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <utility>

#include "bad_input/fixture.h"

namespace cloth_bad_input {
namespace {

TEST_F(BadInput, SetSolverWithAWrongStructSizeReturnsInvalidDescAndKeepsTheSolver) {
    cloth_solver_settings zero;
    std::memset(&zero, 0, sizeof zero);
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_DESC, cloth_set_solver(a_.cloth, &zero));
    for (uint32_t size :
         {0u, uint32_t(sizeof(cloth_solver_settings) - 1), uint32_t(sizeof(cloth_solver_settings) + 1)}) {
        SCOPED_TRACE("struct_size " + std::to_string(size));
        cloth_solver_settings s = cloth_default_solver_settings();
        s.kind = CLOTH_SOLVER_CG;  // a visible change, if it were accepted
        s.struct_size = size;
        EXPECT_REJECTED(CLOTH_ERROR_INVALID_DESC, cloth_set_solver(a_.cloth, &s));
    }
}

TEST_F(BadInput, SetSolverOutOfRangeIsRejectedAndTheSolverIsUnchanged) {
    for (const auto& [what, change, expected] : BadSolver()) {
        SCOPED_TRACE(what);
        cloth_solver_settings s = cloth_default_solver_settings();
        s.substeps = 3;  // a visible change, if it were accepted...
        change(s);       // ...but one field is out of range
        EXPECT_REJECTED(expected, cloth_set_solver(a_.cloth, &s));
    }
}

TEST_F(BadInput, SetSpringParamsNegativeOrNonFiniteIsRejectedAndKeepsTheOldParams) {
    const std::pair<cloth_spring_params, cloth_result> cases[] = {
        {{-1.0f, 0.5f}, CLOTH_ERROR_INVALID_VALUE}, {{1000.0f, -0.5f}, CLOTH_ERROR_INVALID_VALUE},
        {{kNaN, 0.5f}, CLOTH_ERROR_NOT_FINITE},     {{kInf, 0.5f}, CLOTH_ERROR_NOT_FINITE},
        {{1000.0f, kNaN}, CLOTH_ERROR_NOT_FINITE},  {{1000.0f, -kInf}, CLOTH_ERROR_NOT_FINITE},
    };
    for (uint32_t kinds : {uint32_t{CLOTH_SPRING_STRUCTURAL},
                           uint32_t{CLOTH_SPRING_SHEAR | CLOTH_SPRING_BEND}, uint32_t{CLOTH_SPRING_ALL}}) {
        for (const auto& c : cases) {
            const cloth_spring_params params = c.first;
            SCOPED_TRACE("kinds " + std::to_string(kinds) + " {" + std::to_string(params.stiffness) + ", " +
                         std::to_string(params.damping) + "}");
            EXPECT_REJECTED(c.second, cloth_set_spring_params(a_.cloth, kinds, params));
        }
    }
}

TEST_F(BadInput, SetAeroOutOfRangeIsRejectedAndKeepsTheOldAero) {
    for (const auto& [what, change, expected] : BadAero()) {
        SCOPED_TRACE(what);
        cloth_aero_params aero = cloth_default_desc().aero;
        aero.wind[1] = 5.0f;  // a visible change, if it were accepted
        change(aero);
        EXPECT_REJECTED(expected, cloth_set_aero(a_.cloth, &aero));
    }
}

TEST_F(BadInput, SetWindNonFiniteReturnsNotFiniteAndKeepsTheOldWind) {
    for (int axis = 0; axis < 3; ++axis) {
        for (float bad : {kNaN, kInf, -kInf}) {
            SCOPED_TRACE("wind[" + std::to_string(axis) + "] = " + std::to_string(bad));
            float wind[3] = {10.0f, 10.0f, 10.0f};
            wind[axis] = bad;
            EXPECT_REJECTED(CLOTH_ERROR_NOT_FINITE, cloth_set_wind(a_.cloth, wind));
        }
    }
}

TEST_F(BadInput, GetStatsWithAWrongStructSizeReturnsInvalidDescAndWritesNothing) {
    for (uint32_t size : {0u, uint32_t(sizeof(cloth_stats) - 1), uint32_t(sizeof(cloth_stats) + 1)}) {
        SCOPED_TRACE("struct_size " + std::to_string(size));
        cloth_stats stats;
        std::memset(&stats, 0x5A, sizeof stats);
        stats.struct_size = size;
        cloth_stats copy;
        std::memcpy(&copy, &stats, sizeof stats);
        EXPECT_REJECTED(CLOTH_ERROR_INVALID_DESC, cloth_get_stats(a_.cloth, &stats));
        EXPECT_EQ(std::memcmp(&stats, &copy, sizeof stats), 0)
            << "cloth_get_stats wrote into a rejected struct";
    }
}

// A caller built against 1.6, whose cloth_stats ends before the strain
// limit's fields, or against 1.7 to 1.11, whose ends before the rung the
// last step ran at, keeps working: its fields are filled as a whole
// struct's are, and not a byte past its size is written.
TEST_F(BadInput, GetStatsWithAnOlderStructSizeFillsThatPrefixOnly) {
    for (const size_t old_size :
         {offsetof(cloth_stats, strain_limit_excess), offsetof(cloth_stats, last_max_iterations)}) {
        SCOPED_TRACE("struct_size " + std::to_string(old_size));
        cloth_stats whole{};
        whole.struct_size = sizeof whole;
        ASSERT_EQ(cloth_get_stats(a_.cloth, &whole), CLOTH_OK);
        cloth_stats old;
        std::memset(&old, 0x5A, sizeof old);
        old.struct_size = static_cast<uint32_t>(old_size);
        ASSERT_EQ(cloth_get_stats(a_.cloth, &old), CLOTH_OK);
        whole.struct_size = old.struct_size;
        EXPECT_EQ(std::memcmp(&old, &whole, old_size), 0) << "the older fields differ from a whole struct's";
        const unsigned char* tail = reinterpret_cast<const unsigned char*>(&old) + old_size;
        for (size_t b = 0; b < sizeof old - old_size; ++b)
            EXPECT_EQ(tail[b], 0x5A) << "byte " << old_size + b;
    }
}

}  // namespace
}  // namespace cloth_bad_input
