// The fixture of the C API bad-input tests (tests/capi/bad_input/*_test.cpp):
// a world with an 8x8 grid fabric and two cloths with pins and wind,
// stepped a few frames; an identical twin world no test touches; and ids
// of every bad kind (stale in a re-used slot, stale in a free slot, of a
// destroyed world).
//
// Every rejected call is checked the same way (EXPECT_REJECTED, from
// support/contract_gtest.h): its specific code; on a fresh thread the last
// error is "" before it and its message after it; the world's log got one
// error with that code and message; nothing changed: both cloths' whole
// state bit for bit, the world's memory, the output arguments (filled with
// a pattern before each call). At the end of each test the world and its
// twin are stepped together and must stay bit-identical, which catches
// hidden state (gravity, wind, aerodynamics, spring parameters, pin
// targets) that a failed call changed.
//
// Where the header leaves a code open, the intended mapping is:
//   NaN/Inf -> CLOTH_ERROR_NOT_FINITE; negative or out-of-range value ->
//   CLOTH_ERROR_INVALID_VALUE; counts -> CLOTH_ERROR_INVALID_COUNT; indices ->
//   CLOTH_ERROR_INDEX_OUT_OF_RANGE; read buffer too small ->
//   CLOTH_ERROR_INVALID_COUNT.
#pragma once

#include <cloth/cloth.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "support/contract.h"
#include "support/contract_gtest.h"
#include "support/counting_allocator.h"

namespace cloth_bad_input {

using cloth_test::AllFinite;
using cloth_test::ClothState;
using cloth_test::CountingAllocator;
using cloth_test::LogEntry;
using cloth_test::ReadState;
using cloth_test::result_name;
using cloth_test::SameFloats;
using cloth_test::SameState;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr uint32_t kColumns = 8;
constexpr uint32_t kRows = 8;
constexpr uint32_t kParticles = kColumns * kRows;
constexpr uint32_t kFloats = 3 * kParticles;
constexpr uint32_t kMaxCloths = 3;
constexpr uint32_t kMaxFabrics = 3;
constexpr float kFrame = 1.0f / 60.0f;

// A 1 m x 1 m square in the x-z plane, two triangles.
extern const float kQuadPositions[12];
extern const uint32_t kQuadIndices[6];
cloth_mesh_desc QuadMesh();
cloth_grid_desc SmallGrid();  // kColumns x kRows

// A file in the test's temporary directory.
std::string WriteTempFile(const std::string& name, const std::string& text);

// For EXPECT_EQ on ids: the header's cloth_*_id_equal.
bool operator==(const cloth_id& a, const cloth_id& b);
bool operator==(const cloth_fabric_id& a, const cloth_fabric_id& b);

struct Scene {
    CountingAllocator host;
    cloth_world_id world{};
    cloth_fabric_id fabric{};        // the 8x8 grid the cloths use
    cloth_fabric_id other_fabric{};  // re-uses stale_fabric's slot
    cloth_fabric_id stale_fabric{};  // destroyed; its slot now holds other_fabric
    cloth_fabric_id freed_fabric{};  // destroyed; its slot is free
    cloth_id cloth{};                // main cloth: corners of the top row pinned
    cloth_id other{};                // second cloth: whole top row pinned; re-uses stale_cloth's slot
    cloth_id stale_cloth{};          // destroyed; its slot now holds `other`
    cloth_id freed_cloth{};          // destroyed; its slot is free
};

class BadInput : public ::testing::Test {
  protected:
    void SetUp() override;
    void TearDown() override;

    // Output arguments: filled with a pattern before each call; a rejected
    // call must leave them as they were.
    struct Outs {
        cloth_world_id world;
        cloth_fabric_id fabric;
        cloth_id cloth;
        uint32_t count;
        unsigned char pinned_byte;  // a flag output; only compared as a byte
        cloth_solver_settings solver;
        cloth_stats stats;
        float floats[kFloats + 8];
        uint32_t uints[3 * 2 * (kColumns - 1) * (kRows - 1) + 8];
    };
    cloth_test::FlagOut OutPinned() { return {&outs_.pinned_byte}; }

    // See EXPECT_REJECTED in support/contract_gtest.h.
    void ExpectRejected(cloth_result expected, const std::string& what,
                        const std::function<cloth_result()>& call,
                        cloth_test::Logged logged = cloth_test::Logged::kYes);

    cloth_desc ValidClothDesc() const;
    cloth_world_desc HostWorldDesc(CountingAllocator* host) const { return host->world_desc(); }

    Scene a_;                       // the world every test works on
    Scene b_;                       // its twin, never touched by a test
    cloth_test::Watch watch_;       // a_: both cloths, its allocator, outs_
    cloth_test::Watch twin_watch_;  // b_: both cloths
    cloth_world_id dead_world_{};
    cloth_fabric_id dead_fabric_{};
    cloth_id dead_cloth_{};
    Outs outs_{};
    bool check_twin_ = true;

    void ResetOuts();

  private:
    void BuildScene(Scene& s);
    void MakeDeadWorld();
};

// The particle count must fit the uint32 float capacity of cloth_read_positions
// (3 * count <= UINT32_MAX), so larger grids are "too large" counts. A library
// that does not check would try to build them; these run in a child process.
class BadInputDeathTest : public BadInput {
  protected:
    // In the child: makes the call and prints "result=NAME;contract=kept;"
    // if every clause of the rejection contract held, else what broke.
    [[noreturn]] void RejectInChild(cloth_result expected, const std::function<cloth_result()>& call);
};

#define EXPECT_REJECTED_IN_CHILD(expected, call)                                          \
    EXPECT_EXIT(RejectInChild((expected), [&]() -> cloth_result { return (call); }),      \
                ::testing::ExitedWithCode(0),                                             \
                std::string("result=") + cloth_result_name(expected) + ";contract=kept;") \
        << #call

// Mutations that make any description invalid: zeroed, struct sizes no
// version of the header can produce, and a damaged cookie.
template <typename Desc>
std::vector<std::pair<std::string, Desc>> BrokenDescs(const Desc& valid) {
    std::vector<std::pair<std::string, Desc>> out;
    Desc zero;
    std::memset(&zero, 0, sizeof zero);
    out.emplace_back("memset to zero", zero);
    Desc d = valid;
    d.struct_size = 0;
    out.emplace_back("struct_size 0", d);
    d = valid;
    d.struct_size = sizeof(Desc) - 1;
    out.emplace_back("struct_size sizeof - 1", d);
    d = valid;
    d.struct_size = sizeof(Desc) + 1;
    out.emplace_back("struct_size sizeof + 1", d);
    d = valid;
    d.struct_size = UINT32_MAX;
    out.emplace_back("struct_size UINT32_MAX", d);
    d = valid;
    d.internal_cookie ^= 0x1u;
    out.emplace_back("internal_cookie changed", d);
    d = valid;
    d.internal_cookie = 0;
    out.emplace_back("internal_cookie 0 (filled by hand)", d);
    return out;
}

// Out-of-range values of one struct, each with the code it must get.
template <typename T>
using BadValues = std::vector<std::tuple<std::string, std::function<void(T&)>, cloth_result>>;

// Solver settings out of their documented ranges (cloth_create and cloth_set_solver).
BadValues<cloth_solver_settings> BadSolver();
// Aerodynamic parameters out of range (cloth_create and cloth_set_aero).
BadValues<cloth_aero_params> BadAero();

}  // namespace cloth_bad_input
