/*
 * A stand-in for libcloth.so in the ABI check's own test: one exported
 * function reaching every public struct of <cloth/cloth.h>, so that
 * abidw records their layouts, plus one function that a variant drops.
 * Compiled in seconds, unlike the library.
 */
#include <cloth/cloth.h>

CLOTH_API void cloth_abi_probe(cloth_world_desc* world, cloth_grid_desc* grid, cloth_mesh_desc* mesh,
                               cloth_desc* cloth, cloth_stats* stats, cloth_version* version,
                               cloth_world_id* world_id, cloth_fabric_id* fabric_id, cloth_id* cloth_id_) {
    (void)world, (void)grid, (void)mesh, (void)cloth, (void)stats, (void)version;
    (void)world_id, (void)fabric_id, (void)cloth_id_;
}

#ifndef PROBE_DROP_FUNCTION
CLOTH_API cloth_result cloth_abi_probe_extra(void) { return CLOTH_OK; }
#endif
