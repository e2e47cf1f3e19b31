// Small fixed-size math on top of Eigen: 3-vectors and symmetric 3x3 blocks.
#pragma once

// Determinism and the non-finite safeguard rely on IEEE semantics.
#if defined(__FAST_MATH__) || (defined(__FINITE_MATH_ONLY__) && __FINITE_MATH_ONLY__)
#error "cloth must be built without -ffast-math / -ffinite-math-only (it needs IEEE NaN and ordering)"
#endif

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products
#include <cmath>

namespace cloth {

using Vec3 = Eigen::Vector3f;
using Mat3 = Eigen::Matrix3f;

// Symmetric 3x3 matrix stored as its 6 unique entries. Spring Jacobian
// blocks and the diagonal blocks W_ii are symmetric, so this halves the
// memory the solver streams through.
struct Sym3 {
    float xx = 0, xy = 0, xz = 0, yy = 0, yz = 0, zz = 0;

    static Sym3 identity(float s) { return {s, 0, 0, s, 0, s}; }
    // s * u u^T
    static Sym3 outer(const Vec3& u, float s) {
        return {s * u.x() * u.x(), s * u.x() * u.y(), s * u.x() * u.z(),
                s * u.y() * u.y(), s * u.y() * u.z(), s * u.z() * u.z()};
    }

    Vec3 operator*(const Vec3& v) const {
        return {xx * v.x() + xy * v.y() + xz * v.z(), xy * v.x() + yy * v.y() + yz * v.z(),
                xz * v.x() + yz * v.y() + zz * v.z()};
    }
    Sym3& operator+=(const Sym3& o) {
        xx += o.xx;
        xy += o.xy;
        xz += o.xz;
        yy += o.yy;
        yz += o.yz;
        zz += o.zz;
        return *this;
    }
    Sym3 operator+(const Sym3& o) const {
        Sym3 r = *this;
        r += o;
        return r;
    }
    Sym3 operator*(float s) const { return {xx * s, xy * s, xz * s, yy * s, yz * s, zz * s}; }

    Mat3 to_matrix() const {
        Mat3 m;
        m << xx, xy, xz, xy, yy, yz, xz, yz, zz;
        return m;
    }

    // Inverse by cofactors (see invert_symmetric). The matrices inverted
    // here (W_ii) are symmetric positive definite, so det > 0.
    Sym3 inverse() const;
};

// numerator * M^-1 for the symmetric M = (xx, xy, xz, yy, yz, zz), by
// cofactors, written to out[6] in the same order. T is float, or a vector
// of lanes (lanes.h), so one formula serves scalar and vector code;
// always inlined for the reason given in lanes.h.
template <class T>
__attribute__((always_inline)) inline void invert_symmetric(T xx, T xy, T xz, T yy, T yz, T zz, T numerator,
                                                            T* out) {
    const T c_xx = yy * zz - yz * yz, c_xy = xz * yz - xy * zz, c_xz = xy * yz - xz * yy;
    const T scale = numerator / (xx * c_xx + xy * c_xy + xz * c_xz);
    out[0] = c_xx * scale;
    out[1] = c_xy * scale;
    out[2] = c_xz * scale;
    out[3] = (xx * zz - xz * xz) * scale;
    out[4] = (xy * xz - xx * yz) * scale;
    out[5] = (xx * yy - xy * xy) * scale;
}

inline Sym3 Sym3::inverse() const {
    float out[6];
    invert_symmetric(xx, xy, xz, yy, yz, zz, 1.0f, out);
    return {out[0], out[1], out[2], out[3], out[4], out[5]};
}

}  // namespace cloth
