// Shape queries against independent answers. For every shape: a point
// outside is at the reported distance from the surface along the reported
// normal (the foot point lies on the surface, and no sampled surface point
// is closer); inside points report the depth to the nearest face. Hulls and
// closed meshes of a box must give the box's own answers, a flat height
// field the plane's.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "collide/colliders.h"
#include "test_support.h"

namespace cloth {
namespace {

using cloth::testing::heap;

std::vector<Vec3> random_points(int count, float extent, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-extent, extent);
    std::vector<Vec3> out;
    for (int i = 0; i < count; ++i) out.emplace_back(u(rng), u(rng), u(rng));
    return out;
}

// Box corners and its 12 outward triangles.
const float kBoxCorners[] = {-1, -0.5f, -0.25f, 1, -0.5f, -0.25f, 1, 0.5f, -0.25f, -1, 0.5f, -0.25f,
                             -1, -0.5f, 0.25f,  1, -0.5f, 0.25f,  1, 0.5f, 0.25f,  -1, 0.5f, 0.25f};
const uint32_t kBoxTriangles[] = {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                                  3, 6, 2, 3, 7, 6, 0, 4, 7, 0, 7, 3, 1, 2, 6, 1, 6, 5};

TEST(ColliderShapes, SphereCapsuleBoxAndPlaneDistancesMatchTheirClosedForms) {
    Shape sphere(heap()), capsule(heap()), box(heap()), plane(heap());
    ASSERT_TRUE(build_sphere(0.5f, sphere).ok());
    ASSERT_TRUE(build_capsule(0.3f, 0.6f, capsule).ok());
    ASSERT_TRUE(build_box(Vec3(1, 0.5f, 0.25f), box).ok());
    ASSERT_TRUE(build_plane(Vec3(0, 2, 0), 1.0f, plane).ok());  // y <= 0.5
    for (const Vec3& p : random_points(2000, 2.0f, 1)) {
        // Sphere: |p| - r.
        EXPECT_NEAR(query_shape(sphere, p, 10).distance, p.norm() - 0.5f, 1e-5f);
        // Capsule: distance to the segment minus r.
        const float y = std::max(-0.6f, std::min(0.6f, p.y()));
        EXPECT_NEAR(query_shape(capsule, p, 10).distance, (p - Vec3(0, y, 0)).norm() - 0.3f, 1e-5f);
        // Plane: height above y = 0.5 (the normal was not unit length).
        EXPECT_NEAR(query_shape(plane, p, 10).distance, p.y() - 0.5f, 1e-5f);
        // Box, by brute force over a dense sampling of its surface.
        const SurfaceQuery q = query_shape(box, p, 10);
        const Vec3 foot = p - q.normal * q.distance;
        EXPECT_NEAR(query_shape(box, foot, 10).distance, 0.0f, 1e-5f)
            << "the foot point is not on the surface";
        const Vec3 e(1, 0.5f, 0.25f);
        const bool inside = std::abs(p.x()) < e.x() && std::abs(p.y()) < e.y() && std::abs(p.z()) < e.z();
        EXPECT_EQ(q.distance < 0, inside);
        if (inside) {
            const float depth =
                std::min({e.x() - std::abs(p.x()), e.y() - std::abs(p.y()), e.z() - std::abs(p.z())});
            EXPECT_NEAR(q.distance, -depth, 1e-5f);
        } else {
            const Vec3 clamped = p.cwiseMax(-e).cwiseMin(e);
            EXPECT_NEAR(q.distance, (p - clamped).norm(), 1e-5f);
        }
    }
}

// A tapered capsule is the union of the spheres along its axis whose radius
// runs linearly from the bottom's to the top's: outside, its distance is
// the least |p - c(t)| - r(t) over them (sampled finely here); inside, the
// foot point lies on the surface and the depth is no more than the least
// sphere's. With equal radii it is the capsule.
TEST(ColliderShapes, ATaperedCapsulesDistanceIsTheNearestOfTheSpheresAlongItsAxis) {
    const float bottom = 0.35f, top = 0.12f, half = 0.5f;
    Shape tapered(heap()), even(heap()), capsule(heap());
    ASSERT_TRUE(build_tapered_capsule(bottom, top, half, tapered).ok());
    ASSERT_TRUE(build_tapered_capsule(0.3f, 0.3f, 0.6f, even).ok());
    ASSERT_TRUE(build_capsule(0.3f, 0.6f, capsule).ok());
    int inside = 0, outside = 0;
    // |p - c(t)| - r(t) is convex in t (a norm of an affine map less a
    // linear term): sampled coarsely, then finely around the coarse least.
    const auto sphere_distance = [&](const Vec3& p, float t) {
        const Vec3 centre(0.0f, -half + 2.0f * half * t, 0.0f);
        return (p - centre).norm() - (bottom + (top - bottom) * t);
    };
    for (const Vec3& p : random_points(3000, 0.8f, 7)) {
        int best = 0;
        for (int k = 1; k <= 200; ++k) {
            if (sphere_distance(p, float(k) / 200.0f) < sphere_distance(p, float(best) / 200.0f)) best = k;
        }
        float nearest = INFINITY;
        for (int k = -100; k <= 100; ++k) {
            const float t = std::clamp(float(best) / 200.0f + float(k) / 20000.0f, 0.0f, 1.0f);
            nearest = std::min(nearest, sphere_distance(p, t));
        }
        const SurfaceQuery q = query_shape(tapered, p, 10);
        EXPECT_NEAR(q.normal.norm(), 1.0f, 1e-5f);
        EXPECT_NEAR(query_shape(tapered, p - q.normal * q.distance, 10).distance, 0.0f, 2e-5f)
            << "the foot point is not on the surface";
        EXPECT_EQ(q.distance < 0, nearest < 0) << p.transpose();
        if (nearest >= 0) {
            ++outside;
            EXPECT_NEAR(q.distance, nearest, 1e-4f) << p.transpose();
        } else {
            ++inside;
            EXPECT_GE(q.distance, nearest - 1e-4f) << p.transpose();
        }
        EXPECT_NEAR(query_shape(even, p, 10).distance, query_shape(capsule, p, 10).distance, 1e-5f);
    }
    EXPECT_GT(inside, 100);
    EXPECT_GT(outside, 100);
    // One sphere inside the other is a sphere, not a tapered capsule.
    Shape bad(heap());
    EXPECT_FALSE(build_tapered_capsule(0.5f, 0.1f, 0.1f, bad).ok());
    EXPECT_FALSE(build_tapered_capsule(0.0f, 0.1f, 0.5f, bad).ok());
    EXPECT_FALSE(build_tapered_capsule(0.2f, NAN, 0.5f, bad).ok());
}

TEST(ColliderShapes, ConvexHullOfABoxGivesTheBoxAnswerInsideAndNearOutside) {
    Shape hull(heap()), box(heap());
    ASSERT_TRUE(build_convex_hull(kBoxCorners, 8, hull).ok());
    ASSERT_TRUE(build_box(Vec3(1, 0.5f, 0.25f), box).ok());
    // Extra interior and face points must not change the hull.
    std::vector<float> points(kBoxCorners, kBoxCorners + 24);
    for (const Vec3& p : random_points(50, 0.2f, 7)) points.insert(points.end(), {p.x(), p.y(), p.z()});
    points.insert(points.end(), {0.0f, 0.5f, 0.0f, 1.0f, 0.0f, 0.0f});
    Shape noisy(heap());
    ASSERT_TRUE(build_convex_hull(points.data(), static_cast<uint32_t>(points.size() / 3), noisy).ok());
    for (const Vec3& p : random_points(3000, 1.5f, 2)) {
        const SurfaceQuery b = query_shape(box, p, 10);
        for (const Shape* h : {&hull, &noisy}) {
            const SurfaceQuery q = query_shape(*h, p, 10);
            EXPECT_NEAR(q.distance, b.distance, 2e-5f) << p.transpose();
            if (std::abs(b.distance) > 1e-3f) {
                EXPECT_GT(q.normal.dot(b.normal), 0.999f) << p.transpose();
            }
        }
    }
    // Beyond the query radius the hull may answer a lower bound, never more.
    for (const Vec3& p : random_points(500, 5.0f, 3)) {
        EXPECT_LE(query_shape(hull, p, 0.1f).distance, query_shape(box, p, 10).distance + 1e-5f);
    }
}

TEST(ColliderShapes, ClosedTriangleMeshOfABoxGivesTheBoxAnswerWithinTheQueryRadius) {
    Shape mesh(heap()), box(heap());
    ASSERT_TRUE(build_triangle_mesh(kBoxCorners, 8, kBoxTriangles, 12, mesh).ok());
    ASSERT_TRUE(build_box(Vec3(1, 0.5f, 0.25f), box).ok());
    const float radius = 0.3f;
    int checked = 0;
    for (const Vec3& p : random_points(4000, 1.5f, 4)) {
        const SurfaceQuery b = query_shape(box, p, 10);
        const SurfaceQuery q = query_shape(mesh, p, radius);
        if (std::abs(b.distance) < radius) {
            ++checked;
            EXPECT_NEAR(q.distance, b.distance, 2e-5f) << p.transpose();
        } else {
            EXPECT_GE(q.distance, radius - 1e-5f) << "a far point must read as at least the radius";
        }
    }
    EXPECT_GT(checked, 300);
}

TEST(ColliderShapes, HeightFieldIsSolidBelowAndMatchesAPlaneWhenFlatAndASlopeWhenTilted) {
    std::vector<float> flat(5 * 4, 0.25f), slope;
    for (uint32_t r = 0; r < 4; ++r)
        for (uint32_t c = 0; c < 5; ++c) slope.push_back(0.5f * c);  // h = x / 2 (spacing 1)
    Shape field(heap()), tilted(heap());
    ASSERT_TRUE(build_heightfield(5, 4, 1.0f, 1.0f, flat.data(), field).ok());
    ASSERT_TRUE(build_heightfield(5, 4, 1.0f, 1.0f, slope.data(), tilted).ok());
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> ux(0.6f, 3.4f), uz(0.6f, 2.4f), uy(-0.4f, 0.4f);
    const Vec3 slope_normal = Vec3(-0.5f, 1.0f, 0.0f).normalized();
    for (int k = 0; k < 2000; ++k) {
        const Vec3 p(ux(rng), 0.25f + uy(rng), uz(rng));
        const SurfaceQuery q = query_shape(field, p, 0.5f);
        EXPECT_NEAR(q.distance, p.y() - 0.25f, 3e-5f);
        EXPECT_GT(q.normal.y(), 0.9999f);
        const Vec3 s(p.x(), 0.5f * p.x() + uy(rng), p.z());
        const float exact = slope_normal.dot(s);  // signed distance to the plane y = x / 2
        EXPECT_NEAR(query_shape(tilted, s, 0.5f).distance, exact, 2e-5f) << s.transpose();
    }
    // Deep below (beyond the query radius) is still inside, pushed straight up.
    const SurfaceQuery deep = query_shape(field, Vec3(2, -3, 1.5f), 0.5f);
    EXPECT_NEAR(deep.distance, -3.25f, 1e-5f);
    EXPECT_GT(deep.normal.y(), 0.9999f);
}

TEST(ColliderResponse, AParticleTouchingASurfaceSlidesAlongItInsteadOfStickingWhereItTouched) {
    // A particle on (or a hair above) the thickness surface of a static
    // plane, moving along it at 0.5 m/s and into it at 0.2 m/s, without
    // friction: the surface stops the normal motion only, so over one
    // substep the particle moves h * 0.5 m along the plane and ends on the
    // thickness surface. Both sides of the surface must agree (the sweep
    // from a start just outside once held the particle at its start point).
    Shape plane(heap());
    ASSERT_TRUE(build_plane(Vec3(0, 1, 0), 0.0f, plane).ok());
    const MovingCollider collider(&plane, Pose{}, Pose{});
    CollisionParams params;
    params.thickness = 0.01f;
    params.friction = 0.0f;
    const float h = 1.0f / 60.0f;
    const float kinematic[1] = {0.0f};
    for (float start_gap : {-1e-6f, 0.0f, 1e-6f}) {
        SCOPED_TRACE(start_gap);
        Vec3Soa x(heap()), v(heap());
        x.resize(1);
        v.resize(1);
        const Vec3 start(0.0f, params.thickness + start_gap, 0.0f), velocity(0.5f, -0.2f, 0.0f);
        v.set(0, velocity);
        x.set(0, start + velocity * h);  // collide_particles sees the state after integration
        EXPECT_EQ(collide_particles(collider, params, h, kinematic, 0, 1, x, v), 1u);
        EXPECT_NEAR(x.get(0).x(), 0.5f * h, 1e-6f) << "the particle did not slide along the surface";
        EXPECT_NEAR(x.get(0).y(), params.thickness, 1e-6f);
        EXPECT_NEAR(v.get(0).x(), 0.5f, 1e-6f);
        EXPECT_NEAR(v.get(0).y(), 0.0f, 1e-6f);
    }
}

}  // namespace
}  // namespace cloth
