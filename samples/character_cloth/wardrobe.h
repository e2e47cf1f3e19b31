// What the character wears: a cape (a grid hanging from the shoulders
// down the back) and a skirt (a cone of rings welded at its seam, hanging
// from the waist), each skinned to the skeleton with a max distance of 0
// where it is sewn on (shoulders, waist) growing towards the hem, and a
// backstop that keeps it off the body. The root body is each cloth's
// carrier, so the clip's teleport is one of the character.
#pragma once

#include <cloth/cloth.h>

#include <string>
#include <vector>

#include "skeleton.h"

namespace character_cloth {

struct Garment {
    std::string name;
    cloth_id cloth{};
    uint32_t count = 0;
    std::vector<uint32_t> triangles;
    std::vector<float> rest;  // rest positions (xyz), for the check of the cape against itself
    std::vector<std::pair<uint32_t, uint32_t>>
        structural;  // pairs at their rest distance, for the strain check
    std::vector<float> rest_length;
    std::vector<float> max_distance, back_distance, back_radius;
    uint32_t collider_mask = 0;      // the body's collider groups it meets (body.h)
    float particle_mass = 0;         // kg
    float stiffness_offset = 0;      // N/m added to the default structural stiffness (set before make_*)
    std::vector<uint32_t> top, hem;  // the cape's top row and its hem (none for the skirt)
};

// Both in `world` on the skeleton's bind pose, carried by `root`; false with a message.
bool make_cape(cloth_world_id world, cloth_body_id root, Garment* cape, std::string* error);
bool make_skirt(cloth_world_id world, cloth_body_id root, Garment* skirt, std::string* error);

// The skinning matrices of a pose (column-major 4x4, joint order): each
// joint's frame times the inverse of its bind-pose frame.
std::vector<float> skinning_matrices(const Pose& pose);

}  // namespace character_cloth
