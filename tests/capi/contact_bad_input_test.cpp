// Bad body, collider, attachment and carrier input is rejected with its code and changes nothing.
//
// The checks every rejected call gets are those of support/contract.h (its
// code, the last error, the log, and nothing changed: the cloth's whole
// state with its attachments, collision settings and teleport flag, the
// body's pose, the world's memory); at the end of each test the world and
// an identical twin are stepped together with the same body poses and must
// stay bit-identical (a collider half created or a pose a failed call
// changed shows up there).
#include <cloth/cloth.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "support/contract.h"
#include "support/contract_gtest.h"
#include "support/counting_allocator.h"

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kFrame = 1.0f / 60.0f;
constexpr uint32_t kColumns = 6, kRows = 6, kParticles = kColumns * kRows;

struct Scene {
    cloth_test::CountingAllocator host;
    cloth_world_id world{};
    cloth_fabric_id fabric{};
    cloth_id cloth{};
    cloth_body_id body{};   // carries the cloth; two corners attached to it; a sphere fixed to it
    cloth_body_id spare{};  // a body with nothing on it
    cloth_body_id stale_body{};
    cloth_collider_id sphere{}, ground{}, stale_collider{};
    cloth_test::Watch watch;  // the cloth, the carrying body, the allocator
};

class ContactBadInput : public ::testing::Test {
  protected:
    void SetUp() override {
        Build(a_);
        Build(b_);
    }

    void TearDown() override {
        // The body moves, so that attachments, the carrier and the sphere all act.
        EXPECT_TRUE(cloth_test::SameFutureAsTwin(a_.watch, b_.watch, 4, [&](int frame) {
            const float p[3] = {0.1f * static_cast<float>(frame), 0.0f, 0.0f}, q[4] = {0, 0, 0, 1};
            EXPECT_EQ(cloth_body_set_pose(a_.body, p, q), CLOTH_OK);
            EXPECT_EQ(cloth_body_set_pose(b_.body, p, q), CLOTH_OK);
        }));
        for (Scene* s : {&a_, &b_}) {
            EXPECT_EQ(cloth_world_destroy(s->world), CLOTH_OK);
            cloth_test::ExpectAllReturned(s->host);
        }
    }

    static void Build(Scene& s) {
        const cloth_world_desc wd = s.host.world_desc();
        ASSERT_EQ(cloth_world_create(&wd, &s.world), CLOTH_OK);
        cloth_grid_desc grid = cloth_default_grid_desc();
        grid.columns = kColumns;
        grid.rows = kRows;
        ASSERT_EQ(cloth_fabric_create_grid(s.world, &grid, &s.fabric), CLOTH_OK);
        cloth_desc cd = cloth_default_desc();
        cd.fabric = s.fabric;
        ASSERT_EQ(cloth_create(s.world, &cd, &s.cloth), CLOTH_OK);
        const cloth_body_desc bd = cloth_default_body_desc();
        ASSERT_EQ(cloth_body_create(s.world, &bd, &s.stale_body), CLOTH_OK);
        ASSERT_EQ(cloth_body_destroy(s.stale_body), CLOTH_OK);
        ASSERT_EQ(cloth_body_create(s.world, &bd, &s.body), CLOTH_OK);
        ASSERT_EQ(cloth_body_create(s.world, &bd, &s.spare), CLOTH_OK);
        const uint32_t corners[] = {0, kColumns - 1};
        ASSERT_EQ(cloth_attach(s.cloth, s.body, corners, nullptr, 2), CLOTH_OK);
        cloth_collider_desc c = cloth_default_collider_desc();
        c.body = s.body;
        c.local_position[1] = -0.5f;
        c.local_position[2] = 0.3f;
        ASSERT_EQ(cloth_collider_create_sphere(s.world, &c, 0.2f, &s.stale_collider), CLOTH_OK);
        ASSERT_EQ(cloth_collider_destroy(s.stale_collider), CLOTH_OK);
        ASSERT_EQ(cloth_collider_create_sphere(s.world, &c, 0.2f, &s.sphere), CLOTH_OK);
        const float up[3] = {0, 1, 0};
        const cloth_collider_desc g = cloth_default_collider_desc();
        ASSERT_EQ(cloth_collider_create_plane(s.world, &g, up, -2.0f, &s.ground), CLOTH_OK);
        cloth_carrier_desc carrier = cloth_default_carrier_desc();
        carrier.linear_inertia = 0.5f;
        ASSERT_EQ(cloth_set_carrier(s.cloth, s.body, &carrier), CLOTH_OK);
        for (int i = 0; i < 3; ++i)
            ASSERT_EQ(cloth_step(s.world, kFrame), CLOTH_OK) << cloth_get_last_error();
        s.host.clear_logs();
        s.watch.world = s.world;
        s.watch.cloths = {s.cloth};
        s.watch.bodies = {s.body};
        s.watch.memory = &s.host;
    }

