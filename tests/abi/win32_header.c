/*
 * The public header's _WIN32 branch compiles as warning-free C99: CMake
 * checks this file with MinGW-w64 as a static library's user, as a DLL's
 * user (CLOTH_USING_SHARED: dllimport) and while building the DLL
 * (CLOTH_BUILDING_SHARED: dllexport). Syntax only; nothing is linked.
 */
#include <cloth/cloth.h>

#if !defined(_WIN32)
#error "compile this file with a Windows compiler (x86_64-w64-mingw32-gcc)"
#endif

/* An imported function's address is not a constant in C: take it at run time. */
const char* cloth_win32_header_probe(void);
const char* cloth_win32_header_probe(void) {
    const char* (*name)(cloth_result) = cloth_result_name;
    return name(CLOTH_OK);
}
