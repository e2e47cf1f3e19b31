// Bad world descriptions and world values are rejected with their codes and change nothing.
#include <cstdint>
#include <string>
#include <vector>

#include "bad_input/fixture.h"

namespace cloth_bad_input {
namespace {

TEST_F(BadInput, WorldFunctionsRejectEachNullPointerAndChangeNothing) {
    CountingAllocator host;
    const cloth_world_desc wd = HostWorldDesc(&host);
    EXPECT_REJECTED_MAYBE_LOGGED(CLOTH_ERROR_NULL_POINTER, cloth_world_create(nullptr, &outs_.world));
    EXPECT_REJECTED_MAYBE_LOGGED(CLOTH_ERROR_NULL_POINTER, cloth_world_create(&wd, nullptr));
    EXPECT_EQ(host.live_bytes(), 0u) << "a rejected cloth_world_create kept memory";
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_world_set_gravity(a_.world, nullptr));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_world_shift_origin(a_.world, nullptr));
}

TEST_F(BadInput, CreateWorldWithADescNotFromDefaultOrAWrongSizeReturnsInvalidDesc) {
    CountingAllocator host;
    for (const auto& broken : BrokenDescs(HostWorldDesc(&host))) {
        SCOPED_TRACE(broken.first);
        const cloth_world_desc& desc = broken.second;
        EXPECT_REJECTED_MAYBE_LOGGED(CLOTH_ERROR_INVALID_DESC, cloth_world_create(&desc, &outs_.world));
    }
    EXPECT_EQ(host.live_bytes(), 0u);
}

TEST_F(BadInput, CreateWorldWithNonFiniteGravityReturnsNotFinite) {
    CountingAllocator host;
    for (int axis = 0; axis < 3; ++axis) {
        for (float bad : {kNaN, kInf, -kInf}) {
            SCOPED_TRACE("gravity[" + std::to_string(axis) + "] = " + std::to_string(bad));
            cloth_world_desc desc = HostWorldDesc(&host);
            desc.gravity[axis] = bad;
            EXPECT_REJECTED_MAYBE_LOGGED(CLOTH_ERROR_NOT_FINITE, cloth_world_create(&desc, &outs_.world));
        }
    }
    EXPECT_EQ(host.live_bytes(), 0u);
}

TEST_F(BadInput, CreateWorldWithOnlyOneOfAllocAndFreeReturnsInvalidValue) {
    CountingAllocator host;
    cloth_world_desc only_alloc = HostWorldDesc(&host);
    only_alloc.free = nullptr;
    EXPECT_REJECTED_MAYBE_LOGGED(CLOTH_ERROR_INVALID_VALUE, cloth_world_create(&only_alloc, &outs_.world));
    cloth_world_desc only_free = HostWorldDesc(&host);
    only_free.alloc = nullptr;
    EXPECT_REJECTED_MAYBE_LOGGED(CLOTH_ERROR_INVALID_VALUE, cloth_world_create(&only_free, &outs_.world));
    EXPECT_EQ(host.allocations(), 0u);
}

TEST_F(BadInput, CreateWorldWithZeroOrTooLargeTableCapacityReturnsInvalidCount) {
    CountingAllocator host;
    for (uint32_t bad : {0u, 65536u, UINT32_MAX}) {
        cloth_world_desc desc = HostWorldDesc(&host);
        desc.max_cloths = bad;
        SCOPED_TRACE("max_cloths " + std::to_string(bad));
        EXPECT_REJECTED_MAYBE_LOGGED(CLOTH_ERROR_INVALID_COUNT, cloth_world_create(&desc, &outs_.world));
        desc = HostWorldDesc(&host);
        desc.max_fabrics = bad;
        SCOPED_TRACE("max_fabrics " + std::to_string(bad));
        EXPECT_REJECTED_MAYBE_LOGGED(CLOTH_ERROR_INVALID_COUNT, cloth_world_create(&desc, &outs_.world));
    }
    EXPECT_EQ(host.live_bytes(), 0u);
}

