// The product of a grid's off-diagonal 3x3 blocks with a vector, shared by
// the grid spring layout (spring_terms_grid.cpp) and the multigrid's grid
// levels (multigrid.h): family f couples p with p + offset_f through the
// symmetric block A_f[p], stored by first particle after `pad` zero
// entries (pad >= every offset; entries past n - offset_f are zero too).
#pragma once

#include <cstdint>

#include "base/soa.h"

namespace cloth {

struct GridBlocks {
    uint32_t n = 0;    // particles (nodes)
    uint32_t pad = 0;  // leading zero entries of every family
    uint32_t family_count = 0;
    const uint32_t* offsets = nullptr;       // per family
    const Sym3Soa* const* blocks = nullptr;  // per family, n + pad entries
};

// q_p = sum over families, in order, of A_f[p] x[p + offset_f] +
// A_f[p - offset_f] x[p - offset_f], for p in [begin, end). Vectorized; the
// same bits for any split of the range.
void grid_neighbour_sums(const GridBlocks& grid, const Vec3Soa& x, uint32_t begin, uint32_t end, Vec3Soa& q);

}  // namespace cloth
