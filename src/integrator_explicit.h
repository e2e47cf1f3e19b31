// Symplectic (semi-implicit) Euler: the explicit baseline the paper argues
// against. Stable only while h is below about 2 sqrt(m / k).
#pragma once

#include "fabric.h"
#include "soa.h"

namespace cloth {

// Per particle i in [begin, end): v_i += h / m_i (f_ext_i + sum of incident
// spring forces); x_i += h v_i. Pinned particles are left alone.
void integrate_explicit(const Fabric& fabric, const Vec3Soa& spring_force, const Vec3Soa& external_force,
                        const float* mass, const uint8_t* pinned, float h, uint32_t begin, uint32_t end, Vec3Soa& v,
                        Vec3Soa& x);

}  // namespace cloth
