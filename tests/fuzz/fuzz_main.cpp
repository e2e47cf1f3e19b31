// libFuzzer entry point of the C API fuzz harness (clang, CLOTH_FUZZ=ON).
// scripts/fuzz builds and runs it; see api_sequence.h for what it checks.
#include <cstddef>
#include <cstdint>

#include "api_sequence.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    cloth_fuzz::run_api_sequence(data, size);
    return 0;
}
