// C API: bodies, colliders, collision settings, attachments and carriers
// (cloth.h section "Bodies, colliders and attachments"). Every argument is
// checked before anything changes; shapes are built into a fresh object
// and only then put in the world.
#include <cloth/cloth.h>

#include <cmath>
#include <memory>

#include "api_call.h"
#include "api_validation.h"

using namespace cloth;
using namespace cloth::api;

namespace {

Status check_rotation(const float* q, const char* what, Quat* out) {
    if (!q) return null_error(what);
    for (int k = 0; k < 4; ++k) {
        if (!std::isfinite(q[k])) return Status::error(CLOTH_ERROR_NOT_FINITE, "%s is not finite", what);
    }
    const float length = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (std::abs(length - 1.0f) > 1e-2f) {
        return Status::error(CLOTH_ERROR_INVALID_VALUE,
                             "%s has length %g; a unit quaternion (x, y, z, w) is needed", what,
                             double(length));
    }
    *out = Quat(q[3], q[0], q[1], q[2]).normalized();
    return {};
}

Status check_vector(const float* v, const char* what, Vec3* out) {
    if (!v) return null_error(what);
    if (!finite3(v)) return Status::error(CLOTH_ERROR_NOT_FINITE, "%s is not finite", what);
    *out = Vec3(v[0], v[1], v[2]);
    return {};
}

Status check_pose(const float* position, const float* rotation, const char* position_name,
                  const char* rotation_name, Pose* out) {
    Status s = check_vector(position, position_name, &out->position);
    if (s.ok()) s = check_rotation(rotation, rotation_name, &out->rotation);
    return s;
}

template <class Id>
bool same_world(Id id, cloth_world_id world) {
    return id.world1 == world.index1 && id.world_generation == world.generation;
}

Status get_body(cloth_body_id id, World*& world, BodySlot*& body, const World*& log_world) {
    world = find_owning_world(id);
    body = world ? world->contact().find_body(id.index1, id.generation) : nullptr;
    if (!body) return Status::error(CLOTH_ERROR_INVALID_HANDLE, "body handle is null, destroyed or unknown");
    log_world = world;
    return {};
}

Status get_collider(cloth_collider_id id, World*& world, ColliderSlot*& collider, const World*& log_world) {
    world = find_owning_world(id);
    collider = world ? world->contact().find_collider(id.index1, id.generation) : nullptr;
    if (!collider)
        return Status::error(CLOTH_ERROR_INVALID_HANDLE, "collider handle is null, destroyed or unknown");
    log_world = world;
    return {};
}

// The body a cloth refers to, which must live in the cloth's world.
Status get_body_of_cloth_world(cloth_id cloth, cloth_body_id id, BodySlot*& body) {
    World* world = find_owning_world(id);
    body = world ? world->contact().find_body(id.index1, id.generation) : nullptr;
    if (!body) return Status::error(CLOTH_ERROR_INVALID_HANDLE, "body handle is null, destroyed or unknown");
    if (id.world1 != cloth.world1 || id.world_generation != cloth.world_generation) {
        return Status::error(CLOTH_ERROR_INVALID_HANDLE, "body belongs to another world than the cloth");
    }
    return {};
}

// Common part of every collider creation: check the world and the
// description, build the shape with `build`, then take a slot.
template <class Build>
cloth_result create_collider(const char* function, cloth_world_id world_id, const cloth_collider_desc* desc,
                             cloth_collider_id* out, Build build) {
    return api_call(function, [&](const World*& log_world) -> Status {
        World* world;
        Status s = get_world(world_id, world, log_world);
        if (!s.ok()) return s;
        if (!desc) return null_error("desc");
        if (!out) return null_error("out_collider");
        s = check_desc(desc->struct_size, sizeof(cloth_collider_desc), desc->internal_cookie,
                       "cloth_collider_desc");
        if (!s.ok()) return s;
        Collider collider;
        s = check_pose(desc->local_position, desc->local_rotation, "local_position", "local_rotation",
                       &collider.local);
        if (!s.ok()) return s;
        const bool has_body = desc->body.index1 != 0 || desc->body.world1 != 0 ||
                              desc->body.generation != 0 || desc->body.world_generation != 0;
        if (has_body) {
            if (!same_world(desc->body, world_id))
                return Status::error(CLOTH_ERROR_INVALID_HANDLE, "body belongs to another world");
            if (!world->contact().find_body(desc->body.index1, desc->body.generation))
                return Status::error(CLOTH_ERROR_INVALID_HANDLE, "body handle is destroyed or unknown");
            collider.body = desc->body.index1 - 1u;
        }
        collider.group_bits = desc->group_bits;
        auto shape = std::allocate_shared<Shape>(HostAllocator<Shape>(world->memory()), world->memory());
        s = build(*shape);
        if (!s.ok()) return s;
        collider.shape = std::move(shape);
        uint32_t slot;
        uint16_t generation;
        s = world->contact().create_collider(collider, &slot, &generation);
        if (!s.ok()) return s;
        *out = cloth_collider_id{static_cast<uint16_t>(slot + 1), world_id.index1, generation,
                                 world_id.generation};
        return {};
    });
}

Status check_finite_points(const float* xyz, uint32_t count, const char* what) {
    return check_points(xyz, count, what);
}

Status check_collision(const cloth_collision_params& p) {
    if (p.struct_size != sizeof(cloth_collision_params)) {
        return Status::error(CLOTH_ERROR_INVALID_DESC,
                             "cloth_collision_params.struct_size is %u, expected %zu", p.struct_size,
                             sizeof(cloth_collision_params));
    }
    Status s = check_non_negative(p.thickness, "thickness");
    if (s.ok()) s = check_non_negative(p.friction, "friction");
    return s;
}

Status check_unit_interval(float value, const char* what) {
    if (!std::isfinite(value)) return Status::error(CLOTH_ERROR_NOT_FINITE, "%s is not finite", what);
    if (value < 0 || value > 1)
        return Status::error(CLOTH_ERROR_INVALID_VALUE, "%s %g is not in 0..1", what, double(value));
    return {};
}

Status check_carrier(const cloth_carrier_desc& d) {
    Status s = check_desc(d.struct_size, sizeof(cloth_carrier_desc), d.internal_cookie, "cloth_carrier_desc");
    if (s.ok()) s = check_unit_interval(d.linear_inertia, "linear_inertia");
    if (s.ok()) s = check_unit_interval(d.angular_inertia, "angular_inertia");
    if (s.ok()) s = check_unit_interval(d.centrifugal_inertia, "centrifugal_inertia");
    if (s.ok()) s = check_non_negative(d.max_relative_speed, "max_relative_speed");
    if (s.ok()) s = check_non_negative(d.teleport_distance, "teleport_distance");
    if (s.ok()) s = check_non_negative(d.teleport_rotation, "teleport_rotation");
    const int32_t mode = enum_bits(d.teleport_mode);
    if (s.ok() && mode != CLOTH_TELEPORT_DEFAULT && mode != CLOTH_TELEPORT_MOVE &&
        mode != CLOTH_TELEPORT_AND_RESET) {
        return Status::error(CLOTH_ERROR_INVALID_VALUE, "unknown teleport_mode %d", mode);
    }
    return s;
}

void write_id(cloth_body_id* out, uint32_t slot, const BodySlot& body, cloth_id cloth) {
    *out =
        cloth_body_id{static_cast<uint16_t>(slot + 1), cloth.world1, body.generation, cloth.world_generation};
}

}  // namespace