TEST_F(BadInput, SetGravityNonFiniteReturnsNotFiniteAndKeepsTheOldGravity) {
    // The twin check at the end proves the world still uses its old gravity.
    for (int axis = 0; axis < 3; ++axis) {
        for (float bad : {kNaN, kInf, -kInf}) {
            SCOPED_TRACE("gravity[" + std::to_string(axis) + "] = " + std::to_string(bad));
            float g[3] = {0.0f, -20.0f, 0.0f};
            g[axis] = bad;
            EXPECT_REJECTED(CLOTH_ERROR_NOT_FINITE, cloth_world_set_gravity(a_.world, g));
        }
    }
}

TEST_F(BadInput, ShiftOriginNonFiniteReturnsNotFiniteAndMovesNothing) {
    for (int axis = 0; axis < 3; ++axis) {
        for (float bad : {kNaN, kInf, -kInf}) {
            SCOPED_TRACE("shift[" + std::to_string(axis) + "] = " + std::to_string(bad));
            float shift[3] = {32.0f, 0.0f, -64.0f};
            shift[axis] = bad;
            EXPECT_REJECTED(CLOTH_ERROR_NOT_FINITE, cloth_world_shift_origin(a_.world, shift));
        }
    }
}

TEST_F(BadInput, WorkerSpinOverOneSecondReturnsInvalidValue) {
    for (uint32_t spin : {1000001u, 0xFFFFFFFFu}) {
        SCOPED_TRACE("spin = " + std::to_string(spin));
        EXPECT_REJECTED(CLOTH_ERROR_INVALID_VALUE, cloth_world_set_worker_spin(a_.world, spin));
    }
}

TEST_F(BadInput, CreatingMoreThan128WorldsReturnsCapacityAndLeavesTheOthersWorking) {
    const cloth_world_desc wd = [] {
        cloth_world_desc d = cloth_default_world_desc();
        d.max_cloths = 1;
        d.max_fabrics = 1;
        return d;
    }();
    std::vector<cloth_world_id> created;
    cloth_result r = CLOTH_OK;
    for (int i = 0; i < 200; ++i) {
        cloth_world_id w{};
        r = cloth_world_create(&wd, &w);
        if (r != CLOTH_OK) break;
        created.push_back(w);
    }
    EXPECT_EQ(r, CLOTH_ERROR_CAPACITY) << result_name(r);
    EXPECT_EQ(created.size() + 2, 128u) << "the fixture holds 2 worlds; at most 128 may exist at once";
    EXPECT_REJECTED_MAYBE_LOGGED(CLOTH_ERROR_CAPACITY, cloth_world_create(&wd, &outs_.world));
    // Freeing one slot makes room for exactly one more.
    if (!created.empty()) {
        EXPECT_EQ(cloth_world_destroy(created.back()), CLOTH_OK);
        EXPECT_EQ(cloth_world_create(&wd, &created.back()), CLOTH_OK);
    }
    for (const cloth_world_id& w : created) EXPECT_EQ(cloth_world_destroy(w), CLOTH_OK);
}

TEST_F(BadInput, CreateWorldWhenTheAllocatorFailsReturnsOutOfMemoryAndLeaksNothing) {
    CountingAllocator host;
    const cloth_world_desc wd = HostWorldDesc(&host);
    cloth_world_id world{};
    bool created = false;
    for (long n = 0; n < 10000 && !created; ++n) {
        host.fail_after(n);
        SCOPED_TRACE("allocator fails after " + std::to_string(n) + " allocations");
        const cloth_test::CallOutcome o =
            cloth_test::call_on_fresh_thread([&] { return cloth_world_create(&wd, &world); });
        host.fail_after(-1);
        if (o.result == CLOTH_OK) {
            created = true;
            break;
        }
        ++cloth_test::bad_inputs();
        EXPECT_EQ(o.result, CLOTH_ERROR_OUT_OF_MEMORY) << result_name(o.result);
        EXPECT_EQ(host.live_bytes(), 0u) << "memory leaked by a failed cloth_world_create";
        ASSERT_FALSE(HasFailure());
    }
    ASSERT_TRUE(created);
    const cloth_grid_desc grid = SmallGrid();
    cloth_fabric_id fabric{};
    EXPECT_EQ(cloth_fabric_create_grid(world, &grid, &fabric), CLOTH_OK);
    EXPECT_EQ(cloth_world_destroy(world), CLOTH_OK);
    EXPECT_EQ(host.live_bytes(), 0u);
    EXPECT_TRUE(host.violations().empty());
}

}  // namespace
}  // namespace cloth_bad_input
