// The C API contract of contract.h as GoogleTest expectations, for the
// contract tests (the fuzzer uses contract.h alone).
#pragma once

#include <gtest/gtest.h>

#include <atomic>
#include <functional>
#include <string>

#include "support/contract.h"
#include "support/counting_allocator.h"

namespace cloth_test {

// Rejected calls checked so far; every contract test binary prints the
// total when it ends.
std::atomic<int>& bad_inputs();

// Makes `call` on a fresh thread and expects it rejected with `expected`:
// the clauses of rejection_problems (code, last error, the log `host`
// received) and nothing `watch` names changed. `what` names the call in
// failures.
void ExpectRejected(const Watch& watch, const CountingAllocator& host, cloth_result expected,
                    const std::string& what, const std::function<cloth_result()>& call,
                    Logged logged = Logged::kYes);

// A fixture that defines
//   void ExpectRejected(cloth_result, const std::string&, const std::function<cloth_result()>&,
//                       cloth_test::Logged = cloth_test::Logged::kYes)
// (usually forwarding to the function above with its watch) gets these;
// a failure names the line of the test.
#define EXPECT_REJECTED(expected, call) CLOTH_EXPECT_REJECTED_((expected), call, ::cloth_test::Logged::kYes)
// For a call whose handle names no live world, so that no log need hear of it.
#define EXPECT_REJECTED_MAYBE_LOGGED(expected, call) \
    CLOTH_EXPECT_REJECTED_((expected), call, ::cloth_test::Logged::kMaybe)
// For a call that names no live world: no log may hear of it.
#define EXPECT_REJECTED_NOT_LOGGED(expected, call) \
    CLOTH_EXPECT_REJECTED_((expected), call, ::cloth_test::Logged::kNo)
#define CLOTH_EXPECT_REJECTED_(expected, call, logged)                                         \
    do {                                                                                       \
        const ::testing::ScopedTrace cloth_call_site_(__FILE__, __LINE__, #call);              \
        ExpectRejected((expected), #call, [&]() -> cloth_result { return (call); }, (logged)); \
    } while (false)

// The state of a cloth (a failed read is a test failure).
ClothState ReadState(cloth_id cloth);

::testing::AssertionResult SameState(const ClothState& before, const ClothState& after, Compare compare = {});
::testing::AssertionResult SameFloats(const char* what, const std::vector<float>& before,
                                      const std::vector<float>& after);
bool AllFinite(const std::vector<float>& values);

// Steps a world and its twin together `frames` times (see twin_divergence).
::testing::AssertionResult SameFutureAsTwin(const Watch& world, const Watch& twin, int frames,
                                            const std::function<void(int frame)>& before_each = {});

// After cloth_world_destroy: the allocator holds nothing, saw no misuse,
// and no callback got a foreign user pointer.
void ExpectAllReturned(const CountingAllocator& host);

}  // namespace cloth_test
