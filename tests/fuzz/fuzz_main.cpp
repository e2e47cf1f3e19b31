// libFuzzer entry point of the C API fuzz harness (clang, CLOTH_FUZZ=ON).
// scripts/fuzz builds and runs it; see api_sequence.h for what it checks.
// At exit it prints how many C API calls the run made and how many of them
// the library rejected with an error code (bad inputs handled).
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include "api_sequence.h"

namespace {
cloth_fuzz::RunStats g_total;
unsigned long long g_inputs = 0;

void print_totals() {
    std::printf("cloth fuzz: %llu inputs, %llu C API calls, %llu rejected with an error code, %llu steps\n",
                g_inputs, static_cast<unsigned long long>(g_total.calls),
                static_cast<unsigned long long>(g_total.rejected),
                static_cast<unsigned long long>(g_total.steps));
}
}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    std::atexit(print_totals);
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const cloth_fuzz::RunStats s = cloth_fuzz::run_api_sequence(data, size);
    ++g_inputs;
    g_total.calls += s.calls;
    g_total.rejected += s.rejected;
    g_total.steps += s.steps;
    return 0;
}
