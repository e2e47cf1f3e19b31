// Self-collision of one cloth (paper section IV; docs/method.md,
// "Self-collision"):
// particle-particle contacts found through a spatial hash, collision-free
// regions (Volino) to skip pairs that cannot collide, and the paper's
// response (push apart to the thickness theta_c, remove the approaching
// part of the relative velocity, eq. 13), with optional Coulomb friction.
//
// A staged algorithm (base/staged.h): rounds, each a loop over a range with
// a barrier after it (a job system may split any range; results do not
// depend on the split). In the step they are the Stage::kSelf* stages of
// step_stage.h:
//   1. check_regions(regions)     per region: is it still collision-free?
//      compute_keys(particles)    per particle: hash cell and bucket
//   2. sort_into_buckets(x)       serial O(n) counting sort
//   3. find_contacts(particles)   per particle: its own list of nearby
//                                 particles, written only by its owner
//   4. project(particles)         per particle, one Jacobi pass: reads x,
//                                 writes i's next position from i's own
//                                 list (a gather, never a scatter); then
//      apply_positions()          serial O(1) swap; up to `passes` times,
//                                 while any_overlapping()
//   5. respond_velocities(particles), then apply_velocities() (swap)
// Each pair sits in both particles' lists and both ends evaluate the same
// formula with opposite signs, so no atomics and no locks, and the result
// is bit-identical for any thread count.
//
// Rest neighbours never repel: particles joined by a spring or within a few
// rings on the mesh (enough rings that no rest neighbour lies within theta_c
// at rest) are excluded through a sorted per-particle list.
//
// Collision-free regions are fixed patches of the fabric (8x8 tiles on a
// grid, greedy patches of up to 64 particles on a mesh). Each step a region
// is collision-free only if (a) the normals of its triangles lie within a
// cone of half-angle 60 degrees around their mean, and (b) its outline,
// projected on the plane normal to that mean, does not cross itself. Then
// the region is a height field of bounded slope over an embedded outline
// (Volino's criterion), so two of its particles can only be close where the
// surface between them is short, i.e. they are rest neighbours. Pairs inside
// such a region are skipped; a region that fails either test has its pairs
// tested like any others.
#pragma once

#include <cstdint>

#include "base/host_allocator.h"
#include "base/soa.h"
#include "base/staged.h"
#include "collide/spatial_hash.h"
#include "fabric/fabric.h"

namespace cloth {

struct SelfCollisionSettings {
    float thickness = 0.01f;  // theta_c, m: particles closer than this are pushed apart
    float friction = 0.0f;    // Coulomb coefficient on the tangential relative velocity
    bool use_regions = true;  // skip pairs inside collision-free regions
    uint32_t passes = 8;      // Jacobi projection passes per substep (at most; stops when resolved)
};

struct SelfCollisionStats {
    uint32_t contacts = 0;              // pairs closer than theta_c when contacts were found
    uint32_t regions = 0;               // collision-free region candidates of the fabric
    uint32_t valid_regions = 0;         // of those, collision-free at the last check
    uint32_t overflowed_particles = 0;  // particles with more near neighbours than contact slots
    uint32_t passes = 0;                // the stage's own projection passes in the last substep
};

// Rest edges of the fabric's triangles, their mean length (m).
float mean_rest_edge(const Fabric& fabric);
// The thickest theta_c a fabric supports (rest neighbours are excluded up
// to kMaxRings rings, which must cover every particle within theta_c).
float max_self_collision_thickness(const Fabric& fabric);

class SelfCollision final : public StagedAlgorithm {
  public:
    static constexpr uint32_t kMaxContacts = 16;   // per particle; the nearest are kept
    static constexpr uint32_t kMaxRings = 4;       // rest-neighbour rings, at most
    static constexpr float kSearchMargin = 1.25f;  // contacts are gathered within margin * theta_c
    static constexpr float kConeCos = 0.5f;        // cos of the region's normal-cone half-angle

    // Allocates every buffer (nothing is allocated per step).
    SelfCollision(const HostMemory* memory, const Fabric& fabric, const SelfCollisionSettings& settings);

    const SelfCollisionSettings& settings() const { return settings_; }
    uint32_t particle_count() const { return particle_count_; }
    uint32_t region_count() const { return static_cast<uint32_t>(region_valid_.size()); }
    uint32_t rest_rings() const { return rings_; }

