// Air forces: the drag and lift formulas on single triangles, and the grid
// cell path agreeing with the general triangle path on the same cloth.
#include "forces/aerodynamics.h"

#include <gtest/gtest.h>

#include <cmath>

#include "forces/material.h"
#include "solve/solver_settings.h"
#include "test_support.h"

namespace cloth {
namespace {

// One triangle (0,0,0), (1,0,0), (0,1,0): area 1/2, normal +z.
struct OneTriangle {
    Fabric fabric{cloth::testing::heap()};
    Vec3Soa x{cloth::testing::heap()}, v{cloth::testing::heap()}, corner{cloth::testing::heap()};

    OneTriangle() {
        const float positions[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
        const uint32_t indices[] = {0, 1, 2};
        EXPECT_TRUE(build_mesh_fabric(positions, 3, indices, 1, CLOTH_SPRING_ALL, fabric).ok());
        x.resize(3);
        v.resize(3);
        for (uint32_t i = 0; i < 3; ++i) x.set(i, fabric.rest_positions[i]);
        corner.resize(air_storage_size(fabric));
    }

    // Total force on the triangle (three corners).
    Vec3 total(const AeroParams& air) {
        evaluate_air(fabric, air, x, v, 0, air_item_count(fabric), corner);
        return corner.get(0) * 3.0f;
    }
};

AeroParams wind(const Vec3& velocity) {
    AeroParams air;
    air.wind = velocity;
    air.air_density = 1.2f;
    air.drag_coefficient = 1.0f;
    air.lift_coefficient = 0.5f;
    return air;
}

TEST(Aerodynamics, WindStraightAtAFaceGivesPureDragOfHalfRhoCdAU2) {
    OneTriangle t;
    const Vec3 f = t.total(wind(Vec3(0, 0, -10)));
    // 1/2 * 1.2 * 1.0 * 0.5 m^2 * 100 = 30 N along the wind, no lift (cos = 1, sin = 0).
    EXPECT_NEAR(f.z(), -30.0f, 1e-3f);
    EXPECT_NEAR(f.x(), 0.0f, 1e-4f);
    EXPECT_NEAR(f.y(), 0.0f, 1e-4f);
}

TEST(Aerodynamics, WindOnTheOtherFaceGivesTheMirroredDrag) {
    OneTriangle t;
    const Vec3 f = t.total(wind(Vec3(0, 0, 10)));
    EXPECT_NEAR(f.z(), 30.0f, 1e-3f);
    EXPECT_NEAR(f.x(), 0.0f, 1e-4f);
    EXPECT_NEAR(f.y(), 0.0f, 1e-4f);
}

TEST(Aerodynamics, WindAlongTheFaceGivesNoForce) {
    OneTriangle t;
    EXPECT_LT(t.total(wind(Vec3(7, 3, 0))).norm(), 1e-5f);
}

TEST(Aerodynamics, WindAt45DegreesGivesDragAlongTheNormalAndLiftAcrossTheWind) {
    OneTriangle t;
    const Vec3 u = Vec3(0, 1, -1).normalized() * 10.0f;
    const Vec3 f = t.total(wind(u));
    // pressure 1/2 rho A |u|^2 = 30 N; cos = 1/sqrt(2).
    const float cosine = std::sqrt(0.5f);
    const Vec3 n(0, 0, -1);                                  // downwind side
    const Vec3 drag = n * (30.0f * 1.0f * cosine * cosine);  // 15 N
    const Vec3 lift = (n - u.normalized() * cosine) * (30.0f * 0.5f * cosine);
    EXPECT_LT((f - (drag + lift)).norm(), 1e-3f);
    EXPECT_NEAR(lift.dot(u), 0.0f, 1e-4f) << "lift is perpendicular to the wind";
}

TEST(Aerodynamics, MovingWithTheWindFeelsNoAir) {
    OneTriangle t;
    for (uint32_t i = 0; i < 3; ++i) t.v.set(i, Vec3(1, 2, -3));
    EXPECT_LT(t.total(wind(Vec3(1, 2, -3))).norm(), 1e-6f);
}

TEST(Aerodynamics, GridCellsAndTheSameTrianglesAsAMeshGiveTheSameParticleForces) {
    auto grid = cloth::testing::make_grid(7, 5);
    Fabric mesh(cloth::testing::heap());
    std::vector<float> positions;
    for (const Vec3& p : grid->rest_positions) positions.insert(positions.end(), {p.x(), p.y(), p.z()});
    ASSERT_TRUE(build_mesh_fabric(positions.data(), grid->particle_count(), grid->triangles.data(),
                                  grid->triangle_count(), CLOTH_SPRING_ALL, mesh)
                    .ok());
    const uint32_t n = grid->particle_count();
    Vec3Soa x(cloth::testing::heap()), v(cloth::testing::heap());
    x.resize(n);
    v.resize(n);
    for (uint32_t i = 0; i < n; ++i) {
        x.set(i, grid->rest_positions[i] + Vec3(0, 0, 0.05f * std::sin(1.7f * i)));
        v.set(i, Vec3(0.1f * std::cos(0.3f * i), 0, 0.2f));
    }
    const AeroParams air = wind(Vec3(8, 1, 3));
    // Forces per grid vertex; the mesh stores its particles in its own
    // (spatial) order, Fabric::particle maps a vertex to its particle.
    auto vertex_forces = [&](const Fabric& fabric) {
        Vec3Soa xs(cloth::testing::heap()), vs(cloth::testing::heap());
        xs.resize(n);
        vs.resize(n);
        for (uint32_t i = 0; i < n; ++i) {
            xs.set(fabric.particle(i), x.get(i));
            vs.set(fabric.particle(i), v.get(i));
        }
        Vec3Soa corner(cloth::testing::heap()), force(cloth::testing::heap()), out(cloth::testing::heap());
        corner.resize(air_storage_size(fabric));
        force.resize(n);
        out.resize(n);
        evaluate_air(fabric, air, xs, vs, 0, air_item_count(fabric), corner);
        gather_air(fabric, corner, 0, n, force);
        for (uint32_t i = 0; i < n; ++i) out.set(i, force.get(fabric.particle(i)));
        return out;
    };
    const Vec3Soa a = vertex_forces(*grid), b = vertex_forces(mesh);
    for (uint32_t i = 0; i < n; ++i) {
        EXPECT_LT((a.get(i) - b.get(i)).norm(), 1e-5f * (1 + b.get(i).norm())) << "vertex " << i;
    }
}

}  // namespace
}  // namespace cloth
