#include "collide/carrier.h"

#include <cmath>
#include <limits>

#include "base/lanes.h"

namespace cloth {

namespace {

// What begin_step adds to the free particles' velocities, as rotation
// matrices and vectors (a 3x3 product per rotation instead of a quaternion
// product's two cross products), so the loop below vectorizes.
struct CarriedMotion {
    Vec3 origin;
    Mat3 turn, previous_turn_inverse;
    Vec3 turn_vector, previous_turn_vector, previous_linear, linear, linear_change;
    float keep_angular, keep_centrifugal, max_speed, inverse_dt;
};

// One free particle's velocity change: the carrier's rigid velocity at its
// point this frame (B) and the previous one (A), split into tangential and
// centripetal parts, each kept by its share, then the speed relative to
// the carrier clamped. Pinned particles keep theirs.
// Raw __restrict parameters: GCC does not vectorize through restrict locals.
CLOTH_HOT_LOOP void carry_velocities(const CarriedMotion& m, const float* __restrict pinned, uint32_t begin,
                                     uint32_t end, const float* __restrict px, const float* __restrict py,
                                     const float* __restrict pz, float* __restrict vx, float* __restrict vy,
                                     float* __restrict vz) {
    // Every constant in a local: loads through `m` inside the loop could
    // alias the stores, and GCC would not vectorize it.
    const float b00 = m.turn(0, 0), b01 = m.turn(0, 1), b02 = m.turn(0, 2), b10 = m.turn(1, 0),
                b11 = m.turn(1, 1), b12 = m.turn(1, 2), b20 = m.turn(2, 0), b21 = m.turn(2, 1),
                b22 = m.turn(2, 2);
    const Mat3& ai = m.previous_turn_inverse;
    const float a00 = ai(0, 0), a01 = ai(0, 1), a02 = ai(0, 2), a10 = ai(1, 0), a11 = ai(1, 1),
                a12 = ai(1, 2), a20 = ai(2, 0), a21 = ai(2, 1), a22 = ai(2, 2);
    const float tbx = m.turn_vector.x(), tby = m.turn_vector.y(), tbz = m.turn_vector.z();
    const float tax = m.previous_turn_vector.x(), tay = m.previous_turn_vector.y(),
                taz = m.previous_turn_vector.z();
    const float ox = m.origin.x(), oy = m.origin.y(), oz = m.origin.z();
    const float plx = m.previous_linear.x(), ply = m.previous_linear.y(), plz = m.previous_linear.z();
    const float lx = m.linear.x(), ly = m.linear.y(), lz = m.linear.z();
    const float lcx = m.linear_change.x(), lcy = m.linear_change.y(), lcz = m.linear_change.z();
    const float idt = m.inverse_dt, ka = m.keep_angular, kc = m.keep_centrifugal;
    // No clamp: a limit no speed reaches.
    const float max_speed = m.max_speed > 0 ? m.max_speed : std::numeric_limits<float>::infinity();
    for (uint32_t i = begin; i < end; ++i) {
        const float rx = px[i] - ox, ry = py[i] - oy, rz = pz[i] - oz;
        const float bx = b00 * rx + b01 * ry + b02 * rz, by = b10 * rx + b11 * ry + b12 * rz,
                    bz = b20 * rx + b21 * ry + b22 * rz;
        const float ax = a00 * rx + a01 * ry + a02 * rz, ay = a10 * rx + a11 * ry + a12 * rz,
                    az = a20 * rx + a21 * ry + a22 * rz;
        const float rot_bx = (bx - rx) * idt, rot_by = (by - ry) * idt, rot_bz = (bz - rz) * idt;
        const float rot_ax = (rx - ax) * idt, rot_ay = (ry - ay) * idt, rot_az = (rz - az) * idt;
        const float tan_bx = (tby * rz - tbz * ry) * idt, tan_by = (tbz * rx - tbx * rz) * idt,
                    tan_bz = (tbx * ry - tby * rx) * idt;
        const float tan_ax = (tay * rz - taz * ry) * idt, tan_ay = (taz * rx - tax * rz) * idt,
                    tan_az = (tax * ry - tay * rx) * idt;
        const float v0x = vx[i], v0y = vy[i], v0z = vz[i];
        const float relx = v0x - plx - rot_ax, rely = v0y - ply - rot_ay, relz = v0z - plz - rot_az;
        const float turned_x = b00 * relx + b01 * rely + b02 * relz,
                    turned_y = b10 * relx + b11 * rely + b12 * relz,
                    turned_z = b20 * relx + b21 * rely + b22 * relz;
        float wx = v0x + lcx, wy = v0y + lcy, wz = v0z + lcz;
        wx += (tan_bx - tan_ax + (turned_x - relx)) * ka;
        wy += (tan_by - tan_ay + (turned_y - rely)) * ka;
        wz += (tan_bz - tan_az + (turned_z - relz)) * ka;
        wx += ((rot_bx - tan_bx) - (rot_ax - tan_ax)) * kc;
        wy += ((rot_by - tan_by) - (rot_ay - tan_ay)) * kc;
        wz += ((rot_bz - tan_bz) - (rot_az - tan_az)) * kc;
        const float cx = lx + rot_bx, cy = ly + rot_by, cz = lz + rot_bz;
        const float nx = wx - cx, ny = wy - cy, nz = wz - cz;
        const float speed = std::sqrt(nx * nx + ny * ny + nz * nz);
        const float scale = max_speed / speed;
        wx = speed > max_speed ? cx + nx * scale : wx;
        wy = speed > max_speed ? cy + ny * scale : wy;
        wz = speed > max_speed ? cz + nz * scale : wz;
        vx[i] = pinned[i] == 0.0f ? wx : v0x;
        vy[i] = pinned[i] == 0.0f ? wy : v0y;
        vz[i] = pinned[i] == 0.0f ? wz : v0z;
    }
}

}  // namespace

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
    CarriedMotion m;
    m.origin = from.position;
    m.turn = turn.toRotationMatrix();
    m.previous_turn_inverse = previous_turn_inverse.toRotationMatrix();
    m.turn_vector = turn_vector;
    m.previous_turn_vector = previous_turn_vector;
    m.previous_linear = previous_linear_;
    m.linear = linear;
    m.linear_change = (linear - previous_linear_) * (1.0f - params_.linear_inertia);
    m.keep_angular = 1.0f - params_.angular_inertia;
    m.keep_centrifugal = 1.0f - params_.centrifugal_inertia;
    m.max_speed = params_.max_relative_speed;
    m.inverse_dt = 1.0f / dt;
    carry_velocities(m, pinned, 0, n, x.x.data(), x.y.data(), x.z.data(), v.x.data(), v.y.data(), v.z.data());
    previous_linear_ = linear;
    previous_angular_ = angular;
}

}  // namespace cloth
