// A step whose C++ heap fails returns OUT_OF_MEMORY, restores that cloth and leaves the world working.
//
// The CG reference solver is the one part of a step that allocates, and
// from the C++ heap, not from the world's allocator (cloth.h, cloth_step).
// This program replaces the global operator new with one that can be told
// to fail, and checks the contract: the step returns
// CLOTH_ERROR_OUT_OF_MEMORY, the CG cloth is restored bit for bit, a JACOBI
// cloth in the same world still advances, and once the heap works again
// the CG cloth steps and a new cloth can be created. (Allocation failures
// through the world's allocator are covered by tests/capi/bad_input/ and,
// at random points of random call sequences, by the fuzz harness.)
#include <cloth/cloth.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <new>
#include <string>

#include "support/contract.h"
#include "support/contract_gtest.h"

namespace {
bool g_fail_heap = false;  // set only around one cloth_step call, on this thread
unsigned long g_refused = 0;
}  // namespace

void* operator new(std::size_t size) {
    if (g_fail_heap) {
        ++g_refused;
        throw std::bad_alloc();
    }
    if (void* p = std::malloc(size ? size : 1)) return p;
    throw std::bad_alloc();
}
void* operator new[](std::size_t size) { return operator new(size); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }

namespace {

constexpr float kFrame = 1.0f / 60.0f;

using cloth_test::ReadState;
using cloth_test::SameFloats;
using cloth_test::SameState;

TEST(HeapFailure, CgStepWithoutHeapIsOutOfMemoryRestoresThatClothAndTheWorldKeepsWorking) {
    cloth_world_desc wd = cloth_default_world_desc();
    cloth_world_id world{};
    ASSERT_EQ(cloth_world_create(&wd, &world), CLOTH_OK);
    cloth_grid_desc gd = cloth_default_grid_desc();
    gd.columns = gd.rows = 8;
    cloth_fabric_id fabric{};
    ASSERT_EQ(cloth_fabric_create_grid(world, &gd, &fabric), CLOTH_OK);
    cloth_desc cd = cloth_default_desc();
    cd.fabric = fabric;
    cloth_id jacobi{}, cg{};
    ASSERT_EQ(cloth_create(world, &cd, &jacobi), CLOTH_OK);
    cd.solver.kind = CLOTH_SOLVER_CG;
    ASSERT_EQ(cloth_create(world, &cd, &cg), CLOTH_OK);
    const uint32_t corners[] = {0, 7};
    ASSERT_EQ(cloth_pin(jacobi, corners, 2), CLOTH_OK);
    ASSERT_EQ(cloth_pin(cg, corners, 2), CLOTH_OK);
    ASSERT_EQ(cloth_step(world, kFrame), CLOTH_OK) << cloth_get_last_error();  // both in motion

    const cloth_test::ClothState cg_before = ReadState(cg);
    const cloth_test::ClothState jacobi_before = ReadState(jacobi);
    g_fail_heap = true;
    const cloth_result r = cloth_step(world, kFrame);
    g_fail_heap = false;
    EXPECT_GT(g_refused, 0u) << "the CG step did not ask the C++ heap (the test would prove nothing)";
    EXPECT_EQ(r, CLOTH_ERROR_OUT_OF_MEMORY) << cloth_result_name(r);
    EXPECT_NE(std::string(cloth_get_last_error()), "");
    // Restored: its whole state but the diagnostics of the step that failed.
    EXPECT_TRUE(SameState(cg_before, ReadState(cg), cloth_test::Compare{/*step_diagnostics=*/false}))
        << "the CG cloth was not restored";
    EXPECT_FALSE(SameFloats("position", jacobi_before.positions, ReadState(jacobi).positions))
        << "the JACOBI cloth did not advance";
    cloth_stats stats{};
    stats.struct_size = sizeof stats;
    ASSERT_EQ(cloth_get_stats(cg, &stats), CLOTH_OK);
    EXPECT_EQ(stats.last_step_result, CLOTH_ERROR_OUT_OF_MEMORY);
    ASSERT_EQ(cloth_get_stats(jacobi, &stats), CLOTH_OK);
    EXPECT_EQ(stats.last_step_result, CLOTH_OK);

    // The heap is back: the CG cloth advances and a new cloth can be made.
    EXPECT_EQ(cloth_step(world, kFrame), CLOTH_OK) << cloth_get_last_error();
    EXPECT_FALSE(SameFloats("position", cg_before.positions, ReadState(cg).positions));
    cloth_id another{};
    EXPECT_EQ(cloth_create(world, &cd, &another), CLOTH_OK);
    EXPECT_EQ(cloth_step(world, kFrame), CLOTH_OK) << cloth_get_last_error();
    EXPECT_EQ(cloth_world_destroy(world), CLOTH_OK);
}

}  // namespace
