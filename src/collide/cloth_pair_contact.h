// Contact between two cloths of one world (NvCloth's inter-collision):
// a particle of one cloth is kept `thickness` away from the other cloth's
// surface, on the side it came from, and loses the approaching part of
// its velocity relative to it, with optional Coulomb friction on the
// sliding part (self-collision's response, paper eq. 13).
//
// The other surface is seen through its particles: each particle j near
// particle i (within the thickness plus the larger mean rest edge) stands
// for the plane through x_j normal to its vertex normal n_j. The side is
// the one i was on at the end of the last frame (where this contact left
// both cloths), so a particle that crossed within the frame is pushed
// back; in the first frame the cloths are near, the side is the current
// one. Planes, not spheres: a particle over the middle of a cell of the
// other cloth sees its four corners' planes push it straight out, where
// spheres around the corners push sideways and cancel, and let it through.
//
// It runs once per frame, after both cloths' steps (the world's step), so
// what both cloths did in the frame is final when it looks; the world then
// has each touched cloth settle (ClothInstance::settle_after_contact).
// Two cloths whose bounds, grown by the search radius, do not overlap cost
// two bound computations and nothing else.
//
// A staged loop like self-collision's, every round a range loop the
// world's task system may split any way, with a serial step between:
//   1. gather(range)           copy both cloths' positions, velocities,
//                              vertex normals and inverse masses into the
//                              combined arrays (a's particles first); key
//                              per particle in its own cloth's hash
//   2. sort()                  serial counting sort of both hashes (a
//                              particle looks only in the other's)
//   3. find_contacts(range)    per particle: nearest particles of the
//                              other cloth and their planes, written only
//                              by its owner
//   4. project(range)          one Jacobi pass (a gather), then
//      apply_positions()       serial swap; up to `passes` times while
//                              any particle is inside
//   5. respond(range)          velocities, then apply_velocities()
//   6. scatter(range)          write back the particles with contacts,
//                              keep every position as the next start
// Every particle reads the contacts in its own list and writes only
// itself, so the result is bit-identical for any split and thread count.
#pragma once

#include <cstdint>

#include "base/host_allocator.h"
#include "base/soa.h"
#include "collide/spatial_hash.h"
#include "fabric/fabric.h"

namespace cloth {

class ClothInstance;

struct ClothPairSettings {
    float thickness = 0.01f;  // m: how far in front of the other cloth's surface a particle is kept
    float friction = 0.0f;    // Coulomb coefficient on the sliding relative velocity
    uint32_t passes = 4;      // Jacobi projection passes per frame (at most; stops when resolved)
};

class ClothPairContact {
  public:
    static constexpr uint32_t kMaxContacts = 8;  // per particle; the nearest are kept

    // Allocates everything for the two cloths (fabrics of a and b).
    ClothPairContact(const HostMemory* memory, const Fabric& a, const Fabric& b,
                     const ClothPairSettings& settings);

    const ClothPairSettings& settings() const { return settings_; }
    // Both cloths' particles, a's first.
    uint32_t count() const { return count_a_ + count_b_; }

    // Whether the two cloths' bounds, grown by the search radius, overlap
    // (serial; when they do not, nothing else needs to run).
    bool near(const ClothInstance& a, const ClothInstance& b) const;

    void gather(const ClothInstance& a, const ClothInstance& b, uint32_t begin, uint32_t end);
    void sort() {
        hash_a_.sort_into_buckets(x_);
        hash_b_.sort_into_buckets(x_, count_a_);
        found_ = true;
        passes_ = 0;
    }
    // After scatter: the next frame starts where this one ended.
    void finish_frame() { started_ = true; }
    void find_contacts(uint32_t begin, uint32_t end);
    void project(uint32_t begin, uint32_t end);
    // Swaps the projected positions in; whether another pass should run.
    bool apply_positions();
    void respond(uint32_t begin, uint32_t end);
    void apply_velocities() { v_.swap_buffers(next_v_); }
    // Writes back the particles that had a contact, and keeps every
    // position as the next frame's start.
    void scatter(ClothInstance& a, ClothInstance& b, uint32_t begin, uint32_t end);

    // Particles within the thickness of the other cloth's surface when
    // contacts were found (0 when the cloths were not near), and the
    // projection passes run.
    uint32_t contacts() const;
    uint32_t passes() const { return passes_; }
    // The cloths were not near this frame.
    void clear() { passes_ = 0, found_ = false, started_ = false; }

  private:
    bool side_b(uint32_t i) const { return i >= count_a_; }

    ClothPairSettings settings_;
    uint32_t count_a_, count_b_;
    float radius_;  // contacts are gathered within it: the thickness plus the larger mean rest edge
    uint32_t passes_ = 0;
    bool found_ = false;
    bool started_ = false;         // start_ holds the last frame's end
    SpatialHash hash_a_, hash_b_;  // each cloth's particles (b's from entry count_a_ of the arrays)
    Vec3Soa x_, v_, normal_, next_x_, next_v_, start_;
    HostVector<float> inverse_mass_;
    HostVector<uint32_t> contact_other_;  // kMaxContacts per particle
    HostVector<float> contact_distance2_;
    Vec3Soa contact_normal_;  // kMaxContacts per particle: the plane's, towards the particle
    HostVector<uint32_t> contact_count_;
    HostVector<uint8_t> touching_;
    HostVector<uint8_t> overlapping_;
};

}  // namespace cloth
