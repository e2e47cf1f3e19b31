/*
 * A deterministic scene through cloth.h alone, reduced to text that two
 * builds of the library must print identically: every struct size the
 * library reports (cloth_struct_size for each cloth_struct_kind) and a hash
 * of the bits of every particle position after frames 1, 10, 100 and 300 of
 * a 32x32 flag pinned along its top edge, in wind, with the default solver
 * (multigrid PCG, substeps, strain limit), on one worker, in two scenes:
 * falling onto a static sphere, and onto a round cone on a turning body.
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

/* One scene: the flag and, with `moving` 0, a static sphere under it; with
 * `moving` 1, a tapered capsule (round cone) on a body turning about z by a
 * fixed quaternion each frame, which the library interpolates across
 * substeps (slerp) and queries with std::hypot. */
static void run_scene(const char* name, int moving) {
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

    static float positions[3 * PARTICLES];
    check(cloth_read_positions(flag, positions, 3 * PARTICLES), "cloth_read_positions");
    float centre[3] = {0.0f, 0.0f, 0.0f};
    for (uint32_t i = 0; i < PARTICLES; ++i)
        for (int k = 0; k < 3; ++k) centre[k] += positions[3 * i + k] / (float)PARTICLES;
    const float below[3] = {centre[0] + 0.1f, centre[1] - 0.45f, centre[2]};
    cloth_collider_desc shape = cloth_default_collider_desc();
    cloth_collider_id collider;
    cloth_body_id body;
    /* The body's rotation, turned each frame by 0.02 rad about z: products
     * of float constants, so the client computes the same bits everywhere. */
    float rotation[4] = {0.0f, 0.0f, 0.0f, 1.0f}; /* x, y, z, w */
    const float turn[4] = {0.0f, 0.0f, 0.00999983333f, 0.999950000f};
    if (moving) {
        cloth_body_desc bd = cloth_default_body_desc();
        memcpy(bd.position, below, sizeof below);
        check(cloth_body_create(world, &bd, &body), "cloth_body_create");
        shape.body = body;
        check(cloth_collider_create_tapered_capsule(world, &shape, 0.35f, 0.1f, 0.3f, &collider),
              "cloth_collider_create_tapered_capsule");
    } else {
        memcpy(shape.local_position, below, sizeof below);
        check(cloth_collider_create_sphere(world, &shape, 0.35f, &collider), "cloth_collider_create_sphere");
    }

    for (int frame = 1; frame <= FRAMES; ++frame) {
        if (moving) {
            const float x = rotation[0], y = rotation[1], z = rotation[2], w = rotation[3];
            rotation[0] = w * turn[0] + x * turn[3] + y * turn[2] - z * turn[1];
            rotation[1] = w * turn[1] - x * turn[2] + y * turn[3] + z * turn[0];
            rotation[2] = w * turn[2] + x * turn[1] - y * turn[0] + z * turn[3];
            rotation[3] = w * turn[3] - x * turn[0] - y * turn[1] - z * turn[2];
            check(cloth_body_set_pose(body, below, rotation), "cloth_body_set_pose");
        }
        check(cloth_step(world, 1.0f / 60.0f), "cloth_step");
        if (frame == 1 || frame == 10 || frame == 100 || frame == FRAMES) {
            check(cloth_read_positions(flag, positions, 3 * PARTICLES), "cloth_read_positions");
            printf("%s positions_hash frame %d %016llx\n", name, frame,
                   (unsigned long long)hash_bits(positions, 3 * PARTICLES));
        }
    }
    printf("%s particle_0 %.9g %.9g %.9g\n", name, (double)positions[0], (double)positions[1],
           (double)positions[2]);
    printf("%s particle_last %.9g %.9g %.9g\n", name, (double)positions[3 * PARTICLES - 3],
           (double)positions[3 * PARTICLES - 2], (double)positions[3 * PARTICLES - 1]);
    check(cloth_world_destroy(world), "cloth_world_destroy");
}

int main(void) {
    /* Every struct kind the library knows, until the first it does not. */
    for (uint32_t kind = 1; kind < 1000; ++kind) {
        const size_t size = cloth_struct_size((cloth_struct_kind)kind);
        if (size == 0) break;
        printf("struct_size %u %lu\n", kind, (unsigned long)size);
    }

    run_scene("static_sphere", 0);
    run_scene("turning_cone", 1);
    return g_failures == 0 ? 0 : 1;
}
