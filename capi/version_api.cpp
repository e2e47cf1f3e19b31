// C API: what a caller checks about the library it loaded: its version and
// the size of every public struct.
#include <cloth/cloth.h>

#include "api_validation.h"

using namespace cloth::api;

extern "C" {

CLOTH_API cloth_version cloth_get_version(void) {
    return cloth_version{CLOTH_VERSION_MAJOR, CLOTH_VERSION_MINOR, CLOTH_VERSION_PATCH};
}

CLOTH_API size_t cloth_struct_size(cloth_struct_kind kind) {
    switch (enum_bits(kind)) {  // a C caller may pass any int
        case CLOTH_STRUCT_VERSION:
            return sizeof(cloth_version);
        case CLOTH_STRUCT_WORLD_ID:
            return sizeof(cloth_world_id);
        case CLOTH_STRUCT_FABRIC_ID:
            return sizeof(cloth_fabric_id);
        case CLOTH_STRUCT_CLOTH_ID:
            return sizeof(cloth_id);
        case CLOTH_STRUCT_BODY_ID:
            return sizeof(cloth_body_id);
        case CLOTH_STRUCT_COLLIDER_ID:
            return sizeof(cloth_collider_id);
        case CLOTH_STRUCT_WORLD_DESC:
            return sizeof(cloth_world_desc);
        case CLOTH_STRUCT_GRID_DESC:
            return sizeof(cloth_grid_desc);
        case CLOTH_STRUCT_MESH_DESC:
            return sizeof(cloth_mesh_desc);
        case CLOTH_STRUCT_SPRING_PARAMS:
            return sizeof(cloth_spring_params);
        case CLOTH_STRUCT_SOLVER_SETTINGS:
            return sizeof(cloth_solver_settings);
        case CLOTH_STRUCT_STRAIN_LIMIT:
            return sizeof(cloth_strain_limit);
        case CLOTH_STRUCT_AERO_PARAMS:
            return sizeof(cloth_aero_params);
        case CLOTH_STRUCT_CLOTH_DESC:
            return sizeof(cloth_desc);
        case CLOTH_STRUCT_STATS:
            return sizeof(cloth_stats);
        case CLOTH_STRUCT_FRAME_PROFILE:
            return sizeof(cloth_frame_profile);
        case CLOTH_STRUCT_TASK_RECORD:
            return sizeof(cloth_task_record);
        case CLOTH_STRUCT_QUALITY_POLICY:
            return sizeof(cloth_quality_policy);
        case CLOTH_STRUCT_SLEEP_PARAMS:
            return sizeof(cloth_sleep_params);
        case CLOTH_STRUCT_BODY_DESC:
            return sizeof(cloth_body_desc);
        case CLOTH_STRUCT_COLLIDER_DESC:
            return sizeof(cloth_collider_desc);
        case CLOTH_STRUCT_HEIGHTFIELD_DESC:
            return sizeof(cloth_heightfield_desc);
        case CLOTH_STRUCT_COLLISION_PARAMS:
            return sizeof(cloth_collision_params);
        case CLOTH_STRUCT_CARRIER_DESC:
            return sizeof(cloth_carrier_desc);
        case CLOTH_STRUCT_SELF_COLLISION_DESC:
            return sizeof(cloth_self_collision_desc);
        case CLOTH_STRUCT_SELF_COLLISION_STATS:
            return sizeof(cloth_self_collision_stats);
        case CLOTH_STRUCT_SKIN_DESC:
            return sizeof(cloth_skin_desc);
        case CLOTH_STRUCT_CLOTH_CONTACT_DESC:
            return sizeof(cloth_cloth_contact_desc);
        default:
            return 0;
    }
}

}  // extern "C"