    // ---- stages (see the file comment)
    void check_regions(const Vec3Soa& x, uint32_t region_begin, uint32_t region_end);
    void compute_keys(const Vec3Soa& x, uint32_t begin, uint32_t end);
    void sort_into_buckets(const Vec3Soa& x) {
        hash_.sort_into_buckets(x);
        last_passes_ = 0;
    }
    void find_contacts(const Vec3Soa& x, uint32_t begin, uint32_t end);
    // Per-particle inverse masses (0 for pinned particles), for the passes.
    void compute_inverse_mass(const float* mass, const float* pinned, uint32_t begin, uint32_t end);
    // One Jacobi pass: next_i = x_i + mean of the pushes of i's overlapping
    // contacts, into a scratch buffer. Marks the particles with a contact
    // that still overlaps by more than the convergence tolerance.
    void project(const Vec3Soa& x, uint32_t begin, uint32_t end);
    // After a pass (serial, O(1)): the scratch buffer becomes x (swapped).
    void apply_positions(Vec3Soa& x);
    // Whether the last pass found an overlap beyond the tolerance (serial,
    // a scan of one byte per particle: the same answer for any split).
    bool any_overlapping() const;
    // Paper eq. 13 (plus friction): i's new velocity from its touching
    // contacts, into a scratch buffer; apply_velocities swaps it into v.
    void respond_velocities(const Vec3Soa& x, const Vec3Soa& v, uint32_t begin, uint32_t end);
    void apply_velocities(Vec3Soa& v);
    const Vec3Soa& next_velocities() const { return next_v_; }
    const Vec3Soa& next_positions() const { return next_x_; }  // a projection's, before apply_positions

    // The rounds, in order (the file comment's stages 1-5).
    enum class Round : uint8_t { kHash, kSort, kContacts, kProject, kRespond, kDone };
    // Starts the rounds on x, v (which outlive them), resolving this substep's
    // contacts; without `respond` they end after the projection, for a
    // caller that runs respond_velocities itself later in the substep.
    void begin(Vec3Soa& x, Vec3Soa& v, const float* mass, const float* pinned, bool respond = true);
    Round round() const { return round_; }
    bool done() const override { return round_ == Round::kDone; }
    bool single_task() const override { return round_ == Round::kSort; }
    bool last_round() const override { return round_ == Round::kRespond; }
    void run(const GroupTask& task) override;
    void finish_round() override;

    // The same rounds on this thread.
    void run_serially(Vec3Soa& x, Vec3Soa& v, const float* mass, const float* pinned);

    // Fixed-order sums of the per-particle and per-region results.
    SelfCollisionStats stats() const;

    // ---- queries (tests, stats)
    bool is_rest_neighbour(uint32_t i, uint32_t j) const;
    uint32_t region_of(uint32_t i) const { return region_of_[i]; }
    bool region_valid(uint32_t region) const { return region_valid_[region] != 0; }
    // Whether the pair (i, j) is skipped as lying in one collision-free region.
    bool skipped_by_region(uint32_t i, uint32_t j) const {
        return settings_.use_regions && region_of_[i] == region_of_[j] && region_valid_[region_of_[i]] != 0;
    }
    uint32_t contact_count(uint32_t i) const { return contact_count_[i]; }
    uint32_t contact(uint32_t i, uint32_t k) const { return contact_other_[i * kMaxContacts + k]; }
    const SpatialHash& hash() const { return hash_; }

  private:
    void build_rest_neighbours(const Fabric& fabric);
    void build_regions(const Fabric& fabric);
    bool region_is_collision_free(const Vec3Soa& x, uint32_t region);
    // Unit direction from j to i, also for coincident particles (then from
    // their rest positions, antisymmetric by construction).
    Vec3 contact_normal(uint32_t i, uint32_t j, const Vec3& d, float length) const;

    SelfCollisionSettings settings_;
    uint32_t particle_count_;
    uint32_t rings_ = 2;
    float outline_epsilon_ = 0;  // orientation tolerance of the outline test, m^2

    HostVector<Vec3> rest_;  // rest positions, for the normal of coincident particles

    // Rest neighbours: particle i's sorted list is rest_neighbour_[offset[i] .. offset[i+1]).
    HostVector<uint32_t> rest_neighbour_offset_, rest_neighbour_;

    // Regions: particle -> region; per region its triangles and outline edges (CSR).
    HostVector<uint32_t> region_of_;
    HostVector<uint32_t> region_triangle_offset_, region_triangle_;  // 3 indices per triangle
    HostVector<uint32_t> region_outline_offset_, region_outline_;    // 2 indices per edge
    HostVector<uint8_t> region_usable_;                              // every particle on a region triangle
    HostVector<uint8_t> region_valid_;                               // result of the last check
    HostVector<float> outline_u_, outline_v_;  // projected outline endpoints, same layout as region_outline_

    SpatialHash hash_;

    // Per particle: contacts (nearest kMaxContacts within the search radius).
    HostVector<uint32_t> contact_count_;
    HostVector<uint32_t> contact_other_;  // kMaxContacts slots per particle
    HostVector<float> contact_distance2_;
    HostVector<uint32_t> touching_;    // per particle: contacts closer than theta_c when found
    HostVector<uint8_t> overflowed_;   // per particle: more candidates than slots
    HostVector<uint8_t> overlapping_;  // per particle: an overlap beyond tolerance in the last pass
    HostVector<float> inverse_mass_;
    Vec3Soa next_x_, next_v_;
    uint32_t last_passes_ = 0;
    bool respond_ = true;

    // The rounds in progress.
    Round round_ = Round::kDone;
    Vec3Soa* x_ = nullptr;
    Vec3Soa* v_ = nullptr;
    const float* mass_ = nullptr;
    const float* pinned_ = nullptr;
};

}  // namespace cloth
