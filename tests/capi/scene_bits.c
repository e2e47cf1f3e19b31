/*
 * A deterministic scene through cloth.h alone, reduced to text that two
 * builds of the library must print identically: every struct size the
 * library reports (cloth_struct_size for each cloth_struct_kind) and a hash
 * of the bits of every particle position after frames 1, 10, 100 and 300 of
 * a 32x32 flag pinned along its top edge, in wind, with the default solver
 * (multigrid PCG, substeps, strain limit), on one worker, falling past a
 * static sphere.
 *
 * scripts/windows runs the Linux build and the Windows build (cloth.dll
 * under wine64) of this program and fails if a single line differs
 * (tests/windows/CMakeLists.txt, cloth_windows.same_bits_as_linux).
 * Exit status 0 when every call succeeded, 1 otherwise.
 */
#include <cloth/cloth.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#define SIDE 32u
#define PARTICLES (SIDE * SIDE)
#define FRAMES 300

static int g_failures = 0;

static void check(cloth_result r, const char* what) {
    if (r != CLOTH_OK) {
        ++g_failures;
        fprintf(stderr, "scene_bits: %s returned %s: %s\n", what, cloth_result_name(r),
                cloth_get_last_error());
    }
}

/* FNV-1a over the bytes of each float, in a fixed (little-endian) order. */
static uint64_t hash_bits(const float* values, size_t count) {
    uint64_t h = 1469598103934665603ull;
    for (size_t i = 0; i < count; ++i) {
        uint32_t bits;
        memcpy(&bits, &values[i], sizeof bits);
        for (int b = 0; b < 4; ++b) {
            h ^= (bits >> (8 * b)) & 0xffu;
            h *= 1099511628211ull;
        }
    }
    return h;
}

int main(void) {
    /* Every struct kind the library knows, until the first it does not. */
    for (uint32_t kind = 1; kind < 1000; ++kind) {
        const size_t size = cloth_struct_size((cloth_struct_kind)kind);
        if (size == 0) break;
        printf("struct_size %u %lu\n", kind, (unsigned long)size);
    }

    cloth_world_desc wd = cloth_default_world_desc();
    wd.worker_count = 1;
    cloth_world_id world;
    check(cloth_world_create(&wd, &world), "cloth_world_create");

    cloth_grid_desc gd = cloth_default_grid_desc();
    gd.columns = SIDE;
    gd.rows = SIDE;
    cloth_fabric_id fabric;
    check(cloth_fabric_create_grid(world, &gd, &fabric), "cloth_fabric_create_grid");

    cloth_desc cd = cloth_default_desc();
    cd.fabric = fabric;
    cloth_id flag;
    check(cloth_create(world, &cd, &flag), "cloth_create");
    uint32_t top[SIDE];
    for (uint32_t c = 0; c < SIDE; ++c) top[c] = c;
    check(cloth_pin(flag, top, SIDE), "cloth_pin");
    const float wind[3] = {3.0f, 0.5f, 4.0f};
    check(cloth_set_wind(flag, wind), "cloth_set_wind");

    /* A static sphere under the middle of the flag. */
    static float positions[3 * PARTICLES];
    check(cloth_read_positions(flag, positions, 3 * PARTICLES), "cloth_read_positions");
    float centre[3] = {0.0f, 0.0f, 0.0f};
    for (uint32_t i = 0; i < PARTICLES; ++i)
        for (int k = 0; k < 3; ++k) centre[k] += positions[3 * i + k] / (float)PARTICLES;
    cloth_collider_desc sphere = cloth_default_collider_desc();
    sphere.local_position[0] = centre[0] + 0.1f;
    sphere.local_position[1] = centre[1] - 0.45f;
    sphere.local_position[2] = centre[2];
    cloth_collider_id collider;
    check(cloth_collider_create_sphere(world, &sphere, 0.35f, &collider), "cloth_collider_create_sphere");

    for (int frame = 1; frame <= FRAMES; ++frame) {
        check(cloth_step(world, 1.0f / 60.0f), "cloth_step");
        if (frame == 1 || frame == 10 || frame == 100 || frame == FRAMES) {
            check(cloth_read_positions(flag, positions, 3 * PARTICLES), "cloth_read_positions");
            printf("positions_hash frame %d %016llx\n", frame,
                   (unsigned long long)hash_bits(positions, 3 * PARTICLES));
        }
    }
    printf("particle_0 %.9g %.9g %.9g\n", (double)positions[0], (double)positions[1], (double)positions[2]);
    printf("particle_last %.9g %.9g %.9g\n", (double)positions[3 * PARTICLES - 3],
           (double)positions[3 * PARTICLES - 2], (double)positions[3 * PARTICLES - 1]);
    check(cloth_world_destroy(world), "cloth_world_destroy");
    return g_failures == 0 ? 0 : 1;
}
