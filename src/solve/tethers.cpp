#include "solve/tethers.h"

#include <algorithm>
#include <cmath>
#include <functional>

namespace cloth {

Tethers::Tethers(const HostMemory* memory)
    : anchor_(HostAllocator<uint32_t>(memory)),
      length_(HostAllocator<float>(memory)),
      path_(HostAllocator<float>(memory)),
      settled_(HostAllocator<uint8_t>(memory)),
      frontier_(HostAllocator<Reach>(memory)) {}

void Tethers::resize(const Fabric& fabric) {
    const size_t n = fabric.particle_count();
    anchor_.assign(n * kAnchors, kNoAnchor);
    length_.assign(n * kAnchors, 0.0f);
    path_.assign(n * kAnchors, 0.0f);
    settled_.assign(n, 0);
    // Each particle is settled at most kAnchors times, and each settling
    // pushes at most one entry per incident spring: the heap never holds
    // more than kAnchors * (n + 2 * springs) entries.
    frontier_.reserve(kAnchors * (n + 2 * size_t{fabric.spring_count()}));
    any_ = false;
}

void Tethers::plan(const Fabric& f, const float* pinned) {
    const uint32_t n = f.particle_count();
    // Min-heap on (path, particle, anchor): ties resolve by index, so the
    // anchors depend on nothing but the fabric and the pins.
    const auto later = std::greater<Reach>();
    std::fill(anchor_.begin(), anchor_.end(), kNoAnchor);
    std::fill(settled_.begin(), settled_.end(), uint8_t{0});
    frontier_.clear();
    for (uint32_t i = 0; i < n; ++i) {
        if (pinned[i] != 0.0f) frontier_.push_back(Reach{0.0f, i, i});
    }
    std::make_heap(frontier_.begin(), frontier_.end(), later);
    auto has_anchor = [&](uint32_t i, uint32_t a) {
        for (uint32_t k = 0; k < settled_[i]; ++k) {
            if (anchor_[i * kAnchors + k] == a) return true;
        }
        return false;
    };
    while (!frontier_.empty()) {
        std::pop_heap(frontier_.begin(), frontier_.end(), later);
        const Reach reach = frontier_.back();
        frontier_.pop_back();
        const uint32_t i = reach.particle;
        if (settled_[i] == kAnchors || has_anchor(i, reach.anchor)) continue;  // stale or full
        const uint32_t slot = i * kAnchors + settled_[i]++;
        anchor_[slot] = reach.anchor;
        path_[slot] = reach.path;
        if (pinned[i] != 0.0f && i != reach.anchor) continue;  // paths do not run through other pins
        for (uint32_t e = f.incidence_offset[i]; e < f.incidence_offset[i + 1]; ++e) {
            const uint32_t s = f.incidence_spring[e];
            if (f.spring_kind[s] == kBend) continue;
            const uint32_t j = f.spring_first[s] == i ? f.spring_second[s] : f.spring_first[s];
            if (settled_[j] == kAnchors || pinned[j] != 0.0f || has_anchor(j, reach.anchor)) continue;
            frontier_.push_back(Reach{reach.path + f.spring_rest_length[s], j, reach.anchor});
            std::push_heap(frontier_.begin(), frontier_.end(), later);
        }
    }
    any_ = false;
    for (uint32_t i = 0; i < n; ++i) {
        for (uint32_t k = 0; k < kAnchors; ++k) {
            const uint32_t slot = i * kAnchors + k;
            if (pinned[i] != 0.0f || k >= settled_[i]) {
                anchor_[slot] = kNoAnchor;
                length_[slot] = 0.0f;
                continue;
            }
            const float straight = (f.rest_positions[i] - f.rest_positions[anchor_[slot]]).norm();
            length_[slot] = std::max(straight, path_[slot] / kPathOverGeodesic);
            any_ = true;
        }
    }
}

void Tethers::clamp(float max_strain, float h, uint32_t begin, uint32_t end, Vec3Soa& x, Vec3Soa& v) const {
    const float stretch = 1.0f + max_strain;
    const float inverse_h = 1.0f / h;
    for (uint32_t i = begin; i < end; ++i) {
        for (uint32_t k = kAnchors; k-- > 0;) {
            const uint32_t a = anchor(i, k);
            if (a == kNoAnchor) continue;
            const Vec3 d = x.get(i) - x.get(a);
            const float distance = d.norm();
            const float allowed = stretch * length(i, k);
            if (!(distance > allowed)) continue;
            const Vec3 move = d * ((allowed - distance) / distance);
            x.set(i, x.get(i) + move);
            v.set(i, v.get(i) + move * inverse_h);
        }
    }
}

}  // namespace cloth
