// Contact between two cloths of one world (NvCloth's inter-collision):
// a particle of one cloth is kept `thickness` away from the other cloth's
// surface, on the side it came from, and loses the approaching part of
// its velocity relative to it, with optional Coulomb friction on the
// sliding part (self-collision's response, paper eq. 13).
//
// The other surface is seen through its particles: each particle j near
// particle i (within the thickness plus the larger mean rest edge) stands
// for the plane through x_j normal to its vertex normal n_j. The side is
// the one i was on when the contact last looked (the last substep), so a
// particle that crossed within a substep is pushed back; the first time
// the cloths are near, the side is the current one. Planes, not spheres:
// a particle over the middle of a cell of the other cloth sees its four
// corners' planes push it straight out, where spheres around the corners
// push sideways and cancel, and let it through.
//
// It runs inside both cloths' substeps on particle views (no cloth class),
// once a substep after both cloths integrated and met their colliders,
// with both waiting for it (step/pair_rounds.h), as the rounds of this
// staged algorithm over both cloths' particles:
//   1. gather(range)          copy both cloths' positions, velocities and
//                             inverse masses into the combined arrays (a's
//                             first), then key each particle in its own
//                             cloth's hash within a search radius grown by
//                             the fastest speeds; the particles within it of
//                             the other cloth's bounds take their vertex
//                             normals, and only they look for contacts
//   2. sort                   serial counting sort of both hashes
//   3. find_contacts(range)   per particle: the nearest particles of the
//                             other cloth and their planes
//   4. project(range)         one Jacobi pass (a gather), then a serial
//                             swap; up to `passes` times while any
//                             particle is inside
//   5. scatter(range)         write the projected positions back
// Then each cloth's strain limiter takes back the stretch the pushes made,
// and, in each cloth's own stage after it, respond_side removes the
// approaching part of its particles' velocities relative to the other
// cloth's as they were gathered: it reads only the combined arrays and
// writes only the cloth's own particles.
// Every particle reads the contacts in its own list and writes only
// itself, so the result is bit-identical for any split and thread count.
#pragma once

#include <cstdint>

#include "base/host_allocator.h"
#include "base/soa.h"
#include "base/staged.h"
#include "collide/spatial_hash.h"
#include "fabric/fabric.h"

namespace cloth {

struct ClothPairSettings {
    float thickness = 0.01f;  // m: how far in front of the other cloth's surface a particle is kept
    float friction = 0.0f;    // Coulomb coefficient on the sliding relative velocity
    uint32_t passes = 4;      // Jacobi projection passes per substep (at most; stops when resolved)
};

// One cloth's particles as contact sees them. `x` and `v` are written only
// by scatter and respond_side; a cloth that does not step
// (asleep) is seen with every particle kinematic and is never written.
struct ParticleView {
    const Fabric* fabric = nullptr;
    Vec3Soa* x = nullptr;
    Vec3Soa* v = nullptr;
    const float* mass = nullptr;
    const float* pinned = nullptr;  // nonzero: kinematic
    bool steps = true;              // false: read only, every particle kinematic
};

class ClothPairContact final : public StagedAlgorithm {
  public:
    static constexpr uint32_t kMaxContacts = 8;  // per particle; the nearest are kept

    // Allocates everything for the two cloths (fabrics of a and b).
    ClothPairContact(const HostMemory* memory, const Fabric& a, const Fabric& b,
                     const ClothPairSettings& settings);

    const ClothPairSettings& settings() const { return settings_; }
    // Both cloths' particles, a's first; where side 1's particles start.
    uint32_t count() const { return count_a_ + count_b_; }
    uint32_t first_of(uint32_t side) const { return side == 0 ? 0 : count_a_; }

    // Whether the two cloths can come within the search radius over the
    // next `dt` seconds: their bounds, each over its particles now and
    // where their velocities take them, grown by the radius, overlap
    // (serial; when they do not, nothing else needs to run).
    bool near(const ParticleView& a, const ParticleView& b, float dt) const;

    // The rounds of a substep (the file comment's 1-5).
    enum class Round : uint8_t { kGather, kKeys, kSort, kContacts, kProject, kScatter, kDone };
    // `h`: the substep's length, by which the search grows with the speeds.
    void begin(const ParticleView& a, const ParticleView& b, float h);
    Round round() const { return round_; }
    uint32_t task_count() const { return round_ == Round::kSort ? 1 : group_count_of(count()); }
    bool done() const override { return round_ == Round::kDone; }
    bool single_task() const override { return round_ == Round::kSort; }
    bool last_round() const override { return round_ == Round::kScatter; }
    void run(const GroupTask& task) override;  // a task over the combined particles
    void finish_round() override;

    // After the strain limiter: particles [begin, end) of `side` (its own
    // indices) lose the approaching part of their velocities relative to
    // the other cloth's, in place.
    void respond_side(uint32_t side, const Vec3Soa& x, Vec3Soa& v, uint32_t begin, uint32_t end) const;

    // Particles within the thickness of the other cloth's surface when
    // contacts were last found (0 when the cloths were not near), and the
    // mutual projection passes run then.
    uint32_t contacts() const;
    uint32_t passes() const { return passes_; }
    // The cloths are not near: the next contact takes the sides anew.
    void clear() { passes_ = 0, found_ = false, started_ = false; }

  private:
    bool side_b(uint32_t i) const { return i >= count_a_; }
    void gather(uint32_t task, uint32_t begin, uint32_t end);
    // Which particles lie within the search of the other cloth's bounds,
    // and their vertex normals.
    void mark_near(uint32_t begin, uint32_t end);
    void find_contacts(uint32_t begin, uint32_t end);
    void project(uint32_t begin, uint32_t end);
    void scatter(uint32_t begin, uint32_t end);

    ClothPairSettings settings_;
    uint32_t count_a_, count_b_;
    float radius_;  // the thickness plus the larger mean rest edge
    float search_;  // this substep's: contacts are gathered within it (the radius grown by the speeds)
    float h_ = 0;
    uint32_t passes_ = 0;
    bool found_ = false;
    bool started_ = false;  // start_ holds where the contact last left the particles
    Round round_ = Round::kDone;
    ParticleView a_, b_;
    SpatialHash hash_a_, hash_b_;  // each cloth's particles (b's from entry count_a_ of the arrays)
    Vec3Soa x_, v_, normal_, next_x_;
    Vec3Soa start_;  // where the contact last left each particle
    HostVector<float> inverse_mass_;
    HostVector<uint32_t> contact_other_;  // kMaxContacts per particle
    HostVector<float> contact_distance2_;
    Vec3Soa contact_normal_;  // kMaxContacts per particle: the plane's, towards the particle
    HostVector<uint32_t> contact_count_;
    HostVector<uint8_t> touching_;
    HostVector<uint8_t> overlapping_;
    HostVector<uint8_t> border_;         // per particle: on its fabric's border
    HostVector<float> task_speed2_;      // per gather task: the fastest squared speed of a's and of b's
    HostVector<Vec3> task_bounds_;       // per gather task: a's low and high, b's low and high
    Vec3 reach_low_[2], reach_high_[2];  // each cloth's bounds grown by the search
    HostVector<uint8_t> near_;           // per particle: within the other cloth's reach
};

}  // namespace cloth