    // See EXPECT_REJECTED (support/contract_gtest.h). A bad handle may name
    // no live world, so its error may reach no log.
    void ExpectRejected(cloth_result expected, const std::string& what,
                        const std::function<cloth_result()>& call, cloth_test::Logged logged) {
        if (expected == CLOTH_ERROR_INVALID_HANDLE) logged = cloth_test::Logged::kMaybe;
        cloth_test::ExpectRejected(a_.watch, a_.host, expected, what, call, logged);
    }

    Scene a_, b_;
};

const float kOrigin[3] = {0, 0, 0};
const float kIdentity[4] = {0, 0, 0, 1};

TEST_F(ContactBadInput, BodyCallsRejectBadHandlesPosesAndDescriptions) {
    cloth_body_id out{};
    cloth_body_desc d = cloth_default_body_desc();
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_body_create(a_.world, nullptr, &out));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_body_create(a_.world, &d, nullptr));
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_HANDLE, cloth_body_create(cloth_world_id{}, &d, &out));
    cloth_body_desc raw{};
    raw.struct_size = sizeof raw;
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_DESC, cloth_body_create(a_.world, &raw, &out));
    d.struct_size = 4;
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_DESC, cloth_body_create(a_.world, &d, &out));
    d = cloth_default_body_desc();
    d.position[1] = kNaN;
    EXPECT_REJECTED(CLOTH_ERROR_NOT_FINITE, cloth_body_create(a_.world, &d, &out));
    d = cloth_default_body_desc();
    d.rotation[3] = 2.0f;  // not unit length
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_VALUE, cloth_body_create(a_.world, &d, &out));
    d = cloth_default_body_desc();
    d.angular_velocity[2] = kInf;
    EXPECT_REJECTED(CLOTH_ERROR_NOT_FINITE, cloth_body_create(a_.world, &d, &out));

    const float nan3[3] = {0, kNaN, 0};
    const float zero_q[4] = {0, 0, 0, 0};
    const float inf_q[4] = {0, 0, kInf, 1};
    for (auto set : {cloth_body_set_pose, cloth_body_teleport}) {
        EXPECT_REJECTED(CLOTH_ERROR_INVALID_HANDLE, set(a_.stale_body, kOrigin, kIdentity));
        EXPECT_REJECTED(CLOTH_ERROR_INVALID_HANDLE, set(cloth_body_id{}, kOrigin, kIdentity));
        EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, set(a_.body, nullptr, kIdentity));
        EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, set(a_.body, kOrigin, nullptr));
        EXPECT_REJECTED(CLOTH_ERROR_NOT_FINITE, set(a_.body, nan3, kIdentity));
        EXPECT_REJECTED(CLOTH_ERROR_INVALID_VALUE, set(a_.body, kOrigin, zero_q));
        EXPECT_REJECTED(CLOTH_ERROR_NOT_FINITE, set(a_.body, kOrigin, inf_q));
    }
    EXPECT_REJECTED(CLOTH_ERROR_NOT_FINITE, cloth_body_set_velocity(a_.body, nan3, kOrigin));
    EXPECT_REJECTED(CLOTH_ERROR_NOT_FINITE, cloth_body_set_velocity(a_.body, kOrigin, nan3));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_body_set_velocity(a_.body, nullptr, kOrigin));
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_HANDLE, cloth_body_set_velocity(a_.stale_body, kOrigin, kOrigin));
    float p[3], q[4];
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_body_get_pose(a_.body, nullptr, q));
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_HANDLE, cloth_body_get_pose(a_.stale_body, p, q));
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_HANDLE, cloth_body_destroy(a_.stale_body));
    // A body of another world is not this world's body.
    cloth_body_id foreign = b_.body;
    foreign.world1 = a_.body.world1;
    foreign.world_generation = static_cast<uint16_t>(a_.body.world_generation + 1);
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_HANDLE, cloth_body_set_pose(foreign, kOrigin, kIdentity));
}

