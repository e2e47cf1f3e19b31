// The result of a core operation that can fail: a public result code and a
// message for the host. The message lives in a fixed buffer, so reporting
// a failure never allocates (it may be reporting a failed allocation).
#pragma once

#include <cloth/cloth.h>

#include <cstdio>

namespace cloth {

struct Status {
    cloth_result code = CLOTH_OK;
    char message[384] = "";

    bool ok() const { return code == CLOTH_OK; }

    template <class... Args>
    static Status error(cloth_result code, const char* format, Args... args) {
        Status status;
        status.code = code;
        std::snprintf(status.message, sizeof status.message, format, args...);
        return status;
    }
    static Status error(cloth_result code, const char* message) {
        Status status;
        status.code = code;
        std::snprintf(status.message, sizeof status.message, "%s", message);
        return status;
    }
};

}  // namespace cloth
