#include "course_checks.h"

#include <algorithm>
#include <cmath>

namespace vehicle_flag {

void Penetrations::add(const Penetrations& other) {
    chassis += other.chassis;
    pole += other.pole;
    terrain += other.terrain;
    deepest = std::max(deepest, other.deepest);
}

Penetrations count_penetrations(const std::vector<float>& positions, const std::vector<bool>& skip,
                                const btTransform& chassis_pose, const VehicleLayout& v,
                                const Terrain& terrain, float tolerance) {
    Penetrations out;
    const btTransform to_chassis = chassis_pose.inverse();
    const btVector3 box_center(v.box_center[0], v.box_center[1], v.box_center[2]);
    const btVector3 pole_base(v.pole_base[0], v.pole_base[1], v.pole_base[2]);
    for (size_t i = 0; i < positions.size() / 3; ++i) {
        if (skip[i]) continue;
        const btVector3 world(positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]);
        const btVector3 local = to_chassis * world;

        // Box: depth is the distance to the nearest face, when inside on all three axes.
        const btVector3 d = local - box_center;
        float box_depth = 1e30f;
        for (int k = 0; k < 3; ++k) box_depth = std::min(box_depth, v.box_half_extents[k] - std::fabs(d[k]));
        if (box_depth > tolerance) {
            ++out.chassis;
            out.deepest = std::max(out.deepest, box_depth);
        }

        // Capsule: radius minus the distance to the pole's axis segment.
        const float along = std::clamp(local.y() - pole_base.y(), 0.0f, v.pole_height);
        const btVector3 axis_point = pole_base + btVector3(0, along, 0);
        const float pole_depth = v.pole_radius - (local - axis_point).length();
        if (pole_depth > tolerance) {
            ++out.pole;
            out.deepest = std::max(out.deepest, pole_depth);
        }

        // Terrain: vertical depth below the surface, never less than the true
        // depth, so the check errs towards counting.
        const float terrain_depth = terrain.height_at(world.x(), world.z()) - world.y();
        if (terrain_depth > tolerance) {
            ++out.terrain;
            out.deepest = std::max(out.deepest, terrain_depth);
        }
    }
    return out;
}

namespace {

// Distance between the pole's axis (x = z = 0 after subtracting the base,
// y in [0, height]) and the segment a-b, in the chassis frame: the segment
// point nearest the axis line in the horizontal plane, with its height
// clamped to the axis.
float distance_to_axis(const btVector3& a, const btVector3& b, float height) {
    const float dx = b.x() - a.x(), dz = b.z() - a.z();
    const float horizontal = dx * dx + dz * dz;
    float t = horizontal > 0 ? -(a.x() * dx + a.z() * dz) / horizontal : 0.0f;
    t = std::clamp(t, 0.0f, 1.0f);
    const btVector3 p = a + (b - a) * t;
    const float along = std::clamp(p.y(), 0.0f, height);
    return (p - btVector3(0, along, 0)).length();
}

}  // namespace

int count_springs_through_pole(const std::vector<float>& positions, uint32_t columns, uint32_t rows,
                               const btTransform& chassis_pose, const VehicleLayout& v) {
    const btTransform to_chassis = chassis_pose.inverse();
    const btVector3 pole_base(v.pole_base[0], v.pole_base[1], v.pole_base[2]);
    auto local = [&](uint32_t i) {
        const btVector3 world(positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]);
        return to_chassis * world - pole_base;
    };
    int through = 0;
    for (uint32_t r = 0; r < rows; ++r) {
        for (uint32_t c = 0; c < columns; ++c) {
            const uint32_t i = r * columns + c;
            if (c + 1 < columns)
                through += distance_to_axis(local(i), local(i + 1), v.pole_height) < 0.5f * v.pole_radius;
            if (r + 1 < rows)
                through +=
                    distance_to_axis(local(i), local(i + columns), v.pole_height) < 0.5f * v.pole_radius;
        }
    }
    return through;
}

}  // namespace vehicle_flag
