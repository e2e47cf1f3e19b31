// A cloth's skin: where each particle sits on an animated body, and the
// constraints that keep it near there (character cloth: Jolt's skinned
// constraints, NvCloth's motion and separation constraints).
//
// - Skinned positions and normals: linear blend skinning of the fabric's
//   rest positions and normals (the bind pose) by up to kMaxInfluences
//   joints, from the joint matrices the host gives each frame; or
//   positions and normals the host skinned itself.
// - Max distance: a free particle ends every substep within it of its
//   skinned position. 0 makes the particle a pin whose target is its
//   skinned position (ClothInstance pins it; it costs what a pin costs).
// - Backstop: a particle ends every substep outside a sphere of `radius`
//   whose centre lies `distance` behind its skinned position along the
//   skinned normal, so a cape stays off the back it hangs on.
//
// Over a frame's substeps the skinned positions and normals move linearly
// from where the last frame left them to where this frame's skin puts
// them, as pins do. Everything here is per particle: skin() and
// constrain() run on any range of particles with the same bits.
#pragma once

#include <cstdint>
#include <limits>

#include "base/host_allocator.h"
#include "base/math.h"
#include "base/soa.h"
#include "fabric/fabric.h"

namespace cloth {

// A particle without a max distance.
constexpr float kNoMaxDistance = std::numeric_limits<float>::infinity();

class Skin {
  public:
    static constexpr uint32_t kMaxInfluences = 4;
    static constexpr uint32_t kMatrixFloats = 12;  // 3x4, row-major: rotation and scale | translation

    explicit Skin(const HostMemory* memory);

    // Where the skinned positions come from.
    enum class Source : uint8_t { kNone, kJoints, kHost };
    Source source() const { return source_; }
    bool active() const { return source_ != Source::kNone; }

    // Binds n particles (particle order) to joints: `influences` entries
    // per particle of `joints` and `weights` (weights null: one joint,
    // weight 1), the bind pose from the fabric's rest positions and their
    // normals. The joint matrices start as identities (the rest pose).
    void bind(const Fabric& fabric, uint32_t joint_count, uint32_t influences, const uint32_t* joints,
              const float* weights);
    uint32_t joint_count() const { return joint_count_; }
    // This frame's joint matrices, joint_count() of them: column-major 4x4
    // (16 floats each) or row-major 3x4 (kMatrixFloats each). The skin
    // follows the joints from now on. Allocates nothing.
    void set_joint_matrices(const float* matrices, bool column_major_4x4);
    // Positions and normals the host skinned, by vertex (xyz each; the
    // normals are normalised). The skin follows them from now on.
    // Allocates only the first time.
    void set_skinned(const Fabric& fabric, const float* positions, const float* normals);

    // Sizes the per-particle arrays for n particles (no max distance, no
    // backstop) unless they have that size; every setter below needs it.
    // An allocation failure leaves the skin as it was, here and in bind()
    // and set_skinned().
    void size_for(uint32_t n);
    bool sized_for(uint32_t n) const { return n > 0 && max_distance_.size() == n; }
    // Per particle (particle order). max_distance: kNoMaxDistance for
    // none (a pinned particle has none: the cloth's pins hold a 0);
    // backstop radius 0 for none.
    void set_max_distance(uint32_t particle, float distance);
    void set_backstop(uint32_t particle, float distance, float radius);
    float max_distance(uint32_t particle) const { return max_distance_[particle]; }
    // Whether a substep must run constrain(): some max distance above 0
    // and finite, or some backstop.
    bool constrains() const { return constrained_count_ > 0; }

    // The frame: begin_frame (serial) makes the last frame's end this
    // frame's start, or with `jump` (the character teleported) this
    // frame's end, so that nothing moves across the jump; skin() then
    // writes this frame's end for a range; finish_skinning (serial) after
    // every range ran.
    void begin_frame(bool jump);
    void skin(uint32_t begin, uint32_t end);
    void finish_skinning() {
        primed_ = true;
        jump_ = false;
    }
    // This frame's skin jumped (begin_frame), until finish_skinning.
    bool jumping() const { return jump_; }
    // Whether a frame has been skinned (the skinned positions exist).
    bool primed() const { return primed_; }
    // The skinned position and unit normal at `fraction` of the frame.
    Vec3 position(uint32_t i, float fraction) const;
    Vec3 normal(uint32_t i, float fraction) const;
    // Keeps the skinned positions and normals of the constrained particles
    // of [begin, end) at `fraction` of the frame, for constrain() to use
    // while the substep runs its constraints more than once.
    void prepare(uint32_t begin, uint32_t end, float fraction);
    // Moves free particles [begin, end) into their max-distance spheres
    // and out of their backstop spheres at `fraction` of the frame (with
    // `prepared`, from what prepare() kept for it: the same values); what
    // a particle moves is added to its velocity over h.
    void constrain(uint32_t begin, uint32_t end, float fraction, float h, const float* pinned, Vec3Soa& x,
                   Vec3Soa& v, bool prepared = false) const;

    // Origin rebasing: positions and matrices move by -shift.
    void shift_origin(const Vec3& shift);

    // The state a snapshot keeps (step/cloth_snapshot.cpp), so that a
    // restored cloth steps as the original did: whether a frame has been
    // skinned, where the last frame ended (the next one starts there),
    // and what the host gave last (the joint matrices, or its skinned
    // positions and normals), as floats in bytes that need not be
    // aligned. state_floats(): its size in floats, for an active skin of
    // n particles.
    size_t state_floats(uint32_t n) const;
    void save_state(unsigned char* out) const;
    // From save_state's bytes of a skin of the same source and joint
    // count, sized for the same particles (the caller checks both).
    void restore_state(bool primed, const unsigned char* in);

  private:
    // After the max distance pulled p into the backstop sphere again: the
    // point nearest p towards the skinned position s outside it.
    Vec3 back_out_towards(const Vec3& p, const Vec3& s, const Vec3& n, uint32_t i) const;
    // A finite max distance above 0, or a backstop.
    bool constrained(uint32_t particle) const;
    void count_constrained(uint32_t particle, bool before);

    Source source_ = Source::kNone;
    uint32_t joint_count_ = 0, influences_ = 0;
    HostVector<uint32_t> joints_;  // kMaxInfluences per particle; unused entries joint 0, weight 0
    HostVector<float> weights_;
    HostVector<float> matrices_;  // kMatrixFloats per joint
    Vec3Soa bind_x_, bind_n_;
    Vec3Soa host_x_, host_n_;                // the host's skinned positions and normals (Source::kHost)
    Vec3Soa from_x_, from_n_, to_x_, to_n_;  // the frame's start and end
    Vec3Soa held_x_, held_n_;                // prepare()'s: one substep's, constrained particles only
    bool primed_ = false, jump_ = false;
    HostVector<float> max_distance_, backstop_distance_, backstop_radius_;
    uint32_t constrained_count_ = 0;  // particles with a finite max distance above 0 or a backstop
};

}  // namespace cloth
