// C API: fabrics (shared topology built from grids, meshes and OBJ files).
#include <cloth/cloth.h>

#include <cmath>

#include "api_call.h"
#include "api_validation.h"

using namespace cloth;
using namespace cloth::api;

extern "C" {

// ================================================================ fabric

CLOTH_API cloth_grid_desc cloth_default_grid_desc(void) {
    cloth_grid_desc d{};
    d.struct_size = sizeof(cloth_grid_desc);
    d.columns = 32;
    d.rows = 32;
    d.u[0] = 1.0f;
    d.v[1] = -1.0f;
    d.spring_kinds = CLOTH_SPRING_ALL;
    d.internal_cookie = kCookie;
    return d;
}

CLOTH_API cloth_mesh_desc cloth_default_mesh_desc(void) {
    cloth_mesh_desc d{};
    d.struct_size = sizeof(cloth_mesh_desc);
    d.spring_kinds = CLOTH_SPRING_ALL;
    d.internal_cookie = kCookie;
    return d;
}

CLOTH_API cloth_result cloth_fabric_create_grid(cloth_world_id id, const cloth_grid_desc* desc,
                                                cloth_fabric_id* out_fabric) {
    return with_world(__func__, id, [&](World& world) -> Status {
        if (!desc) return null_error("desc");
        if (!out_fabric) return null_error("out_fabric");
        Status s =
            check_desc(desc->struct_size, sizeof(cloth_grid_desc), desc->internal_cookie, "cloth_grid_desc");
        if (!s.ok()) return s;
        return world.create_fabric([&](Fabric& f) { return build_grid_fabric(*desc, f); }, out_fabric);
    });
}

CLOTH_API cloth_result cloth_fabric_create_mesh(cloth_world_id id, const cloth_mesh_desc* desc,
                                                cloth_fabric_id* out_fabric) {
    return with_world(__func__, id, [&](World& world) -> Status {
        if (!desc) return null_error("desc");
        if (!out_fabric) return null_error("out_fabric");
        Status s =
            check_desc(desc->struct_size, sizeof(cloth_mesh_desc), desc->internal_cookie, "cloth_mesh_desc");
        if (!s.ok()) return s;
        return world.create_fabric(
            [&](Fabric& f) {
                return build_mesh_fabric(desc->positions, desc->vertex_count, desc->indices,
                                         desc->triangle_count, desc->spring_kinds, f);
            },
            out_fabric);
    });
}

CLOTH_API cloth_result cloth_fabric_create_obj(cloth_world_id id, const char* path, uint32_t spring_kinds,
                                               cloth_fabric_id* out_fabric) {
    return with_world(__func__, id, [&](World& world) -> Status {
        if (!path) return null_error("path");
        if (!out_fabric) return null_error("out_fabric");
        return world.create_fabric([&](Fabric& f) { return build_obj_fabric(path, spring_kinds, f); },
                                   out_fabric);
    });
}

CLOTH_API cloth_result cloth_fabric_destroy(cloth_fabric_id id) {
    return with_owning_world(__func__, id, "fabric",
                             [&](World& world) -> Status { return world.destroy_fabric(id); });
}

CLOTH_API bool cloth_fabric_is_valid(cloth_fabric_id id) { return is_live(id); }

CLOTH_API cloth_result cloth_fabric_get_particle_count(cloth_fabric_id id, uint32_t* out_count) {
    return with_fabric(__func__, id, [&](const Fabric& fabric) -> Status {
        if (!out_count) return null_error("out_count");
        *out_count = fabric.particle_count();
        return {};
    });
}

CLOTH_API cloth_result cloth_fabric_get_triangle_count(cloth_fabric_id id, uint32_t* out_count) {
    return with_fabric(__func__, id, [&](const Fabric& fabric) -> Status {
        if (!out_count) return null_error("out_count");
        *out_count = fabric.triangle_count();
        return {};
    });
}

CLOTH_API cloth_result cloth_fabric_get_spring_count(cloth_fabric_id id, uint32_t kinds,
                                                     uint32_t* out_count) {
    return with_fabric(__func__, id, [&](const Fabric& fabric) -> Status {
        if (!out_count) return null_error("out_count");
        if (kinds & ~static_cast<uint32_t>(CLOTH_SPRING_ALL)) {
            return Status::error(CLOTH_ERROR_INVALID_VALUE, "unknown spring kind bits 0x%x", kinds);
        }
        uint32_t count = 0;
        for (int k = 0; k < kSpringKindCount; ++k) {
            if (kinds & (1u << k)) count += fabric.springs_of_kind[k];
        }
        *out_count = count;
        return {};
    });
}

CLOTH_API cloth_result cloth_fabric_read_triangles(cloth_fabric_id id, uint32_t* out_indices,
                                                   uint32_t capacity) {
    return with_fabric(__func__, id, [&](const Fabric& fabric) -> Status {
        Status s = check_capacity(out_indices, capacity, fabric.triangles.size());
        if (!s.ok()) return s;
        // In the host's vertex order (a mesh's particles are stored spatially sorted).
        for (size_t i = 0; i < fabric.triangles.size(); ++i)
            out_indices[i] = fabric.vertex(fabric.triangles[i]);
        return {};
    });
}

}  // extern "C"
