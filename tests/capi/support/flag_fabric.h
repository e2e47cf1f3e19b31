// The C API tests' flag fabric: a grid of columns x rows particles spanning
// width along +x and height down -y (its left column is the pole side).
#pragma once

#include <cloth/cloth.h>
#include <gtest/gtest.h>

namespace cloth_test {

inline cloth_fabric_id flag_fabric(cloth_world_id world, uint32_t columns, uint32_t rows, float width,
                                   float height) {
    cloth_grid_desc gd = cloth_default_grid_desc();
    gd.columns = columns;
    gd.rows = rows;
    gd.u[0] = width;
    gd.v[1] = -height;
    cloth_fabric_id fabric{};
    EXPECT_EQ(cloth_fabric_create_grid(world, &gd, &fabric), CLOTH_OK);
    return fabric;
}

}  // namespace cloth_test
