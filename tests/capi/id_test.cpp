// Handles of every kind (world, fabric, cloth, body, collider) against the
// header's rules: the null id is not valid, a live id is valid and equal to
// itself, a destroyed id is neither valid nor equal to the next id of its
// slot, and an id is refused by every other world. Also the id pool under
// them (lowest free slot, generations that skip 0) and cloth_struct_size.
#include <cloth/cloth.h>
#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "base/id_pool.h"

// tests/capi/enum_from_int.c: an out-of-range kind passed the way a C caller can (in C++ the
// load of such an enum value is undefined, and UBSan reports it).
extern "C" size_t cloth_test_struct_size_of_int(int32_t value);
namespace {

struct Scene {
    cloth_world_id world = cloth_null_world_id;
    cloth_fabric_id fabric = cloth_null_fabric_id;
    cloth_id cloth = cloth_null_id;
    cloth_body_id body = cloth_null_body_id;
    cloth_collider_id collider = cloth_null_collider_id;
};

Scene make_scene() {
    Scene s;
    const cloth_world_desc wd = cloth_default_world_desc();
    EXPECT_EQ(cloth_world_create(&wd, &s.world), CLOTH_OK) << cloth_get_last_error();
    cloth_grid_desc gd = cloth_default_grid_desc();
    gd.columns = gd.rows = 4;
    EXPECT_EQ(cloth_fabric_create_grid(s.world, &gd, &s.fabric), CLOTH_OK) << cloth_get_last_error();
    cloth_desc cd = cloth_default_desc();
    cd.fabric = s.fabric;
    EXPECT_EQ(cloth_create(s.world, &cd, &s.cloth), CLOTH_OK) << cloth_get_last_error();
    const cloth_body_desc bd = cloth_default_body_desc();
    EXPECT_EQ(cloth_body_create(s.world, &bd, &s.body), CLOTH_OK) << cloth_get_last_error();
    cloth_collider_desc col = cloth_default_collider_desc();
    col.body = s.body;
    EXPECT_EQ(cloth_collider_create_sphere(s.world, &col, 0.5f, &s.collider), CLOTH_OK)
        << cloth_get_last_error();
    return s;
}

// The same object index in another world (world fields swapped).
template <class Id>
Id in_world(Id id, cloth_world_id world) {
    id.world1 = world.index1;
    id.world_generation = world.generation;
    return id;
}

class Ids : public ::testing::Test {
  protected:
    void SetUp() override {
        a_ = make_scene();
        b_ = make_scene();
    }
    void TearDown() override {
        for (cloth_world_id world : {a_.world, b_.world}) {
            if (cloth_world_is_valid(world)) {
                EXPECT_EQ(cloth_world_destroy(world), CLOTH_OK);
            }
        }
    }
    Scene a_, b_;
};

TEST_F(Ids, NullIdsAreAllZeroAndNotValid) {
    const unsigned char zero[8] = {};
    EXPECT_EQ(std::memcmp(&cloth_null_world_id, zero, sizeof cloth_null_world_id), 0);
    EXPECT_EQ(std::memcmp(&cloth_null_fabric_id, zero, sizeof cloth_null_fabric_id), 0);
    EXPECT_EQ(std::memcmp(&cloth_null_id, zero, sizeof cloth_null_id), 0);
    EXPECT_EQ(std::memcmp(&cloth_null_body_id, zero, sizeof cloth_null_body_id), 0);
    EXPECT_EQ(std::memcmp(&cloth_null_collider_id, zero, sizeof cloth_null_collider_id), 0);
    EXPECT_FALSE(cloth_world_is_valid(cloth_null_world_id));
    EXPECT_FALSE(cloth_fabric_is_valid(cloth_null_fabric_id));
    EXPECT_FALSE(cloth_is_valid(cloth_null_id));
    EXPECT_FALSE(cloth_body_is_valid(cloth_null_body_id));
    EXPECT_FALSE(cloth_collider_is_valid(cloth_null_collider_id));
    EXPECT_TRUE(cloth_world_id_equal(cloth_null_world_id, cloth_world_id{}));
    EXPECT_TRUE(cloth_id_equal(cloth_null_id, cloth_id{}));
}

TEST_F(Ids, IsValidSetsNoError) {
    cloth_world_set_gravity(cloth_null_world_id, nullptr);  // a failing call leaves a message
    const std::string before = cloth_get_last_error();
    ASSERT_FALSE(before.empty());
    EXPECT_FALSE(cloth_is_valid(cloth_null_id));
    EXPECT_FALSE(cloth_world_is_valid(cloth_world_id{200, 1}));
    EXPECT_EQ(before, cloth_get_last_error());
}

TEST_F(Ids, LiveIdsAreValidAndEqualToThemselves) {
    EXPECT_TRUE(cloth_world_is_valid(a_.world));
    EXPECT_TRUE(cloth_fabric_is_valid(a_.fabric));
    EXPECT_TRUE(cloth_is_valid(a_.cloth));
    EXPECT_TRUE(cloth_body_is_valid(a_.body));
    EXPECT_TRUE(cloth_collider_is_valid(a_.collider));
    EXPECT_TRUE(cloth_world_id_equal(a_.world, a_.world));
    EXPECT_TRUE(cloth_fabric_id_equal(a_.fabric, a_.fabric));
    EXPECT_TRUE(cloth_id_equal(a_.cloth, a_.cloth));
    EXPECT_TRUE(cloth_body_id_equal(a_.body, a_.body));
    EXPECT_TRUE(cloth_collider_id_equal(a_.collider, a_.collider));
    EXPECT_FALSE(cloth_world_id_equal(a_.world, cloth_null_world_id));
    EXPECT_FALSE(cloth_fabric_id_equal(a_.fabric, cloth_null_fabric_id));
    EXPECT_FALSE(cloth_id_equal(a_.cloth, cloth_null_id));
    EXPECT_FALSE(cloth_body_id_equal(a_.body, cloth_null_body_id));
    EXPECT_FALSE(cloth_collider_id_equal(a_.collider, cloth_null_collider_id));
    // The same slot of two worlds: different handles.
    EXPECT_FALSE(cloth_world_id_equal(a_.world, b_.world));
    EXPECT_FALSE(cloth_fabric_id_equal(a_.fabric, b_.fabric));
    EXPECT_FALSE(cloth_id_equal(a_.cloth, b_.cloth));
    EXPECT_FALSE(cloth_body_id_equal(a_.body, b_.body));
    EXPECT_FALSE(cloth_collider_id_equal(a_.collider, b_.collider));
}

TEST_F(Ids, DestroyedFabricAndClothAreNotValidNorEqualToTheirSlotsNext) {
    ASSERT_EQ(cloth_destroy(a_.cloth), CLOTH_OK);
    ASSERT_EQ(cloth_fabric_destroy(a_.fabric), CLOTH_OK);
    EXPECT_FALSE(cloth_is_valid(a_.cloth));
    EXPECT_FALSE(cloth_fabric_is_valid(a_.fabric));

    cloth_grid_desc gd = cloth_default_grid_desc();
    gd.columns = gd.rows = 3;
    cloth_fabric_id fabric;
    ASSERT_EQ(cloth_fabric_create_grid(a_.world, &gd, &fabric), CLOTH_OK);
    cloth_desc cd = cloth_default_desc();
    cd.fabric = fabric;
    cloth_id cloth;
    ASSERT_EQ(cloth_create(a_.world, &cd, &cloth), CLOTH_OK);
    EXPECT_EQ(fabric.index1, a_.fabric.index1);  // the lowest free slot: the same one
    EXPECT_EQ(cloth.index1, a_.cloth.index1);
    EXPECT_FALSE(cloth_fabric_id_equal(fabric, a_.fabric));
    EXPECT_FALSE(cloth_id_equal(cloth, a_.cloth));
    EXPECT_TRUE(cloth_fabric_is_valid(fabric));
    EXPECT_TRUE(cloth_is_valid(cloth));
    EXPECT_FALSE(cloth_is_valid(a_.cloth));
    uint32_t count = 0;
    EXPECT_EQ(cloth_get_particle_count(a_.cloth, &count), CLOTH_ERROR_INVALID_HANDLE);
    EXPECT_EQ(cloth_fabric_get_particle_count(a_.fabric, &count), CLOTH_ERROR_INVALID_HANDLE);
}

TEST_F(Ids, ReleasedFabricIsNotValidWhileItsClothLives) {
    ASSERT_EQ(cloth_fabric_destroy(a_.fabric), CLOTH_OK);
    EXPECT_FALSE(cloth_fabric_is_valid(a_.fabric));
    EXPECT_TRUE(cloth_is_valid(a_.cloth));
}

TEST_F(Ids, DestroyedBodyAndColliderAreNotValidNorEqualToTheirSlotsNext) {
    ASSERT_EQ(cloth_collider_destroy(a_.collider), CLOTH_OK);
    EXPECT_FALSE(cloth_collider_is_valid(a_.collider));
    EXPECT_TRUE(cloth_body_is_valid(a_.body));
    ASSERT_EQ(cloth_body_destroy(a_.body), CLOTH_OK);
    EXPECT_FALSE(cloth_body_is_valid(a_.body));

    const cloth_body_desc bd = cloth_default_body_desc();
    cloth_body_id body;
    ASSERT_EQ(cloth_body_create(a_.world, &bd, &body), CLOTH_OK);
    const cloth_collider_desc col = cloth_default_collider_desc();
    cloth_collider_id collider;
    ASSERT_EQ(cloth_collider_create_sphere(a_.world, &col, 1.0f, &collider), CLOTH_OK);
    EXPECT_EQ(body.index1, a_.body.index1);
    EXPECT_EQ(collider.index1, a_.collider.index1);
    EXPECT_FALSE(cloth_body_id_equal(body, a_.body));
    EXPECT_FALSE(cloth_collider_id_equal(collider, a_.collider));
    EXPECT_TRUE(cloth_body_is_valid(body));
    EXPECT_TRUE(cloth_collider_is_valid(collider));
    EXPECT_EQ(cloth_body_set_velocity(a_.body, bd.linear_velocity, bd.angular_velocity),
              CLOTH_ERROR_INVALID_HANDLE);
    EXPECT_EQ(cloth_collider_set_group_bits(a_.collider, 2), CLOTH_ERROR_INVALID_HANDLE);
}

TEST_F(Ids, ColliderDiesWithItsBody) {
    ASSERT_EQ(cloth_body_destroy(a_.body), CLOTH_OK);
    EXPECT_FALSE(cloth_collider_is_valid(a_.collider));
}

TEST_F(Ids, DestroyedWorldTakesEveryIdWithIt) {
    const Scene dead = a_;
    ASSERT_EQ(cloth_world_destroy(a_.world), CLOTH_OK);
    EXPECT_FALSE(cloth_world_is_valid(dead.world));
    EXPECT_FALSE(cloth_fabric_is_valid(dead.fabric));
    EXPECT_FALSE(cloth_is_valid(dead.cloth));
    EXPECT_FALSE(cloth_body_is_valid(dead.body));
    EXPECT_FALSE(cloth_collider_is_valid(dead.collider));

    a_ = make_scene();  // reuses the world's slot
    EXPECT_EQ(a_.world.index1, dead.world.index1);
    EXPECT_FALSE(cloth_world_id_equal(a_.world, dead.world));
    EXPECT_FALSE(cloth_fabric_id_equal(a_.fabric, dead.fabric));
    EXPECT_FALSE(cloth_id_equal(a_.cloth, dead.cloth));
    EXPECT_FALSE(cloth_body_id_equal(a_.body, dead.body));
    EXPECT_FALSE(cloth_collider_id_equal(a_.collider, dead.collider));
    EXPECT_FALSE(cloth_world_is_valid(dead.world));
    EXPECT_FALSE(cloth_is_valid(dead.cloth));
    EXPECT_EQ(cloth_step(dead.world, 0.01f), CLOTH_ERROR_INVALID_HANDLE);
}

TEST_F(Ids, IdsOfAnotherWorldAreRefused) {
    // Second objects in world A: their slots are free in world B.
    cloth_grid_desc gd = cloth_default_grid_desc();
    gd.columns = gd.rows = 3;
    cloth_fabric_id fabric;
    ASSERT_EQ(cloth_fabric_create_grid(a_.world, &gd, &fabric), CLOTH_OK);
    cloth_desc cd = cloth_default_desc();
    cd.fabric = fabric;
    cloth_id cloth;
    ASSERT_EQ(cloth_create(a_.world, &cd, &cloth), CLOTH_OK);
    const cloth_body_desc bd = cloth_default_body_desc();
    cloth_body_id body;
    ASSERT_EQ(cloth_body_create(a_.world, &bd, &body), CLOTH_OK);
    const cloth_collider_desc col = cloth_default_collider_desc();
    cloth_collider_id collider;
    ASSERT_EQ(cloth_collider_create_sphere(a_.world, &col, 1.0f, &collider), CLOTH_OK);

    // The same ids with world B's fields name nothing there.
    uint32_t count;
    EXPECT_FALSE(cloth_fabric_is_valid(in_world(fabric, b_.world)));
    EXPECT_FALSE(cloth_is_valid(in_world(cloth, b_.world)));
    EXPECT_FALSE(cloth_body_is_valid(in_world(body, b_.world)));
    EXPECT_FALSE(cloth_collider_is_valid(in_world(collider, b_.world)));
    EXPECT_EQ(cloth_fabric_get_particle_count(in_world(fabric, b_.world), &count),
              CLOTH_ERROR_INVALID_HANDLE);
    EXPECT_EQ(cloth_get_particle_count(in_world(cloth, b_.world), &count), CLOTH_ERROR_INVALID_HANDLE);
    EXPECT_EQ(cloth_body_destroy(in_world(body, b_.world)), CLOTH_ERROR_INVALID_HANDLE);
    EXPECT_EQ(cloth_collider_destroy(in_world(collider, b_.world)), CLOTH_ERROR_INVALID_HANDLE);
    // A world id that was never handed out.
    EXPECT_FALSE(cloth_world_is_valid(cloth_world_id{128, 1}));
    EXPECT_FALSE(cloth_world_is_valid(cloth_world_id{129, 1}));

    // A's ids passed where world B is meant.
    cd.fabric = a_.fabric;
    cloth_id out;
    EXPECT_EQ(cloth_create(b_.world, &cd, &out), CLOTH_ERROR_INVALID_HANDLE);
    const uint32_t index = 0;
    EXPECT_EQ(cloth_attach(b_.cloth, a_.body, &index, nullptr, 1), CLOTH_ERROR_INVALID_HANDLE);
    const cloth_carrier_desc carrier = cloth_default_carrier_desc();
    EXPECT_EQ(cloth_set_carrier(b_.cloth, a_.body, &carrier), CLOTH_ERROR_INVALID_HANDLE);
    cloth_collider_desc on_body = cloth_default_collider_desc();
    on_body.body = a_.body;
    cloth_collider_id out_collider;
    EXPECT_EQ(cloth_collider_create_sphere(b_.world, &on_body, 1.0f, &out_collider),
              CLOTH_ERROR_INVALID_HANDLE);
}

TEST_F(Ids, IdsWithAStaleWorldGenerationAreRefused) {
    // Every kind, with its world's generation off by one.
    auto stale = [](auto id) {
        id.world_generation = static_cast<uint16_t>(id.world_generation + 1);
        return id;
    };
    EXPECT_FALSE(cloth_fabric_is_valid(stale(a_.fabric)));
    EXPECT_FALSE(cloth_is_valid(stale(a_.cloth)));
    EXPECT_FALSE(cloth_body_is_valid(stale(a_.body)));
    EXPECT_FALSE(cloth_collider_is_valid(stale(a_.collider)));
    cloth_world_id world = a_.world;
    world.generation = static_cast<uint16_t>(world.generation + 1);
    EXPECT_FALSE(cloth_world_is_valid(world));
    uint32_t count;
    EXPECT_EQ(cloth_get_particle_count(stale(a_.cloth), &count), CLOTH_ERROR_INVALID_HANDLE);
    EXPECT_EQ(cloth_fabric_get_particle_count(stale(a_.fabric), &count), CLOTH_ERROR_INVALID_HANDLE);
    EXPECT_EQ(cloth_body_destroy(stale(a_.body)), CLOTH_ERROR_INVALID_HANDLE);
    EXPECT_EQ(cloth_collider_destroy(stale(a_.collider)), CLOTH_ERROR_INVALID_HANDLE);
}

TEST(StructSize, MatchesSizeofForEveryKind) {
    struct Kind {
        cloth_struct_kind kind;
        size_t size;
    };
    const Kind kinds[] = {
        {CLOTH_STRUCT_VERSION, sizeof(cloth_version)},
        {CLOTH_STRUCT_WORLD_ID, sizeof(cloth_world_id)},
        {CLOTH_STRUCT_FABRIC_ID, sizeof(cloth_fabric_id)},
        {CLOTH_STRUCT_CLOTH_ID, sizeof(cloth_id)},
        {CLOTH_STRUCT_BODY_ID, sizeof(cloth_body_id)},
        {CLOTH_STRUCT_COLLIDER_ID, sizeof(cloth_collider_id)},
        {CLOTH_STRUCT_WORLD_DESC, sizeof(cloth_world_desc)},
        {CLOTH_STRUCT_GRID_DESC, sizeof(cloth_grid_desc)},
        {CLOTH_STRUCT_MESH_DESC, sizeof(cloth_mesh_desc)},
        {CLOTH_STRUCT_SPRING_PARAMS, sizeof(cloth_spring_params)},
        {CLOTH_STRUCT_SOLVER_SETTINGS, sizeof(cloth_solver_settings)},
        {CLOTH_STRUCT_STRAIN_LIMIT, sizeof(cloth_strain_limit)},
        {CLOTH_STRUCT_AERO_PARAMS, sizeof(cloth_aero_params)},
        {CLOTH_STRUCT_CLOTH_DESC, sizeof(cloth_desc)},
        {CLOTH_STRUCT_STATS, sizeof(cloth_stats)},
        {CLOTH_STRUCT_FRAME_PROFILE, sizeof(cloth_frame_profile)},
        {CLOTH_STRUCT_TASK_RECORD, sizeof(cloth_task_record)},
        {CLOTH_STRUCT_QUALITY_POLICY, sizeof(cloth_quality_policy)},
        {CLOTH_STRUCT_SLEEP_PARAMS, sizeof(cloth_sleep_params)},
        {CLOTH_STRUCT_BODY_DESC, sizeof(cloth_body_desc)},
        {CLOTH_STRUCT_COLLIDER_DESC, sizeof(cloth_collider_desc)},
        {CLOTH_STRUCT_HEIGHTFIELD_DESC, sizeof(cloth_heightfield_desc)},
        {CLOTH_STRUCT_COLLISION_PARAMS, sizeof(cloth_collision_params)},
        {CLOTH_STRUCT_CARRIER_DESC, sizeof(cloth_carrier_desc)},
        {CLOTH_STRUCT_SELF_COLLISION_DESC, sizeof(cloth_self_collision_desc)},
        {CLOTH_STRUCT_SELF_COLLISION_STATS, sizeof(cloth_self_collision_stats)},
        {CLOTH_STRUCT_SKIN_DESC, sizeof(cloth_skin_desc)},
        {CLOTH_STRUCT_CLOTH_CONTACT_DESC, sizeof(cloth_cloth_contact_desc)},
    };
    for (size_t i = 0; i < sizeof kinds / sizeof kinds[0]; ++i) {
        EXPECT_EQ(static_cast<int>(kinds[i].kind), static_cast<int>(i + 1)) << "kinds are numbered in order";
        EXPECT_EQ(cloth_struct_size(kinds[i].kind), kinds[i].size) << "kind " << kinds[i].kind;
    }
    // Unknown kinds, as a C caller may pass them (formed in C: enum_from_int.c).
    for (int32_t bits : {0, 29, 1000, -1, 0x7FFFFFFF}) {
        EXPECT_EQ(cloth_test_struct_size_of_int(bits), 0u) << bits;
    }
}

// The pool itself: what the handles above rely on.
TEST(IdPool, TakesTheLowestFreeSlotAndNeverHandsOutGenerationZero) {
    cloth::HostMemory heap;
    cloth::IdPool<int> pool(&heap, 3);
    EXPECT_EQ(pool.size(), 0u);
    for (uint32_t i = 0; i < 3; ++i) {
        const uint32_t slot = pool.free_slot();
        ASSERT_EQ(slot, i);
        EXPECT_EQ(pool.occupy(slot, static_cast<int>(10 + i)), 1);
    }
    EXPECT_EQ(pool.free_slot(), pool.kFull);
    ASSERT_NE(pool.get(2, 1), nullptr);
    EXPECT_EQ(*pool.get(2, 1), 11);
    EXPECT_EQ(pool.get(0, 1), nullptr);  // null
    EXPECT_EQ(pool.get(4, 1), nullptr);  // past the table
    EXPECT_EQ(pool.get(2, 2), nullptr);  // another generation

    pool.release(1);
    pool.release(0);
    EXPECT_EQ(pool.get(2, 1), nullptr);
    EXPECT_EQ(pool.free_slot(), 0u);  // the lowest, not the last released
    // A slot's generation counts 1..65535 and then starts at 1 again.
    for (int reuse = 0; reuse < 65535; ++reuse) {
        const uint16_t generation = pool.occupy(0, reuse);
        ASSERT_NE(generation, 0);
        ASSERT_EQ(generation, reuse + 2 <= 65535 ? reuse + 2 : reuse + 2 - 65535);
        pool.release(0);
    }
    EXPECT_EQ(pool[0].generation, 2);
}

TEST(IdPool, MakeAllSlotsSizesTheTableOnce) {
    cloth::HostMemory heap;
    cloth::IdPool<int> pool(&heap, 5);
    pool.make_all_slots();
    EXPECT_EQ(pool.size(), 5u);
    EXPECT_EQ(pool.free_slot(), 0u);
    EXPECT_EQ(pool.size(), 5u);
}

}  // namespace
