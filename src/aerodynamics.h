// Air: wind drag and lift per triangle against the relative air velocity,
// and per-vertex normals. Both are per-triangle passes followed by a
// per-particle gather over the fabric's triangle incidence (fixed order).
#pragma once

#include "fabric.h"
#include "math.h"
#include "soa.h"

namespace cloth {

struct AeroParams;

// Per triangle t in [begin, end): the aerodynamic force on each of its three
// corners (a third of the triangle's total). With u = wind - v_triangle the
// air velocity seen by the triangle, n the unit normal on its downwind side,
// cos = n . u/|u|, and area A:
//   drag = 1/2 rho Cd A |u|^2 cos^2 n                   (pressure on the face)
//   lift = 1/2 rho Cl A |u|^2 cos (n - cos u/|u|)       (perpendicular to u)
void evaluate_triangle_air(const Fabric& fabric, const AeroParams& air, const Vec3Soa& x, const Vec3Soa& v,
                           uint32_t begin, uint32_t end, Vec3Soa& corner_force);

// Sum of corner forces of the triangles incident to particles [begin, end).
void gather_triangle_forces(const Fabric& fabric, const Vec3Soa& corner_force, uint32_t begin, uint32_t end,
                            Vec3Soa& particle_force);

// Unit area-weighted vertex normals for particles [begin, end).
void compute_vertex_normals(const Fabric& fabric, const Vec3Soa& x, uint32_t begin, uint32_t end, Vec3Soa& normal);

}  // namespace cloth
