#include "solve/tethers.h"

#include <algorithm>
#include <cmath>
#include <functional>

#include "base/lanes.h"

namespace cloth {

Tethers::Tethers(const HostMemory* memory)
    : anchor_(HostAllocator<uint32_t>(memory)),
      length_(HostAllocator<float>(memory)),
      found_(HostAllocator<uint32_t>(memory)),
      path_(HostAllocator<float>(memory)),
      settled_(HostAllocator<uint8_t>(memory)),
      frontier_(HostAllocator<Reach>(memory)),
      pins_(HostAllocator<uint32_t>(memory)),
      pin_x_(HostAllocator<float>(memory)),
      pin_y_(HostAllocator<float>(memory)),
      pin_z_(HostAllocator<float>(memory)),
      pin_distance_(HostAllocator<float>(memory)) {}

void Tethers::resize(const Fabric& fabric) {
    const size_t n = fabric.particle_count();
    count_ = static_cast<uint32_t>(n);
    anchor_.assign(n * kAnchors, 0);
    length_.assign(n * kAnchors, 0.0f);
    path_.assign(n * kAnchors, 0.0f);
    found_.assign(n * kAnchors, kNoAnchor);
    settled_.assign(n, 0);
    // Each particle is settled at most kAnchors times, and each settling
    // pushes at most one entry per incident spring: the heap never holds
    // more than kAnchors * (n + 2 * springs) entries; the pairs of pins
    // take at most one per two anchors of each particle.
    const size_t pairs = n * kAnchors * (kAnchors - 1) / 2 + fabric.spring_count();
    frontier_.reserve(std::max(pairs, kAnchors * (n + 2 * size_t{fabric.spring_count()})));
    pins_.reserve(n);
    for (HostVector<float>* a : {&pin_x_, &pin_y_, &pin_z_, &pin_distance_}) a->assign(n, 0.0f);
    any_ = false;
}

void Tethers::plan(const Fabric& f, const float* pinned) {
    const uint32_t n = f.particle_count();
    pins_.clear();
    for (uint32_t i = 0; i < n; ++i) {
        if (pinned[i] != 0.0f) pins_.push_back(i);
    }
    if (by_straight_distance(f, static_cast<uint32_t>(pins_.size()))) {
        plan_by_straight_distance(f, pinned);
    } else {
        plan_by_paths(f, pinned);
    }
    choose_lengths(f, pinned);
    pair_pins(f, pinned);
}

bool Tethers::by_straight_distance(const Fabric& f, uint32_t pins) {
    // Only where straight is geodesic: a grid with structural springs is
    // one connected, flat rectangle at rest. And only while one pass over
    // the pins per particle costs less than the search, which takes about
    // kAnchors * (n + 2 springs) heap steps.
    const bool connected_grid =
        std::any_of(f.grid_families.begin(), f.grid_families.end(),
                    [](const SpringFamily& family) { return family.kind == kStructural; });
    if (!connected_grid) return false;
    const uint64_t straight = uint64_t{f.particle_count()} * pins;
    const uint64_t search = uint64_t{kAnchors} * (f.particle_count() + 2 * uint64_t{f.spring_count()});
    return straight <= kSearchStepOverDistance * search;
}

void Tethers::plan_by_straight_distance(const Fabric& f, const float* pinned) {
    const uint32_t n = f.particle_count();
    const uint32_t pins = static_cast<uint32_t>(pins_.size());
    for (uint32_t k = 0; k < pins; ++k) {
        const Vec3& p = f.rest_positions[pins_[k]];
        pin_x_[k] = p.x();
        pin_y_[k] = p.y();
        pin_z_[k] = p.z();
    }
    for (uint32_t i = 0; i < n; ++i) {
        settled_[i] = 0;
        if (pinned[i] != 0.0f) continue;
        const Vec3& r = f.rest_positions[i];
        // Squared distances to every pin (a loop that vectorizes), then the
        // kAnchors smallest, nearest first; ties go to the lower index
        // because pins are visited in index order and only a strictly
        // nearer pin displaces one.
        const float rx = r.x(), ry = r.y(), rz = r.z();
        float* d = pin_distance_.data();
        for (uint32_t k = 0; k < pins; ++k) {
            const float dx = pin_x_[k] - rx, dy = pin_y_[k] - ry, dz = pin_z_[k] - rz;
            d[k] = dx * dx + dy * dy + dz * dz;
        }
        float best[kAnchors];
        uint32_t best_pin[kAnchors];
        uint32_t count = 0;
        for (uint32_t k = 0; k < pins; ++k) {
            if (count == kAnchors && !(d[k] < best[kAnchors - 1])) continue;
            uint32_t at = count < kAnchors ? count++ : kAnchors - 1;
            while (at > 0 && d[k] < best[at - 1]) {
                best[at] = best[at - 1];
                best_pin[at] = best_pin[at - 1];
                --at;
            }
            best[at] = d[k];
            best_pin[at] = k;
        }
        for (uint32_t a = 0; a < count; ++a) {
            found_[i * kAnchors + a] = pins_[best_pin[a]];
            path_[i * kAnchors + a] = std::sqrt(best[a]);
        }
        settled_[i] = static_cast<uint8_t>(count);
    }
}

void Tethers::plan_by_paths(const Fabric& f, const float* pinned) {
    // Min-heap on (path, particle, anchor): ties resolve by index, so the
    // anchors depend on nothing but the fabric and the pins.
    const auto later = std::greater<Reach>();
    std::fill(settled_.begin(), settled_.end(), uint8_t{0});
    frontier_.clear();
    for (uint32_t i : pins_) frontier_.push_back(Reach{0.0f, i, i});
    std::make_heap(frontier_.begin(), frontier_.end(), later);
    auto has_anchor = [&](uint32_t i, uint32_t a) {
        for (uint32_t k = 0; k < settled_[i]; ++k) {
            if (found_[i * kAnchors + k] == a) return true;
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
        found_[slot] = reach.anchor;
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
}

void Tethers::choose_lengths(const Fabric& f, const float* pinned) {
    const uint32_t n = f.particle_count();
    any_ = false;
    used_ = 0;
    for (uint32_t i = 0; i < n; ++i) {
        if (pinned[i] == 0.0f) used_ = std::max<uint32_t>(used_, settled_[i]);
        for (uint32_t k = 0; k < kAnchors; ++k) {
            const size_t out = size_t{k} * n + i;
            if (pinned[i] != 0.0f || k >= settled_[i]) {
                anchor_[out] = i;  // none: itself, at length 0
                length_[out] = 0.0f;
                continue;
            }
            const uint32_t a = found_[i * kAnchors + k];
            const float straight = (f.rest_positions[i] - f.rest_positions[a]).norm();
            anchor_[out] = a;
            length_[out] = std::max(straight, path_[i * kAnchors + k] / kPathOverGeodesic);
            any_ = true;
        }
    }
}

void Tethers::pair_pins(const Fabric& f, const float* pinned) {
    // Every spring between two pins, and every pair of one particle's
    // anchors, into the search's heap storage (free now, and sized for
    // them), skipping a pair the previous free particle had with as short
    // a reach (pushed, or skipped for one as short), since neighbours
    // mostly share their anchors; then sorted, and the shortest reach of
    // each pair kept at the front.
    frontier_.clear();
    for (uint32_t s = 0; s < f.spring_count(); ++s) {
        const uint32_t a = f.spring_first[s], b = f.spring_second[s];
        if (pinned[a] != 0.0f && pinned[b] != 0.0f && f.spring_rest_length[s] > 0.0f)
            frontier_.push_back(Reach{f.spring_rest_length[s], std::min(a, b), std::max(a, b)});
    }
    constexpr uint32_t kPairs = kAnchors * (kAnchors - 1) / 2;
    Reach previous[kPairs], current[kPairs];  // the last free particle's pairs, and this one's
    uint32_t previous_count = 0;
    for (uint32_t i = 0; i < count_; ++i) {
        if (pinned[i] != 0.0f) continue;
        uint32_t count = 0;
        for (uint32_t k = 0; k < used_; ++k) {
            for (uint32_t l = k + 1; l < used_; ++l) {
                const uint32_t a = anchor(i, k), b = anchor(i, l);
                if (a == kNoAnchor || b == kNoAnchor) continue;
                const Reach pair{length(i, k) + length(i, l), std::min(a, b), std::max(a, b)};
                if (!(pair.path > 0.0f)) continue;
                current[count++] = pair;
                const bool repeat = std::any_of(previous, previous + previous_count, [&](const Reach& p) {
                    return p.particle == pair.particle && p.anchor == pair.anchor && p.path <= pair.path;
                });
                if (!repeat) frontier_.push_back(pair);
            }
        }
        std::copy(current, current + count, previous);
        previous_count = count;
    }
    std::sort(frontier_.begin(), frontier_.end(), [](const Reach& p, const Reach& q) {
        if (p.particle != q.particle) return p.particle < q.particle;
        if (p.anchor != q.anchor) return p.anchor < q.anchor;
        return p.path < q.path;
    });
    const auto same_pins = [](const Reach& p, const Reach& q) {
        return p.particle == q.particle && p.anchor == q.anchor;
    };
    frontier_.erase(std::unique(frontier_.begin(), frontier_.end(), same_pins), frontier_.end());
}

float Tethers::strain_pins_demand(const Vec3Soa& x, const Vec3Soa& v, float h) const {
    float most = 0.0f;
    for (const Reach& pair : frontier_) {
        const uint32_t a = pair.particle, b = pair.anchor;
        const Vec3 apart = x.get(a) - x.get(b) + h * (v.get(a) - v.get(b));
        most = std::max(most, apart.norm() / pair.path - 1.0f);
    }
    return most;
}

namespace {

// One anchor of every particle in [begin, end). An anchor is pinned (this
// pass never writes it) or the particle itself, so no iteration reads what
// another writes.
CLOTH_HOT_LOOP void clamp_kernel(uint32_t begin, uint32_t end, float stretch,
                                 const uint32_t* __restrict anchor, const float* __restrict length,
                                 float* __restrict px, float* __restrict py, float* __restrict pz,
                                 float* __restrict vx, float* __restrict vy, float* __restrict vz) {
#if defined(__clang__)
#pragma clang loop vectorize(assume_safety)
#else
#pragma GCC ivdep
#endif
    for (uint32_t i = begin; i < end; ++i) {
        const uint32_t a = anchor[i];
        const float dx = px[i] - px[a], dy = py[i] - py[a], dz = pz[i] - pz[a];
        const float distance = std::sqrt(dx * dx + dy * dy + dz * dz);
        const float allowed = stretch * length[i];
        // Only a taut tether writes (never a pinned particle, whose slots
        // are itself at length 0: other groups read it as their anchor).
        if (!(distance > allowed)) continue;
        const float s = (allowed - distance) / std::max(distance, 1e-30f);
        px[i] += dx * s;
        py[i] += dy * s;
        pz[i] += dz * s;
        // An inextensible rope: a taut tether takes away the particle's
        // speed away from its anchor (relative to the anchor's), and adds none.
        const float inverse_distance = 1.0f / std::max(distance, 1e-30f);
        const float nx = dx * inverse_distance, ny = dy * inverse_distance, nz = dz * inverse_distance;
        const float away = (vx[i] - vx[a]) * nx + (vy[i] - vy[a]) * ny + (vz[i] - vz[a]) * nz;
        const float take = std::max(away, 0.0f);
        vx[i] -= take * nx;
        vy[i] -= take * ny;
        vz[i] -= take * nz;
    }
}

}  // namespace

void Tethers::clamp(float max_strain, uint32_t begin, uint32_t end, Vec3Soa& x, Vec3Soa& v) const {
    // The farthest anchor first, the nearest last.
    for (uint32_t k = used_; k-- > 0;) {
        const size_t base = size_t{k} * count_;
        clamp_kernel(begin, end, 1.0f + max_strain, anchor_.data() + base, length_.data() + base, x.x.data(),
                     x.y.data(), x.z.data(), v.x.data(), v.y.data(), v.z.data());
    }
}

}  // namespace cloth
