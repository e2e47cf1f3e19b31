// Spatial hash of particles for self-collision (paper section IV,
// algorithm.md 5): cubic cells of a given size, each cell (ix, iy, iz)
// hashed into a power-of-two number of buckets (about twice the particle
// count), particles counting-sorted into their buckets every step.
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
//                                of the 27 cells around i's cell, each once,
//                                cell by cell in a fixed order, ascending
//                                index within a cell.
// With a cell size >= r, every pair closer than r is found by pass 3 from
// both ends: a point within r of i lies in one of the 27 cells. An entry is
// taken only when its own cell is the cell being visited, so particles of
// other cells that share a bucket (hash collisions) are skipped, and two
// neighbour cells hashing to one bucket cannot visit anyone twice.
#pragma once

#include <algorithm>
#include <cstdint>

#include "host_allocator.h"
#include "soa.h"

namespace cloth {

class SpatialHash {
  public:
    explicit SpatialHash(const HostMemory* memory);

    // Size every buffer for `particle_count` particles. Allocates; call it
    // once (not per step).
    void reserve(uint32_t particle_count);

    uint32_t particle_count() const { return static_cast<uint32_t>(bucket_of_.size()); }
    uint32_t bucket_count() const { return bucket_mask_ + 1; }
    float cell_size() const { return cell_size_; }

    // Pass 1 for particles [begin, end): integer cell of x_i at `cell_size`
    // (> 0) and its bucket. Every call of one build must use the same
    // cell size. Non-finite or huge coordinates are clamped, never UB.
    void compute_keys(const Vec3Soa& x, float cell_size, uint32_t begin, uint32_t end);

    // Pass 2: counting sort of all particles into buckets (serial). `x` is
    // the same as in pass 1.
    void sort_into_buckets(const Vec3Soa& x);

    // Pass 3: calls visit(j, xj, yj, zj) for every particle j != i in the
    // 27 cells around particle i's cell, each j once, in a fixed order.
    template <class Visit>
    void for_each_near(uint32_t i, Visit visit) const;

    // The bucket of cell (cx, cy, cz).
    uint32_t bucket_of_cell(int32_t cx, int32_t cy, int32_t cz) const {
        const uint32_t h = (static_cast<uint32_t>(cx) * 73856093u) ^ (static_cast<uint32_t>(cy) * 19349663u) ^
                           (static_cast<uint32_t>(cz) * 83492791u);
        return h & bucket_mask_;
    }

  private:
    float cell_size_ = 1.0f;
    uint32_t bucket_mask_ = 0;
    HostVector<int32_t> cell_x_, cell_y_, cell_z_;  // per particle
    HostVector<uint32_t> bucket_of_;                // per particle
    HostVector<uint32_t> bucket_start_;             // per bucket + 1: first entry in sorted_
    HostVector<uint32_t> bucket_fill_;              // per bucket: scratch of the sort
    // Particles by bucket, ascending index within one, with their cells and positions.
    HostVector<uint32_t> sorted_;
    HostVector<int32_t> sorted_cell_x_, sorted_cell_y_, sorted_cell_z_;
    HostVector<float> sorted_x_, sorted_y_, sorted_z_;
};

template <class Visit>
void SpatialHash::for_each_near(uint32_t i, Visit visit) const {
    // Plain pointers: the visitor's stores cannot alias them, so the loop
    // keeps them in registers.
    const uint32_t* start = bucket_start_.data();
    const uint32_t* sorted = sorted_.data();
    const int32_t *sx = sorted_cell_x_.data(), *sy = sorted_cell_y_.data(), *sz = sorted_cell_z_.data();
    const float *px = sorted_x_.data(), *py = sorted_y_.data(), *pz = sorted_z_.data();
    const int32_t ci_x = cell_x_[i], ci_y = cell_y_[i], ci_z = cell_z_[i];
    for (int32_t cz = ci_z - 1; cz <= ci_z + 1; ++cz) {
        for (int32_t cy = ci_y - 1; cy <= ci_y + 1; ++cy) {
            for (int32_t cx = ci_x - 1; cx <= ci_x + 1; ++cx) {
                const uint32_t bucket = bucket_of_cell(cx, cy, cz);
                const uint32_t last = start[bucket + 1];
                for (uint32_t e = start[bucket]; e < last; ++e) {
                    if (sx[e] != cx || sy[e] != cy || sz[e] != cz || sorted[e] == i) continue;
                    visit(sorted[e], px[e], py[e], pz[e]);
                }
            }
        }
    }
}

}  // namespace cloth
