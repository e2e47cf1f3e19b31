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
