// The vehicle_flag course itself, without cloth: the terrain the checks use
// is the terrain Bullet collides with, the penetration counts find what they
// should, and the scripted driver really drives the course (docs/vehicle_flag.md).
#include "course.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "course_checks.h"
#include "terrain.h"
#include "vehicle_world.h"

namespace vehicle_flag {
namespace {

// The sample's terrain check reads Terrain::height_at; it must be the surface
// Bullet's heightfield has (same samples, same triangle split).
TEST(CourseTerrain, HeightMatchesBulletRayCasts) {
    const Terrain terrain;
    VehicleWorld vehicle(terrain);
    btTransform away = btTransform::getIdentity();
    away.setOrigin(btVector3(0, 50, 0));  // keep the chassis out of the rays
    vehicle.teleport(away);
    std::mt19937 random(7);
    const TerrainLayout& t = terrain.layout();
    std::uniform_real_distribution<float> x(t.min_x + 0.1f, t.min_x + (t.columns - 1) * t.cell - 0.1f);
    std::uniform_real_distribution<float> z(t.min_z + 0.1f, t.min_z + (t.rows - 1) * t.cell - 0.1f);
    for (int i = 0; i < 500; ++i) {
        // Half the points on the kicker, where the slope is steepest.
        const float px = x(random),
                    pz = i % 2 ? z(random) : t.ramp_start_z + t.ramp_length * (i % 97) / 96.0f;
        const btVector3 from(px, 10, pz), to(px, -10, pz);
        btCollisionWorld::ClosestRayResultCallback hit(from, to);
        vehicle.dynamics_world()->rayTest(from, to, hit);
        ASSERT_TRUE(hit.hasHit()) << px << ", " << pz;
        EXPECT_NEAR(hit.m_hitPointWorld.y(), terrain.height_at(px, pz), 2e-4f) << px << ", " << pz;
    }
}

TEST(CourseChecks, CountsPointsInsideEachShapeAndNothingOutside) {
    const Terrain terrain;
    const VehicleLayout v;
    btTransform pose = btTransform::getIdentity();
    pose.setOrigin(btVector3(1.0f, 0.5f, 20.0f));
    pose.setRotation(btQuaternion(btVector3(0, 1, 0), 0.7f));
    const float tolerance = 1e-3f;
    const btVector3 box_center(v.box_center[0], v.box_center[1], v.box_center[2]);
    const btVector3 pole_mid(v.pole_base[0], v.pole_base[1] + 0.5f * v.pole_height, v.pole_base[2]);
    const btVector3 points[] = {
        pose * (box_center + btVector3(0.5f * v.box_half_extents[0], 0, 0)),   // inside the box
        pose * (pole_mid + btVector3(0.5f * v.pole_radius, 0, 0)),             // inside the pole
        btVector3(-5.0f, terrain.height_at(-5.0f, 40.0f) - 0.05f, 40.0f),      // under the terrain
        pose * (box_center + btVector3(0, v.box_half_extents[1] + 0.01f, 0)),  // above the roof
        pose * (pole_mid + btVector3(v.pole_radius + 0.01f, 0, 0)),            // beside the pole
        btVector3(-5.0f, terrain.height_at(-5.0f, 40.0f) + 0.01f, 40.0f),      // on the terrain
    };
    std::vector<float> positions;
    for (const btVector3& p : points) positions.insert(positions.end(), {p.x(), p.y(), p.z()});
    std::vector<bool> skip(6, false);
    const Penetrations found = count_penetrations(positions, skip, pose, v, terrain, tolerance);
    EXPECT_EQ(found.chassis, 1);
    EXPECT_EQ(found.pole, 1);
    EXPECT_EQ(found.terrain, 1);
    // Deepest: the box point, whose nearest face is the roof (0.4 m above the centre).
    EXPECT_NEAR(found.deepest, std::min(0.5f * v.box_half_extents[0], v.box_half_extents[1]), 1e-4f);
    skip[0] = skip[1] = skip[2] = true;
    EXPECT_EQ(count_penetrations(positions, skip, pose, v, terrain, tolerance).total(), 0);
}

// One spring (a 2 x 1 flag) near the pole: it counts when it crosses the
// pole from one side to the other, not when it wraps it as a chord just
// outside its surface, nor when it runs up beside it.
TEST(CourseChecks, CountsSpringsThroughThePoleAndNotThoseWrappedRoundIt) {
    const VehicleLayout v;
    btTransform pose = btTransform::getIdentity();
    pose.setOrigin(btVector3(3.0f, 0.2f, -7.0f));
    pose.setRotation(btQuaternion(btVector3(0, 1, 0), -1.1f));
    const btVector3 base(v.pole_base[0], v.pole_base[1], v.pole_base[2]);
    const float r = v.pole_radius + 0.002f, y = 1.0f;
    const float a = 0.6981317f;  // 40 degrees
    auto count = [&](const btVector3& p, const btVector3& q, uint32_t columns, uint32_t rows) {
        std::vector<float> positions;
        for (const btVector3& local : {p, q}) {
            const btVector3 w = pose * (base + local);
            positions.insert(positions.end(), {w.x(), w.y(), w.z()});
        }
        return count_springs_through_pole(positions, columns, rows, pose, v);
    };
    EXPECT_EQ(count(btVector3(r, y, 0), btVector3(-r, y + 0.01f, 0), 2, 1), 1) << "across the pole";
    EXPECT_EQ(count(btVector3(r, y, 0), btVector3(r * std::cos(a), y, r * std::sin(a)), 2, 1), 0)
        << "a chord round the pole";
    EXPECT_EQ(count(btVector3(r, y, 0), btVector3(r, y + 0.02f, 0), 1, 2), 0) << "up beside the pole";
}

// The whole course: 30 m/s, a slalom, a hard brake, a jump, one teleport.
TEST(CourseDriver, DrivesTheWholeCourse) {
    const Terrain terrain;
    VehicleWorld vehicle(terrain);
    CourseDriver driver(terrain.layout().ramp_start_z);
    const float dt = 1.0f / 60.0f;
    bool seen[static_cast<int>(Phase::kDone) + 1] = {};
    float slowest_after_brake = 1e9f, lateral_swing = 0.0f;
    int frame = 0;
    for (; frame < 4000 && !driver.done(); ++frame) {
        const Controls c = driver.drive(frame * dt, vehicle);
        if (c.teleport) vehicle.teleport(vehicle.start_pose());
        vehicle.set_controls(c.engine, c.brake, c.steering);
        vehicle.step(dt);
        seen[static_cast<int>(driver.phase())] = true;
        if (driver.phase() == Phase::kSlalom) {
            lateral_swing = std::max(lateral_swing, std::fabs(vehicle.chassis_angular_velocity().y()));
        }
        if (driver.phase() == Phase::kToRamp)
            slowest_after_brake = std::min(slowest_after_brake, vehicle.forward_speed());
        // The vehicle stays upright and on the terrain all along.
        ASSERT_GT(vehicle.chassis_pose().getBasis().getColumn(1).y(), 0.8f) << "frame " << frame;
        ASSERT_GT(vehicle.chassis_pose().getOrigin().y(), -1.0f) << "frame " << frame;
    }
    EXPECT_TRUE(driver.done()) << "stuck in " << phase_name(driver.phase());
    for (int p = 0; p <= static_cast<int>(Phase::kDone); ++p)
        EXPECT_TRUE(seen[p]) << phase_name(static_cast<Phase>(p));
    EXPECT_GE(driver.top_speed(), 29.5f);
    EXPECT_GT(lateral_swing, 0.1f);  // rad/s of yaw: the slalom really turns
    EXPECT_LT(slowest_after_brake, 1.0f);
    EXPECT_GT(driver.longest_airtime(), 0.3f);
    EXPECT_EQ(driver.teleports(), 1);
    EXPECT_LT(vehicle.chassis_pose().getOrigin().z(), 60.0f);  // back near the start after the teleport
}

}  // namespace
}  // namespace vehicle_flag
