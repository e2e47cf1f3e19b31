// One file over 400 lines: its scenes share one set of helpers (scene setup,
// the inside-a-collider count) that the checks below all lean on.
// Bodies, colliders, attachments and carriers through the C API, checked
// against what the physics says (not against recorded numbers):
//   - attached particles sit on body pose * offset every frame while the
//     body moves and turns fast (no one-frame lag);
//   - no particle ends a step inside a collider beyond the thickness
//     tolerance (violations are counted, zero expected), including a box
//     crossing a flag at 60 m/s, a whole box length per 1/60 s frame;
//   - carrier controls: with linear inertia 0 an accelerating carrier does
//     not deform the cloth relative to it; a teleport moves the cloth
//     rigidly (strain unchanged); teleport-and-reset restores the reference
//     shape at the new pose.
#include <cloth/cloth.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <string>
#include <vector>

namespace {

constexpr float kFrame = 1.0f / 60.0f;

struct World {
    cloth_world_id world{};
    cloth_fabric_id fabric{};
    cloth_id cloth{};
    uint32_t n = 0;

    // A columns x rows grid of width x height metres hanging from `origin`
    // down -y, spanning +x.
    World(uint32_t columns, uint32_t rows, float width, float height, const float origin[3],
          uint32_t substeps = 1, bool air = true) {
        const cloth_world_desc wd = cloth_default_world_desc();
        EXPECT_EQ(cloth_world_create(&wd, &world), CLOTH_OK);
        cloth_grid_desc g = cloth_default_grid_desc();
        g.columns = columns;
        g.rows = rows;
        for (int k = 0; k < 3; ++k) g.origin[k] = origin[k];
        g.u[0] = width;
        g.v[1] = -height;
        EXPECT_EQ(cloth_fabric_create_grid(world, &g, &fabric), CLOTH_OK);
        cloth_desc cd = cloth_default_desc();
        cd.fabric = fabric;
        cd.solver.kind = CLOTH_SOLVER_JACOBI;  // the figures below were set with the paper's solver
        cd.solver.substeps = substeps;
        if (!air) {
            cd.aero.air_density = 0;
            cd.aero.linear_drag = 0;
        }
        EXPECT_EQ(cloth_create(world, &cd, &cloth), CLOTH_OK) << cloth_get_last_error();
        n = columns * rows;
    }
    ~World() { cloth_world_destroy(world); }

