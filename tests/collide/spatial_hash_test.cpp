// The spatial hash finds every pair closer than the cell size (checked
// against brute force O(n^2)), visits each neighbour once, and gives the
// same result however the key pass is split.
#include "collide/spatial_hash.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "test_support.h"

namespace cloth {
namespace {

using Pairs = std::set<std::pair<uint32_t, uint32_t>>;

Vec3Soa random_cloud(uint32_t n, float extent, float offset, unsigned seed) {
    Vec3Soa x(testing::heap());
    x.resize(n);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> uniform(offset, offset + extent);
    for (uint32_t i = 0; i < n; ++i) x.set(i, Vec3(uniform(rng), uniform(rng), uniform(rng)));
    return x;
}

Pairs brute_force(const Vec3Soa& x, float radius) {
    Pairs pairs;
    for (uint32_t i = 0; i < x.size(); ++i) {
        for (uint32_t j = i + 1; j < x.size(); ++j) {
            if ((x.get(i) - x.get(j)).squaredNorm() < radius * radius) pairs.insert({i, j});
        }
    }
    return pairs;
}

// Pairs the hash reports within `radius`, from both ends; fails on a
// neighbour visited twice or a pair seen from one end only.
Pairs hashed(const Vec3Soa& x, float radius) {
    SpatialHash hash(testing::heap());
    const uint32_t n = static_cast<uint32_t>(x.size());
    hash.reserve(n);
    hash.compute_keys(x, radius, 0, n);
    hash.sort_into_buckets(x);
    Pairs pairs, reversed;
    for (uint32_t i = 0; i < n; ++i) {
        std::vector<uint32_t> seen;
        hash.for_each_near(i, [&](uint32_t j, float xj, float yj, float zj) {
            seen.push_back(j);
            EXPECT_EQ(Vec3(xj, yj, zj), x.get(j)) << "the visit carries j's position";
            if ((x.get(i) - x.get(j)).squaredNorm() < radius * radius) {
                (i < j ? pairs : reversed).insert({std::min(i, j), std::max(i, j)});
            }
        });
        std::sort(seen.begin(), seen.end());
        EXPECT_EQ(std::adjacent_find(seen.begin(), seen.end()), seen.end()) << "particle " << i;
    }
    EXPECT_EQ(pairs, reversed) << "a pair was found from one end only";
    return pairs;
}

TEST(SpatialHash, RandomCloudsMatchBruteForce) {
    // Dense and sparse clouds, off-origin and straddling negative cells.
    struct Case {
        uint32_t n;
        float extent, offset, radius;
    } cases[] = {{1500, 1.0f, 0.0f, 0.05f}, {1500, 0.3f, -0.15f, 0.04f}, {800, 20.0f, -7.3f, 0.9f}};
    unsigned seed = 1;
    for (const Case& c : cases) {
        const Vec3Soa x = random_cloud(c.n, c.extent, c.offset, seed++);
        const Pairs expected = brute_force(x, c.radius);
        EXPECT_GT(expected.size(), 100u) << "the case must have close pairs to test";
        EXPECT_EQ(hashed(x, c.radius), expected);
    }
}

TEST(SpatialHash, CrumpledClothMatchesBruteForce) {
    // A 32x32 cloth folded into four layers 0.6 of the radius apart, with
    // noise: many pairs sit across cell borders.
    auto fabric = testing::make_grid(32, 32);
    const float spacing = 1.0f / 31.0f, radius = 1.3f * spacing;
    Vec3Soa x(testing::heap());
    x.resize(fabric->particle_count());
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> noise(-0.2f * spacing, 0.2f * spacing);
    for (uint32_t i = 0; i < fabric->particle_count(); ++i) {
        const Vec3& p = fabric->rest_positions[i];
        const float period = 0.25f, layer = std::floor(p.x() / period), t = p.x() - layer * period;
        const float folded = static_cast<int>(layer) % 2 ? period - t : t;
        x.set(i, Vec3(folded + noise(rng), p.y() + noise(rng), layer * 0.6f * radius + noise(rng)));
    }
    const Pairs expected = brute_force(x, radius);
    EXPECT_GT(expected.size(), 1000u);
    EXPECT_EQ(hashed(x, radius), expected);
}

TEST(SpatialHash, KeysDoNotDependOnTheRangeSplit) {
    const Vec3Soa x = random_cloud(999, 1.0f, -0.5f, 11);
    SpatialHash whole(testing::heap()), split(testing::heap());
    whole.reserve(999);
    split.reserve(999);
    whole.compute_keys(x, 0.07f, 0, 999);
    for (uint32_t begin = 0; begin < 999; begin += 100)
        split.compute_keys(x, 0.07f, begin, std::min(999u, begin + 100));
    whole.sort_into_buckets(x);
    split.sort_into_buckets(x);
    for (uint32_t i = 0; i < 999; ++i) {
        std::vector<uint32_t> a, b;
        whole.for_each_near(i, [&](uint32_t j, float, float, float) { a.push_back(j); });
        split.for_each_near(i, [&](uint32_t j, float, float, float) { b.push_back(j); });
        ASSERT_EQ(a, b) << "particle " << i;
    }
}

TEST(SpatialHash, NonFiniteAndFarPositionsAreClampedNotUndefined) {
    // A step that went non-finite is undone afterwards; the hash must not
    // crash or misbehave on the way (UBSan checks the float-to-int casts).
    Vec3Soa x(testing::heap());
    x.resize(4);
    x.set(0, Vec3(std::nanf(""), 0, 0));
    x.set(1, Vec3(1e30f, -1e30f, 0));
    x.set(2, Vec3(0, 0, 0));
    x.set(3, Vec3(0.01f, 0, 0));
    SpatialHash hash(testing::heap());
    hash.reserve(4);
    hash.compute_keys(x, 0.1f, 0, 4);
    hash.sort_into_buckets(x);
    bool found = false;
    hash.for_each_near(2, [&](uint32_t j, float, float, float) { found = found || j == 3; });
    EXPECT_TRUE(found);
}

}  // namespace
}  // namespace cloth