extern "C" {

// ================================================================ bodies

CLOTH_API cloth_body_desc cloth_default_body_desc(void) {
    cloth_body_desc d{};
    d.struct_size = sizeof(cloth_body_desc);
    d.rotation[3] = 1.0f;
    d.internal_cookie = kCookie;
    return d;
}

CLOTH_API cloth_result cloth_body_create(cloth_world_id world_id, const cloth_body_desc* desc,
                                         cloth_body_id* out_body) {
    return api_call(__func__, [&](const World*& log_world) -> Status {
        World* world;
        Status s = get_world(world_id, world, log_world);
        if (!s.ok()) return s;
        if (!desc) return null_error("desc");
        if (!out_body) return null_error("out_body");
        s = check_desc(desc->struct_size, sizeof(cloth_body_desc), desc->internal_cookie, "cloth_body_desc");
        if (!s.ok()) return s;
        Body body;
        s = check_pose(desc->position, desc->rotation, "position", "rotation", &body.start);
        if (s.ok()) s = check_vector(desc->linear_velocity, "linear_velocity", &body.linear_velocity);
        if (s.ok()) s = check_vector(desc->angular_velocity, "angular_velocity", &body.angular_velocity);
        if (!s.ok()) return s;
        body.target = body.start;
        uint32_t slot;
        uint16_t generation;
        s = world->contact().create_body(body, &slot, &generation);
        if (!s.ok()) return s;
        *out_body =
            cloth_body_id{static_cast<uint16_t>(slot + 1), world_id.index1, generation, world_id.generation};
        return {};
    });
}

CLOTH_API cloth_result cloth_body_destroy(cloth_body_id id) {
    return api_call(__func__, [&](const World*& log_world) -> Status {
        World* world;
        BodySlot* body;
        Status s = get_body(id, world, body, log_world);
        if (!s.ok()) return s;
        world->destroy_body(id.index1 - 1u);
        return {};
    });
}

CLOTH_API cloth_result cloth_body_set_pose(cloth_body_id id, const float position[3],
                                           const float rotation[4]) {
    return api_call(__func__, [&](const World*& log_world) -> Status {
        World* world;
        BodySlot* body;
        Status s = get_body(id, world, body, log_world);
        Pose pose;
        if (s.ok()) s = check_pose(position, rotation, "position", "rotation", &pose);
        if (!s.ok()) return s;
        body->body.target = pose;
        return {};
    });
}

CLOTH_API cloth_result cloth_body_teleport(cloth_body_id id, const float position[3],
                                           const float rotation[4]) {
    return api_call(__func__, [&](const World*& log_world) -> Status {
        World* world;
        BodySlot* body;
        Status s = get_body(id, world, body, log_world);
        Pose pose;
        if (s.ok()) s = check_pose(position, rotation, "position", "rotation", &pose);
        if (!s.ok()) return s;
        // A carrier moves its cloth from where the body was at the end of
        // the last step (a second teleport before the step keeps that pose).
        if (!body->jumped) body->jumped_from = body->body.start;
        body->body.start = body->body.target = pose;
        body->jumped = true;
        return {};
    });
}

CLOTH_API cloth_result cloth_body_set_velocity(cloth_body_id id, const float linear[3],
                                               const float angular[3]) {
    return api_call(__func__, [&](const World*& log_world) -> Status {
        World* world;
        BodySlot* body;
        Status s = get_body(id, world, body, log_world);
        Vec3 l = Vec3::Zero(), a = Vec3::Zero();
        if (s.ok()) s = check_vector(linear, "linear", &l);
        if (s.ok()) s = check_vector(angular, "angular", &a);
        if (!s.ok()) return s;
        body->body.linear_velocity = l;
        body->body.angular_velocity = a;
        return {};
    });
}

CLOTH_API cloth_result cloth_body_get_pose(cloth_body_id id, float out_position[3], float out_rotation[4]) {
    return api_call(__func__, [&](const World*& log_world) -> Status {
        World* world;
        BodySlot* body;
        Status s = get_body(id, world, body, log_world);
        if (!s.ok()) return s;
        if (!out_position) return null_error("out_position");
        if (!out_rotation) return null_error("out_rotation");
        const Pose& p = body->body.target;
        for (int k = 0; k < 3; ++k) out_position[k] = p.position[k];
        out_rotation[0] = p.rotation.x();
        out_rotation[1] = p.rotation.y();
        out_rotation[2] = p.rotation.z();
        out_rotation[3] = p.rotation.w();
        return {};
    });
}

// ================================================================ colliders

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
    return create_collider(__func__, world, desc, out,
                           [&](Shape& shape) { return build_sphere(radius, shape); });
}