// The batch call checks every entry before it moves any body: entry 0 is
// the watched body with a new pose, a later entry is bad, and the watched
// body keeps its pose.
TEST_F(ContactBadInput, BodyPosesInOneCallRejectABadEntryAndMoveNoBody) {
    const float moved[3] = {0.5f, 0.0f, 0.0f};
    const auto poses = [&](const cloth_body_id(&ids)[2], const float(&p)[6], const float(&q)[8],
                           uint32_t count) { return cloth_world_set_body_poses(a_.world, ids, p, q, count); };
    const cloth_body_id good[2] = {a_.body, a_.spare};
    const float p_ok[6] = {moved[0], moved[1], moved[2], 0, 0, 0};
    const float q_ok[8] = {0, 0, 0, 1, 0, 0, 0, 1};
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_world_set_body_poses(a_.world, nullptr, p_ok, q_ok, 2));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_world_set_body_poses(a_.world, good, nullptr, q_ok, 2));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_world_set_body_poses(a_.world, good, p_ok, nullptr, 2));
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_COUNT, poses(good, p_ok, q_ok, 0));
    EXPECT_REJECTED_NOT_LOGGED(CLOTH_ERROR_INVALID_HANDLE,
                               cloth_world_set_body_poses(cloth_world_id{}, good, p_ok, q_ok, 2));
    const cloth_body_id stale[2] = {a_.body, a_.stale_body};
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_HANDLE, poses(stale, p_ok, q_ok, 2));
    const cloth_body_id foreign[2] = {a_.body, b_.spare};
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_HANDLE, poses(foreign, p_ok, q_ok, 2));
    const float p_nan[6] = {moved[0], moved[1], moved[2], 0, kNaN, 0};
    EXPECT_REJECTED(CLOTH_ERROR_NOT_FINITE, poses(good, p_nan, q_ok, 2));
    const float q_long[8] = {0, 0, 0, 1, 1, 0, 0, 1};
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_VALUE, poses(good, p_ok, q_long, 2));
    ASSERT_EQ(poses(good, p_ok, q_long, 2), CLOTH_ERROR_INVALID_VALUE);
    const std::string message = cloth_get_last_error();
    EXPECT_NE(message.find("entry 1"), std::string::npos) << message;
    EXPECT_NE(message.find("rotations_xyzw"), std::string::npos) << message;
}

