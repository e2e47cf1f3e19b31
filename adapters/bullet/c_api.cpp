// The C entry points of cloth_bullet over the C++ adapter. No exception
// leaves them: allocation failures become CLOTH_ERROR_OUT_OF_MEMORY.
#include <cloth_bullet/cloth_bullet.h>
#include <cloth_bullet/cloth_bullet_c.h>

#include <new>

struct cloth_bullet_mirror {
    explicit cloth_bullet_mirror(cloth_world_id world) : mirror(world) {}
    cloth_bullet::BodyMirror mirror;
};

namespace {

thread_local std::string g_last_error;

cloth_result fail(cloth_result result, const std::string& message) {
    g_last_error = message;
    return result;
}

cloth_result from_mirror(cloth_bullet_mirror* m, cloth_result result) {
    return result == CLOTH_OK ? CLOTH_OK : fail(result, m->mirror.last_error());
}

template <typename Call>
cloth_result guarded(Call&& call) {
    try {
        return call();
    } catch (const std::bad_alloc&) {
        return fail(CLOTH_ERROR_OUT_OF_MEMORY, "cloth_bullet: out of memory");
    } catch (...) {
        return fail(CLOTH_ERROR_INTERNAL, "cloth_bullet: unexpected internal error");
    }
}

}  // namespace

extern "C" {

cloth_result cloth_bullet_mirror_create(cloth_world_id world, cloth_bullet_mirror** out_mirror) {
    if (out_mirror == nullptr) return fail(CLOTH_ERROR_NULL_POINTER, "out_mirror is null");
    return guarded([&] {
        *out_mirror = new cloth_bullet_mirror(world);
        return CLOTH_OK;
    });
}

void cloth_bullet_mirror_destroy(cloth_bullet_mirror* mirror) { delete mirror; }

cloth_result cloth_bullet_mirror_add(cloth_bullet_mirror* mirror, const void* bt_collision_object,
                                     uint32_t group_bits, cloth_body_id* out_body) {
    if (mirror == nullptr) return fail(CLOTH_ERROR_NULL_POINTER, "mirror is null");
    return guarded([&] {
        return from_mirror(
            mirror, mirror->mirror.add(static_cast<const btCollisionObject*>(bt_collision_object), group_bits,
                                       out_body));
    });
}

cloth_result cloth_bullet_mirror_remove(cloth_bullet_mirror* mirror, const void* bt_collision_object) {
    if (mirror == nullptr) return fail(CLOTH_ERROR_NULL_POINTER, "mirror is null");
    return guarded([&] {
        return from_mirror(mirror,
                           mirror->mirror.remove(static_cast<const btCollisionObject*>(bt_collision_object)));
    });
}

cloth_result cloth_bullet_mirror_teleport(cloth_bullet_mirror* mirror, const void* bt_collision_object) {
    if (mirror == nullptr) return fail(CLOTH_ERROR_NULL_POINTER, "mirror is null");
    return guarded([&] {
        return from_mirror(
            mirror, mirror->mirror.teleport(static_cast<const btCollisionObject*>(bt_collision_object)));
    });
}

cloth_result cloth_bullet_mirror_sync(cloth_bullet_mirror* mirror) {
    if (mirror == nullptr) return fail(CLOTH_ERROR_NULL_POINTER, "mirror is null");
    return guarded([&] { return from_mirror(mirror, mirror->mirror.sync()); });
}

cloth_result cloth_bullet_mirror_shift_origin(cloth_bullet_mirror* mirror, const float shift[3]) {
    if (mirror == nullptr || shift == nullptr)
        return fail(CLOTH_ERROR_NULL_POINTER, "mirror or shift is null");
    return guarded([&] {
        return from_mirror(mirror, mirror->mirror.shift_origin(btVector3(shift[0], shift[1], shift[2])));
    });
}

cloth_result cloth_bullet_mirror_get_origin(const cloth_bullet_mirror* mirror, double out_origin[3]) {
    if (mirror == nullptr || out_origin == nullptr) {
        return fail(CLOTH_ERROR_NULL_POINTER, "mirror or out_origin is null");
    }
    for (int k = 0; k < 3; ++k) out_origin[k] = mirror->mirror.origin()[k];
    return CLOTH_OK;
}

cloth_result cloth_bullet_create_colliders(cloth_world_id world, const void* bt_collision_shape,
                                           cloth_body_id body, const float local_position[3],
                                           const float local_rotation[4], uint32_t group_bits,
                                           cloth_collider_id* out_colliders, uint32_t capacity,
                                           uint32_t* out_count) {
    if (bt_collision_shape == nullptr || out_count == nullptr) {
        return fail(CLOTH_ERROR_NULL_POINTER, "bt_collision_shape or out_count is null");
    }
    return guarded([&] {
        btTransform local = btTransform::getIdentity();
        if (local_position)
            local.setOrigin(btVector3(local_position[0], local_position[1], local_position[2]));
        if (local_rotation) {
            local.setRotation(
                btQuaternion(local_rotation[0], local_rotation[1], local_rotation[2], local_rotation[3]));
        }
        std::vector<cloth_bullet::ColliderSpec> specs;
        std::string message;
        if (!cloth_bullet::describe_shape(*static_cast<const btCollisionShape*>(bt_collision_shape), local,
                                          &specs, &message)) {
            return fail(CLOTH_ERROR_INVALID_VALUE, message);
        }
        *out_count = static_cast<uint32_t>(specs.size());
        if (specs.size() > capacity || out_colliders == nullptr) {
            return fail(CLOTH_ERROR_INVALID_COUNT, "the shape makes " + std::to_string(specs.size()) +
                                                       " colliders; capacity is " + std::to_string(capacity));
        }
        for (size_t i = 0; i < specs.size(); ++i) {
            const cloth_result result =
                cloth_bullet::create_collider(world, specs[i], body, group_bits, &out_colliders[i]);
            if (result != CLOTH_OK) {
                for (size_t j = 0; j < i; ++j) cloth_collider_destroy(out_colliders[j]);
                *out_count = 0;
                return fail(result, std::string(cloth_bullet::collider_kind_name(specs[i].kind)) +
                                        " collider: " + cloth_get_last_error());
            }
        }
        return CLOTH_OK;
    });
}

const char* cloth_bullet_get_last_error(void) { return g_last_error.c_str(); }

}  // extern "C"
