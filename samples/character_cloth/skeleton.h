// A procedurally animated character: a skeleton of 17 joints and a
// scripted clip (idle, walk, run, a sharp turn, a jump with its landing, a
// 360-degree spin and a teleport back to the start), evaluated at any
// time. No asset files: every pose comes from a few sines of the gait.
#pragma once

#include <Eigen/Geometry>
#include <array>
#include <cstdint>

namespace character_cloth {

enum Joint : uint32_t {
    kPelvis,
    kSpine,
    kChest,
    kNeck,
    kHead,
    kLeftUpperArm,
    kLeftForearm,
    kLeftHand,
    kRightUpperArm,
    kRightForearm,
    kRightHand,
    kLeftThigh,
    kLeftShin,
    kLeftFoot,
    kRightThigh,
    kRightShin,
    kRightFoot,
    kJointCount
};

// The character faces +z, its left is +x, y is up; the bind pose stands at
// the origin with the arms down.
struct Pose {
    std::array<Eigen::Affine3f, kJointCount> world;  // each joint's frame in the world
};

enum class Phase { kIdle, kWalk, kRun, kTurn, kJump, kSpin, kTeleported };
const char* phase_name(Phase phase);

class Clip {
  public:
    // Seconds the clip lasts.
    static constexpr float kDuration = 14.0f;

    // The pose at time t (>= the last time asked: the root integrates its
    // path), and whether the root jumped back to the start since then.
    Pose advance(float t, bool* teleported);
    Phase phase(float t) const;
    // The bind pose (every joint's frame with the root at the origin).
    static Pose bind_pose();

  private:
    float time_ = 0, gait_ = 0, yaw_ = 0;
    Eigen::Vector3f root_ = Eigen::Vector3f::Zero();
    bool teleported_ = false;
};

}  // namespace character_cloth