TEST_F(ContactBadInput, ColliderCreationRejectsBadShapesAndChangesNothing) {
    cloth_collider_id out{};
    const cloth_collider_desc d = cloth_default_collider_desc();
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_collider_create_sphere(a_.world, nullptr, 1.0f, &out));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_collider_create_sphere(a_.world, &d, 1.0f, nullptr));
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_HANDLE,
                    cloth_collider_create_sphere(cloth_world_id{}, &d, 1.0f, &out));
    cloth_collider_desc raw{};
    raw.struct_size = sizeof raw;
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_DESC, cloth_collider_create_sphere(a_.world, &raw, 1.0f, &out));
    cloth_collider_desc bad = d;
    bad.local_rotation[0] = 1.0f;  // (1, 0, 0, 1): length sqrt 2
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_VALUE, cloth_collider_create_sphere(a_.world, &bad, 1.0f, &out));
    bad = d;
    bad.local_position[0] = kNaN;
    EXPECT_REJECTED(CLOTH_ERROR_NOT_FINITE, cloth_collider_create_sphere(a_.world, &bad, 1.0f, &out));
    bad = d;
    bad.body = a_.stale_body;
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_HANDLE, cloth_collider_create_sphere(a_.world, &bad, 1.0f, &out));
    bad.body = b_.body;  // another world's body
    bad.body.world_generation = static_cast<uint16_t>(bad.body.world_generation + 7);
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_HANDLE, cloth_collider_create_sphere(a_.world, &bad, 1.0f, &out));

    EXPECT_REJECTED(CLOTH_ERROR_INVALID_VALUE, cloth_collider_create_sphere(a_.world, &d, 0.0f, &out));
    EXPECT_REJECTED(CLOTH_ERROR_NOT_FINITE, cloth_collider_create_sphere(a_.world, &d, kNaN, &out));
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_VALUE,
                    cloth_collider_create_capsule(a_.world, &d, -1.0f, 1.0f, &out));
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_VALUE,
                    cloth_collider_create_capsule(a_.world, &d, 1.0f, -1.0f, &out));
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_VALUE,
                    cloth_collider_create_tapered_capsule(a_.world, &d, 0.0f, 0.1f, 1.0f, &out));
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_VALUE,
                    cloth_collider_create_tapered_capsule(a_.world, &d, 0.1f, 0.2f, -1.0f, &out));
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_VALUE,  // the bottom sphere holds the top one: a sphere
                    cloth_collider_create_tapered_capsule(a_.world, &d, 0.5f, 0.1f, 0.1f, &out));
    EXPECT_REJECTED(CLOTH_ERROR_NOT_FINITE,
                    cloth_collider_create_tapered_capsule(a_.world, &d, 0.1f, kNaN, 1.0f, &out));
    const float flat[3] = {1, 0, 1}, nan_box[3] = {1, kNaN, 1};
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_VALUE, cloth_collider_create_box(a_.world, &d, flat, &out));
    EXPECT_REJECTED(CLOTH_ERROR_NOT_FINITE, cloth_collider_create_box(a_.world, &d, nan_box, &out));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_collider_create_box(a_.world, &d, nullptr, &out));
    const float zero[3] = {0, 0, 0}, up[3] = {0, 1, 0};
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_VALUE, cloth_collider_create_plane(a_.world, &d, zero, 0.0f, &out));
    EXPECT_REJECTED(CLOTH_ERROR_NOT_FINITE, cloth_collider_create_plane(a_.world, &d, up, kInf, &out));

    const float square[] = {0, 0, 0, 1, 0, 0, 1, 0, 1, 0, 0, 1, 0.5f, 0, 0.5f};  // all in y = 0
    const float tetra[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, kNaN};
    EXPECT_REJECTED(CLOTH_ERROR_DEGENERATE_GEOMETRY,
                    cloth_collider_create_convex_hull(a_.world, &d, square, 5, &out));
    EXPECT_REJECTED(CLOTH_ERROR_NOT_FINITE, cloth_collider_create_convex_hull(a_.world, &d, tetra, 4, &out));
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_COUNT,
                    cloth_collider_create_convex_hull(a_.world, &d, square, 3, &out));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER,
                    cloth_collider_create_convex_hull(a_.world, &d, nullptr, 4, &out));

    const uint32_t tri[] = {0, 1, 2}, bad_tri[] = {0, 1, 7}, sliver[] = {0, 0, 1};
    EXPECT_REJECTED(CLOTH_ERROR_INDEX_OUT_OF_RANGE,
                    cloth_collider_create_triangle_mesh(a_.world, &d, square, 5, bad_tri, 1, &out));
    EXPECT_REJECTED(CLOTH_ERROR_DEGENERATE_GEOMETRY,
                    cloth_collider_create_triangle_mesh(a_.world, &d, square, 5, sliver, 1, &out));
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_COUNT,
                    cloth_collider_create_triangle_mesh(a_.world, &d, square, 5, tri, 0, &out));
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_COUNT,
                    cloth_collider_create_triangle_mesh(a_.world, &d, square, 2, tri, 1, &out));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER,
                    cloth_collider_create_triangle_mesh(a_.world, &d, square, 5, nullptr, 1, &out));
    EXPECT_REJECTED(CLOTH_ERROR_NOT_FINITE,
                    cloth_collider_create_triangle_mesh(a_.world, &d, tetra, 4, tri, 1, &out));
    // Finite vertices 6.8e38 apart: their span is not a float.
    const float huge = std::numeric_limits<float>::max();
    const float spread[] = {0, 0, 0, 1, 0, 0, 0, 0, 1, -huge, 0, 0, huge, 0, 0};
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_VALUE,
                    cloth_collider_create_triangle_mesh(a_.world, &d, spread, 5, tri, 1, &out));

    const float heights[6] = {0, 0, 0, 0, 0, kNaN};
    cloth_heightfield_desc h = cloth_default_heightfield_desc();
    h.columns = 3;
    h.rows = 2;
    h.heights = heights;
    EXPECT_REJECTED(CLOTH_ERROR_NOT_FINITE, cloth_collider_create_heightfield(a_.world, &d, &h, &out));
    h.heights = nullptr;
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_collider_create_heightfield(a_.world, &d, &h, &out));
    h.heights = heights;
    h.rows = 1;
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_COUNT, cloth_collider_create_heightfield(a_.world, &d, &h, &out));
    h.rows = 2;
    const float level[6] = {0, 0, 0, 0, 0, 0};  // one fault at a time: a NaN height is reported first
    h.heights = level;
    h.spacing_z = 0.0f;
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_VALUE, cloth_collider_create_heightfield(a_.world, &d, &h, &out));
    cloth_heightfield_desc raw_h{};
    raw_h.struct_size = sizeof raw_h;
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_DESC, cloth_collider_create_heightfield(a_.world, &d, &raw_h, &out));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_collider_create_heightfield(a_.world, &d, nullptr, &out));

    EXPECT_REJECTED(CLOTH_ERROR_INVALID_HANDLE, cloth_collider_destroy(a_.stale_collider));
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_HANDLE, cloth_collider_set_group_bits(a_.stale_collider, 2));
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_HANDLE, cloth_collider_destroy(cloth_collider_id{}));
}

