#include "flag_trailing.h"

#include <algorithm>
#include <cmath>

namespace vehicle_flag {

double trailing_angle_degrees(const std::vector<float>& positions, uint32_t columns, uint32_t rows,
                              const btVector3& chassis_velocity) {
    double pole[2] = {0, 0}, edge[2] = {0, 0};
    for (uint32_t r = 0; r < rows; ++r) {
        const size_t p = 3 * (size_t{r} * columns), e = 3 * (size_t{r} * columns + columns - 1);
        pole[0] += positions[p];
        pole[1] += positions[p + 2];
        edge[0] += positions[e];
        edge[1] += positions[e + 2];
    }
    const double flag_x = edge[0] - pole[0], flag_z = edge[1] - pole[1];
    const double back_x = -chassis_velocity.x(), back_z = -chassis_velocity.z();
    const double flag_length = std::hypot(flag_x, flag_z), back_length = std::hypot(back_x, back_z);
    if (!(flag_length > 0) || !(back_length > 0)) return NAN;
    const double cosine = (flag_x * back_x + flag_z * back_z) / (flag_length * back_length);
    return std::acos(std::clamp(cosine, -1.0, 1.0)) * 180.0 / M_PI;
}

void TrailingCount::add(double angle_degrees, double bound_degrees) {
    ++frames;
    if (angle_degrees <= bound_degrees) ++trailing;  // NaN never trails
    if (std::isnan(angle_degrees) || angle_degrees > worst)
        worst = std::isnan(angle_degrees) ? 180.0 : angle_degrees;
}

}  // namespace vehicle_flag