    std::vector<float> positions() const {
        std::vector<float> x(3 * n);
        EXPECT_EQ(cloth_read_positions(cloth, x.data(), 3 * n), CLOTH_OK);
        return x;
    }
    Eigen::Vector3d at(const std::vector<float>& x, uint32_t i) const {
        return {x[3 * i], x[3 * i + 1], x[3 * i + 2]};
    }
    cloth_stats stats() const {
        cloth_stats s{};
        s.struct_size = sizeof s;
        EXPECT_EQ(cloth_get_stats(cloth, &s), CLOTH_OK);
        return s;
    }
};

cloth_body_id make_body(cloth_world_id world, const float position[3]) {
    cloth_body_desc d = cloth_default_body_desc();
    for (int k = 0; k < 3; ++k) d.position[k] = position[k];
    cloth_body_id body{};
    EXPECT_EQ(cloth_body_create(world, &d, &body), CLOTH_OK) << cloth_get_last_error();
    return body;
}

void set_pose(cloth_body_id body, const Eigen::Vector3d& p, const Eigen::Quaterniond& q) {
    const float position[3] = {float(p.x()), float(p.y()), float(p.z())};
    const float rotation[4] = {float(q.x()), float(q.y()), float(q.z()), float(q.w())};
    ASSERT_EQ(cloth_body_set_pose(body, position, rotation), CLOTH_OK) << cloth_get_last_error();
}

// ---------------------------------------------------------------- attachments

TEST(Attachments, FollowAFastMovingTurningBodyExactlyEveryFrameWithAnySubstepCount) {
    for (uint32_t substeps : {1u, 4u}) {
        SCOPED_TRACE(substeps);
        const float origin[3] = {0, 0, 0};
        World w(16, 12, 1.5f, 1.0f, origin, substeps);
        const cloth_body_id body = make_body(w.world, origin);
        // The top row, at its rest offsets from the body.
        std::vector<uint32_t> top;
        for (uint32_t c = 0; c < 16; ++c) top.push_back(c);
        ASSERT_EQ(cloth_attach(w.cloth, body, top.data(), nullptr, 16), CLOTH_OK);
        std::vector<Eigen::Vector3d> offsets;
        for (uint32_t c = 0; c < 16; ++c) offsets.emplace_back(1.5 * c / 15.0, 0, 0);

        // 20 m/s along a curve while spinning at up to 8 rad/s about a tilted axis.
        double max_error = 0;
        for (int frame = 1; frame <= 120; ++frame) {
            const double t = frame * kFrame;
            const Eigen::Vector3d p(20 * t, 2 * std::sin(3 * t), 5 * std::sin(t));
            const Eigen::Quaterniond q(Eigen::AngleAxisd(4 * t * t, Eigen::Vector3d(1, 2, 3).normalized()));
            set_pose(body, p, q);
            ASSERT_EQ(cloth_step(w.world, kFrame), CLOTH_OK) << cloth_get_last_error();
            const std::vector<float> x = w.positions();
            const Eigen::Quaternionf qf(float(q.w()), float(q.x()), float(q.y()), float(q.z()));
            for (uint32_t c = 0; c < 16; ++c) {
                const Eigen::Vector3d target = qf.normalized().cast<double>() * offsets[c] + p;
                max_error = std::max(max_error, (w.at(x, c) - target).norm());
            }
        }
        EXPECT_LT(max_error, 1e-5) << "attached particles left their targets";
        const cloth_stats s = w.stats();
        EXPECT_TRUE(std::isfinite(s.max_speed));
    }
}

TEST(Attachments, DetachedParticlesFallFreelyAndReattachingMovesThemToTheNewOffset) {
    const float origin[3] = {0, 0, 0};
    World w(4, 4, 1.0f, 1.0f, origin);
    const cloth_body_id body = make_body(w.world, origin);
    const uint32_t all[] = {0, 1, 2, 3};
    ASSERT_EQ(cloth_attach(w.cloth, body, all, nullptr, 4), CLOTH_OK);
    for (int i = 0; i < 10; ++i) ASSERT_EQ(cloth_step(w.world, kFrame), CLOTH_OK);
    EXPECT_NEAR(w.positions()[1], 0.0f, 1e-6f) << "an attached particle moved off a still body";
    ASSERT_EQ(cloth_detach(w.cloth, all, 4), CLOTH_OK);
    for (int i = 0; i < 30; ++i) ASSERT_EQ(cloth_step(w.world, kFrame), CLOTH_OK);
    // (One Jacobi sweep falls slowly, see README; any clear drop will do.)
    EXPECT_LT(w.positions()[1], -0.03f) << "detached particles did not fall";
    const float offsets[] = {0, 1, 0, 0.3f, 1, 0, 0.6f, 1, 0, 1, 1, 0};
    ASSERT_EQ(cloth_attach(w.cloth, body, all, offsets, 4), CLOTH_OK);
    ASSERT_EQ(cloth_step(w.world, kFrame), CLOTH_OK);
    const std::vector<float> x = w.positions();
    for (int k = 0; k < 4; ++k) {
        EXPECT_NEAR(x[3 * k], offsets[3 * k], 1e-6f);
        EXPECT_NEAR(x[3 * k + 1], 1.0f, 1e-6f);
    }
}

// ---------------------------------------------------------------- colliders

// Signed distance of world point p to a sphere, box or plane, in double.
double sphere_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& c, double r) {
    return (p - c).norm() - r;
}
double box_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& c, const Eigen::Vector3d& e) {
    const Eigen::Vector3d d = (p - c).cwiseAbs() - e;
    const double outside = d.cwiseMax(0.0).norm();
    return outside > 0 ? outside : d.maxCoeff();
}