CLOTH_API cloth_result cloth_collider_create_capsule(cloth_world_id world, const cloth_collider_desc* desc,
                                                     float radius, float half_height,
                                                     cloth_collider_id* out) {
    return create_collider(__func__, world, desc, out,
                           [&](Shape& shape) { return build_capsule(radius, half_height, shape); });
}

CLOTH_API cloth_result cloth_collider_create_box(cloth_world_id world, const cloth_collider_desc* desc,
                                                 const float half_extents[3], cloth_collider_id* out) {
    return create_collider(__func__, world, desc, out, [&](Shape& shape) {
        Vec3 e = Vec3::Zero();
        Status s = check_vector(half_extents, "half_extents", &e);
        return s.ok() ? build_box(e, shape) : s;
    });
}

CLOTH_API cloth_result cloth_collider_create_plane(cloth_world_id world, const cloth_collider_desc* desc,
                                                   const float normal[3], float offset,
                                                   cloth_collider_id* out) {
    return create_collider(__func__, world, desc, out, [&](Shape& shape) {
        Vec3 n = Vec3::Zero();
        Status s = check_vector(normal, "normal", &n);
        return s.ok() ? build_plane(n, offset, shape) : s;
    });
}

CLOTH_API cloth_result cloth_collider_create_convex_hull(cloth_world_id world,
                                                         const cloth_collider_desc* desc,
                                                         const float* points_xyz, uint32_t point_count,
                                                         cloth_collider_id* out) {
    return create_collider(__func__, world, desc, out, [&](Shape& shape) {
        if (!points_xyz) return null_error("points_xyz");
        if (point_count < 4 || point_count > 4096)
            return Status::error(CLOTH_ERROR_INVALID_COUNT, "point_count %u is not in 4..4096", point_count);
        Status s = check_finite_points(points_xyz, point_count, "points");
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
        if (vertex_count < 3 || vertex_count > (1u << 24))
            return Status::error(CLOTH_ERROR_INVALID_COUNT, "vertex_count %u is not in 3..2^24",
                                 vertex_count);
        if (triangle_count < 1 || triangle_count > (1u << 24))
            return Status::error(CLOTH_ERROR_INVALID_COUNT, "triangle_count %u is not in 1..2^24",
                                 triangle_count);
        Status s = check_finite_points(vertices_xyz, vertex_count, "vertices");
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
        if (field->columns < 2 || field->columns > 65536 || field->rows < 2 || field->rows > 65536) {
            return Status::error(CLOTH_ERROR_INVALID_COUNT,
                                 "heightfield columns %u and rows %u must be in 2..65536", field->columns,
                                 field->rows);
        }
        for (float spacing : {field->spacing_x, field->spacing_z}) {
            if (!std::isfinite(spacing))
                return Status::error(CLOTH_ERROR_NOT_FINITE, "heightfield spacing is not finite");
            if (!(spacing > 0))
                return Status::error(CLOTH_ERROR_INVALID_VALUE, "heightfield spacing must be > 0");
        }
        if (!field->heights) return null_error("heightfield heights");
        const size_t count = static_cast<size_t>(field->columns) * field->rows;
        for (size_t k = 0; k < count; ++k) {
            if (!std::isfinite(field->heights[k]))
                return Status::error(CLOTH_ERROR_NOT_FINITE, "heights[%zu] is not finite", k);
        }
        return build_heightfield(field->columns, field->rows, field->spacing_x, field->spacing_z,
                                 field->heights, shape);
    });
}

