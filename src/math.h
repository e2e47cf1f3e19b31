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
        xx += o.xx; xy += o.xy; xz += o.xz; yy += o.yy; yz += o.yz; zz += o.zz;
        return *this;
    }
    Sym3 operator+(const Sym3& o) const { Sym3 r = *this; r += o; return r; }
    Sym3 operator*(float s) const { return {xx * s, xy * s, xz * s, yy * s, yz * s, zz * s}; }

    Mat3 to_matrix() const {
        Mat3 m;
        m << xx, xy, xz, xy, yy, yz, xz, yz, zz;
        return m;
    }

    // Inverse by cofactors. The matrices inverted here (W_ii) are symmetric
    // positive definite, so the determinant is positive.
    Sym3 inverse() const {
        const float c_xx = yy * zz - yz * yz;
        const float c_xy = xz * yz - xy * zz;
        const float c_xz = xy * yz - xz * yy;
        const float det = xx * c_xx + xy * c_xy + xz * c_xz;
        const float inv = 1.0f / det;
        return {c_xx * inv, c_xy * inv, c_xz * inv, (xx * zz - xz * xz) * inv, (xy * xz - xx * yz) * inv,
                (xx * yy - xy * xy) * inv};
    }
};

}  // namespace cloth
