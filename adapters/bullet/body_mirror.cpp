// BodyMirror: one cloth body (with the colliders of its shape) per mirrored
// Bullet collision object, its pose and velocities copied each frame.
#include <BulletDynamics/Dynamics/btRigidBody.h>
#include <cloth_bullet/cloth_bullet.h>

#include <algorithm>

namespace cloth_bullet {
namespace {

void velocities(const btCollisionObject& object, float linear[3], float angular[3]) {
    // Bullet's world transform is the centre-of-mass frame, so the rigid
    // body's linear velocity is that of the cloth body's origin.
    const btRigidBody* rigid = btRigidBody::upcast(&object);
    const btVector3 v = rigid ? rigid->getLinearVelocity() : object.getInterpolationLinearVelocity();
    const btVector3 w = rigid ? rigid->getAngularVelocity() : object.getInterpolationAngularVelocity();
    for (int k = 0; k < 3; ++k) {
        linear[k] = v[k];
        angular[k] = w[k];
    }
}

}  // namespace

BodyMirror::~BodyMirror() {
    // Destroying a body destroys its colliders; if the world went first, the
    // handles are stale and the calls just report that.
    for (const btCollisionObject* object : order_) cloth_body_destroy(entries_.at(object).body);
}

void BodyMirror::cloth_pose(const btCollisionObject& object, float position[3], float rotation[4]) const {
    to_pose(object.getWorldTransform(), position, rotation);
    const btVector3& p = object.getWorldTransform().getOrigin();
    for (int k = 0; k < 3; ++k) position[k] = static_cast<float>(double{p[k]} - origin_[k]);
}

cloth_result BodyMirror::shift_origin(const btVector3& shift) {
    const float s[3] = {shift.x(), shift.y(), shift.z()};
    const cloth_result result = cloth_world_shift_origin(world_, s);
    if (result != CLOTH_OK) return fail(result, cloth_get_last_error());
    for (int k = 0; k < 3; ++k) origin_[k] += double{s[k]};
    return CLOTH_OK;
}

cloth_result BodyMirror::fail(cloth_result result, const std::string& message) {
    error_ = message;
    return result;
}

cloth_result BodyMirror::add(const btCollisionObject* object, uint32_t group_bits, cloth_body_id* out_body) {
    if (object == nullptr || out_body == nullptr)
        return fail(CLOTH_ERROR_NULL_POINTER, "object or out_body is null");
    if (entries_.count(object)) return fail(CLOTH_ERROR_INVALID_VALUE, "the object is mirrored already");
    if (object->getCollisionShape() == nullptr)
        return fail(CLOTH_ERROR_NULL_POINTER, "the object has no shape");
    std::vector<ColliderSpec> specs;
    std::string message;
    if (!describe_shape(*object->getCollisionShape(), btTransform::getIdentity(), &specs, &message)) {
        return fail(CLOTH_ERROR_INVALID_VALUE, message);
    }

    Entry entry;
    cloth_body_desc desc = cloth_default_body_desc();
    cloth_pose(*object, desc.position, desc.rotation);
    velocities(*object, desc.linear_velocity, desc.angular_velocity);
    cloth_result result = cloth_body_create(world_, &desc, &entry.body);
    if (result != CLOTH_OK) return fail(result, std::string("cloth_body_create: ") + cloth_get_last_error());
    for (const ColliderSpec& spec : specs) {
        cloth_collider_id collider{};
        result = create_collider(world_, spec, entry.body, group_bits, &collider);
        if (result != CLOTH_OK) {
            message = std::string(collider_kind_name(spec.kind)) + " collider: " + cloth_get_last_error();
            cloth_body_destroy(entry.body);  // takes the colliders made so far with it
            return fail(result, message);
        }
        entry.colliders.push_back(collider);
    }
    *out_body = entry.body;
    entries_.emplace(object, std::move(entry));
    order_.push_back(object);
    return CLOTH_OK;
}

cloth_result BodyMirror::remove(const btCollisionObject* object) {
    const auto it = entries_.find(object);
    if (it == entries_.end()) return fail(CLOTH_ERROR_INVALID_VALUE, "the object is not mirrored");
    cloth_body_destroy(it->second.body);
    entries_.erase(it);
    order_.erase(std::find(order_.begin(), order_.end(), object));
    return CLOTH_OK;
}

cloth_result BodyMirror::teleport(const btCollisionObject* object) {
    const auto it = entries_.find(object);
    if (it == entries_.end()) return fail(CLOTH_ERROR_INVALID_VALUE, "the object is not mirrored");
    float position[3], rotation[4], linear[3], angular[3];
    cloth_pose(*object, position, rotation);
    velocities(*object, linear, angular);
    cloth_result result = cloth_body_teleport(it->second.body, position, rotation);
    if (result == CLOTH_OK) result = cloth_body_set_velocity(it->second.body, linear, angular);
    return result == CLOTH_OK ? CLOTH_OK : fail(result, cloth_get_last_error());
}

cloth_result BodyMirror::sync() {
    for (const btCollisionObject* object : order_) {
        const Entry& entry = entries_.at(object);
        float position[3], rotation[4], linear[3], angular[3];
        cloth_pose(*object, position, rotation);
        velocities(*object, linear, angular);
        cloth_result result = cloth_body_set_pose(entry.body, position, rotation);
        if (result == CLOTH_OK) result = cloth_body_set_velocity(entry.body, linear, angular);
        if (result != CLOTH_OK) return fail(result, cloth_get_last_error());
    }
    return CLOTH_OK;
}

cloth_body_id BodyMirror::body(const btCollisionObject* object) const {
    const auto it = entries_.find(object);
    return it == entries_.end() ? cloth_body_id{} : it->second.body;
}

const std::vector<cloth_collider_id>& BodyMirror::colliders(const btCollisionObject* object) const {
    static const std::vector<cloth_collider_id> kNone;
    const auto it = entries_.find(object);
    return it == entries_.end() ? kNone : it->second.colliders;
}

}  // namespace cloth_bullet
