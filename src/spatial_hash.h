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
//   2. sort_into_buckets()       serial O(n + buckets) counting sort; within
//                                a bucket particles stay in ascending index;
//   3. for_each_near(i, visit)   per particle, read-only: every particle j
//                                of the 27 cells around i's cell, each once,
//                                in ascending (bucket, index) order.
// With a cell size >= r, every pair closer than r is found by pass 3 from
// both ends (a point within r of i lies in one of the 27 cells; hash
// collisions only add far particles, which the caller's distance test
// drops).
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

    // Pass 2: counting sort of all particles into buckets (serial).
    void sort_into_buckets();

    // Pass 3: calls visit(j) for every particle j != i in the buckets of
    // the 27 cells around particle i's cell, each j once, in a fixed order.
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
    HostVector<uint32_t> sorted_;                   // particles by bucket, ascending index within one
};

template <class Visit>
void SpatialHash::for_each_near(uint32_t i, Visit visit) const {
    // The 27 buckets, sorted and deduplicated: two neighbour cells that hash
    // to one bucket must not visit its particles twice.
    uint32_t buckets[27];
    uint32_t count = 0;
    for (int32_t dz = -1; dz <= 1; ++dz) {
        for (int32_t dy = -1; dy <= 1; ++dy) {
            for (int32_t dx = -1; dx <= 1; ++dx) {
                buckets[count++] = bucket_of_cell(cell_x_[i] + dx, cell_y_[i] + dy, cell_z_[i] + dz);
            }
        }
    }
    std::sort(buckets, buckets + count);
    count = static_cast<uint32_t>(std::unique(buckets, buckets + count) - buckets);
    for (uint32_t k = 0; k < count; ++k) {
        const uint32_t first = bucket_start_[buckets[k]], last = bucket_start_[buckets[k] + 1];
        for (uint32_t e = first; e < last; ++e) {
            const uint32_t j = sorted_[e];
            if (j != i) visit(j);
        }
    }
}

}  // namespace cloth
