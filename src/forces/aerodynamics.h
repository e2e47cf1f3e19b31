// Air: wind drag and lift per triangle against the relative air velocity,
// and per-vertex normals. The force is a per-triangle pass followed by a
// per-particle gather, both in a fixed order.
//
// Per triangle, with u = wind - v_triangle the air velocity it sees, n its
// unit normal on the downwind side (n . u >= 0), cos = n . u/|u|, area A:
//   drag = 1/2 rho Cd A |u|^2 cos^2 n                   (pressure on the face)
//   lift = 1/2 rho Cl A |u|^2 cos (n - cos u/|u|)       (perpendicular to u)
// and each corner takes a third.
//
// Grid fabrics run both passes over cells (two triangle shapes per cell,
// fabric.h) with contiguous loads; other meshes over their triangle list.
#pragma once

#include "base/math.h"
#include "base/soa.h"
#include "fabric/fabric.h"

namespace cloth {

// The air a cloth moves in (defaults are the library's: cloth_default_desc copies them).
struct AeroParams {
    Vec3 wind = Vec3::Zero();
    float air_density = 1.2f;
    float drag_coefficient = 1.0f;
    float lift_coefficient = 0.5f;
    float linear_drag = 0.02f;
};

// Items of the per-triangle pass: triangles, or particles (cells) on grids.
uint32_t air_item_count(const Fabric& fabric);
// Entries of the per-triangle storage `corner_force` must have.
size_t air_storage_size(const Fabric& fabric);

// Per-triangle pass for items [begin, end): each triangle's corner force.
void evaluate_air(const Fabric& fabric, const AeroParams& air, const Vec3Soa& x, const Vec3Soa& v,
                  uint32_t begin, uint32_t end, Vec3Soa& corner_force);

// Per-particle pass for [begin, end): sum of the corner forces of the
// particle's triangles, written to particle_force.
void gather_air(const Fabric& fabric, const Vec3Soa& corner_force, uint32_t begin, uint32_t end,
                Vec3Soa& particle_force);

// The unit area-weighted vertex normal of particle p.
Vec3 vertex_normal(const Fabric& fabric, const Vec3Soa& x, uint32_t p);
// Unit area-weighted vertex normals for particles [begin, end).
void compute_vertex_normals(const Fabric& fabric, const Vec3Soa& x, uint32_t begin, uint32_t end,
                            Vec3Soa& normal);

}  // namespace cloth