CLOTH_API cloth_result cloth_collider_destroy(cloth_collider_id id) {
    return api_call(__func__, [&](const World*& log_world) -> Status {
        World* world;
        ColliderSlot* collider;
        Status s = get_collider(id, world, collider, log_world);
        if (!s.ok()) return s;
        world->contact().destroy_collider(id.index1 - 1u);
        return {};
    });
}

CLOTH_API cloth_result cloth_collider_set_group_bits(cloth_collider_id id, uint32_t group_bits) {
    return api_call(__func__, [&](const World*& log_world) -> Status {
        World* world;
        ColliderSlot* collider;
        Status s = get_collider(id, world, collider, log_world);
        if (!s.ok()) return s;
        collider->collider.group_bits = group_bits;
        return {};
    });
}

// ================================================================ cloth collision settings

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
    return api_call(__func__, [&](const World*& log_world) -> Status {
        ClothInstance* cloth;
        Status s = get_cloth(id, cloth, log_world);
        if (!s.ok()) return s;
        if (!params) return null_error("params");
        s = check_collision(*params);
        if (!s.ok()) return s;
        CollisionParams& core = cloth->contact().collision();
        core.thickness = params->thickness;
        core.friction = params->friction;
        core.collider_mask = params->collider_mask;
        return {};
    });
}