TEST(Colliders, ClothDrapedOverASphereOntoTheGroundNeverEndsAStepInsideEither) {
    const float origin[3] = {-1, 1.0f, -1};
    World w(24, 24, 2.0f, 2.0f, origin, 2);
    // Lay the cloth flat (horizontal): the grid's v goes along +z.
    std::vector<float> flat(3 * w.n);
    std::vector<uint32_t> all(w.n);
    for (uint32_t r = 0; r < 24; ++r) {
        for (uint32_t c = 0; c < 24; ++c) {
            const uint32_t i = r * 24 + c;
            all[i] = i;
            flat[3 * i] = -1 + 2.0f * c / 23;
            flat[3 * i + 1] = 1.0f;
            flat[3 * i + 2] = -1 + 2.0f * r / 23;
        }
    }
    ASSERT_EQ(cloth_set_positions(w.cloth, all.data(), flat.data(), w.n), CLOTH_OK);
    cloth_collision_params cp = cloth_default_collision_params();
    cp.thickness = 0.02f;
    ASSERT_EQ(cloth_set_collision(w.cloth, &cp), CLOTH_OK);
    cloth_collider_desc d = cloth_default_collider_desc();
    d.local_position[1] = 0.4f;
    cloth_collider_id sphere, ground;
    ASSERT_EQ(cloth_collider_create_sphere(w.world, &d, 0.4f, &sphere), CLOTH_OK);
    const cloth_collider_desc g = cloth_default_collider_desc();
    const float up[3] = {0, 1, 0};
    ASSERT_EQ(cloth_collider_create_plane(w.world, &g, up, 0.0f, &ground), CLOTH_OK);

    int violations = 0, resting_on_sphere = 0;
    for (int frame = 0; frame < 180; ++frame) {
        ASSERT_EQ(cloth_step(w.world, kFrame), CLOTH_OK) << cloth_get_last_error();
        const std::vector<float> x = w.positions();
        for (uint32_t i = 0; i < w.n; ++i) {
            const Eigen::Vector3d p = w.at(x, i);
            if (sphere_distance(p, {0, 0.4, 0}, 0.4) < cp.thickness - 1e-4) ++violations;
            if (p.y() < cp.thickness - 1e-4) ++violations;
        }
    }
    EXPECT_EQ(violations, 0);
    const std::vector<float> x = w.positions();
    for (uint32_t i = 0; i < w.n; ++i) {
        if (sphere_distance(w.at(x, i), {0, 0.4, 0}, 0.4) < cp.thickness + 0.01) ++resting_on_sphere;
    }
    EXPECT_GT(resting_on_sphere, 10) << "the cloth should drape over the sphere";
    EXPECT_LT(w.positions()[3 * (12 * 24 + 12) + 1], 0.9f)
        << "the cloth's middle should rest on the sphere top";
}

TEST(Colliders, ABoxCrossingAFlagAtSixtyMetresPerSecondPushesItAndNeverTunnels) {
    // A 1.2 m x 1 m flag hanging in the x-y plane at z = 0, pinned along its top.
    const float origin[3] = {-0.6f, 1.0f, 0.0f};
    World w(24, 20, 1.2f, 1.0f, origin);
    std::vector<uint32_t> top;
    for (uint32_t c = 0; c < 24; ++c) top.push_back(c);
    ASSERT_EQ(cloth_pin(w.cloth, top.data(), 24), CLOTH_OK);
    // A 0.6 x 0.4 x 0.5 m box (half extents 0.3, 0.2, 0.25) flying along +z
    // at 60 m/s: 1 m per frame, twice its own length.
    const float start[3] = {0, 0.4f, -1.5f};
    const cloth_body_id body = make_body(w.world, start);
    cloth_collider_desc d = cloth_default_collider_desc();
    d.body = body;
    const float half[3] = {0.3f, 0.2f, 0.25f};
    cloth_collider_id box;
    ASSERT_EQ(cloth_collider_create_box(w.world, &d, half, &box), CLOTH_OK);
    const float velocity[3] = {0, 0, 60}, spin[3] = {0, 0, 0};
    ASSERT_EQ(cloth_body_set_velocity(body, velocity, spin), CLOTH_OK);

    int violations = 0, tunneled = 0, carried = 0;
    const Eigen::Vector3d e(0.3, 0.2, 0.25);
    std::vector<float> previous = w.positions();
    Eigen::Vector3d previous_center(start[0], start[1], start[2]);
    auto in_footprint = [](const Eigen::Vector3d& p) {
        return std::abs(p.x()) < 0.25 && std::abs(p.y() - 0.4) < 0.15;
    };
    for (int frame = 1; frame <= 4; ++frame) {
        const Eigen::Vector3d center(0, 0.4, -1.5 + frame * 1.0);
        set_pose(body, center, Eigen::Quaterniond::Identity());
        ASSERT_EQ(cloth_step(w.world, kFrame), CLOTH_OK) << cloth_get_last_error();
        const std::vector<float> x = w.positions();
        for (uint32_t i = 0; i < w.n; ++i) {
            const Eigen::Vector3d p = w.at(x, i), before = w.at(previous, i);
            if (box_distance(p, center, e) < 0.01 - 1e-4) ++violations;
            // A particle in front of the box and in its path at the start
            // of the frame, and still in its path at the end, must still be
            // in front of it: else it went through.
            const bool was_ahead = before.z() > previous_center.z() + e.z() - 0.02;
            if (in_footprint(before) && in_footprint(p) && was_ahead) {
                ++carried;
                if (p.z() < center.z() + e.z() - 0.02) ++tunneled;
            }
        }
        previous = x;
        previous_center = center;
    }
    EXPECT_EQ(violations, 0) << "particles ended a step inside the box";
    EXPECT_EQ(tunneled, 0) << "particles tunneled through the box";
    EXPECT_GT(carried, 100) << "the box should have met the flag";
    // The part of the flag in the box's path travels with it.
    const std::vector<float> x = w.positions();
    const uint32_t middle = 12 * 24 + 12;  // (0, 0.37) at rest
    EXPECT_GT(x[3 * middle + 2], 2.0f) << "the flag's middle was not carried along by the box";
}

