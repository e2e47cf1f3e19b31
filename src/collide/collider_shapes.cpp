// The analytic shapes (sphere, capsule, tapered capsule, box, plane): their
// validation into a Shape and their distance queries, and the query dispatch
// over every shape kind. Hulls are in collider_hull.cpp, triangle meshes and
// height fields in collider_mesh.cpp; the collision stage that runs the
// queries is in colliders.cpp.
#include <algorithm>
#include <cmath>
#include <limits>

#include "collide/colliders.h"

namespace cloth {

namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

bool positive_finite(float value) { return std::isfinite(value) && value > 0; }

SurfaceQuery query_sphere(float radius, const Vec3& p) {
    const float length = p.norm();
    SurfaceQuery q;
    q.distance = length - radius;
    q.normal = length > 0 ? Vec3(p / length) : Vec3(Vec3::UnitY());
    return q;
}

SurfaceQuery query_capsule(float radius, float half_height, const Vec3& p) {
    const Vec3 axis_point(0.0f, std::clamp(p.y(), -half_height, half_height), 0.0f);
    SurfaceQuery q = query_sphere(radius, p - axis_point);
    if (p.x() == 0 && p.z() == 0 && std::abs(p.y()) <= half_height) q.normal = Vec3::UnitX();
    return q;
}

// The convex hull of two spheres on the y axis (a round cone): in the
// plane of the axis and p, with q = (distance from the axis, height above
// the bottom centre), the side is the line at distance r_b from the bottom
// centre along the unit normal (a, s), s = (r_b - r_t) / L the slope the
// radii fall by over the centres' distance L. Points whose foot on that
// line lies below the bottom centre's tangent point are nearest the bottom
// sphere, past the top's the top sphere, else the side: the exact signed
// distance (Quilez's round cone).
SurfaceQuery query_tapered_capsule(float bottom_radius, float top_radius, float half_height, const Vec3& p) {
    const float length = 2.0f * half_height;
    const float slope = (bottom_radius - top_radius) / length;
    const float across = std::sqrt(1.0f - slope * slope);
    const float radial = std::hypot(p.x(), p.z());
    const float up = p.y() + half_height;
    const float along = up * across - radial * slope;  // the foot's position along the side
    if (along < 0.0f) return query_sphere(bottom_radius, p - Vec3(0.0f, -half_height, 0.0f));
    if (along > across * length) return query_sphere(top_radius, p - Vec3(0.0f, half_height, 0.0f));
    const Vec3 out = radial > 0 ? Vec3(p.x() / radial, 0.0f, p.z() / radial) : Vec3(Vec3::UnitX());
    SurfaceQuery q;
    q.distance = radial * across + up * slope - bottom_radius;
    q.normal = across * out + slope * Vec3::UnitY();
    return q;
}

SurfaceQuery query_box(const Vec3& e, const Vec3& p) {
    const Vec3 a = p.cwiseAbs();
    const Vec3 excess = a - e;
    SurfaceQuery q;
    const Vec3 outside = excess.cwiseMax(0.0f);
    const float outside_length = outside.norm();
    if (outside_length > 0) {
        q.distance = outside_length;
        const Vec3 sign(p.x() < 0 ? -1.0f : 1.0f, p.y() < 0 ? -1.0f : 1.0f, p.z() < 0 ? -1.0f : 1.0f);
        q.normal = outside.cwiseProduct(sign) / outside_length;
        return q;
    }
    // Inside (or on the surface): the nearest face.
    int axis = 0;
    if (excess.y() > excess[axis]) axis = 1;
    if (excess.z() > excess[axis]) axis = 2;
    q.distance = excess[axis];
    q.normal = Vec3::Zero();
    q.normal[axis] = p[axis] < 0 ? -1.0f : 1.0f;
    return q;
}

Status not_finite(const char* what) {
    return Status::error(CLOTH_ERROR_NOT_FINITE, "%s is not finite", what);
}

}  // namespace

Status build_sphere(float radius, Shape& shape) {
    if (!std::isfinite(radius)) return not_finite("sphere radius");
    if (!positive_finite(radius))
        return Status::error(CLOTH_ERROR_INVALID_VALUE, "sphere radius must be > 0");
    shape.kind = ShapeKind::kSphere;
    shape.radius = radius;
    shape.bound_radius = radius;
    return {};
}

