/*
 * A C99 client of libcloth.so built against the cloth.h of this version:
 * the library it loads must be the version the header names, and must
 * agree with the header on the size of every versioned struct (each
 * cloth_default_*() returns struct_size = sizeof as this client sees it).
 * A struct_size of another size is refused with CLOTH_ERROR_INVALID_DESC,
 * never read past. Exit status 0 only if all of that holds.
 */
#include <cloth/cloth.h>
#include <stdio.h>
#include <string.h>

static int failures = 0;

#define EXPECT(cond, ...)                                      \
    do {                                                       \
        if (!(cond)) {                                         \
            fprintf(stderr, "abi_client: FAIL: " __VA_ARGS__); \
            fprintf(stderr, "\n");                             \
            ++failures;                                        \
        }                                                      \
    } while (0)

#define EXPECT_SIZE(value, type)                                                                   \
    EXPECT((value) == sizeof(type), #type ": library says %u bytes, header %u", (unsigned)(value), \
           (unsigned)sizeof(type))

int main(void) {
    const cloth_version v = cloth_get_version();
    cloth_world_desc wd = cloth_default_world_desc();
    cloth_world_id world = {0, 0};
    cloth_grid_desc gd = cloth_default_grid_desc();
    cloth_fabric_id fabric = {0, 0, 0, 0};
    cloth_desc cd = cloth_default_desc();
    cloth_id cloth = {0, 0, 0, 0};
    cloth_solver_settings solver;
    cloth_stats stats;

    EXPECT(v.major == CLOTH_VERSION_MAJOR && v.minor == CLOTH_VERSION_MINOR && v.patch == CLOTH_VERSION_PATCH,
           "library %u.%u.%u, header %d.%d.%d", (unsigned)v.major, (unsigned)v.minor, (unsigned)v.patch,
           CLOTH_VERSION_MAJOR, CLOTH_VERSION_MINOR, CLOTH_VERSION_PATCH);
    EXPECT_SIZE(wd.struct_size, cloth_world_desc);
    EXPECT_SIZE(gd.struct_size, cloth_grid_desc);
    EXPECT_SIZE(cloth_default_mesh_desc().struct_size, cloth_mesh_desc);
    EXPECT_SIZE(cd.struct_size, cloth_desc);
    EXPECT_SIZE(cd.solver.struct_size, cloth_solver_settings);
    EXPECT_SIZE(cloth_default_solver_settings().struct_size, cloth_solver_settings);

    if (cloth_world_create(&wd, &world) != CLOTH_OK) {
        fprintf(stderr, "abi_client: cloth_world_create failed: %s\n", cloth_get_last_error());
        return 1;
    }
    gd.columns = gd.rows = 4;
    EXPECT(cloth_fabric_create_grid(world, &gd, &fabric) == CLOTH_OK, "grid: %s", cloth_get_last_error());
    cd.fabric = fabric;
    EXPECT(cloth_create(world, &cd, &cloth) == CLOTH_OK, "cloth: %s", cloth_get_last_error());

    memset(&solver, 0, sizeof solver);
    EXPECT(cloth_get_solver(cloth, &solver) == CLOTH_OK, "get_solver: %s", cloth_get_last_error());
    EXPECT_SIZE(solver.struct_size, cloth_solver_settings);

    /* A caller built against a header with another cloth_stats. */
    memset(&stats, 0, sizeof stats);
    stats.struct_size = (uint32_t)sizeof stats + 8;
    EXPECT(cloth_get_stats(cloth, &stats) == CLOTH_ERROR_INVALID_DESC, "a larger cloth_stats was accepted");
    stats.struct_size = (uint32_t)sizeof stats;
    EXPECT(cloth_get_stats(cloth, &stats) == CLOTH_OK, "get_stats: %s", cloth_get_last_error());
    /* A caller's desc of another size. */
    cd.struct_size = (uint32_t)sizeof cd - 4;
    EXPECT(cloth_create(world, &cd, &cloth) == CLOTH_ERROR_INVALID_DESC, "a smaller cloth_desc was accepted");

    EXPECT(cloth_world_destroy(world) == CLOTH_OK, "world_destroy: %s", cloth_get_last_error());
    if (failures == 0)
        printf("abi_client: library %u.%u.%u matches the header\n", (unsigned)v.major, (unsigned)v.minor,
               (unsigned)v.patch);
    return failures == 0 ? 0 : 1;
}
