// A C API cloth for tests that try the library as a host would.
#pragma once

#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "base/math.h"
#include "cloth/cloth.h"

namespace cloth::testing {

// The cloth's stats now (cloth_get_stats, checked).
inline cloth_stats stats_of(cloth_id cloth) {
    cloth_stats s;
    std::memset(&s, 0, sizeof s);
    s.struct_size = sizeof s;
    EXPECT_EQ(cloth_get_stats(cloth, &s), CLOTH_OK);
    return s;
}

// A 32 x 32 cloth of the C API's defaults, pinned at its two top corners.
// `adjust` may change the cloth's description before it is created.
struct PinnedCloth {
    cloth_world_id world{};
    cloth_id cloth{};
    explicit PinnedCloth(float particle_mass = 0.0f)
        : PinnedCloth([particle_mass](cloth_desc& desc) { desc.particle_mass = particle_mass; }) {}
    template <class Adjust>
    explicit PinnedCloth(Adjust adjust) {
        cloth_world_desc world_desc = cloth_default_world_desc();
        EXPECT_EQ(cloth_world_create(&world_desc, &world), CLOTH_OK);
        cloth_grid_desc grid = cloth_default_grid_desc();
        cloth_fabric_id fabric{};
        EXPECT_EQ(cloth_fabric_create_grid(world, &grid, &fabric), CLOTH_OK);
        cloth_desc desc = cloth_default_desc();
        desc.fabric = fabric;
        adjust(desc);
        EXPECT_EQ(cloth_create(world, &desc, &cloth), CLOTH_OK);
        const uint32_t pins[] = {0, 31};
        EXPECT_EQ(cloth_pin(cloth, pins, 2), CLOTH_OK);
    }
    ~PinnedCloth() { cloth_world_destroy(world); }
    cloth_stats stats() const { return stats_of(cloth); }
    cloth::Vec3 centroid() const {
        std::vector<float> x(3 * 32 * 32);
        EXPECT_EQ(cloth_read_positions(cloth, x.data(), static_cast<uint32_t>(x.size())), CLOTH_OK);
        cloth::Vec3 sum = cloth::Vec3::Zero();
        for (size_t i = 0; i < x.size(); i += 3) sum += cloth::Vec3(x[i], x[i + 1], x[i + 2]);
        return sum / (32.0f * 32.0f);
    }
};

}  // namespace cloth::testing
