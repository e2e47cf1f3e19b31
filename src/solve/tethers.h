// Long-range attachments (Kim, Chentanez and Mueller 2012, "Long range
// attachments"; NvCloth's and Jolt's tethers): every free particle that the
// fabric connects to pinned ones may be no farther from each of its
// kAnchors nearest pinned particles than its rest distance to it times
// (1 + max_strain). One clamp per particle and anchor in one pass: it holds
// the whole cloth's stretch at once, where the local strain-limit passes
// move tension one spring per pass (docs/method.md, "Where one iteration
// stops holding" and "Tethers").
//
// The anchors follow the pin set: plan() runs when it changes, not per
// frame. A grid is flat at rest, so the straight rest distance is the
// geodesic one: its anchors are the nearest pins by that distance, one
// pass over the pins per particle (up to some 800 pins, past which the
// search below is cheaper). On a mesh the nearest pinned particles are
// found along the structural and shear springs (one Dijkstra search from
// every pinned particle at once that settles each particle up to kAnchors
// times, once per source), and each tether's length is the straight rest
// distance to its anchor, or the spring path's length over
// kPathOverGeodesic if that is longer: on a flat sheet the path (octile
// steps) is at most kPathOverGeodesic times the straight distance, and on
// a curved mesh the path divided by it stays close to the geodesic, so a
// tether never holds a cloth at rest. One anchor alone would tear a cloth
// dragged far in one step along the seams between the anchors' regions;
// with several, a particle must lie within reach of each, so the regions
// move together (docs/measurements.md, "Tethers in the strain limiter").
//
// Written by hand: one clamp per particle over the library's SoA buffers,
// and a search that must allocate only when the pin set changes.
#pragma once

#include "base/host_allocator.h"
#include "base/soa.h"
#include "fabric/fabric.h"

namespace cloth {

class Tethers {
  public:
    // The longest detour a path of structural and shear steps on a grid
    // takes over the straight line: 1 / cos(22.5 degrees).
    static constexpr float kPathOverGeodesic = 1.0823922f;
    static constexpr uint32_t kNoAnchor = UINT32_MAX;
    static constexpr uint32_t kAnchors = 4;

    explicit Tethers(const HostMemory* memory);

    // Storage for `fabric` (once per cloth), so that plan allocates nothing.
    void resize(const Fabric& fabric);
    // Anchors and lengths for the pins of `pinned` (1 pinned, 0 free).
    void plan(const Fabric& fabric, const float* pinned);
    // Whether any free particle has an anchor.
    bool empty() const { return !any_; }
    // Particle i's k-th anchor (nearest first), kNoAnchor past its last.
    uint32_t anchor(uint32_t particle, uint32_t k) const {
        const uint32_t a = anchor_[size_t{k} * count_ + particle];
        return a == particle ? kNoAnchor : a;
    }
    float length(uint32_t particle, uint32_t k) const { return length_[size_t{k} * count_ + particle]; }

    // Particles [begin, end) farther than (1 + max_strain) * length from
    // an anchor move onto that sphere (the farthest anchor first, the
    // nearest last) and lose their speed away from it, relative to the
    // anchor's: a rope, which adds no energy (the move over h as speed, as
    // the Provot passes give it, makes a stiff flag in wind gain energy).
    // Writes only free particles and reads only pinned ones besides its
    // own, so groups run in parallel.
    void clamp(float max_strain, uint32_t begin, uint32_t end, Vec3Soa& x, Vec3Soa& v) const;

    // The least strain at which every spring between two pins and every
    // particle's tethers can hold at once with the pins at x + h v:
    // |x_a - x_b| / reach - 1, the largest over the pairs of pins a and b
    // that a spring joins (reach: its rest length) or that anchor one
    // particle (the length to a plus the length to b), or 0. Pins moved
    // apart farther than the cloth reaches ask more than any limit gives;
    // the strain limit then holds this instead for the substep
    // (docs/method.md, "When the pins ask for more"). One distance per
    // pair of pins.
    float strain_pins_demand(const Vec3Soa& x, const Vec3Soa& v, float h) const;

    // How many distance-and-compare steps of a grid's plan cost as much as
    // one heap step of the search (cloth_bench Tethers/Plan;
    // docs/measurements.md, "What a change of the pin set costs").
    static constexpr uint64_t kSearchStepOverDistance = 16;

  private:
    static bool by_straight_distance(const Fabric& fabric, uint32_t pins);
    void plan_by_straight_distance(const Fabric& fabric, const float* pinned);
    void plan_by_paths(const Fabric& fabric, const float* pinned);
    // From found_, path_ and settled_: anchor_, length_, used_, any_.
    void choose_lengths(const Fabric& fabric, const float* pinned);
    // From the springs, anchor_ and length_: the pairs of pins in frontier_.
    void pair_pins(const Fabric& fabric, const float* pinned);

    // Anchor k of every particle, then anchor k + 1 (so the clamp is a
    // contiguous loop per k); a missing anchor is the particle itself at
    // length 0, which never moves it.
    HostVector<uint32_t> anchor_;
    HostVector<float> length_;
    uint32_t count_ = 0;
    uint32_t used_ = 0;  // anchors any particle has (fewer pins than kAnchors: fewer passes)
    struct Reach {
        float path;
        uint32_t particle, anchor;
        bool operator>(const Reach& other) const {
            if (path != other.path) return path > other.path;
            if (particle != other.particle) return particle > other.particle;
            return anchor > other.anchor;
        }
    };
    HostVector<uint32_t> found_;   // the plan's anchors, kAnchors per particle (particle-major)
    HostVector<float> path_;       // and their path lengths (on a grid: straight distances)
    HostVector<uint8_t> settled_;  // anchors found per particle
    // The search's heap; after plan, the pairs of pins (particle < anchor)
    // joined by a spring or sharing a particle, each with its reach (path):
    // the spring's rest length, or the least length to one plus length to
    // the other over the particles they share.
    HostVector<Reach> frontier_;
    HostVector<uint32_t> pins_;  // the pinned particles, in index order
    HostVector<float> pin_x_, pin_y_, pin_z_,
        pin_distance_;  // the straight plan's: pins' rest positions, squared distances
    bool any_ = false;
};

}  // namespace cloth
