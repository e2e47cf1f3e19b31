// A cloth's side of bodies and colliders: its collision settings, its
// attachments to bodies and its carrier. ClothInstance holds one and calls
// it at three places of the step: begin_step (carrier, once per frame),
// attached_position (the kinematic target of an attached particle at a
// fraction of the frame, used where pins are driven) and collide (the
// collision stage after integration, over a particle range).
//
// Nothing here allocates until the feature is used: the attachment arrays
// on the first cloth_attach, the carrier's reference shape on
// cloth_set_carrier. The collision stage runs only while some collider
// meets the cloth's mask.
#pragma once

#include <cstdint>

#include "base/host_allocator.h"
#include "base/soa.h"
#include "collide/bodies.h"
#include "collide/carrier.h"
#include "collide/colliders.h"
#include "collide/contact_world.h"

namespace cloth {

class ClothContact {
  public:
    explicit ClothContact(const HostMemory* memory)
        : attached_body_(HostAllocator<uint32_t>(memory)),
          attached_offset_(memory),
          carrier_(memory),
          recorded_collider_(HostAllocator<uint16_t>(memory)),
          recorded_count_(HostAllocator<uint8_t>(memory)) {}

    void bind(const ContactWorld* world) { world_ = world; }
    const ContactWorld* world() const { return world_; }

    CollisionParams& collision() { return collision_; }
    const CollisionParams& collision() const { return collision_; }

    // Attachments. attach() may throw bad_alloc before changing anything.
    void reserve_attachments(uint32_t particle_count);
    void attach(uint32_t particle, uint32_t body_slot, const Vec3& offset);
    void detach(uint32_t particle);
    bool is_attached(uint32_t particle) const {
        return !attached_body_.empty() && attached_body_[particle] != UINT32_MAX;
    }
    uint32_t attached_body(uint32_t particle) const { return attached_body_[particle]; }
    Vec3 attached_offset(uint32_t particle) const { return attached_offset_.get(particle); }
    // Where an attached particle is at `fraction` of the current frame.
    Vec3 attached_position(uint32_t particle, float fraction) const;

    Carrier& carrier() { return carrier_; }
    const Carrier& carrier() const { return carrier_; }
    // A cloth the host put to sleep does not travel with its carrier while
    // asleep; the first step after it wakes moves it with the carrier from
    // where the carrier was when it fell asleep, as a teleport does.
    void fall_asleep();
    void wake_up();
    // The host placed the cloth (positions, a snapshot): nothing to catch up with.
    void forget_sleep() { slept_on_ = catch_up_on_ = UINT32_MAX; }

    // Once per frame, before the substeps (carrier).
    void begin_step(float dt, const float* pinned, Vec3Soa& x, Vec3Soa& v);
    // Whether collide() has anything to do for this cloth.
    bool collides() const {
        return world_ && collision_.collider_mask && world_->any_collider(collision_.collider_mask);
    }
    // Whether the cloth follows bodies that the host moves (attachments, a
    // carrier or colliders): such a cloth never goes to sleep, since a body
    // can move without any call on the cloth.
    bool follows_bodies() const { return rides_bodies() || collides(); }
    // Whether bodies carry the cloth (attachments or a carrier): a body's
    // motion and teleports are seen frame by frame, so such a cloth steps
    // at update rate 1 (update_rate.h).
    bool rides_bodies() const { return !attached_body_.empty() || carrier_.active(); }
    // Which colliders a collision pass tests. The first of the rounds
    // between the strain limiter's passes tests every one and records,
    // per particle, those it is within reach of: nearer than twice the
    // thickness plus its path over the substep in the collider's frame
    // plus twice its own path (what the passes after it move a particle,
    // mostly). The later rounds between the passes test each particle
    // against its record only, so a particle far from every collider costs
    // nothing there. What a record misses (a particle the passes pull
    // further, after a neighbour a collider pushed) the round after the
    // last pass finds: it tests every collider again, so the substep ends
    // out of every one.
    enum class Pass : uint8_t { kRecord, kRecorded, kEvery };
    // Sizes the record for the cloth's particles (at its creation).
    void size_record(uint32_t particle_count);
    // The collision stage over particles [begin, end) (a particle group) of
    // a substep from fraction `from` to `to` of the frame, of length h.
    // Returns the number of particle-collider contacts.
    uint32_t collide(float h, float from, float to, const float* kinematic, uint32_t begin, uint32_t end,
                     Vec3Soa& x, Vec3Soa& v, Pass pass = Pass::kEvery);

  private:
    Pose body_pose(uint32_t body_slot, float fraction) const;
    MovingCollider moving_collider(const Collider& collider, float from, float to) const;
    // Records which colliders each free particle of [begin, end) is within reach of.
    void record(const MovingCollider& collider, uint16_t slot, float h, const float* kinematic,
                uint32_t begin, uint32_t end, const Vec3Soa& x, const Vec3Soa& v);
    // The rounds between the strain limiter's passes: each particle of
    // [begin, end) against the colliders of its record.
    uint32_t collide_recorded(float h, float from, float to, const float* kinematic, uint32_t begin,
                              uint32_t end, Vec3Soa& x, Vec3Soa& v);

    const ContactWorld* world_ = nullptr;
    CollisionParams collision_;
    HostVector<uint32_t> attached_body_;  // per particle body slot, UINT32_MAX: none; empty until used
    Vec3Soa attached_offset_;             // per particle, body frame
    Carrier carrier_;
    uint32_t slept_on_ = UINT32_MAX;     // the carrier's slot when the cloth fell asleep, or none
    uint16_t slept_generation_ = 0;      // its generation (the slot may be reused)
    Pose slept_at_;                      // and the carrier's pose then
    uint32_t catch_up_on_ = UINT32_MAX;  // woken: the next begin_step jumps from slept_at_ on this carrier
    // The record of Pass::kRecord: per particle, up to kRecordedColliders
    // collider slots (particle i's from entry i * kRecordedColliders) and
    // their count, kEveryCollider when there were more.
    static constexpr uint32_t kRecordedColliders = 4;
    static constexpr uint8_t kEveryCollider = 0xFF;
    HostVector<uint16_t> recorded_collider_;
    HostVector<uint8_t> recorded_count_;
};

}  // namespace cloth
