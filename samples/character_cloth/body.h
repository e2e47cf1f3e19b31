// The character's body as the cloth sees it: tapered capsules on the
// limbs, capsules on the spine and neck, spheres for the pelvis, head,
// hands and feet, each a collider on the body of its joint. One call
// moves every body each frame. Also a mesh of each part for the pictures,
// and the signed distance to the body, computed here (not by the library)
// for the sample's checks.
#pragma once

#include <cloth/cloth.h>

#include <string>
#include <vector>

#include "skeleton.h"

namespace character_cloth {

// Collider groups: a cape hangs clear of the arms' swing and collides
// with the trunk and legs only (an arm that swings through it would
// otherwise hook it); a skirt collides with everything.
constexpr uint32_t kTrunkAndLegs = 1, kArms = 2;

struct BodyPart {
    Joint joint;
    float bottom_radius, top_radius, half_height;  // a sphere: half_height 0 and equal radii
    float x, y, z;                                 // centre in the joint's frame (axis: the joint's y)
    uint32_t group;
};

class CharacterBody {
  public:
    // Bodies and colliders in `world` at the pose; false with a message.
    bool create(cloth_world_id world, const Pose& pose, std::string* error);
    // Every joint's body to the pose: one call, or with `teleport` one
    // cloth_body_teleport per body (no sweep across the jump).
    cloth_result move(const Pose& pose, bool teleport);
    cloth_body_id root() const { return bodies_[kPelvis]; }

    // The least signed distance of world point p to the body's parts in
    // the groups of `mask`, m.
    static float distance(const Pose& pose, const float* p, uint32_t mask);
    // Triangles of every part at the pose, for drawing.
    static void append_mesh(const Pose& pose, std::vector<float>* positions, std::vector<float>* normals,
                            std::vector<uint32_t>* indices);
    static const std::vector<BodyPart>& parts();

  private:
    cloth_world_id world_{};
    std::vector<cloth_body_id> bodies_;
};

}  // namespace character_cloth