TEST_F(ContactBadInput, CollisionAttachAndCarrierCallsRejectBadInput) {
    cloth_collision_params p = cloth_default_collision_params();
    p.thickness = -0.1f;
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_VALUE, cloth_set_collision(a_.cloth, &p));
    p = cloth_default_collision_params();
    p.friction = kNaN;
    EXPECT_REJECTED(CLOTH_ERROR_NOT_FINITE, cloth_set_collision(a_.cloth, &p));
    p = cloth_default_collision_params();
    p.struct_size = 3;
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_DESC, cloth_set_collision(a_.cloth, &p));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_set_collision(a_.cloth, nullptr));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_get_collision(a_.cloth, nullptr));
    p = cloth_default_collision_params();
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_HANDLE, cloth_set_collision(cloth_id{}, &p));

    const uint32_t good[] = {1, 2}, out_of_range[] = {1, kParticles};
    const float offsets[] = {0, 0, 0, 0, 0, 0}, nan_offsets[] = {0, 0, 0, kNaN, 0, 0};
    EXPECT_REJECTED(CLOTH_ERROR_INDEX_OUT_OF_RANGE,
                    cloth_attach(a_.cloth, a_.spare, out_of_range, offsets, 2));
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_COUNT, cloth_attach(a_.cloth, a_.spare, good, offsets, 0));
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_COUNT,
                    cloth_attach(a_.cloth, a_.spare, good, offsets, kParticles + 1));
    EXPECT_REJECTED(CLOTH_ERROR_NOT_FINITE, cloth_attach(a_.cloth, a_.spare, good, nan_offsets, 2));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_attach(a_.cloth, a_.spare, nullptr, offsets, 2));
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_HANDLE, cloth_attach(a_.cloth, a_.stale_body, good, offsets, 2));
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_HANDLE, cloth_attach(a_.cloth, b_.body, good, offsets, 2));
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_HANDLE, cloth_attach(cloth_id{}, a_.spare, good, offsets, 2));
    const uint32_t not_attached[] = {0, 3};  // 0 is attached, 3 is not
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_VALUE, cloth_detach(a_.cloth, not_attached, 2));
    EXPECT_REJECTED(CLOTH_ERROR_INDEX_OUT_OF_RANGE, cloth_detach(a_.cloth, out_of_range, 2));
    const uint32_t corner[] = {0};
    const float target[] = {1, 1, 1};
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_VALUE, cloth_set_pin_targets(a_.cloth, corner, target, 1));
    cloth_body_id body;
    float offset[3];
    EXPECT_REJECTED(CLOTH_ERROR_INDEX_OUT_OF_RANGE,
                    cloth_get_attachment(a_.cloth, kParticles, &body, offset));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_get_attachment(a_.cloth, 0, nullptr, offset));

    cloth_carrier_desc c = cloth_default_carrier_desc();
    c.linear_inertia = 1.5f;
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_VALUE, cloth_set_carrier(a_.cloth, a_.spare, &c));
    c = cloth_default_carrier_desc();
    c.centrifugal_inertia = kNaN;
    EXPECT_REJECTED(CLOTH_ERROR_NOT_FINITE, cloth_set_carrier(a_.cloth, a_.spare, &c));
    c = cloth_default_carrier_desc();
    c.teleport_distance = -1.0f;
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_VALUE, cloth_set_carrier(a_.cloth, a_.spare, &c));
    c = cloth_default_carrier_desc();
    c.max_relative_speed = kInf;
    EXPECT_REJECTED(CLOTH_ERROR_NOT_FINITE, cloth_set_carrier(a_.cloth, a_.spare, &c));
    c = cloth_default_carrier_desc();
    c.teleport_mode = static_cast<cloth_teleport_mode>(9);
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_VALUE, cloth_set_carrier(a_.cloth, a_.spare, &c));
    cloth_carrier_desc raw{};
    raw.struct_size = sizeof raw;
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_DESC, cloth_set_carrier(a_.cloth, a_.spare, &raw));
    c = cloth_default_carrier_desc();
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_set_carrier(a_.cloth, a_.spare, nullptr));
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_HANDLE, cloth_set_carrier(a_.cloth, a_.stale_body, &c));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_get_teleported(a_.cloth, nullptr));
}

