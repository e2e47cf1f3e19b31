#include "errors.h"

#include <cstring>

namespace cloth {
namespace {
thread_local char last_error[1024] = "";
}

void set_last_error(const char* message) {
    std::strncpy(last_error, message, sizeof last_error - 1);
    last_error[sizeof last_error - 1] = '\0';
}

void end_at_utf8_boundary(char* text) {
    const size_t length = std::strlen(text);
    size_t lead = length;
    // Back over at most three continuation bytes (top bits 10) to the sequence's first byte.
    while (lead > 0 && length - lead < 3 && (static_cast<unsigned char>(text[lead - 1]) & 0xC0) == 0x80) {
        --lead;
    }
    if (lead == 0) return;
    const unsigned char first = static_cast<unsigned char>(text[lead - 1]);
    const size_t needed = first < 0x80             ? 1
                          : (first & 0xE0) == 0xC0 ? 2
                          : (first & 0xF0) == 0xE0 ? 3
                          : (first & 0xF8) == 0xF0 ? 4
                                                   : 1;
    if (lead - 1 + needed > length) text[lead - 1] = '\0';
}

}  // namespace cloth

extern "C" {

CLOTH_API const char* cloth_get_last_error(void) { return cloth::last_error; }

CLOTH_API const char* cloth_result_name(cloth_result result) {
    switch (result) {
        case CLOTH_OK:
            return "CLOTH_OK";
        case CLOTH_ERROR_NULL_POINTER:
            return "CLOTH_ERROR_NULL_POINTER";
        case CLOTH_ERROR_INVALID_HANDLE:
            return "CLOTH_ERROR_INVALID_HANDLE";
        case CLOTH_ERROR_INVALID_DESC:
            return "CLOTH_ERROR_INVALID_DESC";
        case CLOTH_ERROR_INVALID_COUNT:
            return "CLOTH_ERROR_INVALID_COUNT";
        case CLOTH_ERROR_INDEX_OUT_OF_RANGE:
            return "CLOTH_ERROR_INDEX_OUT_OF_RANGE";
        case CLOTH_ERROR_NOT_FINITE:
            return "CLOTH_ERROR_NOT_FINITE";
        case CLOTH_ERROR_INVALID_VALUE:
            return "CLOTH_ERROR_INVALID_VALUE";
        case CLOTH_ERROR_DEGENERATE_GEOMETRY:
            return "CLOTH_ERROR_DEGENERATE_GEOMETRY";
        case CLOTH_ERROR_OUT_OF_MEMORY:
            return "CLOTH_ERROR_OUT_OF_MEMORY";
        case CLOTH_ERROR_CAPACITY:
            return "CLOTH_ERROR_CAPACITY";
        case CLOTH_ERROR_IO:
            return "CLOTH_ERROR_IO";
        case CLOTH_ERROR_NONFINITE_STATE:
            return "CLOTH_ERROR_NONFINITE_STATE";
        case CLOTH_ERROR_SOLVER_FAILED:
            return "CLOTH_ERROR_SOLVER_FAILED";
        case CLOTH_ERROR_INTERNAL:
            return "CLOTH_ERROR_INTERNAL";
        case CLOTH_ERROR_OVER_BUDGET:
            return "CLOTH_ERROR_OVER_BUDGET";
        case CLOTH_ERROR_CORRUPT_SNAPSHOT:
            return "CLOTH_ERROR_CORRUPT_SNAPSHOT";
        case CLOTH_RESULT_FORCE_U32:
            break;
    }
    return "CLOTH_ERROR_UNKNOWN";
}

}  // extern "C"
