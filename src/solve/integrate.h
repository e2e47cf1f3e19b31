// Symplectic (semi-implicit) Euler: the explicit baseline the paper argues
// against. Stable only while h is below about 2 sqrt(m / k).
#pragma once

#include "base/soa.h"

namespace cloth {

// Per particle i in [begin, end): v_i += h f_i / m_i; x_i += h v_i, where
// `force` already holds external and spring forces. Pinned particles are
// left alone.
void integrate_explicit(const Vec3Soa& force, const float* mass, const float* pinned, float h, uint32_t begin,
                        uint32_t end, Vec3Soa& v, Vec3Soa& x);

}  // namespace cloth
