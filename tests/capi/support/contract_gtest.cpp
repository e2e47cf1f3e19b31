// The C API contract as GoogleTest expectations (see contract_gtest.h).
#include "support/contract_gtest.h"

#include <cmath>
#include <cstdio>

namespace cloth_test {

std::atomic<int>& bad_inputs() {
    static std::atomic<int> count{0};
    return count;
}

void ExpectRejected(const Watch& watch, const CountingAllocator& host, cloth_result expected,
                    const std::string& what, const std::function<cloth_result()>& call, Logged logged) {
    ++bad_inputs();
    const Unchanged unchanged(watch);
    const size_t logs_before = host.logs().size();
    const CallOutcome outcome = call_on_fresh_thread(call);
    for (const std::string& problem :
         rejection_problems(expected, outcome, host.errors_since(logs_before), logged))
        ADD_FAILURE() << "\n    call: " << what << "\n    " << problem;
    const std::string changed = unchanged.what_changed();
    if (!changed.empty()) ADD_FAILURE() << "\n    call: " << what << "\n    rejected, but " << changed;
}

ClothState ReadState(cloth_id cloth) {
    ClothState state;
    const std::string error = read_cloth_state(cloth, &state);
    EXPECT_EQ(error, "");
    return state;
}

::testing::AssertionResult SameState(const ClothState& before, const ClothState& after, Compare compare) {
    const std::string d = first_difference(before, after, compare);
    if (d.empty()) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << d;
}

::testing::AssertionResult SameFloats(const char* what, const std::vector<float>& before,
                                      const std::vector<float>& after) {
    const std::string d = float_difference(what, before, after);
    if (d.empty()) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << d;
}

bool AllFinite(const std::vector<float>& values) {
    for (float v : values)
        if (!std::isfinite(v)) return false;
    return true;
}

::testing::AssertionResult SameFutureAsTwin(const Watch& world, const Watch& twin, int frames,
                                            const std::function<void(int frame)>& before_each) {
    const std::string d = twin_divergence(world, twin, frames, before_each);
    if (d.empty()) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "the world no longer evolves like its untouched twin: " << d;
}

void ExpectAllReturned(const CountingAllocator& host) {
    EXPECT_EQ(host.live_bytes(), 0u) << "bytes still allocated after cloth_world_destroy";
    EXPECT_EQ(host.live_blocks(), 0u);
    EXPECT_EQ(host.allocations(), host.frees());
    for (const std::string& v : host.violations()) ADD_FAILURE() << "allocator/log misuse: " << v;
    EXPECT_EQ(CountingAllocator::wrong_user_pointers().load(), 0)
        << "a callback received a user pointer that is not desc.user";
}

namespace {

// Prints how many bad inputs the run exercised.
class CountReporter : public ::testing::Environment {
  public:
    void TearDown() override {
        if (bad_inputs() > 0)
            std::printf("[ cloth    ] %d bad inputs exercised through the C API\n", bad_inputs().load());
    }
};
[[maybe_unused]] const auto* const kReporter = ::testing::AddGlobalTestEnvironment(new CountReporter);

}  // namespace
}  // namespace cloth_test
