// C API: colliders, the shapes cloths stay out of, and a cloth's
// collision settings (which colliders it meets, how thick, how rough).
// Every argument is checked before anything changes; shapes are built into
// a fresh object and only then put in the world.
#include <cloth/cloth.h>

#include <cmath>
#include <memory>

#include "api_call.h"
#include "api_validation.h"

using namespace cloth;
using namespace cloth::api;

namespace {

// Common part of every collider creation: check the world and the
// description, build the shape with `build`, then take a slot.
template <class Build>
cloth_result create_collider(const char* function, cloth_world_id world_id, const cloth_collider_desc* desc,
                             cloth_collider_id* out, Build build) {
    return with_world(function, world_id, [&](World& world) -> Status {
        if (!desc) return null_error("desc");
        if (!out) return null_error("out_collider");
        Status s = check_desc(desc->struct_size, sizeof(cloth_collider_desc), desc->internal_cookie,
                              "cloth_collider_desc");
        if (!s.ok()) return s;
        Collider collider;
        s = check_pose(desc->local_position, desc->local_rotation, "local_position", "local_rotation",
                       &collider.local);
        if (!s.ok()) return s;
        if (!cloth_body_id_equal(desc->body, cloth_null_body_id)) {  // null: a static collider
            s = check_same_world(desc->body, world_id, "body", "the call's world");
            if (!s.ok()) return s;
            if (!world.contact().find_body(desc->body.index1, desc->body.generation))
                return no_object_error("body");
            collider.body = desc->body.index1 - 1u;
        }
        collider.group_bits = desc->group_bits;
        auto shape = std::allocate_shared<Shape>(HostAllocator<Shape>(world.memory()), world.memory());
        s = build(*shape);
        if (!s.ok()) return s;
        collider.shape = std::move(shape);
        uint32_t slot;
        uint16_t generation;
        s = world.contact().create_collider(collider, &slot, &generation);
        if (!s.ok()) return s;
        *out = cloth_collider_id{static_cast<uint16_t>(slot + 1), world_id.index1, generation,
                                 world_id.generation};
        return {};
    });
}

Status check_collision(const cloth_collision_params& p) {
    if (p.struct_size != sizeof(cloth_collision_params)) {
        return Status::error(CLOTH_ERROR_INVALID_DESC,
                             "cloth_collision_params.struct_size is %u, expected %zu", p.struct_size,
                             sizeof(cloth_collision_params));
    }
    Status s = check_finite(p.thickness, "thickness");
    if (s.ok()) s = check_finite(p.friction, "friction");
    if (s.ok()) s = check_non_negative(p.thickness, "thickness");
    if (s.ok()) s = check_coordinate(p.thickness, "thickness");
    if (s.ok()) s = check_non_negative(p.friction, "friction");
    return s;
}

}  // namespace