TEST(ContactApi, DestroyingABodyDetachesItsParticlesRemovesItsCollidersAndCarrierLinks) {
    cloth_world_desc wd = cloth_default_world_desc();
    cloth_world_id world;
    ASSERT_EQ(cloth_world_create(&wd, &world), CLOTH_OK);
    cloth_grid_desc grid = cloth_default_grid_desc();
    grid.columns = grid.rows = 4;
    cloth_fabric_id fabric;
    ASSERT_EQ(cloth_fabric_create_grid(world, &grid, &fabric), CLOTH_OK);
    cloth_desc cd = cloth_default_desc();
    cd.fabric = fabric;
    cloth_id cloth;
    ASSERT_EQ(cloth_create(world, &cd, &cloth), CLOTH_OK);
    const cloth_body_desc bd = cloth_default_body_desc();
    cloth_body_id body;
    ASSERT_EQ(cloth_body_create(world, &bd, &body), CLOTH_OK);
    const uint32_t top[] = {0, 1, 2, 3};
    ASSERT_EQ(cloth_attach(cloth, body, top, nullptr, 4), CLOTH_OK);
    cloth_collider_desc c = cloth_default_collider_desc();
    c.body = body;
    cloth_collider_id sphere;
    ASSERT_EQ(cloth_collider_create_sphere(world, &c, 0.1f, &sphere), CLOTH_OK);
    const cloth_carrier_desc carrier = cloth_default_carrier_desc();
    ASSERT_EQ(cloth_set_carrier(cloth, body, &carrier), CLOTH_OK);

    ASSERT_EQ(cloth_body_destroy(body), CLOTH_OK);
    for (uint32_t i : top) {
        uint8_t pinned = 1;
        cloth_body_id attached{1, 1, 1, 1};
        ASSERT_EQ(cloth_test::read_flag(cloth_is_pinned, cloth, i, &pinned), CLOTH_OK);
        ASSERT_EQ(cloth_get_attachment(cloth, i, &attached, nullptr), CLOTH_OK);
        EXPECT_FALSE(pinned) << "particle " << i << " is still held by a destroyed body";
        EXPECT_EQ(attached.index1, 0u);
    }
    EXPECT_EQ(cloth_collider_destroy(sphere), CLOTH_ERROR_INVALID_HANDLE)
        << "the body's collider outlived it";
    EXPECT_EQ(cloth_body_set_pose(body, kOrigin, kIdentity), CLOTH_ERROR_INVALID_HANDLE);
    EXPECT_EQ(cloth_step(world, kFrame), CLOTH_OK) << cloth_get_last_error();
    EXPECT_EQ(cloth_world_destroy(world), CLOTH_OK);
}

