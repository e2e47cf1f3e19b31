/* Built against an installed cloth: creates a world and steps a cloth. */
#include <cloth/cloth.h>
#include <stdio.h>

int main(void) {
    cloth_world_desc world_desc = cloth_default_world_desc();
    cloth_world_id world;
    cloth_grid_desc grid = cloth_default_grid_desc();
    cloth_fabric_id fabric;
    cloth_desc desc = cloth_default_desc();
    cloth_id cloth;
    if (cloth_world_create(&world_desc, &world) != CLOTH_OK) return 1;
    if (cloth_fabric_create_grid(world, &grid, &fabric) != CLOTH_OK) return 1;
    desc.fabric = fabric;
    if (cloth_create(world, &desc, &cloth) != CLOTH_OK) return 1;
    if (cloth_step(world, 1.0f / 60.0f) != CLOTH_OK) return 1;
    if (cloth_world_destroy(world) != CLOTH_OK) return 1;
    printf("cloth %u.%u.%u ok\n", cloth_get_version().major, cloth_get_version().minor,
           cloth_get_version().patch);
    return 0;
}