extern "C" {

CLOTH_API cloth_collider_desc cloth_default_collider_desc(void) {
    cloth_collider_desc d{};
    d.struct_size = sizeof(cloth_collider_desc);
    d.local_rotation[3] = 1.0f;
    d.group_bits = 1;
    d.internal_cookie = kCookie;
    return d;
}

CLOTH_API cloth_result cloth_collider_create_sphere(cloth_world_id world, const cloth_collider_desc* desc,
                                                    float radius, cloth_collider_id* out) {
    return create_collider(__func__, world, desc, out, [&](Shape& shape) {
        Status s = check_coordinate(radius, "radius");
        return s.ok() ? build_sphere(radius, shape) : s;
    });
}

CLOTH_API cloth_result cloth_collider_create_capsule(cloth_world_id world, const cloth_collider_desc* desc,
                                                     float radius, float half_height,
                                                     cloth_collider_id* out) {
    return create_collider(__func__, world, desc, out, [&](Shape& shape) {
        Status s = check_finite(radius, "radius");
        if (s.ok()) s = check_finite(half_height, "half_height");
        if (s.ok()) s = check_coordinate(radius, "radius");
        if (s.ok()) s = check_coordinate(half_height, "half_height");
        return s.ok() ? build_capsule(radius, half_height, shape) : s;
    });
}

CLOTH_API cloth_result cloth_collider_create_tapered_capsule(cloth_world_id world,
                                                             const cloth_collider_desc* desc,
                                                             float bottom_radius, float top_radius,
                                                             float half_height, cloth_collider_id* out) {
    return create_collider(__func__, world, desc, out, [&](Shape& shape) {
        Status s = check_finite(bottom_radius, "bottom_radius");
        if (s.ok()) s = check_finite(top_radius, "top_radius");
        if (s.ok()) s = check_finite(half_height, "half_height");
        if (s.ok()) s = check_coordinate(bottom_radius, "bottom_radius");
        if (s.ok()) s = check_coordinate(top_radius, "top_radius");
        if (s.ok()) s = check_coordinate(half_height, "half_height");
        return s.ok() ? build_tapered_capsule(bottom_radius, top_radius, half_height, shape) : s;
    });
}

CLOTH_API cloth_result cloth_collider_create_box(cloth_world_id world, const cloth_collider_desc* desc,
                                                 const float half_extents[3], cloth_collider_id* out) {
    return create_collider(__func__, world, desc, out, [&](Shape& shape) {
        Vec3 e = Vec3::Zero();
        Status s = check_position(half_extents, "half_extents", &e);
        return s.ok() ? build_box(e, shape) : s;
    });
}

CLOTH_API cloth_result cloth_collider_create_plane(cloth_world_id world, const cloth_collider_desc* desc,
                                                   const float normal[3], float offset,
                                                   cloth_collider_id* out) {
    return create_collider(__func__, world, desc, out, [&](Shape& shape) {
        Vec3 n = Vec3::Zero();
        Status s = check_vector(normal, "normal", &n);
        if (s.ok()) s = check_coordinate(offset, "offset");
        return s.ok() ? build_plane(n, offset, shape) : s;
    });
}

CLOTH_API cloth_result cloth_collider_create_convex_hull(cloth_world_id world,
                                                         const cloth_collider_desc* desc,
                                                         const float* points_xyz, uint32_t point_count,
                                                         cloth_collider_id* out) {
    return create_collider(__func__, world, desc, out, [&](Shape& shape) {
        if (!points_xyz) return null_error("points_xyz");
        if (point_count < 4 || point_count > CLOTH_MAX_HULL_POINTS)
            return Status::error(CLOTH_ERROR_INVALID_COUNT, "point_count %u is not in 4..%d", point_count,
                                 CLOTH_MAX_HULL_POINTS);
        Status s = check_points(points_xyz, point_count, "points");
        return s.ok() ? build_convex_hull(points_xyz, point_count, shape) : s;
    });
}

CLOTH_API cloth_result cloth_collider_create_triangle_mesh(cloth_world_id world,
                                                           const cloth_collider_desc* desc,
                                                           const float* vertices_xyz, uint32_t vertex_count,
                                                           const uint32_t* indices, uint32_t triangle_count,
                                                           cloth_collider_id* out) {
    return create_collider(__func__, world, desc, out, [&](Shape& shape) {
        if (!vertices_xyz) return null_error("vertices_xyz");
        if (!indices) return null_error("indices");
        if (vertex_count < 3 || vertex_count > CLOTH_MAX_MESH_COLLIDER_VERTICES)
            return Status::error(CLOTH_ERROR_INVALID_COUNT, "vertex_count %u is not in 3..%u", vertex_count,
                                 CLOTH_MAX_MESH_COLLIDER_VERTICES);
        if (triangle_count < 1 || triangle_count > CLOTH_MAX_MESH_COLLIDER_TRIANGLES)
            return Status::error(CLOTH_ERROR_INVALID_COUNT, "triangle_count %u is not in 1..%u",
                                 triangle_count, CLOTH_MAX_MESH_COLLIDER_TRIANGLES);
        Status s = check_points(vertices_xyz, vertex_count, "vertices");
        return s.ok() ? build_triangle_mesh(vertices_xyz, vertex_count, indices, triangle_count, shape) : s;
    });
}

CLOTH_API cloth_heightfield_desc cloth_default_heightfield_desc(void) {
    cloth_heightfield_desc d{};
    d.struct_size = sizeof(cloth_heightfield_desc);
    d.columns = 2;
    d.rows = 2;
    d.spacing_x = 1.0f;
    d.spacing_z = 1.0f;
    d.internal_cookie = kCookie;
    return d;
}

CLOTH_API cloth_result cloth_collider_create_heightfield(cloth_world_id world,
                                                         const cloth_collider_desc* desc,
                                                         const cloth_heightfield_desc* field,
                                                         cloth_collider_id* out) {
    return create_collider(__func__, world, desc, out, [&](Shape& shape) {
        if (!field) return null_error("heightfield");
        Status s = check_desc(field->struct_size, sizeof(cloth_heightfield_desc), field->internal_cookie,
                              "cloth_heightfield_desc");
        if (!s.ok()) return s;
        if (field->columns < 2 || field->columns > CLOTH_MAX_HEIGHTFIELD_SIDE || field->rows < 2 ||
            field->rows > CLOTH_MAX_HEIGHTFIELD_SIDE) {
            return Status::error(CLOTH_ERROR_INVALID_COUNT,
                                 "heightfield columns %u and rows %u must be in 2..%d", field->columns,
                                 field->rows, CLOTH_MAX_HEIGHTFIELD_SIDE);
        }
        if (!std::isfinite(field->spacing_x) || !std::isfinite(field->spacing_z))
            return Status::error(CLOTH_ERROR_NOT_FINITE, "heightfield spacing is not finite");
        if (!field->heights) return null_error("heightfield heights");
        const size_t count = static_cast<size_t>(field->columns) * field->rows;
        for (size_t k = 0; k < count; ++k) {
            if (!std::isfinite(field->heights[k]))
                return Status::error(CLOTH_ERROR_NOT_FINITE, "heights[%zu] is not finite", k);
        }
        for (float spacing : {field->spacing_x, field->spacing_z}) {
            s = check_coordinate(spacing, "heightfield spacing");
            if (!s.ok()) return s;
            if (!(spacing > 0))
                return Status::error(CLOTH_ERROR_INVALID_VALUE, "heightfield spacing must be > 0");
        }
        for (size_t k = 0; k < count; ++k) {
            s = check_coordinate(field->heights[k], "a height");
            if (!s.ok()) return s;
        }
        return build_heightfield(field->columns, field->rows, field->spacing_x, field->spacing_z,
                                 field->heights, shape);
    });
}

CLOTH_API cloth_result cloth_collider_destroy(cloth_collider_id id) {
    return with_collider(__func__, id, [&](Collider&, World& world) -> Status {
        world.contact().destroy_collider(id.index1 - 1u);
        return {};
    });
}

CLOTH_API bool cloth_collider_is_valid(cloth_collider_id id) { return is_live(id); }

CLOTH_API cloth_result cloth_collider_set_group_bits(cloth_collider_id id, uint32_t group_bits) {
    return with_collider(__func__, id, [&](Collider& collider) -> Status {
        collider.group_bits = group_bits;
        return {};
    });
}

CLOTH_API cloth_collision_params cloth_default_collision_params(void) {
    const CollisionParams core;
    cloth_collision_params p{};
    p.struct_size = sizeof(cloth_collision_params);
    p.thickness = core.thickness;
    p.friction = core.friction;
    p.collider_mask = core.collider_mask;
    return p;
}

CLOTH_API cloth_result cloth_set_collision(cloth_id id, const cloth_collision_params* params) {
    return with_cloth(__func__, id, [&](ClothInstance& cloth) -> Status {
        if (!params) return null_error("params");
        Status s = check_collision(*params);
        if (!s.ok()) return s;
        CollisionParams& core = cloth.contact().collision();
        core.thickness = params->thickness;
        core.friction = params->friction;
        core.collider_mask = params->collider_mask;
        return {};
    });
}

CLOTH_API cloth_result cloth_get_collision(cloth_id id, cloth_collision_params* out) {
    return with_cloth(__func__, id, [&](ClothInstance& cloth) -> Status {
        if (!out) return null_error("out_params");
        const CollisionParams& core = cloth.contact().collision();
        *out = cloth_default_collision_params();
        out->thickness = core.thickness;
        out->friction = core.friction;
        out->collider_mask = core.collider_mask;
        return {};
    });
}

}  // extern "C"
