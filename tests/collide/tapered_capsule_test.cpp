// A tapered capsule through the C API as a character's limb: swept fast
// across a hanging flag it pushes the flag along and no particle ends a
// step inside it or passes through it. Its distance is checked against
// the union of spheres along its axis, independently of the library's.
#include <cloth/cloth.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <vector>

namespace {

// Signed distance (outside: exact; inside: the least sphere's, a bound)
// of local point p to the hull of a sphere of radius `bottom` at
// y = -half and one of `top` at y = +half.
double limb_distance(const Eigen::Vector3d& p, double bottom, double top, double half) {
    double nearest = INFINITY;
    for (int k = 0; k <= 2000; ++k) {
        const double t = k / 2000.0;
        const Eigen::Vector3d centre(0.0, -half + 2.0 * half * t, 0.0);
        nearest = std::min(nearest, (p - centre).norm() - (bottom + (top - bottom) * t));
    }
    return nearest;
}

TEST(TaperedCapsule, ALimbSweptAcrossAFlagAtThirtyMetresPerSecondPushesItAndNeverTunnels) {
    cloth_world_desc wd = cloth_default_world_desc();
    cloth_world_id world{};
    ASSERT_EQ(cloth_world_create(&wd, &world), CLOTH_OK);
    constexpr uint32_t kColumns = 24, kRows = 20, kCount = kColumns * kRows;
    cloth_grid_desc g = cloth_default_grid_desc();
    g.columns = kColumns;
    g.rows = kRows;
    g.origin[0] = -0.6f;
    g.origin[1] = 1.0f;
    g.u[0] = 1.2f;
    g.v[1] = -1.0f;
    cloth_fabric_id fabric{};
    ASSERT_EQ(cloth_fabric_create_grid(world, &g, &fabric), CLOTH_OK);
    cloth_desc cd = cloth_default_desc();
    cd.fabric = fabric;
    // The paper's solver without a strain limit, as the box's sweep test
    // runs: the flag stretches and stays on the limb rather than sliding
    // off it round its curve.
    cd.solver.kind = CLOTH_SOLVER_JACOBI;
    cloth_id cloth{};
    ASSERT_EQ(cloth_create(world, &cd, &cloth), CLOTH_OK);
    std::vector<uint32_t> top_row(kColumns);
    for (uint32_t c = 0; c < kColumns; ++c) top_row[c] = c;
    ASSERT_EQ(cloth_pin(cloth, top_row.data(), kColumns), CLOTH_OK);

    // A thigh-like limb lying along x (local y turned onto world x), thick
    // end (0.15 m) at +x, thin end (0.07 m) at -x, 0.8 m between centres,
    // flying along +z at 30 m/s (0.5 m a frame, more than its thickness).
    const double bottom = 0.07, top = 0.15, half = 0.4;
    const Eigen::Quaterniond turn(Eigen::AngleAxisd(-M_PI / 2, Eigen::Vector3d::UnitZ()));
    cloth_body_desc bd = cloth_default_body_desc();
    bd.position[1] = 0.45f;
    bd.position[2] = -1.0f;
    bd.rotation[0] = float(turn.x());
    bd.rotation[1] = float(turn.y());
    bd.rotation[2] = float(turn.z());
    bd.rotation[3] = float(turn.w());
    cloth_body_id body{};
    ASSERT_EQ(cloth_body_create(world, &bd, &body), CLOTH_OK);
    cloth_collider_desc d = cloth_default_collider_desc();
    d.body = body;
    cloth_collider_id limb{};
    ASSERT_EQ(cloth_collider_create_tapered_capsule(world, &d, float(bottom), float(top), float(half), &limb),
              CLOTH_OK)
        << cloth_get_last_error();
    const float velocity[3] = {0, 0, 30}, spin[3] = {0, 0, 0};
    ASSERT_EQ(cloth_body_set_velocity(body, velocity, spin), CLOTH_OK);

    auto positions = [&] {
        std::vector<float> x(3 * kCount);
        EXPECT_EQ(cloth_read_positions(cloth, x.data(), 3 * kCount), CLOTH_OK);
        return x;
    };
    int violations = 0, carried = 0, tunneled = 0;
    std::vector<float> previous = positions();
    Eigen::Vector3d previous_centre(0.0, 0.45, -1.0);
    for (int frame = 1; frame <= 4; ++frame) {
        const Eigen::Vector3d centre(0.0, 0.45, -1.0 + 0.5 * frame);
        const float p[3] = {float(centre.x()), float(centre.y()), float(centre.z())};
        ASSERT_EQ(cloth_body_set_pose(body, p, bd.rotation), CLOTH_OK);
        ASSERT_EQ(cloth_step(world, 1.0f / 60.0f), CLOTH_OK) << cloth_get_last_error();
        const std::vector<float> x = positions();
        for (uint32_t i = 0; i < kCount; ++i) {
            const Eigen::Vector3d at(x[3 * i], x[3 * i + 1], x[3 * i + 2]);
            const Eigen::Vector3d before(previous[3 * i], previous[3 * i + 1], previous[3 * i + 2]);
            if (limb_distance(turn.inverse() * (at - centre), bottom, top, half) < 0.01 - 1e-4) ++violations;
            // In the limb's path (within its thin end's reach of its axis,
            // between its centres) ahead of it before the frame and still
            // in its path after: it must still be ahead.
            auto in_path = [&](const Eigen::Vector3d& q) {
                return std::abs(q.x()) < half && std::abs(q.y() - 0.45) < 0.5 * bottom;
            };
            if (in_path(before) && in_path(at) && before.z() > previous_centre.z() + bottom) {
                ++carried;
                if (at.z() < centre.z()) ++tunneled;
            }
        }
        previous = x;
        previous_centre = centre;
    }
    EXPECT_EQ(violations, 0) << "particles ended a step inside the limb";
    EXPECT_EQ(tunneled, 0) << "particles passed through the limb";
    EXPECT_GT(carried, 20) << "the limb should have met the flag";
    const std::vector<float> x = positions();
    const uint32_t middle = 11 * kColumns + 12;  // about (0, 0.42) at rest
    EXPECT_GT(x[3 * middle + 2], 0.75f)
        << "the flag was not pushed along by the limb (its centre is at z = 1)";
    cloth_world_destroy(world);
}

}  // namespace