// ---------------------------------------------------------------- carrier

// Positions of a cloth in its carrier's frame (translation only).
std::vector<Eigen::Vector3d> relative(const World& w, const Eigen::Vector3d& carrier) {
    const std::vector<float> x = w.positions();
    std::vector<Eigen::Vector3d> out;
    for (uint32_t i = 0; i < w.n; ++i) out.push_back(w.at(x, i) - carrier);
    return out;
}

TEST(Carrier, WithLinearInertiaZeroAnAcceleratingCarrierDoesNotDeformTheCloth) {
    // The same hanging cloth twice: carrier at rest, and carrier accelerating
    // at 15 m/s^2 along x. With linear inertia 0 the second cloth, seen from
    // its carrier, must do exactly what the first does; with inertia 1 it
    // must trail behind (so the comparison can fail).
    double deviation[2] = {0, 0};
    const float inertias[2] = {0.0f, 1.0f};
    for (int run = 0; run < 2; ++run) {
        const float origin[3] = {0, 0, 0};
        World still(10, 10, 1, 1, origin, 1, false), moving(10, 10, 1, 1, origin, 1, false);
        const cloth_body_id a = make_body(still.world, origin), b = make_body(moving.world, origin);
        const uint32_t corners[] = {0, 9};
        ASSERT_EQ(cloth_attach(still.cloth, a, corners, nullptr, 2), CLOTH_OK);
        ASSERT_EQ(cloth_attach(moving.cloth, b, corners, nullptr, 2), CLOTH_OK);
        cloth_carrier_desc c = cloth_default_carrier_desc();
        c.linear_inertia = inertias[run];
        ASSERT_EQ(cloth_set_carrier(moving.cloth, b, &c), CLOTH_OK);
        for (int frame = 1; frame <= 90; ++frame) {
            const double t = frame * kFrame;
            const Eigen::Vector3d p(0.5 * 15 * t * t, 0, 0);
            set_pose(b, p, Eigen::Quaterniond::Identity());
            ASSERT_EQ(cloth_step(still.world, kFrame), CLOTH_OK);
            ASSERT_EQ(cloth_step(moving.world, kFrame), CLOTH_OK);
            const auto rs = relative(still, Eigen::Vector3d::Zero()), rm = relative(moving, p);
            for (uint32_t i = 0; i < still.n; ++i)
                deviation[run] = std::max(deviation[run], (rs[i] - rm[i]).norm());
        }
    }
    EXPECT_LT(deviation[0], 2e-3) << "inertia 0: the accelerating carrier deformed the cloth";
    EXPECT_GT(deviation[1], 0.05) << "inertia 1: the cloth should trail an accelerating carrier";
}

