/*
 * cloth_bullet C entry points: the Bullet adapter for hosts that speak C to
 * the cloth library. Bullet objects are passed as opaque pointers
 * (`const void*` to a btCollisionObject or a btCollisionShape of the same
 * Bullet build the adapter was compiled against); no Bullet type appears
 * here. See cloth_bullet.h for what is mirrored and how (one-way coupling).
 * Results are cloth_result codes; cloth_bullet_get_last_error() explains
 * the last failure on the calling thread.
 */
#ifndef CLOTH_BULLET_C_H
#define CLOTH_BULLET_C_H

#include <cloth/cloth.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct cloth_bullet_mirror cloth_bullet_mirror;

/// Create a mirror of Bullet objects into `world`.
cloth_result cloth_bullet_mirror_create(cloth_world_id world, cloth_bullet_mirror** out_mirror);
/// Destroy the mirror and the bodies and colliders it made. NULL is fine.
void cloth_bullet_mirror_destroy(cloth_bullet_mirror* mirror);
/// Mirror a btCollisionObject: a body at its pose, colliders for its shape.
cloth_result cloth_bullet_mirror_add(cloth_bullet_mirror* mirror, const void* bt_collision_object,
                                     uint32_t group_bits, cloth_body_id* out_body);
/// Stop mirroring an object (its body and colliders are destroyed).
cloth_result cloth_bullet_mirror_remove(cloth_bullet_mirror* mirror, const void* bt_collision_object);
/// The object was teleported: move its body there now, without a sweep.
cloth_result cloth_bullet_mirror_teleport(cloth_bullet_mirror* mirror, const void* bt_collision_object);
/// Copy all mirrored poses and velocities into the bodies (after the Bullet
/// step, before cloth_step).
cloth_result cloth_bullet_mirror_sync(cloth_bullet_mirror* mirror);
/// Origin rebasing (cloth_world_shift_origin): move the cloth world's origin
/// by `shift` and remember it; every pose the mirror copies from then on is
/// Bullet's minus the accumulated origin (kept in double). A cloth position
/// plus the origin is its Bullet position.
cloth_result cloth_bullet_mirror_shift_origin(cloth_bullet_mirror* mirror, const float shift[3]);
/// The Bullet position of the cloth world's origin (0 until the first shift).
cloth_result cloth_bullet_mirror_get_origin(const cloth_bullet_mirror* mirror, double out_origin[3]);

/// Colliders for a btCollisionShape, fixed to `body` (null: static) at the
/// local pose (position xyz, quaternion xyzw; NULL: identity). Writes up to
/// `capacity` ids and the number made to *out_count; with too small a
/// capacity nothing is created and CLOTH_ERROR_INVALID_COUNT tells the count
/// needed in *out_count.
cloth_result cloth_bullet_create_colliders(cloth_world_id world, const void* bt_collision_shape,
                                           cloth_body_id body, const float local_position[3],
                                           const float local_rotation[4], uint32_t group_bits,
                                           cloth_collider_id* out_colliders, uint32_t capacity,
                                           uint32_t* out_count);

/// The message of the last failed cloth_bullet call on this thread ("" if none).
const char* cloth_bullet_get_last_error(void);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* CLOTH_BULLET_C_H */
