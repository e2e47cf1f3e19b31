// The bodies and colliders of one world, each kind in an id pool (slot +
// generation, like cloths) that grows on creation, never during a step.
// Cloths refer to bodies by slot; destroying a body is cascaded by World
// (attachments, carriers) and here (its colliders).
#pragma once

#include <cstdint>
#include <memory>

#include "base/host_allocator.h"
#include "base/id_pool.h"
#include "base/status.h"
#include "collide/bodies.h"
#include "collide/colliders.h"

namespace cloth {

struct BodyState {
    Body body;
    bool jumped = false;  // teleported since the last step (no sweep, no interpolation)
    Pose before_jump;     // while jumped: where the first teleport took it from (for carriers)
};

class ContactWorld {
  public:
    static constexpr uint32_t kMaxSlots = 65535;

    explicit ContactWorld(const HostMemory* memory)
        : memory_(memory), bodies_(memory, kMaxSlots), colliders_(memory, kMaxSlots) {}

    const HostMemory* memory() const { return memory_; }

    // Bodies. Lookups take the public id's index1 (slot + 1) and generation.
    Status create_body(const Body& body, uint32_t* out_slot, uint16_t* out_generation);
    BodyState* find_body(uint16_t index1, uint16_t generation) { return bodies_.get(index1, generation); }
    const BodyState& body(uint32_t slot) const { return bodies_[slot].object; }
    uint16_t body_generation(uint32_t slot) const { return bodies_[slot].generation; }
    // Frees the slot and destroys the colliders fixed to the body.
    void destroy_body(uint32_t slot);

    Status create_collider(const Collider& collider, uint32_t* out_slot, uint16_t* out_generation);
    Collider* find_collider(uint16_t index1, uint16_t generation) {
        return colliders_.get(index1, generation);
    }
    void destroy_collider(uint32_t slot) { colliders_.release(slot); }
    const IdPool<Collider>& colliders() const { return colliders_; }
    // Whether any live collider meets `mask` (else the collision stage is skipped).
    bool any_collider(uint32_t mask) const;

    // After a world step: every body starts the next step where it is now.
    void end_step();
    // Subtract `shift` from every body pose and static collider pose;
    // can_shift_origin: whether every result stays finite.
    bool can_shift_origin(const Vec3& shift) const;
    void shift_origin(const Vec3& shift);

  private:
    const HostMemory* memory_;
    IdPool<BodyState> bodies_;
    IdPool<Collider> colliders_;
};

}  // namespace cloth
