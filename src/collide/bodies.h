// Rigid frames the host moves (bodies) and the pose math shared by bodies,
// colliders, attachments and carriers. A body holds the pose it had at the
// end of the last step (`start`) and the pose the host set for the end of
// the next one (`target`); the step moves it between them across substeps
// (position linearly, rotation by slerp), so what rides on it never lags a
// frame behind.
#pragma once

#include <cstdint>

#include "base/math.h"

namespace cloth {

using Quat = Eigen::Quaternionf;

struct Pose {
    Vec3 position = Vec3::Zero();
    Quat rotation = Quat::Identity();

    Vec3 apply(const Vec3& p) const { return rotation * p + position; }
    Vec3 apply_inverse(const Vec3& p) const { return rotation.conjugate() * (p - position); }
    Pose operator*(const Pose& local) const {
        return {apply(local.position), (rotation * local.rotation).normalized()};
    }
};

// The pose at `fraction` of the way from a to b; exactly a at 0 and b at 1.
inline Pose interpolate(const Pose& a, const Pose& b, float fraction) {
    if (fraction <= 0.0f) return a;
    if (fraction >= 1.0f) return b;
    return {a.position + (b.position - a.position) * fraction, a.rotation.slerp(fraction, b.rotation)};
}

// The rotation vector (axis * angle, |angle| <= pi) of a unit quaternion.
inline Vec3 rotation_vector(const Quat& q) {
    Quat r = q.w() < 0 ? Quat(-q.w(), -q.x(), -q.y(), -q.z()) : q;
    const float s = r.vec().norm();
    if (s < 1e-7f) return r.vec() * 2.0f;
    return r.vec() * (2.0f * std::atan2(s, r.w()) / s);
}

struct Body {
    Pose start;   // at the end of the last step
    Pose target;  // at the end of the next step
    Vec3 linear_velocity = Vec3::Zero();
    Vec3 angular_velocity = Vec3::Zero();

    Pose pose_at(float fraction) const { return interpolate(start, target, fraction); }
    // Velocity of the material point now at world position p (for friction).
    Vec3 point_velocity(const Vec3& p) const {
        return linear_velocity + angular_velocity.cross(p - target.position);
    }
};

}  // namespace cloth
