// How a grid fabric coarsens: 2 x 2 blocks of particles, each one node of
// the next level. One definition shared by the default solver's multigrid
// (solve/multigrid_levels.cpp), whose V-cycle runs on these blocks, and by
// a fabric's levels of detail (fabric/fabric_levels.h), which step a cloth
// on them, so a level of detail is the multigrid's own coarser copy.
#pragma once

#include <algorithm>
#include <cstdint>

#include "base/host_allocator.h"
#include "fabric/fabric.h"

namespace cloth {

// The next level's shape: a block of 2 x 2, the last column (row) alone
// when the count is odd.
inline uint32_t coarse_grid_extent(uint32_t extent) { return (extent + 1) / 2; }

// 2 x 2 blocks of a columns x rows grid: aggregate[particle] is its block's
// node (row-major over the coarse grid); returns the coarse node count.
inline uint32_t aggregate_grid(uint32_t columns, uint32_t rows, HostVector<uint32_t>& aggregate) {
    const uint32_t coarse_columns = coarse_grid_extent(columns);
    aggregate.resize(size_t{columns} * rows);
    for (uint32_t r = 0; r < rows; ++r) {
        for (uint32_t c = 0; c < columns; ++c) aggregate[r * columns + c] = (r / 2) * coarse_columns + c / 2;
    }
    return coarse_columns * coarse_grid_extent(rows);
}

// The grid shape of a grid fabric with structural springs: its vertical
// structural family joins p to p + columns (a chain has only the offset 1).
// False for mesh fabrics and grids without structural springs.
inline bool grid_shape(const Fabric& fabric, uint32_t& columns, uint32_t& rows) {
    const uint32_t n = fabric.particle_count();
    uint32_t widest = 0;
    bool structural = false;
    for (const SpringFamily& family : fabric.grid_families) {
        if (family.kind != kStructural) continue;
        structural = true;
        widest = std::max(widest, family.offset);
    }
    if (!structural) return false;
    columns = widest > 1 ? widest : n;
    rows = n / columns;
    return columns * rows == n;
}

}  // namespace cloth