// One call for many bodies is the same as one cloth_body_set_pose each: a
// cloth attached to one moving body and pushed by a sphere on another ends
// bit-identical either way.
TEST(ContactApi, BodyPosesInOneCallMoveTheBodiesAsOneCallEach) {
    struct World {
        cloth_world_id world{};
        cloth_id cloth{};
        cloth_body_id bodies[2]{};
    } one_each, batched;
    for (World* w : {&one_each, &batched}) {
        cloth_world_desc wd = cloth_default_world_desc();
        ASSERT_EQ(cloth_world_create(&wd, &w->world), CLOTH_OK);
        cloth_grid_desc grid = cloth_default_grid_desc();
        grid.columns = grid.rows = 8;
        cloth_fabric_id fabric;
        ASSERT_EQ(cloth_fabric_create_grid(w->world, &grid, &fabric), CLOTH_OK);
        cloth_desc cd = cloth_default_desc();
        cd.fabric = fabric;
        ASSERT_EQ(cloth_create(w->world, &cd, &w->cloth), CLOTH_OK);
        const cloth_body_desc bd = cloth_default_body_desc();
        for (cloth_body_id& b : w->bodies) ASSERT_EQ(cloth_body_create(w->world, &bd, &b), CLOTH_OK);
        const uint32_t corners[] = {0, 7};
        ASSERT_EQ(cloth_attach(w->cloth, w->bodies[0], corners, nullptr, 2), CLOTH_OK);
        cloth_collider_desc c = cloth_default_collider_desc();
        c.body = w->bodies[1];
        cloth_collider_id sphere;
        ASSERT_EQ(cloth_collider_create_sphere(w->world, &c, 0.2f, &sphere), CLOTH_OK);
    }
    for (int frame = 0; frame < 30; ++frame) {
        const float t = static_cast<float>(frame) * kFrame;
        const float p[6] = {0.5f * t, 0.0f, 0.0f, 0.5f, -0.6f + t, 0.3f - t};
        const float q[8] = {0, 0, std::sin(t), std::cos(t), 0, 0, 0, 1};
        for (int k = 0; k < 2; ++k)
            ASSERT_EQ(cloth_body_set_pose(one_each.bodies[k], p + 3 * k, q + 4 * k), CLOTH_OK);
        ASSERT_EQ(cloth_world_set_body_poses(batched.world, batched.bodies, p, q, 2), CLOTH_OK);
        for (World* w : {&one_each, &batched}) ASSERT_EQ(cloth_step(w->world, kFrame), CLOTH_OK);
    }
    std::vector<float> a(3 * 64), b(3 * 64), start(3 * 64);
    ASSERT_EQ(cloth_read_positions(one_each.cloth, a.data(), 3 * 64), CLOTH_OK);
    ASSERT_EQ(cloth_read_positions(batched.cloth, b.data(), 3 * 64), CLOTH_OK);
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)), 0);
    EXPECT_GT(std::fabs(a[0]), 0.1f) << "the attached corner followed its body";
    for (World* w : {&one_each, &batched}) EXPECT_EQ(cloth_world_destroy(w->world), CLOTH_OK);
}

}  // namespace
