#include "collide/contact_world.h"

namespace cloth {

namespace {

template <class Slots>
Status take_slot(Slots& slots, const char* what, uint32_t* out_slot) {
    for (uint32_t i = 0; i < slots.size(); ++i) {
        if (!slots[i].live) {
            *out_slot = i;
            return {};
        }
    }
    if (slots.size() >= ContactWorld::kMaxSlots) {
        return Status::error(CLOTH_ERROR_CAPACITY, "the world has %u %s already", ContactWorld::kMaxSlots,
                             what);
    }
    slots.emplace_back();  // may throw bad_alloc; nothing changed then
    *out_slot = static_cast<uint32_t>(slots.size() - 1);
    return {};
}

template <class Slots>
auto* find_slot(Slots& slots, uint16_t index1, uint16_t generation) {
    using Slot = typename Slots::value_type;
    if (index1 == 0 || index1 > slots.size()) return static_cast<Slot*>(nullptr);
    Slot& slot = slots[index1 - 1];
    return slot.live && slot.generation == generation ? &slot : static_cast<Slot*>(nullptr);
}

}  // namespace

Status ContactWorld::create_body(const Body& body, uint32_t* out_slot, uint16_t* out_generation) {
    Status s = take_slot(bodies_, "bodies", out_slot);
    if (!s.ok()) return s;
    BodySlot& slot = bodies_[*out_slot];
    slot.body = body;
    slot.jumped = false;
    slot.live = true;
    *out_generation = slot.generation;
    return {};
}

BodySlot* ContactWorld::find_body(uint16_t index1, uint16_t generation) {
    return find_slot(bodies_, index1, generation);
}

void ContactWorld::destroy_body(uint32_t slot) {
    for (uint32_t c = 0; c < colliders_.size(); ++c) {
        if (colliders_[c].live && colliders_[c].collider.body == slot) destroy_collider(c);
    }
    BodySlot& b = bodies_[slot];
    const uint16_t generation = static_cast<uint16_t>(b.generation + 1 == 0 ? 1 : b.generation + 1);
    b = BodySlot{};
    b.generation = generation;
}

Status ContactWorld::create_collider(const Collider& collider, uint32_t* out_slot, uint16_t* out_generation) {
    Status s = take_slot(colliders_, "colliders", out_slot);
    if (!s.ok()) return s;
    ColliderSlot& slot = colliders_[*out_slot];
    slot.collider = collider;
    slot.live = true;
    *out_generation = slot.generation;
    return {};
}

ColliderSlot* ContactWorld::find_collider(uint16_t index1, uint16_t generation) {
    return find_slot(colliders_, index1, generation);
}

void ContactWorld::destroy_collider(uint32_t slot) {
    ColliderSlot& c = colliders_[slot];
    const uint16_t generation = static_cast<uint16_t>(c.generation + 1 == 0 ? 1 : c.generation + 1);
    c = ColliderSlot{};
    c.generation = generation;
}

bool ContactWorld::any_collider(uint32_t mask) const {
    for (const ColliderSlot& c : colliders_) {
        if (c.live && (c.collider.group_bits & mask)) return true;
    }
    return false;
}

void ContactWorld::end_step() {
    for (BodySlot& b : bodies_) {
        if (!b.live) continue;
        b.body.start = b.body.target;
        b.jumped = false;
    }
}

bool ContactWorld::can_shift_origin(const Vec3& shift) const {
    const auto fits = [&](const Vec3& p) { return (p - shift).allFinite(); };
    for (const BodySlot& b : bodies_) {
        if (b.live &&
            !(fits(b.body.start.position) && fits(b.body.target.position) && fits(b.before_jump.position)))
            return false;
    }
    for (const ColliderSlot& c : colliders_) {
        if (c.live && c.collider.body == UINT32_MAX && !fits(c.collider.local.position)) return false;
    }
    return true;
}

void ContactWorld::shift_origin(const Vec3& shift) {
    for (BodySlot& b : bodies_) {
        if (!b.live) continue;
        b.body.start.position -= shift;
        b.body.target.position -= shift;
        b.before_jump.position -= shift;
    }
    for (ColliderSlot& c : colliders_) {
        if (c.live && c.collider.body == UINT32_MAX) c.collider.local.position -= shift;
    }
}

}  // namespace cloth
