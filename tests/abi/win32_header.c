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

/* The calling convention is spelled out on Windows (CLOTH_CALL is __cdecl). */
static void CLOTH_CALL win32_zone(const char* name, uint32_t worker, void* user) {
    (void)name;
    (void)worker;
    (void)user;
}

/* An imported function's address is not a constant in C: take it at run time. */
const char* cloth_win32_header_probe(void);
const char* cloth_win32_header_probe(void) {
    const char*(CLOTH_CALL * name)(cloth_result) = cloth_result_name;
    cloth_zone_begin_fn* begin = win32_zone;
    begin("probe", 0, NULL);
    return name(CLOTH_OK);
}
