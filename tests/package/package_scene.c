/* The first scene of UnityPackageConsumer.cs through cloth.h alone: a
 * 16x16 default grid cloth pinned at two corners, in 2 m/s wind along +z,
 * 60 steps of 1/60 s on a world of two workers. Prints the FNV-1a hash of
 * its positions' bytes, which the C# program from the Unity package must
 * print too (check_packages.sh): the same values as the native library. */
#include <cloth/cloth.h>
#include <inttypes.h>
#include <stdio.h>
#include <string.h>

int main(void) {
    cloth_world_desc wd = cloth_default_world_desc();
    wd.worker_count = 2;
    cloth_world_id world;
    if (cloth_world_create(&wd, &world) != CLOTH_OK) return 1;
    cloth_grid_desc gd = cloth_default_grid_desc();
    gd.columns = 16;
    gd.rows = 16;
    cloth_fabric_id fabric;
    if (cloth_fabric_create_grid(world, &gd, &fabric) != CLOTH_OK) return 1;
    cloth_desc cd = cloth_default_desc();
    cd.fabric = fabric;
    cloth_id cloth;
    if (cloth_create(world, &cd, &cloth) != CLOTH_OK) return 1;
    const uint32_t pins[2] = {0, 15};
    const float wind[3] = {0.0f, 0.0f, 2.0f};
    if (cloth_pin(cloth, pins, 2) != CLOTH_OK || cloth_set_wind(cloth, wind) != CLOTH_OK) return 1;
    for (int frame = 0; frame < 60; ++frame) {
        if (cloth_step(world, 1.0f / 60.0f) != CLOTH_OK) return 1;
    }
    float x[3 * 256];
    if (cloth_read_positions(cloth, x, 3 * 256) != CLOTH_OK) return 1;
    uint64_t hash = 14695981039346656037ull;
    const unsigned char* bytes = (const unsigned char*)x;
    for (size_t i = 0; i < sizeof x; ++i) hash = (hash ^ bytes[i]) * 1099511628211ull;
    printf("positions hash %016" PRIx64 "\n", hash);
    return cloth_world_destroy(world) == CLOTH_OK ? 0 : 1;
}
