#include "body.h"

#include <algorithm>
#include <cmath>

namespace character_cloth {

namespace {

const std::vector<BodyPart> kParts = {
    {kPelvis, 0.16f, 0.16f, 0.0f, 0, 0.02f, 0, kTrunkAndLegs},
    {kSpine, 0.14f, 0.14f, 0.05f, 0, 0.1f, 0, kTrunkAndLegs},
    {kChest, 0.14f, 0.17f, 0.09f, 0, 0.11f, 0, kTrunkAndLegs},
    {kNeck, 0.05f, 0.05f, 0.04f, 0, 0.05f, 0, kTrunkAndLegs},
    {kHead, 0.11f, 0.11f, 0.0f, 0, 0.1f, 0, kTrunkAndLegs},
    {kLeftUpperArm, 0.045f, 0.06f, 0.14f, 0, -0.14f, 0, kArms},
    {kLeftForearm, 0.035f, 0.045f, 0.125f, 0, -0.125f, 0, kArms},
    {kLeftHand, 0.045f, 0.045f, 0.0f, 0, -0.05f, 0, kArms},
    {kRightUpperArm, 0.045f, 0.06f, 0.14f, 0, -0.14f, 0, kArms},
    {kRightForearm, 0.035f, 0.045f, 0.125f, 0, -0.125f, 0, kArms},
    {kRightHand, 0.045f, 0.045f, 0.0f, 0, -0.05f, 0, kArms},
    {kLeftThigh, 0.06f, 0.085f, 0.21f, 0, -0.21f, 0, kTrunkAndLegs},
    {kLeftShin, 0.045f, 0.06f, 0.21f, 0, -0.21f, 0, kTrunkAndLegs},
    {kLeftFoot, 0.05f, 0.05f, 0.0f, 0, -0.02f, 0.05f, kTrunkAndLegs},
    {kRightThigh, 0.06f, 0.085f, 0.21f, 0, -0.21f, 0, kTrunkAndLegs},
    {kRightShin, 0.045f, 0.06f, 0.21f, 0, -0.21f, 0, kTrunkAndLegs},
    {kRightFoot, 0.05f, 0.05f, 0.0f, 0, -0.02f, 0.05f, kTrunkAndLegs},
};

void pose_of(const Eigen::Affine3f& frame, float position[3], float rotation[4]) {
    const Eigen::Quaternionf q(frame.rotation());
    for (int k = 0; k < 3; ++k) position[k] = frame.translation()[k];
    rotation[0] = q.x();
    rotation[1] = q.y();
    rotation[2] = q.z();
    rotation[3] = q.w();
}

}  // namespace

const std::vector<BodyPart>& CharacterBody::parts() { return kParts; }

bool CharacterBody::create(cloth_world_id world, const Pose& pose, std::string* error) {
    world_ = world;
    bodies_.assign(kJointCount, cloth_body_id{});
    for (uint32_t j = 0; j < kJointCount; ++j) {
        cloth_body_desc desc = cloth_default_body_desc();
        pose_of(pose.world[j], desc.position, desc.rotation);
        if (cloth_body_create(world, &desc, &bodies_[j]) != CLOTH_OK) {
            *error = std::string("cloth_body_create: ") + cloth_get_last_error();
            return false;
        }
    }
    for (const BodyPart& part : kParts) {
        cloth_collider_desc desc = cloth_default_collider_desc();
        desc.body = bodies_[part.joint];
        desc.local_position[0] = part.x;
        desc.local_position[1] = part.y;
        desc.local_position[2] = part.z;
        desc.group_bits = part.group;
        cloth_collider_id collider{};
        const cloth_result r =
            part.half_height == 0.0f
                ? cloth_collider_create_sphere(world, &desc, part.bottom_radius, &collider)
                : cloth_collider_create_tapered_capsule(world, &desc, part.bottom_radius, part.top_radius,
                                                        part.half_height, &collider);
        if (r != CLOTH_OK) {
            *error = std::string("collider: ") + cloth_get_last_error();
            return false;
        }
    }
    return true;
}

cloth_result CharacterBody::move(const Pose& pose, bool teleport) {
    std::vector<float> positions(3 * kJointCount), rotations(4 * kJointCount);
    for (uint32_t j = 0; j < kJointCount; ++j) pose_of(pose.world[j], &positions[3 * j], &rotations[4 * j]);
    if (!teleport)
        return cloth_world_set_body_poses(world_, bodies_.data(), positions.data(), rotations.data(),
                                          kJointCount);
    for (uint32_t j = 0; j < kJointCount; ++j) {
        const cloth_result r = cloth_body_teleport(bodies_[j], &positions[3 * j], &rotations[4 * j]);
        if (r != CLOTH_OK) return r;
    }
    return CLOTH_OK;
}

float CharacterBody::distance(const Pose& pose, const float* p, uint32_t mask) {
    const Eigen::Vector3f point(p[0], p[1], p[2]);
    float nearest = INFINITY;
    for (const BodyPart& part : kParts) {
        if ((part.group & mask) == 0) continue;
        const Eigen::Vector3f local =
            pose.world[part.joint].inverse() * point - Eigen::Vector3f(part.x, part.y, part.z);
        // The union of the spheres along the axis, radius running linearly
        // from bottom to top (exact outside; a bound inside).
        const int samples = part.half_height == 0.0f ? 1 : 64;
        for (int k = 0; k < samples; ++k) {
            const float t = samples == 1 ? 0.5f : float(k) / float(samples - 1);
            const Eigen::Vector3f centre(0.0f, -part.half_height + 2.0f * part.half_height * t, 0.0f);
            nearest =
                std::min(nearest, (local - centre).norm() -
                                      (part.bottom_radius + (part.top_radius - part.bottom_radius) * t));
        }
    }
    return nearest;
}

void CharacterBody::append_mesh(const Pose& pose, std::vector<float>* positions, std::vector<float>* normals,
                                std::vector<uint32_t>* indices) {
    constexpr int kAround = 12, kHalfRings = 4;  // per hemisphere
    constexpr float kPi = 3.14159265f;
    for (const BodyPart& part : kParts) {
        const uint32_t first = static_cast<uint32_t>(positions->size() / 3);
        const Eigen::Affine3f frame = pose.world[part.joint] * Eigen::Translation3f(part.x, part.y, part.z);
        const int rings = 2 * kHalfRings + 2;
        for (int r = 0; r < rings; ++r) {
            // Bottom hemisphere, then the top one: latitude from -90 to 90 degrees.
            const bool top = r > kHalfRings;
            const int k = top ? r - 1 : r;
            const float latitude = -0.5f * kPi + kPi * float(k) / float(2 * kHalfRings);
            const float radius = top ? part.top_radius : part.bottom_radius;
            const float centre = top ? part.half_height : -part.half_height;
            for (int a = 0; a < kAround; ++a) {
                const float angle = 2.0f * kPi * float(a) / kAround;
                const Eigen::Vector3f n(std::cos(latitude) * std::cos(angle), std::sin(latitude),
                                        std::cos(latitude) * std::sin(angle));
                const Eigen::Vector3f at = frame * (Eigen::Vector3f(0, centre, 0) + radius * n);
                const Eigen::Vector3f world_n = frame.rotation() * n;
                for (int c = 0; c < 3; ++c) {
                    positions->push_back(at[c]);
                    normals->push_back(world_n[c]);
                }
            }
        }
        for (int r = 0; r + 1 < rings; ++r) {
            for (int a = 0; a < kAround; ++a) {
                const uint32_t i0 = first + r * kAround + a, i1 = first + r * kAround + (a + 1) % kAround;
                const uint32_t j0 = i0 + kAround, j1 = i1 + kAround;
                indices->insert(indices->end(), {i0, j0, i1, i1, j0, j1});
            }
        }
    }
}

}  // namespace character_cloth
