// What the fabric builders share (fabric.cpp: grids and the common tail;
// mesh_fabric.cpp: triangle meshes; obj_loader.cpp reads into the mesh
// builder). Internal to src/fabric/.
#pragma once

#include <cstdint>
#include <vector>

#include "fabric/fabric.h"

namespace cloth {

// A spring between particles i and j, before the fabric's arrays exist.
struct SpringSpec {
    uint32_t i, j;
    SpringKind kind;
};

// Shared tail of every builder: validates the geometry, computes rest
// lengths, lumped areas and the incidence lists.
Status finish_fabric(const std::vector<SpringSpec>& springs, Fabric& f);

// A grid's triangles and springs over rest positions already in f (cols x
// rows of them, row-major, in one plane), then finish_fabric: the grid
// builder's tail, and a fabric level's (fabric_levels.cpp).
Status build_grid_topology(uint32_t cols, uint32_t rows, uint32_t spring_kinds, Fabric& f);

bool finite3(const float* v);
// Within CLOTH_MAX_COORDINATE (cloth.h, "Coordinates"); v is finite.
bool within_range3(const float* v);

}  // namespace cloth