CLOTH_API cloth_result cloth_get_collision(cloth_id id, cloth_collision_params* out) {
    return api_call(__func__, [&](const World*& log_world) -> Status {
        ClothInstance* cloth;
        Status s = get_cloth(id, cloth, log_world);
        if (!s.ok()) return s;
        if (!out) return null_error("out_params");
        const CollisionParams& core = cloth->contact().collision();
        *out = cloth_default_collision_params();
        out->thickness = core.thickness;
        out->friction = core.friction;
        out->collider_mask = core.collider_mask;
        return {};
    });
}

// ================================================================ attachments

CLOTH_API cloth_result cloth_attach(cloth_id id, cloth_body_id body_id, const uint32_t* indices,
                                    const float* local_offsets_xyz, uint32_t count) {
    return api_call(__func__, [&](const World*& log_world) -> Status {
        ClothInstance* cloth;
        Status s = get_cloth(id, cloth, log_world);
        BodySlot* body = nullptr;
        if (s.ok()) s = get_body_of_cloth_world(id, body_id, body);
        if (s.ok()) s = check_indices(indices, count, cloth->particle_count());
        if (s.ok() && local_offsets_xyz) s = check_points(local_offsets_xyz, count, "local_offsets");
        if (!s.ok()) return s;
        ClothContact& contact = cloth->contact();
        contact.reserve_attachments(cloth->particle_count());  // may throw; nothing changed then
        const uint32_t slot = body_id.index1 - 1u;
        // A particle attached now sits at its target from the start of the
        // next step: the body's pose at the start of that step.
        const Pose& pose = body->body.start;
        const Fabric& fabric = cloth->fabric();
        for (uint32_t k = 0; k < count; ++k) {
            const uint32_t i = fabric.particle(indices[k]);
            const Vec3 offset = local_offsets_xyz
                                    ? Vec3(local_offsets_xyz[3 * k], local_offsets_xyz[3 * k + 1],
                                           local_offsets_xyz[3 * k + 2])
                                    : pose.apply_inverse(cloth->positions().get(i));
            contact.attach(i, slot, offset);
        }
        cloth->set_pinned(indices, count, true, /*vertex_indices=*/true);
        for (uint32_t k = 0; k < count; ++k) {
            const uint32_t i = fabric.particle(indices[k]);
            cloth->set_position(i, pose.apply(contact.attached_offset(i)));
        }
        return {};
    });
}

CLOTH_API cloth_result cloth_detach(cloth_id id, const uint32_t* indices, uint32_t count) {
    return api_call(__func__, [&](const World*& log_world) -> Status {
        ClothInstance* cloth;
        Status s = get_cloth(id, cloth, log_world);
        if (s.ok()) s = check_indices(indices, count, cloth->particle_count());
        if (!s.ok()) return s;
        for (uint32_t k = 0; k < count; ++k) {
            if (!cloth->contact().is_attached(cloth->fabric().particle(indices[k])))
                return Status::error(CLOTH_ERROR_INVALID_VALUE, "particle %u is not attached", indices[k]);
        }
        cloth->set_pinned(indices, count, false, /*vertex_indices=*/true);
        return {};
    });
}

