// A grid fabric's levels of detail (fabric/fabric_levels.h): how many and
// how large, each a grid fabric of its own with the full fabric's spring
// kinds and rest lengths between its nodes, areas that sum to the full
// fabric's, and the transfer: restriction keeps mass and momentum, any
// affine map of the rest shape (a flat sheet) prolongs back exactly, pins
// carry to the nodes of their blocks.
#include "fabric/fabric_levels.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "fabric/grid_coarsening.h"
#include "test_support.h"

namespace cloth {
namespace {

using cloth::testing::heap;
using cloth::testing::make_grid;

Vec3Soa soa_of(const HostVector<Vec3>& points) {
    Vec3Soa out(heap());
    out.resize(points.size());
    for (size_t i = 0; i < points.size(); ++i) out.set(i, points[i]);
    return out;
}

TEST(FabricLevels, AGridHasLevelsOfAQuarterTheParticlesDownToThreeColumnsAndRows) {
    const auto big = make_grid(64, 64);
    ASSERT_EQ(big->levels.size(), 3u);
    const uint32_t sides[] = {32, 16, 8};
    for (size_t k = 0; k < 3; ++k) {
        EXPECT_EQ(big->levels[k]->columns, sides[k]);
        EXPECT_EQ(big->levels[k]->rows, sides[k]);
        EXPECT_EQ(big->levels[k]->fabric->particle_count(), sides[k] * sides[k]);
        EXPECT_EQ(big->levels[k]->node_count(), sides[k] * sides[k]);
    }
    const auto flag = make_grid(16, 11);  // odd rows: the last row of blocks is one particle high
    ASSERT_EQ(flag->levels.size(), 2u);
    EXPECT_EQ(flag->levels[0]->columns, 8u);
    EXPECT_EQ(flag->levels[0]->rows, 6u);
    EXPECT_EQ(flag->levels[1]->columns, 4u);
    EXPECT_EQ(flag->levels[1]->rows, 3u);
    EXPECT_TRUE(make_grid(4, 9)->levels.empty()) << "fewer than 5 columns";
    EXPECT_TRUE(cloth::testing::make_mesh_from_grid(16, 16)->levels.empty()) << "meshes have no levels";
}

TEST(FabricLevels, ALevelIsAGridWithTheFullKindsAndRestLengthsBetweenItsNodes) {
    for (uint32_t kinds :
         {uint32_t{CLOTH_SPRING_ALL}, uint32_t{CLOTH_SPRING_STRUCTURAL | CLOTH_SPRING_BEND}}) {
        const auto full = make_grid(13, 10, kinds);
        for (const auto& level : full->levels) {
            const Fabric& f = *level->fabric;
            const uint32_t c = level->columns, r = level->rows;
            EXPECT_EQ(f.springs_of_kind[kStructural], (c - 1) * r + c * (r - 1));
            EXPECT_EQ(f.springs_of_kind[kShear], (kinds & CLOTH_SPRING_SHEAR) ? 2 * (c - 1) * (r - 1) : 0u);
            EXPECT_EQ(f.springs_of_kind[kBend], (c - 2) * r + c * (r - 2));
            EXPECT_EQ(f.triangle_count(), 2 * (c - 1) * (r - 1));
            EXPECT_EQ(f.grid_families.size(), full->grid_families.size());
            uint32_t columns = 0, rows = 0;
            ASSERT_TRUE(grid_shape(f, columns, rows));
            EXPECT_EQ(columns, c);
            EXPECT_EQ(rows, r);
            for (uint32_t s = 0; s < f.spring_count(); ++s) {
                const float length =
                    (f.rest_positions[f.spring_second[s]] - f.rest_positions[f.spring_first[s]]).norm();
                EXPECT_NEAR(f.spring_rest_length[s], length, 1e-6f);
            }
        }
    }
}

TEST(FabricLevels, EachLevelsAreasAndMassesSumToTheFullFabrics) {
    const auto full = make_grid(21, 14);
    double total = 0;
    for (float a : full->rest_area) total += a;
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> mass_of(0.001f, 0.01f);
    std::vector<float> mass(full->particle_count());
    double mass_total = 0;
    for (float& m : mass) mass_total += (m = mass_of(rng));
    for (const auto& level : full->levels) {
        double area = 0;
        for (float a : level->fabric->rest_area) area += a;
        EXPECT_NEAR(area, total, 1e-6 * total);
        std::vector<float> node_mass(level->node_count());
        restrict_masses(*level, mass.data(), node_mass.data());
        double sum = 0;
        for (float m : node_mass) sum += m;
        EXPECT_NEAR(sum, mass_total, 1e-6 * mass_total);
    }
}

TEST(FabricLevels, RestrictionKeepsTotalMassAndMomentum) {
    const auto full = make_grid(32, 24);
    const uint32_t n = full->particle_count();
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> mass_of(0.0005f, 0.002f), speed(-3.0f, 3.0f);
    std::vector<float> mass(n);
    Vec3Soa v(heap());
    v.resize(n);
    Eigen::Vector3d momentum = Eigen::Vector3d::Zero();
    double mass_total = 0;
    for (uint32_t i = 0; i < n; ++i) {
        mass[i] = mass_of(rng);
        v.set(i, Vec3(speed(rng), speed(rng), speed(rng)));
        mass_total += mass[i];
        momentum += double(mass[i]) * v.get(i).cast<double>();
    }
    for (const auto& level : full->levels) {
        std::vector<float> node_mass(level->node_count());
        Vec3Soa node_v(heap());
        node_v.resize(level->node_count());
        restrict_masses(*level, mass.data(), node_mass.data());
        restrict_velocities(*level, mass.data(), v, node_v);
        Eigen::Vector3d node_momentum = Eigen::Vector3d::Zero();
        double node_total = 0;
        for (uint32_t node = 0; node < level->node_count(); ++node) {
            node_total += node_mass[node];
            node_momentum += double(node_mass[node]) * node_v.get(node).cast<double>();
        }
        EXPECT_NEAR(node_total, mass_total, 1e-6 * mass_total);
        // Float precision of the sums: each term to 1e-7, the total mass and speeds of a few m/s.
        const double tolerance = 1e-6 * mass_total * 3.0;
        for (int a = 0; a < 3; ++a) EXPECT_NEAR(node_momentum[a], momentum[a], tolerance) << "axis " << a;
    }
}

TEST(FabricLevels, AFlatSheetMovedTurnedOrStretchedRestrictsAndProlongsBackExactly) {
    const auto full = make_grid(19, 14);
    const uint32_t n = full->particle_count();
    const Eigen::Matrix3f turn =
        Eigen::AngleAxisf(0.7f, Vec3(0.3f, 1.0f, -0.4f).normalized()).toRotationMatrix();
    Eigen::Matrix3f stretch = Eigen::Matrix3f::Identity();
    stretch(0, 0) = 1.3f;
    stretch(1, 0) = 0.2f;
    const Eigen::Matrix3f maps[] = {Eigen::Matrix3f::Identity(), turn, turn * stretch};
    for (const Eigen::Matrix3f& map : maps) {
        Vec3Soa x(heap()), back(heap());
        x.resize(n);
        back.resize(n);
        for (uint32_t i = 0; i < n; ++i) x.set(i, map * full->rest_positions[i] + Vec3(2.0f, -1.0f, 0.5f));
        for (const auto& level : full->levels) {
            Vec3Soa node_x(heap());
            node_x.resize(level->node_count());
            restrict_positions(*level, x, node_x);
            prolong(*level, node_x, back);
            for (uint32_t i = 0; i < n; ++i)
                EXPECT_LT((back.get(i) - x.get(i)).norm(), 2e-6f) << "particle " << i;
        }
    }
}

TEST(FabricLevels, ANodeIsPinnedIfAnyOfItsParticlesIsAndTargetsItsBlocksRestMean) {
    const auto full = make_grid(12, 9);
    const uint32_t n = full->particle_count(), columns = 12;
    const Vec3Soa rest = soa_of(full->rest_positions);
    std::vector<float> pinned(n, 0.0f);
    for (uint32_t r = 0; r < 9; ++r) pinned[r * columns] = 1.0f;  // the left column
    pinned[5 * columns + 7] = 1.0f;                               // and one inside
    for (const auto& level : full->levels) {
        std::vector<float> node_pinned(level->node_count());
        Vec3Soa node_target(heap());
        node_target.resize(level->node_count());
        restrict_pins(*level, pinned.data(), rest, rest, node_pinned.data(), node_target);
        for (uint32_t node = 0; node < level->node_count(); ++node) {
            bool any = false;
            for (uint32_t k = level->child_start[node]; k < level->child_start[node + 1]; ++k)
                any = any || pinned[level->child[k]] != 0.0f;
            EXPECT_EQ(node_pinned[node] != 0.0f, any) << "node " << node;
            if (any) {
                // Targets at rest: the node's target is its rest position.
                EXPECT_LT((node_target.get(node) - level->fabric->rest_positions[node]).norm(), 1e-6f);
            }
        }
    }
    // A pin's target moved: its node's target moves by the pin's share of the block's area.
    const auto& level = *full->levels[0];
    Vec3Soa target = rest;
    const Vec3 shift(0.0f, 0.0f, 0.1f);
    target.set(0, rest.get(0) + shift);
    std::vector<float> node_pinned(level.node_count());
    Vec3Soa node_target(heap());
    node_target.resize(level.node_count());
    restrict_pins(level, pinned.data(), target, rest, node_pinned.data(), node_target);
    float share = 0;
    for (uint32_t k = level.child_start[0]; k < level.child_start[1]; ++k)
        if (level.child[k] == 0) share = level.child_area_weight[k];
    EXPECT_GT(share, 0.0f);
    EXPECT_LT((node_target.get(0) - (level.fabric->rest_positions[0] + share * shift)).norm(), 1e-6f);
}

}  // namespace
}  // namespace cloth
