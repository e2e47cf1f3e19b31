// Result names and the per-thread last-error message of the C API.
#pragma once

#include <cloth/cloth.h>

namespace cloth {

// Store `message` as this thread's last error.
void set_last_error(const char* message);

// Cut a UTF-8 sequence that a truncating format left incomplete at the end
// of `text`: messages echo caller strings (an OBJ path), and cloth.h
// promises them as UTF-8.
void end_at_utf8_boundary(char* text);

}  // namespace cloth
