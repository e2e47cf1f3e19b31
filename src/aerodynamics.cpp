#include "aerodynamics.h"

#include "cloth_instance.h"

namespace cloth {

void evaluate_triangle_air(const Fabric& fabric, const AeroParams& air, const Vec3* x, const Vec3* v,
                           uint32_t begin, uint32_t end, Vec3* corner_force) {
    const float third = 1.0f / 3.0f;
    for (uint32_t t = begin; t < end; ++t) {
        const uint32_t a = fabric.triangles[3 * t], b = fabric.triangles[3 * t + 1], c = fabric.triangles[3 * t + 2];
        const Vec3 cross = (x[b] - x[a]).cross(x[c] - x[a]);
        const float twice_area = cross.norm();
        const Vec3 air_velocity = air.wind - (v[a] + v[b] + v[c]) * third;
        const float speed_squared = air_velocity.squaredNorm();
        if (!(twice_area > 0.0f) || !(speed_squared > 1e-12f)) {
            corner_force[t].setZero();
            continue;
        }
        const float speed = std::sqrt(speed_squared);
        const Vec3 air_direction = air_velocity / speed;
        Vec3 normal = cross / twice_area;
        float cosine = normal.dot(air_direction);
        if (cosine < 0.0f) {  // face the air
            normal = -normal;
            cosine = -cosine;
        }
        const float pressure = 0.5f * air.air_density * speed_squared * (0.5f * twice_area);
        const Vec3 drag = normal * (pressure * air.drag_coefficient * cosine * cosine);
        const Vec3 lift = (normal - air_direction * cosine) * (pressure * air.lift_coefficient * cosine);
        corner_force[t] = (drag + lift) * third;
    }
}

void gather_triangle_forces(const Fabric& fabric, const Vec3* corner_force, uint32_t begin, uint32_t end,
                            Vec3* particle_force) {
    for (uint32_t p = begin; p < end; ++p) {
        Vec3 sum = Vec3::Zero();
        for (uint32_t e = fabric.triangle_incidence_offset[p]; e < fabric.triangle_incidence_offset[p + 1]; ++e) {
            sum += corner_force[fabric.triangle_incidence[e]];
        }
        particle_force[p] = sum;
    }
}

void compute_vertex_normals(const Fabric& fabric, const Vec3* x, uint32_t begin, uint32_t end, Vec3* normal) {
    for (uint32_t p = begin; p < end; ++p) {
        Vec3 sum = Vec3::Zero();
        for (uint32_t e = fabric.triangle_incidence_offset[p]; e < fabric.triangle_incidence_offset[p + 1]; ++e) {
            const uint32_t t = fabric.triangle_incidence[e];
            const uint32_t a = fabric.triangles[3 * t], b = fabric.triangles[3 * t + 1], c = fabric.triangles[3 * t + 2];
            sum += (x[b] - x[a]).cross(x[c] - x[a]);
        }
        const float length = sum.norm();
        normal[p] = length > 0.0f ? Vec3(sum / length) : Vec3(0.0f, 0.0f, 1.0f);
    }
}

}  // namespace cloth