// Deviation of a cloth on a carrier spinning up about y (to 6 rad/s in one
// second) from its shape on a carrier at rest, seen from the carrier, with
// the given inertia scales (no gravity, no air).
double spin_deviation(float inertia) {
    const float origin[3] = {0, 0, 0};
    World still(8, 8, 1, 1, origin, 1, false), spun(8, 8, 1, 1, origin, 1, false);
    const cloth_body_id a = make_body(still.world, origin), b = make_body(spun.world, origin);
    const uint32_t corners[] = {0, 7};
    EXPECT_EQ(cloth_attach(still.cloth, a, corners, nullptr, 2), CLOTH_OK);
    EXPECT_EQ(cloth_attach(spun.cloth, b, corners, nullptr, 2), CLOTH_OK);
    cloth_carrier_desc c = cloth_default_carrier_desc();
    c.linear_inertia = c.angular_inertia = c.centrifugal_inertia = inertia;
    EXPECT_EQ(cloth_set_carrier(spun.cloth, b, &c), CLOTH_OK);
    const float zero[3] = {0, 0, 0};
    EXPECT_EQ(cloth_world_set_gravity(still.world, zero), CLOTH_OK);
    EXPECT_EQ(cloth_world_set_gravity(spun.world, zero), CLOTH_OK);
    double deviation = 0;
    for (int frame = 1; frame <= 60; ++frame) {
        const double t = frame * kFrame;
        const Eigen::Quaterniond q(Eigen::AngleAxisd(3 * t * t, Eigen::Vector3d::UnitY()));
        set_pose(b, Eigen::Vector3d::Zero(), q);
        EXPECT_EQ(cloth_step(still.world, kFrame), CLOTH_OK);
        EXPECT_EQ(cloth_step(spun.world, kFrame), CLOTH_OK);
        const std::vector<float> xs = still.positions(), xr = spun.positions();
        const Eigen::Quaternionf qf(float(q.w()), float(q.x()), float(q.y()), float(q.z()));
        for (uint32_t i = 0; i < still.n; ++i) {
            const Eigen::Vector3d local = qf.normalized().cast<double>().conjugate() * spun.at(xr, i);
            deviation = std::max(deviation, (local - still.at(xs, i)).norm());
        }
    }
    return deviation;
}

TEST(Carrier, WithInertiaZeroASpinningCarrierTurnsTheClothWithIt) {
    // The carrier's rotation is handed over as a velocity change at the
    // start of each frame, so the particles move along the chord of the
    // arc; the implicit solve resists the chord's slight compression, which
    // leaves a small outward drift (about omega^2 h^2 of the radius per
    // frame). A cloth at inertia 1 instead stays behind almost entirely.
    const double carried = spin_deviation(0.0f), physical = spin_deviation(1.0f);
    EXPECT_LT(carried, 0.25 * physical) << "inertia 0: " << carried << " m, inertia 1: " << physical << " m";
    EXPECT_GT(physical, 0.5) << "a cloth held at two corners should lag a carrier spun up to 6 rad/s";
}

