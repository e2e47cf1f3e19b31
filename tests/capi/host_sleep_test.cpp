// cloth_sleep through cloth.h: the host puts a cloth to sleep whatever its
// motion (a cloth out of view). Asleep it costs nothing and keeps its
// state; waking it continues its motion with the same bits as a cloth that
// never slept; moving bodies do not wake it; a cloth on a carrier catches
// up with the carrier when it wakes; snapshots keep the host's sleep.
#include <cloth/cloth.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "support/contract_gtest.h"
#include "support/counting_allocator.h"
#include "support/flag_fabric.h"

namespace {

constexpr uint32_t kColumns = 16, kRows = 12, kParticles = kColumns * kRows;
constexpr float kFrame = 1.0f / 60.0f;
const float kIdentity[4] = {0.0f, 0.0f, 0.0f, 1.0f};

// A flag in wind, 0.8 x 0.6 m, its left column pinned or attached to a body.
struct Scene {
    cloth_test::CountingAllocator host;
    cloth_world_id world{};
    cloth_fabric_id fabric{};
    cloth_id flag{};

    Scene() {
        cloth_world_desc wd = host.world_desc();
        EXPECT_EQ(cloth_world_create(&wd, &world), CLOTH_OK);
        fabric = cloth_test::flag_fabric(world, kColumns, kRows, 0.8f, 0.6f);
        cloth_desc cd = cloth_default_desc();
        cd.fabric = fabric;
        EXPECT_EQ(cloth_create(world, &cd, &flag), CLOTH_OK);
        const float wind[3] = {6.0f, 0.0f, 1.5f};
        EXPECT_EQ(cloth_set_wind(flag, wind), CLOTH_OK);
    }
    ~Scene() {
        EXPECT_EQ(cloth_world_destroy(world), CLOTH_OK);
        cloth_test::ExpectAllReturned(host);
    }
    static std::vector<uint32_t> left_column() {
        std::vector<uint32_t> column;
        for (uint32_t r = 0; r < kRows; ++r) column.push_back(r * kColumns);
        return column;
    }
    void pin_left_column() {
        const std::vector<uint32_t> column = left_column();
        EXPECT_EQ(cloth_pin(flag, column.data(), kRows), CLOTH_OK);
    }
    // A static sphere beside the flag: the cloth now follows bodies and
    // colliders, so it never falls asleep by itself.
    void add_collider() {
        cloth_collider_desc desc = cloth_default_collider_desc();
        desc.local_position[0] = 0.4f;
        desc.local_position[1] = -0.3f;
        desc.local_position[2] = -1.0f;
        cloth_collider_id sphere{};
        EXPECT_EQ(cloth_collider_create_sphere(world, &desc, 0.2f, &sphere), CLOTH_OK);
    }
    void step() { ASSERT_EQ(cloth_step(world, kFrame), CLOTH_OK); }
    std::vector<float> positions() const {
        std::vector<float> x(3 * kParticles);
        EXPECT_EQ(cloth_read_positions(flag, x.data(), 3 * kParticles), CLOTH_OK);
        return x;
    }
    bool sleeping() const {
        bool s = false;
        EXPECT_EQ(cloth_is_sleeping(flag, &s), CLOTH_OK);
        return s;
    }
    uint32_t sleeping_in_last_call() const {
        cloth_frame_profile p{};
        p.struct_size = sizeof p;
        EXPECT_EQ(cloth_world_get_frame_profile(world, &p), CLOTH_OK);
        return p.sleeping_cloths;
    }
};

TEST(HostSleep, AMovingClothPutToSleepCostsNothingAndContinuesItsMotionWithTheSameBitsOnWaking) {
    Scene slept, twin;
    for (Scene* s : {&slept, &twin}) {
        s->pin_left_column();
        for (int call = 0; call < 20; ++call) s->step();
    }
    ASSERT_EQ(slept.positions(), twin.positions());
    ASSERT_EQ(cloth_sleep(slept.flag), CLOTH_OK);
    const std::vector<float> at_sleep = slept.positions();
    for (int call = 0; call < 30; ++call) {
        slept.step();
        EXPECT_TRUE(slept.sleeping());
        EXPECT_EQ(slept.sleeping_in_last_call(), 1u) << "the step skips it";
    }
    EXPECT_EQ(slept.positions(), at_sleep) << "asleep, the flag stays where it was";
    ASSERT_EQ(cloth_wake(slept.flag), CLOTH_OK);
    for (int call = 0; call < 20; ++call) {
        slept.step();
        twin.step();
        ASSERT_EQ(slept.positions(), twin.positions())
            << "woken, it continues with its velocities as if it had not slept (call " << call << ")";
    }
}

TEST(HostSleep, MovingBodiesAndCollidersDoNotWakeAClothTheHostPutToSleep) {
    Scene s;
    s.pin_left_column();
    s.add_collider();
    cloth_body_desc bd = cloth_default_body_desc();
    cloth_body_id body{};
    ASSERT_EQ(cloth_body_create(s.world, &bd, &body), CLOTH_OK);
    cloth_collider_desc desc = cloth_default_collider_desc();
    desc.body = body;
    cloth_collider_id moving{};
    ASSERT_EQ(cloth_collider_create_sphere(s.world, &desc, 0.1f, &moving), CLOTH_OK);
    for (int call = 0; call < 10; ++call) s.step();
    ASSERT_EQ(cloth_sleep(s.flag), CLOTH_OK);
    const std::vector<float> at_sleep = s.positions();
    for (int call = 0; call < 30; ++call) {
        const float position[3] = {0.01f * static_cast<float>(call), -0.3f, 0.0f};
        ASSERT_EQ(cloth_body_set_pose(body, position, kIdentity), CLOTH_OK);
        s.step();
        ASSERT_TRUE(s.sleeping()) << "call " << call;
    }
    EXPECT_EQ(s.positions(), at_sleep);
    // A cloth that fell asleep by itself would have been woken: this one
    // wakes on the host's word.
    ASSERT_EQ(cloth_wake(s.flag), CLOTH_OK);
    s.step();
    EXPECT_FALSE(s.sleeping());
    EXPECT_NE(s.positions(), at_sleep);
}

TEST(HostSleep, AClothOnACarrierCatchesUpWithItsCarrierWhenItWakes) {
    Scene s;
    cloth_body_desc bd = cloth_default_body_desc();
    cloth_body_id vehicle{};
    ASSERT_EQ(cloth_body_create(s.world, &bd, &vehicle), CLOTH_OK);
    const std::vector<uint32_t> column = Scene::left_column();
    ASSERT_EQ(cloth_attach(s.flag, vehicle, column.data(), nullptr, kRows), CLOTH_OK);
    const cloth_carrier_desc carrier = cloth_default_carrier_desc();
    ASSERT_EQ(cloth_set_carrier(s.flag, vehicle, &carrier), CLOTH_OK);
    for (int call = 0; call < 30; ++call) s.step();
    ASSERT_EQ(cloth_sleep(s.flag), CLOTH_OK);
    const std::vector<float> at_sleep = s.positions();
    // The vehicle drives 50 m while the flag sleeps.
    const float kDrive = 50.0f;
    for (int call = 1; call <= 60; ++call) {
        const float position[3] = {kDrive * static_cast<float>(call) / 60.0f, 0.0f, 0.0f};
        ASSERT_EQ(cloth_body_set_pose(vehicle, position, kIdentity), CLOTH_OK);
        s.step();
    }
    ASSERT_TRUE(s.sleeping());
    EXPECT_EQ(s.positions(), at_sleep) << "asleep, the flag stays behind";
    ASSERT_EQ(cloth_wake(s.flag), CLOTH_OK);
    s.step();
    const std::vector<float> woken = s.positions();
    // Every particle is where it was relative to the vehicle, give or take
    // one frame of its own motion: no particle is stretched across 50 m.
    float largest = 0;
    for (size_t i = 0; i < woken.size(); i += 3) {
        const float dx = woken[i] - kDrive - at_sleep[i], dy = woken[i + 1] - at_sleep[i + 1],
                    dz = woken[i + 2] - at_sleep[i + 2];
        largest = std::max(largest, std::sqrt(dx * dx + dy * dy + dz * dz));
    }
    EXPECT_LT(largest, 0.1f) << "the first step moves the flag with its carrier";
}

TEST(HostSleep, ASnapshotKeepsThatTheHostPutTheClothToSleep) {
    Scene s;
    s.pin_left_column();
    s.add_collider();
    for (int call = 0; call < 10; ++call) s.step();
    ASSERT_EQ(cloth_sleep(s.flag), CLOTH_OK);
    size_t size = 0;
    ASSERT_EQ(cloth_get_snapshot_size(s.flag, &size), CLOTH_OK);
    std::vector<unsigned char> snapshot(size);
    ASSERT_EQ(cloth_save_snapshot(s.flag, snapshot.data(), size), CLOTH_OK);
    const std::vector<float> at_sleep = s.positions();
    ASSERT_EQ(cloth_wake(s.flag), CLOTH_OK);
    for (int call = 0; call < 5; ++call) s.step();
    ASSERT_EQ(cloth_restore_snapshot(s.flag, snapshot.data(), size), CLOTH_OK);
    for (int call = 0; call < 5; ++call) {
        s.step();
        EXPECT_TRUE(s.sleeping()) << "restored asleep; the collider does not wake it";
    }
    EXPECT_EQ(s.positions(), at_sleep);
    EXPECT_EQ(cloth_sleep(cloth_id{}), CLOTH_ERROR_INVALID_HANDLE);
}

}  // namespace
