// Convex hull colliders: the hull of a point cloud, built once by the
// incremental algorithm (add points one by one, replace the faces a point
// sees by a fan from the point to their horizon), and the distance query.
// Written by hand: Eigen has no hull, and the core must not depend on
// Bullet (the C API takes plain points, e.g. from btConvexHullShape).
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "collide/colliders.h"

namespace cloth {

namespace {

struct Face {
    uint32_t a, b, c;
    Vec3 normal;
    float offset;
    bool live;
};

Face make_face(const std::vector<Vec3>& points, uint32_t a, uint32_t b, uint32_t c) {
    const Vec3 n = (points[b] - points[a]).cross(points[c] - points[a]);
    const float length = n.norm();
    const Vec3 unit = length > 0 ? Vec3(n / length) : Vec3(Vec3::Zero());
    return {a, b, c, unit, unit.dot(points[a]), true};
}

}  // namespace

Status build_convex_hull(const float* xyz, uint32_t count, Shape& shape) {
    if (count < 4 || count > 4096)
        return Status::error(CLOTH_ERROR_INVALID_COUNT, "convex hull point_count %u is not in 4..4096",
                             count);
    std::vector<Vec3> points(count);
    Vec3 lo = Vec3::Constant(std::numeric_limits<float>::infinity()), hi = -lo;
    for (uint32_t i = 0; i < count; ++i) {
        points[i] = Vec3(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
        lo = lo.cwiseMin(points[i]);
        hi = hi.cwiseMax(points[i]);
    }
    const float scale = (hi - lo).norm();
    const float eps = 1e-5f * scale;
    auto degenerate = [] {
        return Status::error(CLOTH_ERROR_DEGENERATE_GEOMETRY, "convex hull points are (nearly) coplanar");
    };
    if (!(scale > 0)) return degenerate();

    // Initial tetrahedron from extreme points.
    uint32_t i0 = 0;
    for (uint32_t i = 1; i < count; ++i)
        if (points[i].x() < points[i0].x()) i0 = i;
    uint32_t i1 = i0;
    float best = 0;
    for (uint32_t i = 0; i < count; ++i) {
        const float d = (points[i] - points[i0]).squaredNorm();
        if (d > best) best = d, i1 = i;
    }
    const Vec3 axis = (points[i1] - points[i0]).normalized();
    uint32_t i2 = i0;
    best = 0;
    for (uint32_t i = 0; i < count; ++i) {
        const Vec3 r = points[i] - points[i0];
        const float d = (r - axis * r.dot(axis)).squaredNorm();
        if (d > best) best = d, i2 = i;
    }
    if (best <= eps * eps) return degenerate();
    const Vec3 plane = (points[i1] - points[i0]).cross(points[i2] - points[i0]).normalized();
    uint32_t i3 = i0;
    best = 0;
    for (uint32_t i = 0; i < count; ++i) {
        const float d = std::abs((points[i] - points[i0]).dot(plane));
        if (d > best) best = d, i3 = i;
    }
    if (best <= eps) return degenerate();

    std::vector<Face> faces;
    const Vec3 inside = (points[i0] + points[i1] + points[i2] + points[i3]) * 0.25f;
    auto add = [&](uint32_t a, uint32_t b, uint32_t c) {
        Face f = make_face(points, a, b, c);
        if (f.normal.dot(inside) > f.offset) f = make_face(points, a, c, b);  // face outward
        faces.push_back(f);
    };
    add(i0, i1, i2);
    add(i0, i1, i3);
    add(i0, i2, i3);
    add(i1, i2, i3);

    std::vector<std::pair<uint32_t, uint32_t>> edges;
    for (uint32_t p = 0; p < count; ++p) {
        if (p == i0 || p == i1 || p == i2 || p == i3) continue;
        edges.clear();
        bool sees_any = false;
        for (Face& f : faces) {
            if (!f.live || f.normal.dot(points[p]) - f.offset <= eps) continue;
            sees_any = true;
            f.live = false;
            edges.push_back({f.a, f.b});
            edges.push_back({f.b, f.c});
            edges.push_back({f.c, f.a});
        }
        if (!sees_any) continue;
        // Horizon: edges of visible faces whose reverse is not also visible.
        for (const auto& e : edges) {
            const bool interior =
                std::find(edges.begin(), edges.end(), std::make_pair(e.second, e.first)) != edges.end();
            if (!interior) faces.push_back(make_face(points, e.first, e.second, p));
        }
        faces.erase(std::remove_if(faces.begin(), faces.end(), [](const Face& f) { return !f.live; }),
                    faces.end());
    }

    HullShape& hull = shape.hull;
    hull.vertices.assign(points.begin(), points.end());
    hull.triangles.clear();
    hull.normals.clear();
    hull.offsets.clear();
    for (const Face& f : faces) {
        if (f.normal.isZero()) continue;  // a sliver from nearly coplanar points
        hull.triangles.insert(hull.triangles.end(), {f.a, f.b, f.c});
        hull.normals.push_back(f.normal);
        hull.offsets.push_back(f.offset);
    }
    shape.kind = ShapeKind::kConvexHull;
    shape.bound_center = (lo + hi) * 0.5f;
    float radius = 0;
    for (const Vec3& q : points) radius = std::max(radius, (q - shape.bound_center).norm());
    shape.bound_radius = radius;
    return {};
}

SurfaceQuery query_hull(const HullShape& hull, const Vec3& p, float radius) {
    // The largest face-plane distance is the exact signed distance inside
    // and a lower bound outside.
    const size_t faces = hull.normals.size();
    size_t best = 0;
    float plane_distance = -std::numeric_limits<float>::infinity();
    for (size_t f = 0; f < faces; ++f) {
        const float d = hull.normals[f].dot(p) - hull.offsets[f];
        if (d > plane_distance) plane_distance = d, best = f;
    }
    SurfaceQuery q{plane_distance, hull.normals[best]};
    if (plane_distance <= 0 || plane_distance >= radius) return q;
    // Outside and near: the exact distance to the closest face triangle.
    float nearest = std::numeric_limits<float>::infinity();
    Vec3 closest = p;
    for (size_t f = 0; f < faces; ++f) {
        const Vec3 c = closest_point_on_triangle(p, hull.vertices[hull.triangles[3 * f]],
                                                 hull.vertices[hull.triangles[3 * f + 1]],
                                                 hull.vertices[hull.triangles[3 * f + 2]]);
        const float d = (p - c).squaredNorm();
        if (d < nearest) nearest = d, closest = c;
    }
    const float distance = std::sqrt(nearest);
    if (distance > 0) q = {distance, (p - closest) / distance};
    return q;
}

}  // namespace cloth