Status build_capsule(float radius, float half_height, Shape& shape) {
    if (!std::isfinite(radius)) return not_finite("capsule radius");
    if (!std::isfinite(half_height)) return not_finite("capsule half_height");
    if (!positive_finite(radius))
        return Status::error(CLOTH_ERROR_INVALID_VALUE, "capsule radius must be > 0");
    if (half_height < 0) return Status::error(CLOTH_ERROR_INVALID_VALUE, "capsule half_height must be >= 0");
    shape.kind = ShapeKind::kCapsule;
    shape.radius = radius;
    shape.half_height = half_height;
    shape.bound_radius = radius + half_height;
    return {};
}

Status build_tapered_capsule(float bottom_radius, float top_radius, float half_height, Shape& shape) {
    if (!std::isfinite(bottom_radius) || !std::isfinite(top_radius))
        return not_finite("tapered capsule radius");
    if (!std::isfinite(half_height)) return not_finite("tapered capsule half_height");
    if (!positive_finite(bottom_radius) || !positive_finite(top_radius))
        return Status::error(CLOTH_ERROR_INVALID_VALUE, "tapered capsule radii must be > 0");
    // One sphere inside the other has no side: that is a sphere.
    if (!(std::abs(bottom_radius - top_radius) < 2.0f * half_height))
        return Status::error(CLOTH_ERROR_INVALID_VALUE,
                             "tapered capsule: the radii must differ by less than 2 * half_height "
                             "(else one sphere holds the other: use a sphere)");
    shape.kind = ShapeKind::kTaperedCapsule;
    shape.radius = bottom_radius;
    shape.top_radius = top_radius;
    shape.half_height = half_height;
    shape.bound_radius = half_height + std::max(bottom_radius, top_radius);
    return {};
}

Status build_box(const Vec3& half_extents, Shape& shape) {
    if (!half_extents.allFinite()) return not_finite("box half extents");
    for (int k = 0; k < 3; ++k) {
        if (!positive_finite(half_extents[k]))
            return Status::error(CLOTH_ERROR_INVALID_VALUE, "box half extents must be > 0");
    }
    shape.kind = ShapeKind::kBox;
    shape.half_extents = half_extents;
    shape.bound_radius = half_extents.norm();
    return {};
}

Status build_plane(const Vec3& normal, float offset, Shape& shape) {
    if (!normal.allFinite() || !std::isfinite(offset))
        return Status::error(CLOTH_ERROR_NOT_FINITE, "plane normal or offset is not finite");
    Vec3 unit = Vec3::Zero();
    float length = normal.norm();
    if (std::isfinite(length)) {
        if (!(length > 1e-12f)) return Status::error(CLOTH_ERROR_INVALID_VALUE, "plane normal is zero");
        unit = normal / length;
    } else {
        // A finite normal whose squared length overflows: scaled by its
        // largest component first.
        const float largest = normal.cwiseAbs().maxCoeff();
        const Vec3 scaled = normal / largest;
        unit = scaled / scaled.norm();
        length = scaled.norm() * largest;
    }
    shape.kind = ShapeKind::kPlane;
    shape.plane_normal = unit;
    shape.plane_offset = offset / length;
    shape.bound_radius = kInfinity;
    return {};
}

SurfaceQuery query_shape(const Shape& shape, const Vec3& p, float radius) {
    switch (shape.kind) {
        case ShapeKind::kSphere:
            return query_sphere(shape.radius, p);
        case ShapeKind::kCapsule:
            return query_capsule(shape.radius, shape.half_height, p);
        case ShapeKind::kTaperedCapsule:
            return query_tapered_capsule(shape.radius, shape.top_radius, shape.half_height, p);
        case ShapeKind::kBox:
            return query_box(shape.half_extents, p);
        case ShapeKind::kPlane:
            return {shape.plane_normal.dot(p) - shape.plane_offset, shape.plane_normal};
        case ShapeKind::kConvexHull:
            return query_hull(shape.hull, p, radius);
        case ShapeKind::kTriangleMesh:
            return query_mesh(shape.mesh, p, radius);
        case ShapeKind::kHeightfield:
            return query_heightfield(shape.heightfield, p, radius);
    }
    return {kInfinity, Vec3::UnitY()};
}

}  // namespace cloth