// The jump is either a pose beyond the carrier's teleport distance or a
// host teleport (cloth_body_teleport), which is one whatever the distance.
TEST(Carrier, TeleportMovesTheClothRigidlyAndResetRestoresTheReferenceShape) {
    for (bool host_teleport : {false, true})
        for (cloth_teleport_mode mode : {CLOTH_TELEPORT_MOVE, CLOTH_TELEPORT_AND_RESET}) {
            SCOPED_TRACE(std::string(host_teleport ? "cloth_body_teleport" : "cloth_body_set_pose") +
                         ", mode " + std::to_string(mode));
            const float origin[3] = {0, 0, 0};
            World w(12, 12, 1, 1, origin, 4);  // substeps keep one Jacobi sweep stable in motion
            const cloth_body_id body = make_body(w.world, origin);
            const uint32_t corners[] = {0, 11};
            ASSERT_EQ(cloth_attach(w.cloth, body, corners, nullptr, 2), CLOTH_OK);
            cloth_carrier_desc c = cloth_default_carrier_desc();
            c.teleport_distance = 5.0f;
            c.teleport_mode = mode;
            ASSERT_EQ(cloth_set_carrier(w.cloth, body, &c), CLOTH_OK);
            const std::vector<float> reference = w.positions();
            // Drive along x at 10 m/s for a second so the cloth swings and stretches.
            Eigen::Vector3d p(0, 0, 0);
            for (int frame = 1; frame <= 60; ++frame) {
                p = Eigen::Vector3d(10.0 * frame * kFrame, 0, 0);
                set_pose(body, p, Eigen::Quaterniond::Identity());
                ASSERT_EQ(cloth_step(w.world, kFrame), CLOTH_OK);
            }
            const cloth_stats before = w.stats();
            bool teleported = true;
            ASSERT_EQ(cloth_get_teleported(w.cloth, &teleported), CLOTH_OK);
            EXPECT_FALSE(teleported);
            // Jump 100 m back and a quarter turn.
            const Eigen::Vector3d jump(-90, 3, 4);
            const Eigen::Quaterniond turn(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()));
            if (host_teleport) {
                const float position[3] = {float(jump.x()), float(jump.y()), float(jump.z())};
                const float rotation[4] = {float(turn.x()), float(turn.y()), float(turn.z()),
                                           float(turn.w())};
                ASSERT_EQ(cloth_body_teleport(body, position, rotation), CLOTH_OK);
            } else {
                set_pose(body, jump, turn);
            }
            ASSERT_EQ(cloth_step(w.world, kFrame), CLOTH_OK) << cloth_get_last_error();
            ASSERT_EQ(cloth_get_teleported(w.cloth, &teleported), CLOTH_OK);
            EXPECT_TRUE(teleported);
            const cloth_stats after = w.stats();
            const std::vector<float> x = w.positions();
            double max_distance = 0, from_reference = 0;
            for (uint32_t i = 0; i < w.n; ++i) {
                max_distance = std::max(max_distance, (w.at(x, i) - jump).norm());
                const Eigen::Vector3d ref = turn * w.at(reference, i) + jump;
                from_reference = std::max(from_reference, (w.at(x, i) - ref).norm());
            }
            EXPECT_LT(max_distance, 2.0) << "the cloth did not come along with the carrier";
            if (mode == CLOTH_TELEPORT_MOVE) {
                EXPECT_LT(after.max_strain, before.max_strain + 0.02f) << "teleport stretched the cloth";
                EXPECT_GT(from_reference, 0.01)
                    << "a plain teleport keeps the swing, not the reference shape";
            } else {
                EXPECT_LT(after.max_strain, 0.01f) << "reset should restore the unstretched reference shape";
                // One frame of free fall from the reference: g dt^2 / 2 plus rounding.
                EXPECT_LT(from_reference, 5e-3) << "reset should put the cloth in its reference shape";
            }
        }
}

TEST(Carrier, AHostTeleportMovesTheClothFromWhereTheBodyWasAtTheEndOfTheLastStep) {
    // cloth_body_teleport puts the body at its new pose at once (start and
    // target), as a host does when it teleports a vehicle; the host then
    // sets the pose for the end of the step as usual. The carrier must move
    // the cloth by the jump from the pose the cloth was left at, so the
    // cloth arrives with the body, in the same shape.
    const float origin[3] = {0, 0, 0};
    World w(12, 12, 1, 1, origin, 4);
    const cloth_body_id body = make_body(w.world, origin);
    const uint32_t corners[] = {0, 11};
    ASSERT_EQ(cloth_attach(w.cloth, body, corners, nullptr, 2), CLOTH_OK);
    cloth_carrier_desc c = cloth_default_carrier_desc();
    c.teleport_mode = CLOTH_TELEPORT_MOVE;
    ASSERT_EQ(cloth_set_carrier(w.cloth, body, &c), CLOTH_OK);
    Eigen::Vector3d p(0, 0, 0);
    for (int frame = 1; frame <= 60; ++frame) {
        p = Eigen::Vector3d(10.0 * frame * kFrame, 0, 0);
        set_pose(body, p, Eigen::Quaterniond::Identity());
        ASSERT_EQ(cloth_step(w.world, kFrame), CLOTH_OK);
    }
    const cloth_stats before = w.stats();
    const std::vector<float> x_before = w.positions();
    const Eigen::Vector3d jump(-90, 3, 4);
    const float to[3] = {-90, 3, 4}, identity[4] = {0, 0, 0, 1};
    ASSERT_EQ(cloth_body_teleport(body, to, identity), CLOTH_OK);
    set_pose(body, jump + Eigen::Vector3d(0.01, 0, 0), Eigen::Quaterniond::Identity());
    ASSERT_EQ(cloth_step(w.world, kFrame), CLOTH_OK) << cloth_get_last_error();
    bool teleported = false;
    ASSERT_EQ(cloth_get_teleported(w.cloth, &teleported), CLOTH_OK);
    EXPECT_TRUE(teleported);
    const std::vector<float> x = w.positions();
    double moved_off = 0;  // how far each particle is from where the jump alone takes it
    for (uint32_t i = 0; i < w.n; ++i)
        moved_off = std::max(moved_off, (w.at(x, i) - (w.at(x_before, i) - p + jump)).norm());
    // One frame of motion (10 m/s swing, gravity) is well under half a metre.
    EXPECT_LT(moved_off, 0.5) << "the cloth did not come along with the teleported body";
    EXPECT_LT(w.stats().max_strain, before.max_strain + 0.02f) << "the teleport stretched the cloth";
}

