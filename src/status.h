// The result of a core operation that can fail: a public result code and a
// message for the host. The C API hands both over unchanged.
#pragma once

#include <cloth/cloth.h>

#include <cstdio>
#include <string>

namespace cloth {

struct Status {
    cloth_result code = CLOTH_OK;
    std::string message;

    bool ok() const { return code == CLOTH_OK; }

    template <class... Args>
    static Status error(cloth_result code, const char* format, Args... args) {
        char buffer[512];
        std::snprintf(buffer, sizeof buffer, format, args...);
        return Status{code, buffer};
    }
};

}  // namespace cloth
