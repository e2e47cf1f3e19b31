// Separate worlds on separate threads (cloth.h, threading contract): four
// threads each build, step and destroy worlds of their own, with fabrics,
// cloths, bodies and colliders, the step on the world's own worker threads,
// over and over; every run ends in the same bits (a hash of the positions)
// as the same run made alone on one thread. The ThreadSanitizer tree of
// scripts/test builds and runs it (THREADED_TESTS).
#include <cloth/cloth.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

namespace {

#ifdef CLOTH_SANITIZED_BUILD
constexpr int kRounds = 2;
constexpr int kFrames = 8;
#else
constexpr int kRounds = 6;
constexpr int kFrames = 30;
#endif
constexpr int kThreads = 4;

uint64_t Fnv1a(const void* data, size_t size, uint64_t hash) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < size; ++i) hash = (hash ^ bytes[i]) * 1099511628211ull;
    return hash;
}

#define RUN_CHECK(call)                                                                              \
    do {                                                                                             \
        const cloth_result r_ = (call);                                                              \
        if (r_ != CLOTH_OK)                                                                          \
            return std::string(#call) + ": " + cloth_result_name(r_) + " " + cloth_get_last_error(); \
    } while (false)

// One run: a world with its own workers, a flag pinned at two corners and
// attached at a third to a body that moves, a sphere on the body, a static
// ground plane and a second, free cloth; `variant` changes sizes and wind
// so that the threads do not all compute the same thing. Writes the hash
// of every cloth's positions after the last frame.
std::string RunWorld(int variant, uint64_t* out_hash) {
    cloth_world_desc wd = cloth_default_world_desc();
    wd.worker_count = 2 + static_cast<uint32_t>(variant % 2);
    wd.max_cloths = 4;
    wd.max_fabrics = 4;
    cloth_world_id world{};
    RUN_CHECK(cloth_world_create(&wd, &world));
    RUN_CHECK(cloth_world_set_worker_spin(world, 50));

    cloth_grid_desc grid = cloth_default_grid_desc();
    grid.columns = 10 + static_cast<uint32_t>(variant % 3);
    grid.rows = 10;
    cloth_fabric_id fabric{};
    RUN_CHECK(cloth_fabric_create_grid(world, &grid, &fabric));
    cloth_desc desc = cloth_default_desc();
    desc.fabric = fabric;
    desc.aero.wind[2] = 2.0f + static_cast<float>(variant);
    cloth_id flag{}, loose{};
    RUN_CHECK(cloth_create(world, &desc, &flag));
    desc.solver.kind = CLOTH_SOLVER_JACOBI;
    desc.solver.iterations = 4;
    RUN_CHECK(cloth_create(world, &desc, &loose));
    RUN_CHECK(cloth_fabric_destroy(fabric));  // the cloths keep it alive

    const uint32_t corners[] = {0, grid.columns - 1};
    RUN_CHECK(cloth_pin(flag, corners, 2));
    cloth_body_desc bd = cloth_default_body_desc();
    bd.position[1] = 0.2f;
    cloth_body_id body{};
    RUN_CHECK(cloth_body_create(world, &bd, &body));
    const uint32_t middle[] = {grid.columns / 2};
    RUN_CHECK(cloth_attach(flag, body, middle, nullptr, 1));
    cloth_collider_desc cd = cloth_default_collider_desc();
    cd.body = body;
    cd.local_position[1] = -0.8f;
    cd.local_position[2] = 0.3f;
    cloth_collider_id sphere{}, ground{};
    RUN_CHECK(cloth_collider_create_sphere(world, &cd, 0.25f, &sphere));
    const cloth_collider_desc static_desc = cloth_default_collider_desc();
    const float up[3] = {0.0f, 1.0f, 0.0f};
    RUN_CHECK(cloth_collider_create_plane(world, &static_desc, up, -1.2f, &ground));

    const float rotation[4] = {0.0f, 0.0f, 0.0f, 1.0f};
    for (int frame = 0; frame < kFrames; ++frame) {
        const float position[3] = {0.01f * static_cast<float>(frame), 0.2f, 0.0f};
        RUN_CHECK(cloth_body_set_pose(body, position, rotation));
        RUN_CHECK(cloth_step(world, 1.0f / 60.0f));
    }

    uint64_t hash = 14695981039346656037ull;
    for (cloth_id cloth : {flag, loose}) {
        uint32_t n = 0;
        RUN_CHECK(cloth_get_particle_count(cloth, &n));
        std::vector<float> x(3 * size_t{n});
        RUN_CHECK(cloth_read_positions(cloth, x.data(), 3 * n));
        hash = Fnv1a(x.data(), x.size() * sizeof(float), hash);
    }
    RUN_CHECK(cloth_collider_destroy(ground));
    RUN_CHECK(cloth_body_destroy(body));  // its sphere and the attachment go with it
    RUN_CHECK(cloth_destroy(loose));
    RUN_CHECK(cloth_destroy(flag));
    RUN_CHECK(cloth_world_destroy(world));
    *out_hash = hash;
    return "";
}

TEST(ConcurrentWorlds, FourThreadsWithWorldsOfTheirOwnGetTheBitsOfTheSameRunsAloneOnOneThread) {
    // Alone: every thread's sequence, one after the other.
    std::vector<uint64_t> alone(kThreads * kRounds);
    for (int t = 0; t < kThreads; ++t) {
        for (int round = 0; round < kRounds; ++round) {
            const std::string error = RunWorld(t, &alone[t * kRounds + round]);
            ASSERT_EQ(error, "");
        }
    }
    // Together: the same sequences on four threads at once.
    std::vector<uint64_t> together(kThreads * kRounds, 0);
    std::vector<std::string> errors(kThreads);
    std::vector<std::thread> threads;
    for (int t = 0; t < kThreads; ++t) {
        threads.emplace_back([&, t] {
            for (int round = 0; round < kRounds && errors[t].empty(); ++round)
                errors[t] = RunWorld(t, &together[t * kRounds + round]);
        });
    }
    for (std::thread& thread : threads) thread.join();
    for (int t = 0; t < kThreads; ++t) {
        EXPECT_EQ(errors[t], "") << "thread " << t;
        for (int round = 0; round < kRounds; ++round) {
            EXPECT_EQ(together[t * kRounds + round], alone[t * kRounds + round])
                << "thread " << t << ", round " << round << ": other bits than the same run alone";
            if (round > 0) {
                EXPECT_EQ(alone[t * kRounds + round], alone[t * kRounds]) << "runs differ";
            }
        }
    }
}

}  // namespace
