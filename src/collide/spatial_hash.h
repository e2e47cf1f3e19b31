// Spatial hash of particles for self-collision (paper section IV;
// docs/method.md, "Self-collision"): cubic cells of twice the search radius r, each cell
// (ix, iy, iz) hashed into a power-of-two number of buckets (about twice
// the particle count), particles counting-sorted into their buckets every
// step.
//
// Written by hand: no Debian package offers a particle hash with fixed
// memory (sized once per cloth), no allocation per frame, a result order
// that is fixed by construction (so results are bit-identical whatever
// the thread count), and range passes a job system can split. The hash
// maps in Debian (e.g. in Boost, Abseil) allocate per insert and iterate
// in an order that depends on the insert history.
//
// Three passes:
//   1. compute_keys(begin, end)  per particle, any split: cell and bucket;
//   2. sort_into_buckets(x)      serial O(n + buckets) counting sort; within
//                                a bucket particles stay in ascending index,
//                                stored with their cell and position so a
//                                query streams through contiguous memory;
//   3. for_each_near(i, visit)   per particle, read-only: every particle j
//                                of the 2x2x2 cells nearest i, each once,
//                                cell by cell in a fixed order, ascending
//                                index within a cell.
// Why 2x2x2 cells of size 2r find every pair closer than r (the gap the
// paper leaves; docs/method.md, "Self-collision"): along each axis, if p lies in the lower
// half of its cell [k c, k c + c/2), every q with |q - p| < r = c/2 lies in
// cells k-1 or k; if p lies in the upper half, in cells k or k+1. So the
// block starting at floor(p / c - 1/2) holds every neighbour within r. It
// visits 8 cells instead of the 27 a cell of size r needs, over about the
// same area of a cloth surface. An entry is taken only when its own cell is
// the cell being visited, so particles of other cells that share a bucket
// (hash collisions) are skipped, and two visited cells hashing to one
// bucket cannot visit anyone twice.
#pragma once

#include <algorithm>
#include <cstdint>

#include "base/host_allocator.h"
#include "base/soa.h"

namespace cloth {

class SpatialHash {
  public:
    explicit SpatialHash(const HostMemory* memory);

    // Size every buffer for `particle_count` particles. Allocates; call it
    // once (not per step).
    void reserve(uint32_t particle_count);

    uint32_t particle_count() const { return static_cast<uint32_t>(bucket_of_.size()); }
    uint32_t bucket_count() const { return bucket_mask_ + 1; }

    // Pass 1 for particles [begin, end): cell of x_i (cells of 2 * radius,
    // radius > 0), its bucket, and the first cell of its 2x2x2 query block.
    // Every call of one build must use the same radius. Non-finite or huge
    // coordinates are clamped, never UB. Particle i's position is entry
    // first + i of x (a hash of part of a larger array).
    void compute_keys(const Vec3Soa& x, float radius, uint32_t begin, uint32_t end, uint32_t first = 0);

    // Pass 2: counting sort of all particles into buckets (serial). `x` and
    // `first` are the same as in pass 1.
    void sort_into_buckets(const Vec3Soa& x, uint32_t first = 0);

    // Pass 3: calls visit(j, xj, yj, zj) for every particle j != i in the
    // 2x2x2 cells nearest particle i (a superset of those within the
    // radius), each j once, in a fixed order.
    template <class Visit>
    void for_each_near(uint32_t i, Visit visit) const {
        for_each_in_block(block_x_[i], block_y_[i], block_z_[i], i, visit);
    }

    // The same for a point that is not one of the hashed particles (of
    // another set): its query block for the build's radius, then every
    // particle of that block.
    static void query_block(const Vec3& p, float radius, int32_t& bx, int32_t& by, int32_t& bz);
    template <class Visit>
    void for_each_in_block(int32_t bx, int32_t by, int32_t bz, uint32_t skip, Visit visit) const;

    // The bucket of cell (cx, cy, cz).
    uint32_t bucket_of_cell(int32_t cx, int32_t cy, int32_t cz) const {
        const uint32_t h = (static_cast<uint32_t>(cx) * 73856093u) ^ (static_cast<uint32_t>(cy) * 19349663u) ^
                           (static_cast<uint32_t>(cz) * 83492791u);
        return h & bucket_mask_;
    }

  private:
    uint32_t bucket_mask_ = 0;
    HostVector<int32_t> cell_x_, cell_y_, cell_z_;     // per particle
    HostVector<int32_t> block_x_, block_y_, block_z_;  // per particle: first cell of its query block
    HostVector<uint32_t> bucket_of_;                   // per particle
    HostVector<uint32_t> bucket_start_;                // per bucket + 1: first entry in sorted_
    HostVector<uint32_t> bucket_fill_;                 // per bucket: scratch of the sort
    // Particles by bucket, ascending index within one, with their cells and positions.
    HostVector<uint32_t> sorted_;
    HostVector<int32_t> sorted_cell_x_, sorted_cell_y_, sorted_cell_z_;
    HostVector<float> sorted_x_, sorted_y_, sorted_z_;
};

template <class Visit>
void SpatialHash::for_each_in_block(int32_t bx, int32_t by, int32_t bz, uint32_t skip, Visit visit) const {
    // Plain pointers: the visitor's stores cannot alias them, so the loop
    // keeps them in registers.
    const uint32_t* start = bucket_start_.data();
    const uint32_t* sorted = sorted_.data();
    const int32_t *sx = sorted_cell_x_.data(), *sy = sorted_cell_y_.data(), *sz = sorted_cell_z_.data();
    const float *px = sorted_x_.data(), *py = sorted_y_.data(), *pz = sorted_z_.data();
    for (int32_t cz = bz; cz <= bz + 1; ++cz) {
        for (int32_t cy = by; cy <= by + 1; ++cy) {
            for (int32_t cx = bx; cx <= bx + 1; ++cx) {
                const uint32_t bucket = bucket_of_cell(cx, cy, cz);
                const uint32_t last = start[bucket + 1];
                for (uint32_t e = start[bucket]; e < last; ++e) {
                    if (sx[e] != cx || sy[e] != cy || sz[e] != cz || sorted[e] == skip) continue;
                    visit(sorted[e], px[e], py[e], pz[e]);
                }
            }
        }
    }
}

}  // namespace cloth
