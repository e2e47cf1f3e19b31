// Topology: spring counts per kind, lumped masses, meshes and OBJ files.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "test_support.h"

namespace cloth {
namespace {

TEST(Fabric, GridHasTheExpectedSpringsOfEachKind) {
    const uint32_t c = 7, r = 5;
    auto fabric = cloth::testing::make_grid(c, r);
    EXPECT_EQ(fabric->particle_count(), c * r);
    EXPECT_EQ(fabric->triangle_count(), 2 * (c - 1) * (r - 1));
    EXPECT_EQ(fabric->springs_of_kind[kStructural], (c - 1) * r + c * (r - 1));
    EXPECT_EQ(fabric->springs_of_kind[kShear], 2 * (c - 1) * (r - 1));
    EXPECT_EQ(fabric->springs_of_kind[kBend], (c - 2) * r + c * (r - 2));
}

TEST(Fabric, SwitchedOffKindsCreateNoSprings) {
    auto fabric = cloth::testing::make_grid(6, 6, CLOTH_SPRING_STRUCTURAL);
    EXPECT_EQ(fabric->springs_of_kind[kShear], 0u);
    EXPECT_EQ(fabric->springs_of_kind[kBend], 0u);
    EXPECT_EQ(fabric->spring_count(), fabric->springs_of_kind[kStructural]);
}

TEST(Fabric, LumpedAreasSumToTheClothArea) {
    auto fabric = cloth::testing::make_grid(9, 13);
    double area = 0;
    for (float a : fabric->rest_area) area += a;
    EXPECT_NEAR(area, 1.0, 1e-5);  // 1 m x 1 m
    // A corner touches one or two triangles, an interior particle six: masses differ accordingly.
    EXPECT_LT(fabric->rest_area[0], fabric->rest_area[9 * 6 + 4]);
}

TEST(Fabric, PaddedSlotsListEveryIncidentSpringOnceInIncreasingOrderWithSignAndOtherEnd) {
    // 600 particles: three slot chunks, the last one partial.
    auto fabric = cloth::testing::make_grid(30, 20);
    const PaddedSlots& slots = fabric->spring_slots;
    std::vector<std::vector<uint32_t>> seen(fabric->particle_count());
    slots.for_each_slot(fabric->particle_count(), 0, fabric->particle_count(),
                        [&](uint32_t lo, uint32_t hi, int64_t base, uint32_t) {
                            for (uint32_t p = lo; p < hi; ++p) {
                                const size_t slot = static_cast<size_t>(base + p);
                                const uint32_t s = slots.item[slot];
                                if (s == fabric->spring_count()) {  // padding
                                    EXPECT_EQ(slots.sign[slot], 0.0f);
                                    continue;
                                }
                                const bool first = fabric->spring_first[s] == p;
                                ASSERT_TRUE(first || fabric->spring_second[s] == p);
                                EXPECT_EQ(slots.other[slot],
                                          first ? fabric->spring_second[s] : fabric->spring_first[s]);
                                EXPECT_EQ(slots.sign[slot], first ? 1.0f : -1.0f);
                                seen[p].push_back(s);
                            }
                        });
    size_t total = 0;
    for (uint32_t p = 0; p < fabric->particle_count(); ++p) {
        EXPECT_TRUE(std::is_sorted(seen[p].begin(), seen[p].end())) << "particle " << p;
        EXPECT_EQ(seen[p].size(), fabric->incidence_offset[p + 1] - fabric->incidence_offset[p]);
        total += seen[p].size();
    }
    EXPECT_EQ(total, 2 * fabric->spring_count()) << "every spring once at each end";
}

TEST(Fabric, OneHighValenceVertexPadsOnlyItsOwnChunk) {
    // A fan: vertex 0 joined to a rim of 2000 vertices.
    const uint32_t rim = 2000;
    std::vector<float> positions = {0, 0, 0};
    std::vector<uint32_t> indices;
    for (uint32_t i = 0; i < rim; ++i) {
        const float angle = 6.2831853f * static_cast<float>(i) / rim;
        positions.insert(positions.end(), {std::cos(angle), std::sin(angle), 0.0f});
        indices.insert(indices.end(), {0, 1 + i, 1 + (i + 1) % rim});
    }
    Fabric fan(cloth::testing::heap());
    ASSERT_TRUE(
        build_mesh_fabric(positions.data(), rim + 1, indices.data(), rim, CLOTH_SPRING_STRUCTURAL, fan).ok());
    // Unchunked padding would need (rim + 1) * rim slots (4M); per chunk it stays near the real count.
    EXPECT_LT(fan.spring_slots.item.size(), 3 * PaddedSlots::kChunk * static_cast<size_t>(rim) / 2);
    EXPECT_LT(fan.spring_slots.item.size(), static_cast<size_t>(rim + 1) * rim / 4);
}

// Two triangles sharing the edge (1, 2) of the unit square.
const float kSquare[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
const uint32_t kTwoTriangles[] = {0, 1, 2, 2, 1, 3};

TEST(Fabric, MeshGetsEdgeSpringsAndOneBendSpringAcrossTheSharedEdge) {
    Fabric fabric(cloth::testing::heap());
    ASSERT_TRUE(build_mesh_fabric(kSquare, 4, kTwoTriangles, 2, CLOTH_SPRING_ALL, fabric).ok());
    EXPECT_EQ(fabric.springs_of_kind[kStructural], 5u);
    EXPECT_EQ(fabric.springs_of_kind[kShear], 0u);
    ASSERT_EQ(fabric.springs_of_kind[kBend], 1u);
    uint32_t s = 0;  // the bend spring joins the two opposite corners 0 and 3
    while (fabric.spring_kind[s] != kBend) ++s;
    EXPECT_EQ(std::min(fabric.spring_first[s], fabric.spring_second[s]), 0u);
    EXPECT_EQ(std::max(fabric.spring_first[s], fabric.spring_second[s]), 3u);
    EXPECT_NEAR(fabric.spring_rest_length[s], std::sqrt(2.0f), 1e-6f);
}

TEST(Fabric, MeshRejectsDegenerateTriangles) {
    Fabric fabric(cloth::testing::heap());
    const float collinear[] = {0, 0, 0, 1, 0, 0, 2, 0, 0};
    const uint32_t tri[] = {0, 1, 2};
    EXPECT_EQ(build_mesh_fabric(collinear, 3, tri, 1, CLOTH_SPRING_ALL, fabric).code,
              CLOTH_ERROR_DEGENERATE_GEOMETRY);
    const uint32_t repeated[] = {0, 1, 1};
    Fabric other(cloth::testing::heap());
    EXPECT_EQ(build_mesh_fabric(kSquare, 4, repeated, 1, CLOTH_SPRING_ALL, other).code,
              CLOTH_ERROR_DEGENERATE_GEOMETRY);
}

TEST(Fabric, ObjFileLoadsLikeTheSameMesh) {
    const std::string path = ::testing::TempDir() + "cloth_fabric_test_quad.obj";
    {
        std::ofstream obj(path);
        obj << "# unit square as one quad face\n"
               "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
               "f 1 2 3 4\n";
    }
    Fabric fabric(cloth::testing::heap());
    const Status status = build_obj_fabric(path.c_str(), CLOTH_SPRING_ALL, fabric);
    ASSERT_TRUE(status.ok()) << status.message;
    EXPECT_EQ(fabric.particle_count(), 4u);
    EXPECT_EQ(fabric.triangle_count(), 2u);
    EXPECT_EQ(fabric.springs_of_kind[kStructural], 5u);
    EXPECT_EQ(fabric.springs_of_kind[kBend], 1u);
    std::remove(path.c_str());

    Fabric missing(cloth::testing::heap());
    EXPECT_EQ(build_obj_fabric("/nonexistent/cloth.obj", CLOTH_SPRING_ALL, missing).code, CLOTH_ERROR_IO);
}

}  // namespace
}  // namespace cloth

namespace cloth {
namespace {

TEST(Fabric, GridFamiliesHoldExactlyTheGridSprings) {
    const uint32_t c = 6, r = 5;
    auto fabric = cloth::testing::make_grid(c, r);
    ASSERT_EQ(fabric->grid_families.size(), 6u);
    uint32_t per_kind[kSpringKindCount] = {0, 0, 0};
    for (const SpringFamily& family : fabric->grid_families) {
        for (uint32_t p = 0; p < c * r; ++p) {
            if (family.mask[p] == 0.0f) continue;
            ASSERT_LT(p + family.offset, c * r);
            ++per_kind[family.kind];
            // The spring's rest length is the distance at rest.
            const float rest = (fabric->rest_positions[p + family.offset] - fabric->rest_positions[p]).norm();
            EXPECT_NEAR(family.rest_length[p], rest, 1e-6f);
        }
    }
    for (int k = 0; k < kSpringKindCount; ++k)
        EXPECT_EQ(per_kind[k], fabric->springs_of_kind[k]) << "kind " << k;
}

}  // namespace
}  // namespace cloth
