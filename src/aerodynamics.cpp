#include "aerodynamics.h"

#include <algorithm>
#include <cmath>

#include "cloth_instance.h"

namespace cloth {

namespace {

// Every array is a __restrict parameter so GCC vectorizes the indexed loads.
void triangle_air_kernel(uint32_t begin, uint32_t end, const AeroParams& air, const uint32_t* __restrict tri,
                         const float* __restrict px, const float* __restrict py, const float* __restrict pz,
                         const float* __restrict vx, const float* __restrict vy, const float* __restrict vz,
                         float* __restrict fx, float* __restrict fy, float* __restrict fz) {
    const float third = 1.0f / 3.0f;
    // Per corner: a third of 1/2 rho |u|^2 A, with A = |cross| / 2.
    const float pressure_scale = 0.5f * air.air_density * 0.5f * third;
    const float wx = air.wind.x(), wy = air.wind.y(), wz = air.wind.z();
    const float drag_coefficient = air.drag_coefficient, lift_coefficient = air.lift_coefficient;
    for (uint32_t t = begin; t < end; ++t) {
        const uint32_t a = tri[3 * t], b = tri[3 * t + 1], c = tri[3 * t + 2];
        const float e1x = px[b] - px[a], e1y = py[b] - py[a], e1z = pz[b] - pz[a];
        const float e2x = px[c] - px[a], e2y = py[c] - py[a], e2z = pz[c] - pz[a];
        const float nx = e1y * e2z - e1z * e2y, ny = e1z * e2x - e1x * e2z, nz = e1x * e2y - e1y * e2x;
        const float twice_area = std::sqrt(nx * nx + ny * ny + nz * nz);
        const float ux = wx - (vx[a] + vx[b] + vx[c]) * third;
        const float uy = wy - (vy[a] + vy[b] + vy[c]) * third;
        const float uz = wz - (vz[a] + vz[b] + vz[c]) * third;
        const float speed_squared = ux * ux + uy * uy + uz * uz;
        const float speed = std::sqrt(speed_squared);
        // Still air or a collapsed triangle: no force (a select, not a branch).
        const bool active = twice_area > 0.0f && speed_squared > 1e-12f;
        const float inv_area = active ? 1.0f / twice_area : 0.0f;
        const float inv_speed = active ? 1.0f / speed : 0.0f;
        const float cosine_signed = (nx * ux + ny * uy + nz * uz) * inv_area * inv_speed;
        // Face the normal downwind: n . u >= 0.
        const float side = cosine_signed < 0.0f ? -inv_area : inv_area;
        const float cosine = std::fabs(cosine_signed);
        const float pressure = pressure_scale * speed_squared * twice_area;
        // drag along n: Cd cos^2; lift along (n - cos u/|u|): Cl cos.
        const float normal_part = pressure * cosine * (drag_coefficient * cosine + lift_coefficient) * side;
        const float wind_part = -pressure * lift_coefficient * cosine * cosine * inv_speed;
        fx[t] = nx * normal_part + ux * wind_part;
        fy[t] = ny * normal_part + uy * wind_part;
        fz[t] = nz * normal_part + uz * wind_part;
    }
}

}  // namespace

void evaluate_triangle_air(const Fabric& fabric, const AeroParams& air, const Vec3Soa& x, const Vec3Soa& v,
                           uint32_t begin, uint32_t end, Vec3Soa& corner_force) {
    triangle_air_kernel(begin, end, air, fabric.triangles.data(), x.x.data(), x.y.data(), x.z.data(), v.x.data(),
                        v.y.data(), v.z.data(), corner_force.x.data(), corner_force.y.data(),
                        corner_force.z.data());
}

namespace {

void gather_triangles_kernel(uint32_t begin, uint32_t end, size_t slot, const uint32_t* __restrict triangle,
                             const float* __restrict cx, const float* __restrict cy, const float* __restrict cz,
                             float* __restrict fx, float* __restrict fy, float* __restrict fz) {
    for (uint32_t i = begin; i < end; ++i) {
        const uint32_t t = triangle[slot + i];
        fx[i] += cx[t];
        fy[i] += cy[t];
        fz[i] += cz[t];
    }
}

}  // namespace

void gather_triangle_forces(const Fabric& fabric, const Vec3Soa& corner_force, uint32_t begin, uint32_t end,
                            Vec3Soa& particle_force) {
    const size_t n = fabric.particle_count();
    std::fill(particle_force.x.begin() + begin, particle_force.x.begin() + end, 0.0f);
    std::fill(particle_force.y.begin() + begin, particle_force.y.begin() + end, 0.0f);
    std::fill(particle_force.z.begin() + begin, particle_force.z.begin() + end, 0.0f);
    for (uint32_t k = 0; k < fabric.padded_triangle_width; ++k) {
        gather_triangles_kernel(begin, end, k * n, fabric.padded_triangle.data(), corner_force.x.data(),
                                corner_force.y.data(), corner_force.z.data(), particle_force.x.data(),
                                particle_force.y.data(), particle_force.z.data());
    }
}

void compute_vertex_normals(const Fabric& fabric, const Vec3Soa& x, uint32_t begin, uint32_t end, Vec3Soa& normal) {
    for (uint32_t p = begin; p < end; ++p) {
        Vec3 sum = Vec3::Zero();
        for (uint32_t e = fabric.triangle_incidence_offset[p]; e < fabric.triangle_incidence_offset[p + 1]; ++e) {
            const uint32_t t = fabric.triangle_incidence[e];
            const uint32_t a = fabric.triangles[3 * t], b = fabric.triangles[3 * t + 1], c = fabric.triangles[3 * t + 2];
            sum += (x.get(b) - x.get(a)).cross(x.get(c) - x.get(a));
        }
        const float length = sum.norm();
        normal.set(p, length > 0.0f ? Vec3(sum / length) : Vec3(0.0f, 0.0f, 1.0f));
    }
}

}  // namespace cloth
