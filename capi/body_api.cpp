// C API: bodies, the rigid frames the host moves (cloth.h section "Bodies,
// colliders and attachments"). Every argument is checked before anything
// changes.
#include <cloth/cloth.h>

#include "api_call.h"
#include "api_validation.h"

using namespace cloth;
using namespace cloth::api;

extern "C" {

CLOTH_API cloth_body_desc cloth_default_body_desc(void) {
    cloth_body_desc d{};
    d.struct_size = sizeof(cloth_body_desc);
    d.rotation[3] = 1.0f;
    d.internal_cookie = kCookie;
    return d;
}

CLOTH_API cloth_result cloth_body_create(cloth_world_id world_id, const cloth_body_desc* desc,
                                         cloth_body_id* out_body) {
    return with_world(__func__, world_id, [&](World& world) -> Status {
        if (!desc) return null_error("desc");
        if (!out_body) return null_error("out_body");
        Status s =
            check_desc(desc->struct_size, sizeof(cloth_body_desc), desc->internal_cookie, "cloth_body_desc");
        if (!s.ok()) return s;
        Body body;
        s = check_pose(desc->position, desc->rotation, "position", "rotation", &body.start);
        if (s.ok()) s = check_vector(desc->linear_velocity, "linear_velocity", &body.linear_velocity);
        if (s.ok()) s = check_vector(desc->angular_velocity, "angular_velocity", &body.angular_velocity);
        if (!s.ok()) return s;
        body.target = body.start;
        uint32_t slot;
        uint16_t generation;
        s = world.contact().create_body(body, &slot, &generation);
        if (!s.ok()) return s;
        *out_body =
            cloth_body_id{static_cast<uint16_t>(slot + 1), world_id.index1, generation, world_id.generation};
        return {};
    });
}

CLOTH_API cloth_result cloth_body_destroy(cloth_body_id id) {
    return with_body(__func__, id, [&](BodyState&, World& world) -> Status {
        world.destroy_body(id.index1 - 1u);
        return {};
    });
}

CLOTH_API bool cloth_body_is_valid(cloth_body_id id) { return is_live(id); }

CLOTH_API cloth_result cloth_body_set_pose(cloth_body_id id, const float position[3],
                                           const float rotation[4]) {
    return with_body(__func__, id, [&](BodyState& body) -> Status {
        Pose pose;
        Status s = check_pose(position, rotation, "position", "rotation", &pose);
        if (!s.ok()) return s;
        body.body.target = pose;
        return {};
    });
}

CLOTH_API cloth_result cloth_world_set_body_poses(cloth_world_id world_id, const cloth_body_id* bodies,
                                                  const float* positions_xyz, const float* rotations_xyzw,
                                                  uint32_t count) {
    return with_world(__func__, world_id, [&](World& world) -> Status {
        if (!bodies) return null_error("bodies");
        if (!positions_xyz) return null_error("positions_xyz");
        if (!rotations_xyzw) return null_error("rotations_xyzw");
        if (count == 0 || count > CLOTH_MAX_BODIES) {
            return Status::error(CLOTH_ERROR_INVALID_COUNT, "count %u is not in 1..%u", count,
                                 static_cast<uint32_t>(CLOTH_MAX_BODIES));
        }
        // Every entry first: a rejected call moves no body.
        for (uint32_t k = 0; k < count; ++k) {
            Status s = check_same_world(bodies[k], world_id, "body", "the call's world");
            if (s.ok() && !find_object(world, bodies[k])) s = no_object_error("body");
            Pose pose;
            if (s.ok())
                s = check_pose(positions_xyz + 3 * k, rotations_xyzw + 4 * k, "positions_xyz",
                               "rotations_xyzw", &pose);
            if (!s.ok()) return Status::error(s.code, "entry %u: %.360s", k, s.message);  // fits the message
        }
        for (uint32_t k = 0; k < count; ++k) {
            Pose pose;
            check_pose(positions_xyz + 3 * k, rotations_xyzw + 4 * k, "positions_xyz", "rotations_xyzw",
                       &pose);
            find_object(world, bodies[k])->body.target = pose;
        }
        return {};
    });
}

CLOTH_API cloth_result cloth_body_teleport(cloth_body_id id, const float position[3],
                                           const float rotation[4]) {
    return with_body(__func__, id, [&](BodyState& body) -> Status {
        Pose pose;
        Status s = check_pose(position, rotation, "position", "rotation", &pose);
        if (!s.ok()) return s;
        if (!body.jumped) body.before_jump = body.body.start;
        body.body.start = body.body.target = pose;
        body.jumped = true;
        return {};
    });
}

CLOTH_API cloth_result cloth_body_set_velocity(cloth_body_id id, const float linear[3],
                                               const float angular[3]) {
    return with_body(__func__, id, [&](BodyState& body) -> Status {
        Vec3 l = Vec3::Zero(), a = Vec3::Zero();
        Status s = check_vector(linear, "linear", &l);
        if (s.ok()) s = check_vector(angular, "angular", &a);
        if (!s.ok()) return s;
        body.body.linear_velocity = l;
        body.body.angular_velocity = a;
        return {};
    });
}

CLOTH_API cloth_result cloth_body_get_pose(cloth_body_id id, float out_position[3], float out_rotation[4]) {
    return with_body(__func__, id, [&](BodyState& body) -> Status {
        if (!out_position) return null_error("out_position");
        if (!out_rotation) return null_error("out_rotation");
        const Pose& p = body.body.target;
        for (int k = 0; k < 3; ++k) out_position[k] = p.position[k];
        out_rotation[0] = p.rotation.x();
        out_rotation[1] = p.rotation.y();
        out_rotation[2] = p.rotation.z();
        out_rotation[3] = p.rotation.w();
        return {};
    });
}

}  // extern "C"
