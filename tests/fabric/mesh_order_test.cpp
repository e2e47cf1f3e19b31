// Mesh fabrics store their particles in a spatial (Morton) order so that
// each group of consecutive particles is a compact patch whatever order
// the host's mesh came in, while every C API call keeps speaking the
// host's vertex indices.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

#include "fabric/fabric.h"
#include "step/cloth_instance.h"
#include "test_support.h"

namespace cloth {
namespace {

// A side x side sheet (1 m square, in the xy plane) as a triangle mesh
// whose vertex k is grid vertex order[k].
struct Sheet {
    std::vector<float> positions;
    std::vector<uint32_t> indices;
};

Sheet sheet(uint32_t side, const std::vector<uint32_t>& order) {
    std::vector<uint32_t> slot_of(order.size());
    for (uint32_t k = 0; k < order.size(); ++k) slot_of[order[k]] = k;
    Sheet s;
    s.positions.resize(3 * order.size());
    for (uint32_t k = 0; k < order.size(); ++k) {
        const uint32_t g = order[k];
        s.positions[3 * k] = static_cast<float>(g % side) / static_cast<float>(side - 1);
        s.positions[3 * k + 1] = 1.0f - static_cast<float>(g / side) / static_cast<float>(side - 1);
        s.positions[3 * k + 2] = 0.0f;
    }
    for (uint32_t r = 0; r + 1 < side; ++r) {
        for (uint32_t c = 0; c + 1 < side; ++c) {
            const uint32_t a = r * side + c;
            for (uint32_t g : {a, a + side, a + 1, a + 1, a + side, a + side + 1})
                s.indices.push_back(slot_of[g]);
        }
    }
    return s;
}

std::vector<uint32_t> shuffled(uint32_t n, unsigned seed) {
    std::vector<uint32_t> order(n);
    std::iota(order.begin(), order.end(), 0u);
    std::shuffle(order.begin(), order.end(), std::mt19937(seed));
    return order;
}

// Largest bounding-box diagonal over the groups of kChunk consecutive particles.
float widest_group(const std::vector<Vec3>& points) {
    float widest = 0;
    for (size_t first = 0; first < points.size(); first += PaddedSlots::kChunk) {
        const size_t last = std::min(points.size(), first + PaddedSlots::kChunk);
        Vec3 lo = points[first], hi = points[first];
        for (size_t i = first; i < last; ++i) {
            lo = lo.cwiseMin(points[i]);
            hi = hi.cwiseMax(points[i]);
        }
        widest = std::max(widest, (hi - lo).norm());
    }
    return widest;
}

TEST(MeshOrder, GroupsOfAShuffledMeshAreCompactPatches) {
    const uint32_t side = 64;
    const Sheet s = sheet(side, shuffled(side * side, 3));
    std::vector<Vec3> host_order;
    for (uint32_t v = 0; v < side * side; ++v)
        host_order.emplace_back(s.positions[3 * v], s.positions[3 * v + 1], s.positions[3 * v + 2]);
    EXPECT_GT(widest_group(host_order), 1.3f) << "in the host's shuffled order a group spans the sheet";

    Fabric fabric(testing::heap());
    ASSERT_TRUE(build_mesh_fabric(s.positions.data(), side * side, s.indices.data(),
                                  static_cast<uint32_t>(s.indices.size() / 3), CLOTH_SPRING_ALL, fabric)
                    .ok());
    const std::vector<Vec3> stored(fabric.rest_positions.begin(), fabric.rest_positions.end());
    // 256 particles of a 64 x 64 sheet: a 16 x 16 patch has a diagonal of 0.34 m.
    EXPECT_LT(widest_group(stored), 0.5f) << "stored groups are patches";
    for (uint32_t v = 0; v < side * side; ++v) {
        EXPECT_EQ(fabric.vertex(fabric.particle(v)), v);
        EXPECT_EQ(fabric.rest_positions[fabric.particle(v)], host_order[v]);
    }
}

// The same sheet given in grid order and shuffled: every call that takes or
// returns per-vertex data uses the host's indices, so pinning the same top
// row, stepping and reading back gives the same flag.
TEST(MeshOrder, TheCApiSpeaksTheHostsVertexIndices) {
    const uint32_t side = 24;
    std::vector<uint32_t> identity(side * side);
    std::iota(identity.begin(), identity.end(), 0u);
    const std::vector<uint32_t> order = shuffled(side * side, 11);
    std::vector<uint32_t> slot_of(order.size());
    for (uint32_t k = 0; k < order.size(); ++k) slot_of[order[k]] = k;

    struct Run {
        std::vector<float> start, end;
        std::vector<uint32_t> triangles;
        bool top_pinned = true, middle_pinned = false;
    };
    auto run = [&](const std::vector<uint32_t>& vertex_order, auto vertex_of_grid) {
        const Sheet s = sheet(side, vertex_order);
        Run out;
        cloth_world_desc wd = cloth_default_world_desc();
        cloth_world_id world{};
        EXPECT_EQ(cloth_world_create(&wd, &world), CLOTH_OK);
        cloth_mesh_desc md = cloth_default_mesh_desc();
        md.positions = s.positions.data();
        md.vertex_count = side * side;
        md.indices = s.indices.data();
        md.triangle_count = static_cast<uint32_t>(s.indices.size() / 3);
        cloth_fabric_id fabric{};
        EXPECT_EQ(cloth_fabric_create_mesh(world, &md, &fabric), CLOTH_OK);
        out.triangles.resize(s.indices.size());
        EXPECT_EQ(cloth_fabric_read_triangles(fabric, out.triangles.data(),
                                              static_cast<uint32_t>(out.triangles.size())),
                  CLOTH_OK);
        EXPECT_EQ(out.triangles, s.indices) << "triangles come back in the host's vertex indices";
        cloth_desc cd = cloth_default_desc();
        cd.fabric = fabric;
        cloth_id cloth{};
        EXPECT_EQ(cloth_create(world, &cd, &cloth), CLOTH_OK);
        out.start.resize(3 * side * side);
        EXPECT_EQ(cloth_read_positions(cloth, out.start.data(), static_cast<uint32_t>(out.start.size())),
                  CLOTH_OK);
        EXPECT_EQ(out.start, s.positions) << "positions come back in the host's vertex order";
        std::vector<uint32_t> top;
        for (uint32_t c = 0; c < side; ++c) top.push_back(vertex_of_grid(c));
        EXPECT_EQ(cloth_pin(cloth, top.data(), side), CLOTH_OK);
        const float wind[3] = {3.0f, 0.0f, 2.0f};
        EXPECT_EQ(cloth_set_wind(cloth, wind), CLOTH_OK);
        for (int frame = 0; frame < 60; ++frame) EXPECT_EQ(cloth_step(world, 1.0f / 60.0f), CLOTH_OK);
        for (uint32_t v : top) {
            bool pinned = false;
            EXPECT_EQ(cloth_is_pinned(cloth, v, &pinned), CLOTH_OK);
            out.top_pinned = out.top_pinned && pinned;
        }
        EXPECT_EQ(cloth_is_pinned(cloth, vertex_of_grid(side * side / 2), &out.middle_pinned), CLOTH_OK);
        std::vector<float> host_order(3 * side * side);
        EXPECT_EQ(cloth_read_positions(cloth, host_order.data(), static_cast<uint32_t>(host_order.size())),
                  CLOTH_OK);
        out.end.resize(host_order.size());  // back to grid order for comparison
        for (uint32_t g = 0; g < side * side; ++g)
            for (int k = 0; k < 3; ++k) out.end[3 * g + k] = host_order[3 * vertex_of_grid(g) + k];
        EXPECT_EQ(cloth_world_destroy(world), CLOTH_OK);
        return out;
    };
    const Run grid = run(identity, [](uint32_t g) { return g; });
    const Run mixed = run(order, [&](uint32_t g) { return slot_of[g]; });
    EXPECT_TRUE(grid.top_pinned && mixed.top_pinned);
    EXPECT_FALSE(grid.middle_pinned || mixed.middle_pinned);
    float largest_move = 0, largest_difference = 0;
    for (size_t i = 0; i < grid.end.size(); ++i) {
        const uint32_t g = static_cast<uint32_t>(i / 3);
        largest_move = std::max(largest_move, std::fabs(grid.end[i] - grid.start[3 * g + i % 3]));
        largest_difference = std::max(largest_difference, std::fabs(grid.end[i] - mixed.end[i]));
    }
    EXPECT_GT(largest_move, 0.05f) << "the flag moved";
    // The stored order depends on the geometry alone, so the two cloths are
    // the same cloth, bit for bit.
    EXPECT_EQ(largest_difference, 0.0f) << "and moved the same way whatever the host's vertex order";
}

}  // namespace
}  // namespace cloth
