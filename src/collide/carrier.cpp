#include "collide/carrier.h"

#include <cmath>

namespace cloth {

void Carrier::set(uint32_t body_slot, const Body& body, const CarrierParams& params, const Vec3Soa& x) {
    reference_.resize(x.size());  // may throw; nothing changed then
    for (size_t i = 0; i < x.size(); ++i) reference_.set(i, body.start.apply_inverse(x.get(i)));
    body_ = body_slot;
    params_ = params;
    previous_linear_ = body.linear_velocity;
    previous_angular_ = body.angular_velocity;
    teleported_ = false;
}

void Carrier::clear() {
    body_ = UINT32_MAX;
    teleported_ = false;
}

void Carrier::begin_step(const Body& body, const Pose* jumped_from, float dt, const float* pinned,
                         const HostVector<uint32_t>* attached_body, Vec3Soa& x, Vec3Soa& v) {
    const bool body_jumped = jumped_from != nullptr;
    const Pose& from = body_jumped ? *jumped_from : body.start;
    const Pose& to = body.target;
    const Quat turn = (to.rotation * from.rotation.conjugate()).normalized();
    const Vec3 turn_vector = rotation_vector(turn);
    const Vec3 move = to.position - from.position;
    const uint32_t n = static_cast<uint32_t>(x.size());
    auto attached = [&](uint32_t i) { return attached_body && (*attached_body)[i] != UINT32_MAX; };

    teleported_ = body_jumped || (params_.teleport_distance > 0 && move.norm() > params_.teleport_distance) ||
                  (params_.teleport_rotation > 0 && turn_vector.norm() > params_.teleport_rotation);
    if (teleported_) {
        // The jump is not a velocity. Motion relative to the carrier turns
        // with it; the carrier moves on with the velocities the host gave
        // the body (cloth_body_set_velocity).
        const bool reset = params_.teleport_mode == CLOTH_TELEPORT_AND_RESET;
        const Vec3 old_linear = previous_linear_, old_angular = previous_angular_;
        previous_linear_ = body.linear_velocity;
        previous_angular_ = body.angular_velocity;
        for (uint32_t i = 0; i < n; ++i) {
            if (pinned[i] != 0.0f && !attached(i)) continue;
            if (reset) {
                const Vec3 p = to.apply(reference_.get(i));
                x.set(i, p);
                v.set(i, previous_linear_ + previous_angular_.cross(p - to.position));
            } else {
                const Vec3 r = x.get(i) - from.position;
                const Vec3 relative = v.get(i) - old_linear - old_angular.cross(r);
                const Vec3 p = turn * r + to.position;
                x.set(i, p);
                v.set(i, previous_linear_ + previous_angular_.cross(p - to.position) + turn * relative);
            }
        }
        return;
    }

    const Vec3 linear = move / dt;
    const Vec3 angular = turn_vector / dt;
    const Vec3 previous_turn_vector = previous_angular_ * dt;
    const float previous_angle = previous_turn_vector.norm();
    const Quat previous_turn_inverse =
        previous_angle > 0 ? Quat(Eigen::AngleAxisf(-previous_angle, previous_turn_vector / previous_angle))
                           : Quat::Identity();
    const float keep_linear = 1.0f - params_.linear_inertia;
    const float keep_angular = 1.0f - params_.angular_inertia;
    const float keep_centrifugal = 1.0f - params_.centrifugal_inertia;
    const float max_speed = params_.max_relative_speed;
    const Vec3 linear_change = (linear - previous_linear_) * keep_linear;
    const float inverse_dt = 1.0f / dt;

    for (uint32_t i = 0; i < n; ++i) {
        if (pinned[i] != 0.0f) continue;
        const Vec3 r = x.get(i) - from.position;
        // Rotation part of the carrier's rigid velocity at this point, this
        // frame (B) and the previous one (A), split into tangential and
        // centripetal parts.
        const Vec3 rotation_b = (turn * r - r) * inverse_dt;
        const Vec3 tangential_b = turn_vector.cross(r) * inverse_dt;
        const Vec3 rotation_a = (r - previous_turn_inverse * r) * inverse_dt;
        const Vec3 tangential_a = previous_turn_vector.cross(r) * inverse_dt;
        Vec3 velocity = v.get(i);
        const Vec3 relative = velocity - previous_linear_ - rotation_a;
        velocity += linear_change;
        velocity += (tangential_b - tangential_a + (turn * relative - relative)) * keep_angular;
        velocity += ((rotation_b - tangential_b) - (rotation_a - tangential_a)) * keep_centrifugal;
        if (max_speed > 0) {
            const Vec3 carried = linear + rotation_b;
            const Vec3 relative_now = velocity - carried;
            const float speed = relative_now.norm();
            if (speed > max_speed) velocity = carried + relative_now * (max_speed / speed);
        }
        v.set(i, velocity);
    }
    previous_linear_ = linear;
    previous_angular_ = angular;
}

}  // namespace cloth