CLOTH_API cloth_result cloth_get_attachment(cloth_id id, uint32_t index, cloth_body_id* out_body,
                                            float out_local_offset[3]) {
    return api_call(__func__, [&](const World*& log_world) -> Status {
        ClothInstance* cloth;
        Status s = get_cloth(id, cloth, log_world);
        if (!s.ok()) return s;
        if (!out_body) return null_error("out_body");
        if (index >= cloth->particle_count()) {
            return Status::error(CLOTH_ERROR_INDEX_OUT_OF_RANGE, "index %u, but the cloth has %u particles",
                                 index, cloth->particle_count());
        }
        const ClothContact& contact = cloth->contact();
        const uint32_t particle = cloth->fabric().particle(index);
        if (!contact.is_attached(particle)) {
            *out_body = cloth_body_id{};
            if (out_local_offset) out_local_offset[0] = out_local_offset[1] = out_local_offset[2] = 0.0f;
            return {};
        }
        const uint32_t slot = contact.attached_body(particle);
        write_id(out_body, slot, contact.world()->body(slot), id);
        if (out_local_offset) {
            const Vec3 offset = contact.attached_offset(particle);
            for (int k = 0; k < 3; ++k) out_local_offset[k] = offset[k];
        }
        return {};
    });
}

// ================================================================ carrier

CLOTH_API cloth_carrier_desc cloth_default_carrier_desc(void) {
    const CarrierParams core;
    cloth_carrier_desc d{};
    d.struct_size = sizeof(cloth_carrier_desc);
    d.linear_inertia = core.linear_inertia;
    d.angular_inertia = core.angular_inertia;
    d.centrifugal_inertia = core.centrifugal_inertia;
    d.max_relative_speed = core.max_relative_speed;
    d.teleport_distance = core.teleport_distance;
    d.teleport_rotation = core.teleport_rotation;
    d.teleport_mode = CLOTH_TELEPORT_DEFAULT;
    d.internal_cookie = kCookie;
    return d;
}

CLOTH_API cloth_result cloth_set_carrier(cloth_id id, cloth_body_id body_id, const cloth_carrier_desc* desc) {
    return api_call(__func__, [&](const World*& log_world) -> Status {
        ClothInstance* cloth;
        Status s = get_cloth(id, cloth, log_world);
        if (!s.ok()) return s;
        const bool null_body = body_id.index1 == 0 && body_id.world1 == 0 && body_id.generation == 0 &&
                               body_id.world_generation == 0;
        if (null_body) {
            cloth->contact().carrier().clear();
            return {};
        }
        BodySlot* body = nullptr;
        s = get_body_of_cloth_world(id, body_id, body);
        if (!s.ok()) return s;
        if (!desc) return null_error("desc");
        s = check_carrier(*desc);
        if (!s.ok()) return s;
        CarrierParams params;
        params.linear_inertia = desc->linear_inertia;
        params.angular_inertia = desc->angular_inertia;
        params.centrifugal_inertia = desc->centrifugal_inertia;
        params.max_relative_speed = desc->max_relative_speed;
        params.teleport_distance = desc->teleport_distance;
        params.teleport_rotation = desc->teleport_rotation;
        params.teleport_mode =
            desc->teleport_mode == CLOTH_TELEPORT_DEFAULT ? CLOTH_TELEPORT_MOVE : desc->teleport_mode;
        cloth->contact().carrier().set(body_id.index1 - 1u, body->body, params, cloth->positions());
        return {};
    });
}

CLOTH_API cloth_result cloth_get_teleported(cloth_id id, bool* out_teleported) {
    return api_call(__func__, [&](const World*& log_world) -> Status {
        ClothInstance* cloth;
        Status s = get_cloth(id, cloth, log_world);
        if (!s.ok()) return s;
        if (!out_teleported) return null_error("out_teleported");
        *out_teleported = cloth->contact().carrier().teleported();
        return {};
    });
}

}  // extern "C"
