// Spatial hash of particles: see spatial_hash.h (and why it is hand-written).
#include "collide/spatial_hash.h"

#include <cmath>

namespace cloth {

namespace {

// Cells beyond +-2^30 would overflow the neighbour offsets; such far (or
// non-finite) particles are clamped into the outermost cell. fmax/fmin
// send NaN to the clamp bound too.
constexpr float kCellLimit = 1073741824.0f;

// floor(scaled) as a cell index.
int32_t cell_of(float scaled) {
    const float c = std::floor(scaled);
    return static_cast<int32_t>(std::fmin(std::fmax(c, -kCellLimit), kCellLimit));
}

}  // namespace

SpatialHash::SpatialHash(const HostMemory* memory)
    : cell_x_(HostAllocator<int32_t>(memory)),
      cell_y_(HostAllocator<int32_t>(memory)),
      cell_z_(HostAllocator<int32_t>(memory)),
      block_x_(HostAllocator<int32_t>(memory)),
      block_y_(HostAllocator<int32_t>(memory)),
      block_z_(HostAllocator<int32_t>(memory)),
      bucket_of_(HostAllocator<uint32_t>(memory)),
      bucket_start_(HostAllocator<uint32_t>(memory)),
      bucket_fill_(HostAllocator<uint32_t>(memory)),
      sorted_(HostAllocator<uint32_t>(memory)),
      sorted_cell_x_(HostAllocator<int32_t>(memory)),
      sorted_cell_y_(HostAllocator<int32_t>(memory)),
      sorted_cell_z_(HostAllocator<int32_t>(memory)),
      sorted_x_(HostAllocator<float>(memory)),
      sorted_y_(HostAllocator<float>(memory)),
      sorted_z_(HostAllocator<float>(memory)) {}

void SpatialHash::reserve(uint32_t particle_count) {
    // About two buckets per particle (a power of two, so the hash is a mask).
    uint32_t buckets = 64;
    while (buckets < 2u * particle_count && buckets < (1u << 30)) buckets *= 2;
    bucket_mask_ = buckets - 1;
    for (HostVector<int32_t>* a : {&cell_x_, &cell_y_, &cell_z_, &block_x_, &block_y_, &block_z_}) {
        a->assign(particle_count, 0);
    }
    bucket_of_.assign(particle_count, 0);
    sorted_.assign(particle_count, 0);
    for (HostVector<int32_t>* a : {&sorted_cell_x_, &sorted_cell_y_, &sorted_cell_z_})
        a->assign(particle_count, 0);
    for (HostVector<float>* a : {&sorted_x_, &sorted_y_, &sorted_z_}) a->assign(particle_count, 0.0f);
    bucket_start_.assign(static_cast<size_t>(buckets) + 1, 0);
    bucket_fill_.assign(buckets, 0);
}

void SpatialHash::query_block(const Vec3& p, float radius, int32_t& bx, int32_t& by, int32_t& bz) {
    const float inverse = 1.0f / (2.0f * radius);
    bx = cell_of(p.x() * inverse - 0.5f);
    by = cell_of(p.y() * inverse - 0.5f);
    bz = cell_of(p.z() * inverse - 0.5f);
}

void SpatialHash::compute_keys(const Vec3Soa& x, float radius, uint32_t begin, uint32_t end, uint32_t first) {
    // Tasks of one build run this concurrently: it writes only entries of its own range.
    const float inverse = 1.0f / (2.0f * radius);
    for (uint32_t i = begin; i < end; ++i) {
        const float sx = x.x[first + i] * inverse, sy = x.y[first + i] * inverse,
                    sz = x.z[first + i] * inverse;
        cell_x_[i] = cell_of(sx);
        cell_y_[i] = cell_of(sy);
        cell_z_[i] = cell_of(sz);
        // The 2x2x2 block starts one cell down on each axis where x_i lies
        // in the lower half of its cell (see the header).
        block_x_[i] = cell_of(sx - 0.5f);
        block_y_[i] = cell_of(sy - 0.5f);
        block_z_[i] = cell_of(sz - 0.5f);
        bucket_of_[i] = bucket_of_cell(cell_x_[i], cell_y_[i], cell_z_[i]);
    }
}

void SpatialHash::sort_into_buckets(const Vec3Soa& x, uint32_t first) {
    const uint32_t n = particle_count();
    std::fill(bucket_fill_.begin(), bucket_fill_.end(), 0u);
    for (uint32_t i = 0; i < n; ++i) ++bucket_fill_[bucket_of_[i]];
    uint32_t sum = 0;
    for (uint32_t b = 0; b < bucket_count(); ++b) {
        bucket_start_[b] = sum;
        sum += bucket_fill_[b];
        bucket_fill_[b] = bucket_start_[b];
    }
    bucket_start_[bucket_count()] = sum;
    // Ascending i, so each bucket lists its particles in ascending index.
    for (uint32_t i = 0; i < n; ++i) {
        const uint32_t e = bucket_fill_[bucket_of_[i]]++;
        sorted_[e] = i;
        sorted_cell_x_[e] = cell_x_[i];
        sorted_cell_y_[e] = cell_y_[i];
        sorted_cell_z_[e] = cell_z_[i];
        sorted_x_[e] = x.x[first + i];
        sorted_y_[e] = x.y[first + i];
        sorted_z_[e] = x.z[first + i];
    }
}

}  // namespace cloth
