// Result names and the per-thread last-error message of the C API.
#pragma once

#include <cloth/cloth.h>

namespace cloth {

// Store `message` as this thread's last error.
void set_last_error(const char* message);

}  // namespace cloth
