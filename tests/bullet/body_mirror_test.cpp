// BodyMirror and the adapter's C entry points, through the public cloth API:
//   - sync() hands the cloth body the Bullet object's pose and velocities,
//     reached at the end of the next step;
//   - add() makes one collider per compound child, remove() destroys them;
//   - bad arguments get an error code and a message and create nothing;
//   - with origin shifts, attached particles 400 m from the start sit
//     within 1e-5 m of the Bullet pose times their offset;
//   - the C entry points do the same and report NULL arguments.
#include <BulletDynamics/Dynamics/btRigidBody.h>
#include <cloth/cloth.h>
#include <cloth_bullet/cloth_bullet.h>
#include <cloth_bullet/cloth_bullet_c.h>
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

namespace {

constexpr float kFrame = 1.0f / 60.0f;

struct ClothWorld {
    cloth_world_id world{};
    ClothWorld() {
        const cloth_world_desc d = cloth_default_world_desc();
        EXPECT_EQ(cloth_world_create(&d, &world), CLOTH_OK);
    }
    ~ClothWorld() { cloth_world_destroy(world); }
};

// A Bullet rigid body (never added to a Bullet world: the mirror only reads it).
struct BulletBody {
    std::unique_ptr<btCollisionShape> shape;
    std::unique_ptr<btRigidBody> body;
    explicit BulletBody(std::unique_ptr<btCollisionShape> s) : shape(std::move(s)) {
        btRigidBody::btRigidBodyConstructionInfo info(10.0f, nullptr, shape.get());
        body = std::make_unique<btRigidBody>(info);
    }
    void move(const btVector3& position, const btQuaternion& rotation, const btVector3& linear,
              const btVector3& angular) {
        body->setWorldTransform(btTransform(rotation, position));
        body->setLinearVelocity(linear);
        body->setAngularVelocity(angular);
    }
};

std::unique_ptr<btCollisionShape> box() { return std::make_unique<btBoxShape>(btVector3(1.0f, 0.5f, 2.0f)); }

TEST(BodyMirror, SyncHandsTheBodyTheObjectsPoseForTheEndOfTheNextStep) {
    ClothWorld w;
    BulletBody chassis(box());
    cloth_bullet::BodyMirror mirror(w.world);
    cloth_body_id body{};
    ASSERT_EQ(mirror.add(chassis.body.get(), 1u, &body), CLOTH_OK) << mirror.last_error();
    EXPECT_EQ(mirror.colliders(chassis.body.get()).size(), 1u) << "one box collider";

    const btQuaternion turn(btVector3(0, 1, 0), 0.4f);
    chassis.move(btVector3(3.0f, 1.0f, -2.0f), turn, btVector3(5, 0, 1), btVector3(0, 2, 0));
    ASSERT_EQ(mirror.sync(), CLOTH_OK) << mirror.last_error();
    ASSERT_EQ(cloth_step(w.world, kFrame), CLOTH_OK);
    float position[3], rotation[4];
    ASSERT_EQ(cloth_body_get_pose(body, position, rotation), CLOTH_OK);
    EXPECT_FLOAT_EQ(position[0], 3.0f);
    EXPECT_FLOAT_EQ(position[1], 1.0f);
    EXPECT_FLOAT_EQ(position[2], -2.0f);
    const float sign = rotation[3] * turn.w() < 0 ? -1.0f : 1.0f;  // q and -q are one rotation
    EXPECT_NEAR(sign * rotation[1], turn.y(), 1e-6f);
    EXPECT_NEAR(sign * rotation[3], turn.w(), 1e-6f);
}

TEST(BodyMirror, AddMakesAColliderPerCompoundChildAndRemoveDestroysThem) {
    ClothWorld w;
    auto compound = std::make_unique<btCompoundShape>();
    btBoxShape chassis_box(btVector3(1, 0.5f, 2));
    btCapsuleShape pole(0.05f, 2.0f);
    compound->addChildShape(btTransform::getIdentity(), &chassis_box);
    compound->addChildShape(btTransform(btQuaternion::getIdentity(), btVector3(0, 1.5f, -1.5f)), &pole);
    BulletBody vehicle(std::move(compound));
    cloth_bullet::BodyMirror mirror(w.world);
    cloth_body_id body{};
    ASSERT_EQ(mirror.add(vehicle.body.get(), 1u, &body), CLOTH_OK) << mirror.last_error();
    const std::vector<cloth_collider_id> colliders = mirror.colliders(vehicle.body.get());
    ASSERT_EQ(colliders.size(), 2u) << "a box and a capsule";
    for (const cloth_collider_id& c : colliders) EXPECT_EQ(cloth_collider_set_group_bits(c, 1u), CLOTH_OK);

    ASSERT_EQ(mirror.remove(vehicle.body.get()), CLOTH_OK);
    for (const cloth_collider_id& c : colliders) {
        EXPECT_EQ(cloth_collider_set_group_bits(c, 1u), CLOTH_ERROR_INVALID_HANDLE)
            << "a collider outlived remove()";
    }
    const float still[3] = {0, 0, 0};
    EXPECT_EQ(cloth_body_set_velocity(body, still, still), CLOTH_ERROR_INVALID_HANDLE)
        << "the body outlived remove()";
    EXPECT_TRUE(mirror.colliders(vehicle.body.get()).empty());
}

TEST(BodyMirror, BadArgumentsGetACodeAndAMessageAndCreateNothing) {
    ClothWorld w;
    cloth_bullet::BodyMirror mirror(w.world);
    BulletBody chassis(box());
    BulletBody cone(std::make_unique<btConeShape>(0.5f, 1.0f));
    cloth_body_id body{};

    EXPECT_EQ(mirror.add(nullptr, 1u, &body), CLOTH_ERROR_NULL_POINTER);
    EXPECT_EQ(mirror.add(chassis.body.get(), 1u, nullptr), CLOTH_ERROR_NULL_POINTER);
    EXPECT_EQ(mirror.add(cone.body.get(), 1u, &body), CLOTH_ERROR_INVALID_VALUE);
    EXPECT_NE(mirror.last_error().find("Cone"), std::string::npos) << mirror.last_error();
    EXPECT_EQ(mirror.body(cone.body.get()).index1, 0) << "a rejected add() left a body";
    EXPECT_EQ(mirror.remove(chassis.body.get()), CLOTH_ERROR_INVALID_VALUE);
    EXPECT_EQ(mirror.teleport(chassis.body.get()), CLOTH_ERROR_INVALID_VALUE);

    ASSERT_EQ(mirror.add(chassis.body.get(), 1u, &body), CLOTH_OK);
    cloth_body_id again{};
    EXPECT_EQ(mirror.add(chassis.body.get(), 1u, &again), CLOTH_ERROR_INVALID_VALUE) << "mirrored twice";
    EXPECT_EQ(again.index1, 0);

    const float nan = std::nanf("");
    EXPECT_EQ(mirror.shift_origin(btVector3(nan, 0, 0)), CLOTH_ERROR_NOT_FINITE);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(mirror.origin()[k], 0.0) << "a rejected shift moved the origin";
}

// A 6x4 flag whose pole-side column rides on a box driving 400 m along z at
// 30 m/s; the host shifts the origin in 32 m steps. Returns the largest
// distance (in Bullet's frame, double) of an attached particle from the
// Bullet pose times its offset.
double drive_far(bool rebase) {
    ClothWorld w;
    BulletBody chassis(box());
    chassis.move(btVector3(0, 1, 0), btQuaternion::getIdentity(), btVector3(0, 0, 30), btVector3(0, 0, 0));
    cloth_bullet::BodyMirror mirror(w.world);
    cloth_body_id body{};
    EXPECT_EQ(mirror.add(chassis.body.get(), 1u, &body), CLOTH_OK) << mirror.last_error();

    cloth_grid_desc g = cloth_default_grid_desc();
    g.columns = 6;
    g.rows = 4;
    g.origin[1] = 3.0f;
    g.origin[2] = -2.5f;
    g.u[2] = -1.0f;
    g.v[1] = -0.6f;
    cloth_fabric_id fabric{};
    EXPECT_EQ(cloth_fabric_create_grid(w.world, &g, &fabric), CLOTH_OK);
    cloth_desc cd = cloth_default_desc();
    cd.fabric = fabric;
    cloth_id cloth{};
    EXPECT_EQ(cloth_create(w.world, &cd, &cloth), CLOTH_OK) << cloth_get_last_error();
    const uint32_t column[] = {0, 6, 12, 18};
    std::vector<btVector3> offsets;
    std::vector<float> flat;
    for (int r = 0; r < 4; ++r) {
        offsets.emplace_back(0.0f, 2.0f - 0.2f * r, -2.5f);
        flat.insert(flat.end(), {offsets.back().x(), offsets.back().y(), offsets.back().z()});
    }
    EXPECT_EQ(cloth_attach(cloth, body, column, flat.data(), 4), CLOTH_OK);

    double worst = 0;
    std::vector<float> x(3 * 24);
    for (int frame = 1; frame <= 800; ++frame) {
        const float t = frame * kFrame;
        chassis.move(btVector3(std::sin(t), 1.0f, 30.0f * t),
                     btQuaternion(btVector3(0, 1, 0), 0.2f * std::sin(t)), btVector3(std::cos(t), 0, 30),
                     btVector3(0, 0.2f * std::cos(t), 0));
        const btVector3& p = chassis.body->getWorldTransform().getOrigin();
        const double* o = mirror.origin();
        if (rebase && std::abs(p.z() - o[2]) > 32.0) {
            const float shift = static_cast<float>(std::round(p.z() / 32.0) * 32.0 - o[2]);
            EXPECT_EQ(mirror.shift_origin(btVector3(0, 0, shift)), CLOTH_OK) << mirror.last_error();
        }
        EXPECT_EQ(mirror.sync(), CLOTH_OK);
        EXPECT_EQ(cloth_step(w.world, kFrame), CLOTH_OK) << cloth_get_last_error();
        EXPECT_EQ(cloth_read_positions(cloth, x.data(), 3 * 24), CLOTH_OK);
        const btTransform& pose = chassis.body->getWorldTransform();
        // The target in double from Bullet's float pose (Bullet's own float
        // product would round to 3e-5 m out here).
        for (int r = 0; r < 4; ++r) {
            double d2 = 0;
            for (int k = 0; k < 3; ++k) {
                const btVector3& row = pose.getBasis()[k];
                double target = pose.getOrigin()[k];
                for (int j = 0; j < 3; ++j) target += double{row[j]} * double{offsets[r][j]};
                const double d = double{x[3 * column[r] + k]} + mirror.origin()[k] - target;
                d2 += d * d;
            }
            worst = std::max(worst, std::sqrt(d2));
        }
    }
    return worst;
}

TEST(BodyMirror, WithOriginShiftsAttachmentsFarFromTheStartStayWithin1e5mOfTheBulletPose) {
    EXPECT_LT(drive_far(true), 1e-5);
    // The control: 400 m out a float coordinate steps by 3e-5 m.
    EXPECT_GT(drive_far(false), 1e-5) << "the drive no longer reaches the float limit shifts remove";
}

TEST(BulletCApi, EntryPointsWorkEndToEndAndReportNullArguments) {
    ClothWorld w;
    BulletBody chassis(box());
    chassis.move(btVector3(40, 0, 0), btQuaternion::getIdentity(), btVector3(0, 0, 0), btVector3(0, 0, 0));

    EXPECT_EQ(cloth_bullet_mirror_create(w.world, nullptr), CLOTH_ERROR_NULL_POINTER);
    EXPECT_STRNE(cloth_bullet_get_last_error(), "");
    cloth_bullet_mirror* mirror = nullptr;
    ASSERT_EQ(cloth_bullet_mirror_create(w.world, &mirror), CLOTH_OK);
    EXPECT_EQ(cloth_bullet_mirror_add(nullptr, chassis.body.get(), 1u, nullptr), CLOTH_ERROR_NULL_POINTER);
    cloth_body_id body{};
    ASSERT_EQ(cloth_bullet_mirror_add(mirror, chassis.body.get(), 1u, &body), CLOTH_OK);
    EXPECT_EQ(cloth_bullet_mirror_add(mirror, chassis.body.get(), 1u, &body), CLOTH_ERROR_INVALID_VALUE);
    EXPECT_NE(std::string(cloth_bullet_get_last_error()).find("already"), std::string::npos);

    const float shift[3] = {32.0f, 0.0f, 0.0f};
    EXPECT_EQ(cloth_bullet_mirror_shift_origin(mirror, nullptr), CLOTH_ERROR_NULL_POINTER);
    EXPECT_EQ(cloth_bullet_mirror_shift_origin(nullptr, shift), CLOTH_ERROR_NULL_POINTER);
    ASSERT_EQ(cloth_bullet_mirror_shift_origin(mirror, shift), CLOTH_OK);
    double origin[3];
    EXPECT_EQ(cloth_bullet_mirror_get_origin(mirror, nullptr), CLOTH_ERROR_NULL_POINTER);
    ASSERT_EQ(cloth_bullet_mirror_get_origin(mirror, origin), CLOTH_OK);
    EXPECT_EQ(origin[0], 32.0);

    // The body, at 40 m in Bullet, sits at 8 m in the shifted cloth world.
    EXPECT_EQ(cloth_bullet_mirror_sync(nullptr), CLOTH_ERROR_NULL_POINTER);
    ASSERT_EQ(cloth_bullet_mirror_sync(mirror), CLOTH_OK);
    ASSERT_EQ(cloth_step(w.world, kFrame), CLOTH_OK);
    float position[3], rotation[4];
    ASSERT_EQ(cloth_body_get_pose(body, position, rotation), CLOTH_OK);
    EXPECT_FLOAT_EQ(position[0], 8.0f);
    chassis.move(btVector3(-100, 0, 0), btQuaternion::getIdentity(), btVector3(0, 0, 0), btVector3(0, 0, 0));
    EXPECT_EQ(cloth_bullet_mirror_teleport(nullptr, chassis.body.get()), CLOTH_ERROR_NULL_POINTER);
    ASSERT_EQ(cloth_bullet_mirror_teleport(mirror, chassis.body.get()), CLOTH_OK);
    ASSERT_EQ(cloth_body_get_pose(body, position, rotation), CLOTH_OK);
    EXPECT_FLOAT_EQ(position[0], -132.0f);

    // Colliders for a shape: too small a capacity creates nothing and tells the count.
    btCompoundShape compound;
    btSphereShape ball(0.5f);
    compound.addChildShape(btTransform::getIdentity(), &ball);
    compound.addChildShape(btTransform(btQuaternion::getIdentity(), btVector3(0, 1, 0)), &ball);
    cloth_collider_id colliders[2];
    uint32_t count = 0;
    EXPECT_EQ(cloth_bullet_create_colliders(w.world, nullptr, cloth_body_id{}, nullptr, nullptr, 1u,
                                            colliders, 2, &count),
              CLOTH_ERROR_NULL_POINTER);
    EXPECT_EQ(
        cloth_bullet_create_colliders(w.world, &compound, body, nullptr, nullptr, 1u, colliders, 1, &count),
        CLOTH_ERROR_INVALID_COUNT);
    EXPECT_EQ(count, 2u);
    ASSERT_EQ(
        cloth_bullet_create_colliders(w.world, &compound, body, nullptr, nullptr, 1u, colliders, 2, &count),
        CLOTH_OK);
    EXPECT_EQ(count, 2u);
    for (const cloth_collider_id& c : colliders) EXPECT_EQ(cloth_collider_set_group_bits(c, 2u), CLOTH_OK);

    EXPECT_EQ(cloth_bullet_mirror_remove(nullptr, chassis.body.get()), CLOTH_ERROR_NULL_POINTER);
    ASSERT_EQ(cloth_bullet_mirror_remove(mirror, chassis.body.get()), CLOTH_OK);
    for (const cloth_collider_id& c : colliders) {
        EXPECT_EQ(cloth_collider_set_group_bits(c, 2u), CLOTH_ERROR_INVALID_HANDLE)
            << "colliders fixed to a removed body outlived it";
    }
    cloth_bullet_mirror_destroy(mirror);
    cloth_bullet_mirror_destroy(nullptr);
}

}  // namespace
