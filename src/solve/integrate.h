// Position updates: where a substep's velocities take the particles.
//
//   integrate_implicit   the paper's update after the solve (paper eq. 6):
//                        v' = v + dv, x' = x + h (v + theta dv); theta = 1
//                        is backward Euler (docs/method.md, "The linear
//                        system"; theta < 1: "The theta step")
//   integrate_explicit   symplectic Euler, the explicit baseline the paper
//                        argues against (stable only while h is below about
//                        2 sqrt(m / k)): v' = v + h f / m, x' = x + h v'
//
// Both are per-particle loops over [begin, end), so any split over workers
// gives the same bits. Pinned particles are placed by the caller.
#pragma once

#include "base/soa.h"

namespace cloth {

// x_out_i = x_i + h (v_i + theta dv_i), v_out_i = v_i + dv_i (theta = 1:
// backward Euler). The outputs may be the inputs (in place) or other
// buffers.
void integrate_implicit(const Vec3Soa& x, const Vec3Soa& v, const Vec3Soa& dv, float h, float theta,
                        uint32_t begin, uint32_t end, Vec3Soa& x_out, Vec3Soa& v_out);

// v_i += h f_i / m_i; x_i += h v_i, where `force` already holds external and
// spring forces. Pinned particles are left alone.
void integrate_explicit(const Vec3Soa& force, const float* mass, const float* pinned, float h, uint32_t begin,
                        uint32_t end, Vec3Soa& v, Vec3Soa& x);

}  // namespace cloth
