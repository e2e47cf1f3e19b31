// Each error reaches the log and the per-thread last error; result and stage names are never NULL.
#include <cstdint>
#include <functional>
#include <string>
#include <thread>
#include <utility>

#include "bad_input/fixture.h"

// tests/capi/enum_from_int.c: an out-of-range enum passed the way a C caller can.
extern "C" const char* cloth_test_stage_name_of_int(int32_t value);

namespace cloth_bad_input {
namespace {

TEST_F(BadInput, LogCallbackReceivesEachErrorWithItsCodeAndTheLastErrorMessage) {
    const float nan_wind[3] = {kNaN, 0.0f, 0.0f};
    const uint32_t bad_index[] = {kParticles};
    struct Call {
        cloth_result expected;
        std::function<cloth_result()> call;
    };
    const Call calls[] = {
        {CLOTH_ERROR_NOT_FINITE, [&] { return cloth_set_wind(a_.cloth, nan_wind); }},
        {CLOTH_ERROR_INDEX_OUT_OF_RANGE, [&] { return cloth_pin(a_.cloth, bad_index, 1); }},
        {CLOTH_ERROR_INVALID_VALUE, [&] { return cloth_step(a_.world, 0.0f); }},
        {CLOTH_ERROR_NULL_POINTER, [&] { return cloth_world_set_gravity(a_.world, nullptr); }},
    };
    for (const Call& c : calls) {
        const size_t before = a_.host.logs().size();
        const cloth_result r = c.call();
        EXPECT_EQ(r, c.expected) << result_name(r);
        size_t errors = 0;
        for (size_t i = before; i < a_.host.logs().size(); ++i)
            errors += a_.host.logs()[i].level == CLOTH_LOG_ERROR;
        ASSERT_EQ(errors, 1u) << "expected exactly one error logged for " << result_name(c.expected);
        const LogEntry& e = a_.host.logs().back();
        EXPECT_EQ(e.level, CLOTH_LOG_ERROR);
        EXPECT_EQ(e.code, c.expected) << result_name(e.code);
        EXPECT_EQ(e.message, std::string(cloth_get_last_error()));
        EXPECT_NE(e.message, "");
    }
    // Successful calls log no error.
    const size_t before = a_.host.logs().size();
    ASSERT_EQ(cloth_step(a_.world, kFrame), CLOTH_OK);
    ASSERT_EQ(cloth_step(b_.world, kFrame), CLOTH_OK);
    for (size_t i = before; i < a_.host.logs().size(); ++i)
        EXPECT_NE(a_.host.logs()[i].level, CLOTH_LOG_ERROR);
    // The twin world saw none of the errors above.
    for (const LogEntry& e : b_.host.logs()) EXPECT_NE(e.level, CLOTH_LOG_ERROR) << e.message;
}

TEST_F(BadInput, LastErrorIsPerThread) {
    const float nan_wind[3] = {kNaN, 0.0f, 0.0f};
    std::string main_message;
    std::string other_before, other_after;
    std::thread first([&] {
        EXPECT_EQ(cloth_set_wind(a_.cloth, nan_wind), CLOTH_ERROR_NOT_FINITE);
        main_message = cloth_get_last_error();
        std::thread second([&] {
            other_before = cloth_get_last_error();
            EXPECT_EQ(cloth_step(a_.world, -1.0f), CLOTH_ERROR_INVALID_VALUE);
            other_after = cloth_get_last_error();
        });
        second.join();
        EXPECT_EQ(std::string(cloth_get_last_error()), main_message)
            << "another thread's failure replaced this thread's last error";
    });
    first.join();
    EXPECT_NE(main_message, "");
    EXPECT_EQ(other_before, "") << "a thread sees another thread's last error";
    EXPECT_NE(other_after, "");
    EXPECT_NE(other_after, main_message);
}

TEST_F(BadInput, LastErrorKeepsTheMessageOfTheLastFailedCallAcrossSuccessfulCalls) {
    std::string failed, after_success;
    std::thread t([&] {
        EXPECT_EQ(cloth_step(a_.world, 0.0f), CLOTH_ERROR_INVALID_VALUE);
        failed = cloth_get_last_error();
        uint32_t count = 0;
        EXPECT_EQ(cloth_get_particle_count(a_.cloth, &count), CLOTH_OK);
        after_success = cloth_get_last_error();
    });
    t.join();
    EXPECT_NE(failed, "");
    EXPECT_EQ(after_success, failed)
        << "the header: \"the message of the last failed call made on this thread\"";
}

// A C host may pass any int where the header says cloth_stage (or any other
// enum): the library reads it without undefined behaviour (UBSan checks this
// in the sanitizer build; the fuzzer once found it) and answers "?".
TEST_F(BadInput, StageNameOfAnIntOutsideTheEnumIsAQuestionMark) {
    for (int32_t bad : {int32_t{-1}, int32_t{99}, int32_t{0x7FFFFFFF}, static_cast<int32_t>(0x8000057Au)}) {
        ++cloth_test::bad_inputs();
        const char* name = cloth_test_stage_name_of_int(bad);
        ASSERT_NE(name, nullptr) << bad;
        EXPECT_STREQ(name, "?") << bad;
    }
    EXPECT_STREQ(cloth_stage_name(CLOTH_STAGE_AIR), "air");
}

TEST_F(BadInput, ResultNameIsTheEnumeratorNameAndNeverNull) {
    const std::pair<cloth_result, const char*> names[] = {
        {CLOTH_OK, "CLOTH_OK"},
        {CLOTH_ERROR_NULL_POINTER, "CLOTH_ERROR_NULL_POINTER"},
        {CLOTH_ERROR_INVALID_HANDLE, "CLOTH_ERROR_INVALID_HANDLE"},
        {CLOTH_ERROR_INVALID_DESC, "CLOTH_ERROR_INVALID_DESC"},
        {CLOTH_ERROR_INVALID_COUNT, "CLOTH_ERROR_INVALID_COUNT"},
        {CLOTH_ERROR_INDEX_OUT_OF_RANGE, "CLOTH_ERROR_INDEX_OUT_OF_RANGE"},
        {CLOTH_ERROR_NOT_FINITE, "CLOTH_ERROR_NOT_FINITE"},
        {CLOTH_ERROR_INVALID_VALUE, "CLOTH_ERROR_INVALID_VALUE"},
        {CLOTH_ERROR_DEGENERATE_GEOMETRY, "CLOTH_ERROR_DEGENERATE_GEOMETRY"},
        {CLOTH_ERROR_OUT_OF_MEMORY, "CLOTH_ERROR_OUT_OF_MEMORY"},
        {CLOTH_ERROR_CAPACITY, "CLOTH_ERROR_CAPACITY"},
        {CLOTH_ERROR_IO, "CLOTH_ERROR_IO"},
        {CLOTH_ERROR_NONFINITE_STATE, "CLOTH_ERROR_NONFINITE_STATE"},
        {CLOTH_ERROR_SOLVER_FAILED, "CLOTH_ERROR_SOLVER_FAILED"},
        {CLOTH_ERROR_INTERNAL, "CLOTH_ERROR_INTERNAL"},
        {CLOTH_ERROR_OVER_BUDGET, "CLOTH_ERROR_OVER_BUDGET"},
        {CLOTH_ERROR_CORRUPT_SNAPSHOT, "CLOTH_ERROR_CORRUPT_SNAPSHOT"},
    };
    for (const auto& [code, name] : names) {
        const char* got = cloth_result_name(code);
        ASSERT_NE(got, nullptr) << static_cast<int>(code);
        EXPECT_STREQ(got, name);
    }
    for (int bad : {17, 99, -1, 0x7FFFFFFF}) {
        ++cloth_test::bad_inputs();
        const char* got = cloth_result_name(static_cast<cloth_result>(bad));
        ASSERT_NE(got, nullptr) << "cloth_result_name(" << bad << ") returned NULL";
        EXPECT_NE(std::string(got), "") << bad;
    }
}

}  // namespace
}  // namespace cloth_bad_input
