/* C helpers for the C++ contract tests: in C an enum argument may hold any
 * int, and a C caller can pass one. C++ code cannot even form such a value
 * without undefined behaviour (UBSan reports the load), so the tests that
 * pass out-of-range enums to the library go through here. */
#include <cloth/cloth.h>
#include <stdint.h>

const char* cloth_test_stage_name_of_int(int32_t value);

const char* cloth_test_stage_name_of_int(int32_t value) { return cloth_stage_name((cloth_stage)value); }

size_t cloth_test_struct_size_of_int(int32_t value);

size_t cloth_test_struct_size_of_int(int32_t value) { return cloth_struct_size((cloth_struct_kind)value); }
