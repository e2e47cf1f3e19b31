#include "forces/aerodynamics.h"

#include <algorithm>
#include <cmath>

#include "base/lanes.h"
#include "forces/material.h"

namespace cloth {
namespace {

struct AirConstants {
    float wx, wy, wz;
    float pressure_scale;  // a third of 1/2 rho, times 1/2 for A = |cross| / 2
    float drag, lift;

    explicit AirConstants(const AeroParams& air)
        : wx(air.wind.x()),
          wy(air.wind.y()),
          wz(air.wind.z()),
          pressure_scale(0.5f * air.air_density * 0.5f / 3.0f),
          drag(air.drag_coefficient),
          lift(air.lift_coefficient) {}
};

// The force on each corner of a triangle with edges e1, e2 whose corner
// velocities sum to (svx, svy, svz). With n = e1 x e2 (|n| = 2A), u the air
// velocity, d = n . u and r = 1 / (|n| |u|), the formulas of aerodynamics.h
// reduce to
//   f = s |u|^2 d r (Cd |d| r + Cl) n  -  s Cl d^2 r u,   s = rho / 12
// (A |u|^2 cos^2 n/|n| = |u|^2 d |d| r^2 n / 2 and so on): one square root
// and one division. Branch-free so the loops vectorize; still air or a
// collapsed triangle gives zero.
inline void corner_force(const AirConstants& k, float e1x, float e1y, float e1z, float e2x, float e2y,
                         float e2z, float svx, float svy, float svz, float& fx, float& fy, float& fz) {
    const float third = 1.0f / 3.0f;
    const float nx = e1y * e2z - e1z * e2y, ny = e1z * e2x - e1x * e2z, nz = e1x * e2y - e1y * e2x;
    const float ux = k.wx - svx * third, uy = k.wy - svy * third, uz = k.wz - svz * third;
    const float normal_squared = nx * nx + ny * ny + nz * nz;
    const float speed_squared = ux * ux + uy * uy + uz * uz;
    const float product_squared = normal_squared * speed_squared;
    const float r = product_squared > 1e-30f ? 1.0f / std::sqrt(product_squared) : 0.0f;
    const float d = nx * ux + ny * uy + nz * uz;
    const float dr = d * r;
    const float normal_part = k.pressure_scale * speed_squared * dr * (k.drag * std::fabs(dr) + k.lift);
    const float wind_part = -k.pressure_scale * k.lift * d * dr;
    fx = nx * normal_part + ux * wind_part;
    fy = ny * normal_part + uy * wind_part;
    fz = nz * normal_part + uz * wind_part;
}

// Every array is a __restrict parameter so GCC vectorizes the loops.
CLOTH_HOT_LOOP void triangle_air_kernel(uint32_t begin, uint32_t end, AirConstants k,
                                        const uint32_t* __restrict tri, const float* __restrict px,
                                        const float* __restrict py, const float* __restrict pz,
                                        const float* __restrict vx, const float* __restrict vy,
                                        const float* __restrict vz, float* __restrict fx,
                                        float* __restrict fy, float* __restrict fz) {
    for (uint32_t t = begin; t < end; ++t) {
        const uint32_t a = tri[3 * t], b = tri[3 * t + 1], c = tri[3 * t + 2];
        corner_force(k, px[b] - px[a], py[b] - py[a], pz[b] - pz[a], px[c] - px[a], py[c] - py[a],
                     pz[c] - pz[a], vx[a] + vx[b] + vx[c], vy[a] + vy[b] + vy[c], vz[a] + vz[b] + vz[c],
                     fx[t], fy[t], fz[t]);
    }
}

// Both triangles of the grid cells [begin, end): corners a = p, b = p + o1,
// c = p + o2, d = p + o3 form the fan (a, b, c), (a, c, d) (fabric.h), so
// the two share their loads and the edge a-c. Cells where mask[p] is 0
// get zero forces.
CLOTH_HOT_LOOP void grid_cell_air_kernel(uint32_t begin, uint32_t end, AirConstants k, uint32_t o1,
                                         uint32_t o2, uint32_t o3, const float* __restrict mask,
                                         const float* __restrict px, const float* __restrict py,
                                         const float* __restrict pz, const float* __restrict vx,
                                         const float* __restrict vy, const float* __restrict vz,
                                         float* __restrict f1x, float* __restrict f1y, float* __restrict f1z,
                                         float* __restrict f2x, float* __restrict f2y,
                                         float* __restrict f2z) {
    // 64-bit indices: in 32 bits (which could wrap) GCC loads b, c and d
    // lane by lane instead of as vectors.
    for (size_t p = begin; p < end; ++p) {
        const size_t b = p + o1, c = p + o2, d = p + o3;
        const float acx = px[c] - px[p], acy = py[c] - py[p], acz = pz[c] - pz[p];
        const float sx = vx[p] + vx[c], sy = vy[p] + vy[c], sz = vz[p] + vz[c];
        float x, y, z;
        corner_force(k, px[b] - px[p], py[b] - py[p], pz[b] - pz[p], acx, acy, acz, sx + vx[b], sy + vy[b],
                     sz + vz[b], x, y, z);
        f1x[p] = x * mask[p];
        f1y[p] = y * mask[p];
        f1z[p] = z * mask[p];
        corner_force(k, acx, acy, acz, px[d] - px[p], py[d] - py[p], pz[d] - pz[p], sx + vx[d], sy + vy[d],
                     sz + vz[d], x, y, z);
        f2x[p] = x * mask[p];
        f2y[p] = y * mask[p];
        f2z[p] = z * mask[p];
    }
}

// One incidence slot (entry of particle i at base + i): f_i += corner force.
void gather_slot_kernel(uint32_t begin, uint32_t end, int64_t base, const uint32_t* __restrict triangle,
                        const float* __restrict cx, const float* __restrict cy, const float* __restrict cz,
                        float* __restrict fx, float* __restrict fy, float* __restrict fz) {
    for (uint32_t i = begin; i < end; ++i) {
        const uint32_t t = triangle[base + i];
        fx[i] += cx[t];
        fy[i] += cy[t];
        fz[i] += cz[t];
    }
}

bool is_grid(const Fabric& fabric) { return !fabric.grid_cell_mask.empty(); }

}  // namespace

uint32_t air_item_count(const Fabric& fabric) {
    return is_grid(fabric) ? fabric.particle_count() : fabric.triangle_count();
}

size_t air_storage_size(const Fabric& fabric) {
    // Grids: one entry per shape per particle. Meshes: one per triangle plus
    // the zero dummy that padded incidence slots point at.
    return is_grid(fabric) ? fabric.grid_triangle_shapes.size() / 3 * fabric.particle_count()
                           : fabric.triangle_count() + 1;
}

void evaluate_air(const Fabric& fabric, const AeroParams& air, const Vec3Soa& x, const Vec3Soa& v,
                  uint32_t begin, uint32_t end, Vec3Soa& corner_force) {
    const AirConstants k(air);
    if (!is_grid(fabric)) {
        triangle_air_kernel(begin, end, k, fabric.triangles.data(), x.x.data(), x.y.data(), x.z.data(),
                            v.x.data(), v.y.data(), v.z.data(), corner_force.x.data(), corner_force.y.data(),
                            corner_force.z.data());
        return;
    }
    // Cells whose far corner would fall past the grid have no triangles
    // (their mask is 0) and their entries are never written.
    const uint32_t n = fabric.particle_count();
    const uint32_t* shape = fabric.grid_triangle_shapes.data();
    const uint32_t o1 = shape[1], o2 = shape[2], o3 = shape[5];
    const uint32_t reach = std::max({o1, o2, o3});
    grid_cell_air_kernel(begin, std::min(end, n - reach), k, o1, o2, o3, fabric.grid_cell_mask.data(),
                         x.x.data(), x.y.data(), x.z.data(), v.x.data(), v.y.data(), v.z.data(),
                         corner_force.x.data(), corner_force.y.data(), corner_force.z.data(),
                         corner_force.x.data() + n, corner_force.y.data() + n, corner_force.z.data() + n);
}

CLOTH_HOT_LOOP void gather_air(const Fabric& fabric, const Vec3Soa& corner_force, uint32_t begin,
                               uint32_t end, Vec3Soa& particle_force) {
    const size_t n = fabric.particle_count();
    if (!is_grid(fabric)) {
        for (HostVector<float>* a : {&particle_force.x, &particle_force.y, &particle_force.z}) {
            std::fill(a->begin() + begin, a->begin() + end, 0.0f);
        }
        const PaddedSlots& slots = fabric.triangle_slots;
        slots.for_each_slot(
            static_cast<uint32_t>(n), begin, end, [&](uint32_t lo, uint32_t hi, int64_t base, uint32_t) {
                gather_slot_kernel(lo, hi, base, slots.item.data(), corner_force.x.data(),
                                   corner_force.y.data(), corner_force.z.data(), particle_force.x.data(),
                                   particle_force.y.data(), particle_force.z.data());
            });
        return;
    }
    // Grid: particle p is corner i of shape s of the cell at p - offset_i.
    const uint32_t shapes = static_cast<uint32_t>(fabric.grid_triangle_shapes.size() / 3);
    uint32_t max_offset = 0;
    for (uint32_t o : fabric.grid_triangle_shapes) max_offset = std::max(max_offset, o);
    const uint32_t* shape = fabric.grid_triangle_shapes.data();
    const float *cx = corner_force.x.data(), *cy = corner_force.y.data(), *cz = corner_force.z.data();
    for_each_lane_group(begin, end, max_offset, static_cast<uint32_t>(n), [&](auto lanes, uint32_t p) {
        using L = decltype(lanes);
        // Eight at a time only from max_offset on, where p - offset is always valid.
        constexpr bool kAllValid = L::width > 1;
        typename L::type fx{}, fy{}, fz{};
        for (uint32_t s = 0; s < shapes; ++s) {
            for (uint32_t i = 0; i < 3; ++i) {
                const uint32_t offset = shape[3 * s + i];
                if (!kAllValid && p < offset) continue;
                const size_t entry = s * n + (p - offset);
                fx += L::load(cx + entry);
                fy += L::load(cy + entry);
                fz += L::load(cz + entry);
            }
        }
        store_vec3<L>(particle_force, p, fx, fy, fz);
    });
}

Vec3 vertex_normal(const Fabric& fabric, const Vec3Soa& x, uint32_t p) {
    Vec3 sum = Vec3::Zero();
    for (uint32_t e = fabric.triangle_incidence_offset[p]; e < fabric.triangle_incidence_offset[p + 1]; ++e) {
        const uint32_t t = fabric.triangle_incidence[e];
        const uint32_t a = fabric.triangles[3 * t], b = fabric.triangles[3 * t + 1],
                       c = fabric.triangles[3 * t + 2];
        sum += (x.get(b) - x.get(a)).cross(x.get(c) - x.get(a));
    }
    const float length = sum.norm();
    return length > 0.0f ? Vec3(sum / length) : Vec3(0.0f, 0.0f, 1.0f);
}

void compute_vertex_normals(const Fabric& fabric, const Vec3Soa& x, uint32_t begin, uint32_t end,
                            Vec3Soa& normal) {
    for (uint32_t p = begin; p < end; ++p) normal.set(p, vertex_normal(fabric, x, p));
}

}  // namespace cloth
