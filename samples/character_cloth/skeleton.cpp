#include "skeleton.h"

#include <algorithm>
#include <cmath>

namespace character_cloth {

namespace {

constexpr float kPi = 3.14159265f;

struct Bone {
    Joint parent;
    float x, y, z;  // offset from the parent's joint in the bind pose
};
// Offsets along the body; the root (the pelvis) is 0.97 m above the feet's soles.
constexpr Bone kBones[kJointCount] = {
    {kPelvis, 0, 0.97f, 0},         {kPelvis, 0, 0.12f, 0},        {kSpine, 0, 0.2f, 0},
    {kChest, 0, 0.22f, 0},          {kNeck, 0, 0.1f, 0},           {kChest, 0.22f, 0.16f, 0},
    {kLeftUpperArm, 0, -0.28f, 0},  {kLeftForearm, 0, -0.25f, 0},  {kChest, -0.22f, 0.16f, 0},
    {kRightUpperArm, 0, -0.28f, 0}, {kRightForearm, 0, -0.25f, 0}, {kPelvis, 0.1f, -0.05f, 0},
    {kLeftThigh, 0, -0.42f, 0},     {kLeftShin, 0, -0.42f, 0},     {kPelvis, -0.1f, -0.05f, 0},
    {kRightThigh, 0, -0.42f, 0},    {kRightShin, 0, -0.42f, 0},
};

// When each part of the clip starts, s.
constexpr float kWalkAt = 2.0f, kRunAt = 4.5f, kTurnAt = 7.0f, kTurnEnd = 7.35f, kJumpAt = 8.6f,
                kLandAt = 9.3f, kSpinAt = 10.3f, kSpinEnd = 11.3f, kTeleportAt = 12.3f;
constexpr float kTakeOffSpeed = 3.4f;  // m/s up: 0.69 s in the air

float smooth(float edge0, float edge1, float t) {
    const float s = std::clamp((t - edge0) / (edge1 - edge0), 0.0f, 1.0f);
    return s * s * (3.0f - 2.0f * s);
}

float ground_speed(float t) {
    if (t < kWalkAt) return 0.0f;
    if (t < kRunAt) return 1.4f * smooth(kWalkAt, kWalkAt + 0.5f, t);
    if (t < kSpinAt) return 1.4f + 3.6f * smooth(kRunAt, kRunAt + 0.8f, t);
    return 5.0f * (1.0f - smooth(kSpinAt - 0.3f, kSpinAt + 0.2f, t));
}

Eigen::Quaternionf about(float angle, const Eigen::Vector3f& axis) {
    return Eigen::Quaternionf(Eigen::AngleAxisf(angle, axis));
}

}  // namespace

const char* phase_name(Phase phase) {
    switch (phase) {
        case Phase::kIdle:
            return "idle";
        case Phase::kWalk:
            return "walk";
        case Phase::kRun:
            return "run";
        case Phase::kTurn:
            return "sharp turn";
        case Phase::kJump:
            return "jump";
        case Phase::kSpin:
            return "spin";
        case Phase::kTeleported:
            return "teleported";
    }
    return "?";
}

Phase Clip::phase(float t) const {
    if (t >= kTeleportAt) return Phase::kTeleported;
    if (t >= kSpinAt) return Phase::kSpin;
    if (t >= kJumpAt - 0.2f) return Phase::kJump;
    if (t >= kTurnAt && t < kTurnEnd) return Phase::kTurn;
    if (t >= kRunAt) return Phase::kRun;
    if (t >= kWalkAt) return Phase::kWalk;
    return Phase::kIdle;
}

Pose Clip::bind_pose() {
    Pose pose;
    for (uint32_t j = 0; j < kJointCount; ++j) {
        const Bone& b = kBones[j];
        const Eigen::Affine3f local(Eigen::Translation3f(b.x, b.y, b.z));
        pose.world[j] = j == kPelvis ? local : pose.world[b.parent] * local;
    }
    return pose;
}

Pose Clip::advance(float t, bool* teleported) {
    // The root's path: speed along the heading, the heading turned by the
    // sharp turn and the spin; the gait's phase follows the distance.
    const float dt = std::max(0.0f, t - time_);
    const float speed = ground_speed(t);
    if (t >= kTurnAt && time_ < kTurnEnd) yaw_ = 0.5f * kPi * smooth(kTurnAt, kTurnEnd, t);
    float spin = 0.0f;
    if (t >= kSpinAt) spin = 2.0f * kPi * smooth(kSpinAt, kSpinEnd, t);
    root_ += dt * speed * Eigen::Vector3f(std::sin(yaw_), 0.0f, std::cos(yaw_));
    gait_ += dt * (speed > 0.0f ? 2.0f * kPi * speed / (speed < 2.0f ? 1.4f : 2.4f) : 0.0f);
    *teleported = false;
    if (t >= kTeleportAt && !teleported_) {
        teleported_ = true;
        *teleported = true;
        root_ = Eigen::Vector3f::Zero();
        yaw_ = 0.0f;
    }
    time_ = t;
    const float heading = teleported_ ? 0.0f : yaw_ + spin;

    // The jump: a crouch, a parabola, a crouch on landing.
    float lift = 0.0f, crouch = 0.0f;
    if (t >= kJumpAt && t < kLandAt) {
        const float air = t - kJumpAt;
        lift = std::max(0.0f, kTakeOffSpeed * air - 0.5f * 9.81f * air * air);
    }
    crouch +=
        0.12f * smooth(kJumpAt - 0.2f, kJumpAt - 0.05f, t) * (1.0f - smooth(kJumpAt - 0.05f, kJumpAt, t));
    crouch += 0.15f * smooth(kLandAt - 0.02f, kLandAt + 0.05f, t) *
              (1.0f - smooth(kLandAt + 0.1f, kLandAt + 0.4f, t));
    const bool airborne = t >= kJumpAt && t < kLandAt;

    // Limbs: thighs and arms swing with the gait, more when running;
    // shins bend on the swing; the chest leans into a run.
    const float stride = std::min(1.0f, speed / 5.0f);
    const float swing = (0.35f + 0.35f * stride) * (speed > 0.05f ? 1.0f : 0.0f);
    const float s = std::sin(gait_), c = std::cos(gait_);
    const float breathe = 0.02f * std::sin(1.7f * t);
    const Eigen::Vector3f x = Eigen::Vector3f::UnitX(), y = Eigen::Vector3f::UnitY(),
                          z = Eigen::Vector3f::UnitZ();
    std::array<Eigen::Quaternionf, kJointCount> turn;
    turn.fill(Eigen::Quaternionf::Identity());
    turn[kSpine] = about(0.25f * stride + breathe + 0.6f * crouch, x);
    turn[kChest] = about(0.1f * stride * s, y);
    turn[kHead] = about(-0.2f * stride, x);
    const float tuck = airborne ? 0.5f : 0.0f;
    turn[kLeftThigh] = about(-swing * s - tuck - 2.0f * crouch, x);
    turn[kRightThigh] = about(swing * s - tuck - 2.0f * crouch, x);
    turn[kLeftShin] = about(swing * 1.4f * std::max(0.0f, c) + 1.4f * tuck + 3.5f * crouch, x);
    turn[kRightShin] = about(swing * 1.4f * std::max(0.0f, -c) + 1.4f * tuck + 3.5f * crouch, x);
    turn[kLeftUpperArm] = about(swing * 0.8f * s, x) * about(0.3f + (airborne ? 1.2f : 0.0f), z);
    turn[kRightUpperArm] = about(-swing * 0.8f * s, x) * about(-0.3f - (airborne ? 1.2f : 0.0f), z);
    turn[kLeftForearm] = about(-0.3f - 0.9f * stride, x);
    turn[kRightForearm] = about(-0.3f - 0.9f * stride, x);

    Pose pose;
    const float bounce = 0.03f * stride * std::abs(c);
    for (uint32_t j = 0; j < kJointCount; ++j) {
        const Bone& b = kBones[j];
        if (j == kPelvis) {
            pose.world[j] = Eigen::Translation3f(root_.x(), b.y + lift + bounce - 0.9f * crouch, root_.z()) *
                            about(heading, y) * turn[j];
        } else {
            pose.world[j] = pose.world[b.parent] * Eigen::Translation3f(b.x, b.y, b.z) * turn[j];
        }
    }
    return pose;
}

}  // namespace character_cloth
