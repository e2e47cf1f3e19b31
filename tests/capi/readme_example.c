/*
 * The README's example ("Using it"), compiled from README.md itself: the
 * build copies the lines of its C block after the #include into
 * readme_example.inc (tests/CMakeLists.txt), so the README cannot show a
 * call or a struct that cloth.h does not have. Compiled as C99 with every
 * warning an error, and run: every call it makes succeeds, and the flag
 * hangs from its two pinned corners.
 *
 * Exit status 0 on success; otherwise every failed check is printed and the
 * program returns 1.
 */
#include <cloth/cloth.h>
#include <math.h>
#include <stdio.h>

static int failures = 0;

static void check(int ok, const char* what) {
    if (!ok) {
        ++failures;
        fprintf(stderr, "readme_example: FAILED %s\n", what);
    }
}

int main(void) {
#include "readme_example.inc"

    /* No call failed on this thread (the last error is set only by a failure). */
    check(cloth_get_last_error()[0] == '\0', "every call of the example succeeds");
    check(!cloth_world_is_valid(world), "the world is destroyed");
    for (int i = 0; i < 3 * 32 * 32; ++i) {
        if (!isfinite(positions[i]) || !isfinite(normals[i])) {
            check(0, "positions and normals are finite");
            break;
        }
    }
    /* The pinned corners stay where the default grid puts them: (0, 0, 0) and (1, 0, 0). */
    check(positions[0] == 0.0f && positions[1] == 0.0f && positions[2] == 0.0f, "corner 0 stays pinned");
    check(positions[3 * 31] == 1.0f && positions[3 * 31 + 1] == 0.0f, "corner 31 stays pinned");
    /* The free bottom row hangs about 1 m below the pins. */
    float bottom = positions[3 * (31 * 32 + 16) + 1];
    check(bottom < -0.8f && bottom > -1.3f, "the bottom row hangs about 1 m below the pins");
    if (failures == 0) printf("readme_example: the README's example ran, every call succeeded\n");
    return failures == 0 ? 0 : 1;
}