TEST(Colliders, AStripPulledRoundAThinPoleWrapsItWithinTheStrainLimit) {
    // A 60 cm strip in front of a vertical pole (radius 3.5 cm) has its two
    // ends pulled back past the pole at 3 m/s, to 5 cm either side of it
    // and 20 cm behind, then held. The path round the pole (about 0.55 m)
    // is shorter than the strip, so the strip can wrap the pole with every
    // spring within the 10% strain limit, and no particle may be inside the
    // pole. The limiter pulls along straight springs, through the pole;
    // unless the colliders act between its rounds, a spring that wraps the
    // pole stays stretched (or slips through it). PCG at two substeps, as
    // vehicle_flag runs it (at one, the strip's particles move further per
    // step than the pole is thick: docs/vehicle_flag.md, Known limits).
    const float origin[3] = {-0.3f, 0.01f, 0.06f};
    constexpr uint32_t kColumns = 30;
    World w(kColumns, 2, 0.6f, 0.02f, origin, 1, false);
    cloth_solver_settings solver = cloth_default_solver_settings();
    solver.kind = CLOTH_SOLVER_PCG;
    solver.iterations = 16;
    solver.substeps = 2;
    ASSERT_EQ(cloth_set_solver(w.cloth, &solver), CLOTH_OK);
    cloth_strain_limit limit = cloth_default_strain_limit();
    limit.max_strain = 0.1f;
    ASSERT_EQ(cloth_set_strain_limit(w.cloth, &limit), CLOTH_OK);
    const float zero[3] = {0, 0, 0};
    ASSERT_EQ(cloth_world_set_gravity(w.world, zero), CLOTH_OK);
    const float radius = 0.035f;
    cloth_collider_desc d = cloth_default_collider_desc();
    cloth_collider_id pole;
    ASSERT_EQ(cloth_collider_create_capsule(w.world, &d, radius, 1.0f, &pole), CLOTH_OK);
    const float left_at[3] = {-0.3f, 0.0f, 0.06f}, right_at[3] = {0.3f, 0.0f, 0.06f};
    const cloth_body_id left = make_body(w.world, left_at), right = make_body(w.world, right_at);
    const uint32_t left_end[] = {0, kColumns}, right_end[] = {kColumns - 1, 2 * kColumns - 1};
    ASSERT_EQ(cloth_attach(w.cloth, left, left_end, nullptr, 2), CLOTH_OK);
    ASSERT_EQ(cloth_attach(w.cloth, right, right_end, nullptr, 2), CLOTH_OK);

    float worst_strain = 0;
    double deepest = 0;
    for (int frame = 1; frame <= 90; ++frame) {
        const double s = std::min(1.0, frame / 10.0);  // 10 frames: ends at about 3 m/s
        const Eigen::Vector3d l(-0.3 + 0.25 * s, 0, 0.06 - 0.26 * s), r(0.3 - 0.25 * s, 0, 0.06 - 0.26 * s);
        set_pose(left, l, Eigen::Quaterniond::Identity());
        set_pose(right, r, Eigen::Quaterniond::Identity());
        ASSERT_EQ(cloth_step(w.world, kFrame), CLOTH_OK) << cloth_get_last_error();
        if (frame > 30) worst_strain = std::max(worst_strain, w.stats().max_strain);
        const std::vector<float> x = w.positions();
        for (uint32_t i = 0; i < w.n; ++i) {
            const Eigen::Vector3d p = w.at(x, i);
            deepest = std::max(deepest, radius - std::hypot(p.x(), p.z()));
        }
    }
    EXPECT_LT(deepest, 1e-3) << "a particle went into the pole";
    EXPECT_LT(worst_strain, 0.2f) << "a spring stayed stretched round the pole";
    // The strip really wraps the pole: its middle is in front of it.
    const std::vector<float> x = w.positions();
    EXPECT_GT(w.at(x, kColumns / 2).z(), 0.0) << "the strip should be caught by the pole";
}

}  // namespace
