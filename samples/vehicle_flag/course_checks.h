// The course's physical checks, done on the flag after every frame: is any
// particle inside the chassis box, the pole capsule or the terrain by more
// than a tolerance? Shapes are read from the sample's own description of the
// vehicle and the terrain, independently of the colliders the cloth uses.
#pragma once

#include <cstdint>
#include <vector>

#include "terrain.h"
#include "vehicle_world.h"

namespace vehicle_flag {

struct Penetrations {
    int chassis = 0;       // particles deeper than the tolerance inside the chassis box
    int pole = 0;          // ...inside the pole capsule
    int terrain = 0;       // ...below the terrain surface
    float deepest = 0.0f;  // m, deepest of them all (0 when none)

    int total() const { return chassis + pole + terrain; }
    void add(const Penetrations& other);
};

// positions: xyz per particle; skip[i] true for particles not to check (attached ones).
Penetrations count_penetrations(const std::vector<float>& positions, const std::vector<bool>& skip,
                                const btTransform& chassis_pose, const VehicleLayout& vehicle,
                                const Terrain& terrain, float tolerance);

// Structural springs of the flag (a columns x rows grid, particle r *
// columns + c) whose segment passes within half the pole's radius of its
// axis: the flag pulled through its pole. A spring wrapped round the pole
// cuts a chord inside the capsule but never comes that close to the axis.
int count_springs_through_pole(const std::vector<float>& positions, uint32_t columns, uint32_t rows,
                               const btTransform& chassis_pose, const VehicleLayout& vehicle);

}  // namespace vehicle_flag
