// Does the flag look like a flag? At speed the free edge should stream
// behind the pole, against the direction of travel. This measures the
// angle, in the horizontal plane, between the direction from the pole-side
// column to the free edge (mean positions) and the reverse of the chassis'
// velocity, and counts the frames where it stays within a bound.
#pragma once

#include <cstdint>
#include <vector>

#include "vehicle_world.h"

namespace vehicle_flag {

// Degrees; positions are 3 floats per particle of a columns x rows grid
// whose column 0 is on the pole. NaN when the vehicle or the flag has no
// horizontal extent to compare.
double trailing_angle_degrees(const std::vector<float>& positions, uint32_t columns, uint32_t rows,
                              const btVector3& chassis_velocity);

struct TrailingCount {
    int frames = 0;    // frames that counted (fast enough, in a measured phase)
    int trailing = 0;  // of those, within the bound
    double worst = 0;  // largest angle over the counted frames, degrees

    void add(double angle_degrees, double bound_degrees);
    double fraction() const { return frames > 0 ? double(trailing) / frames : 1.0; }
};

}  // namespace vehicle_flag
