#include "collide/contact_world.h"

namespace cloth {

namespace {

template <class T>
Status take_slot(IdPool<T>& pool, const char* what, uint32_t* out_slot) {
    *out_slot = pool.free_slot();  // may throw bad_alloc; nothing changed then
    if (*out_slot == IdPool<T>::kFull) {
        return Status::error(CLOTH_ERROR_CAPACITY, "the world has %u %s already", ContactWorld::kMaxSlots,
                             what);
    }
    return {};
}

}  // namespace

Status ContactWorld::create_body(const Body& body, uint32_t* out_slot, uint16_t* out_generation) {
    Status s = take_slot(bodies_, "bodies", out_slot);
    if (!s.ok()) return s;
    BodyState state;
    state.body = body;
    *out_generation = bodies_.occupy(*out_slot, state);
    return {};
}

void ContactWorld::destroy_body(uint32_t slot) {
    for (uint32_t c = 0; c < colliders_.size(); ++c) {
        if (colliders_[c].live && colliders_[c].object.body == slot) destroy_collider(c);
    }
    bodies_.release(slot);
}

Status ContactWorld::create_collider(const Collider& collider, uint32_t* out_slot, uint16_t* out_generation) {
    Status s = take_slot(colliders_, "colliders", out_slot);
    if (!s.ok()) return s;
    *out_generation = colliders_.occupy(*out_slot, collider);
    return {};
}

bool ContactWorld::any_collider(uint32_t mask) const {
    for (const auto& c : colliders_) {
        if (c.live && (c.object.group_bits & mask)) return true;
    }
    return false;
}

void ContactWorld::end_step() {
    for (auto& b : bodies_) {
        if (!b.live) continue;
        b.object.body.start = b.object.body.target;
        b.object.jumped = false;
    }
}

bool ContactWorld::can_shift_origin(const Vec3& shift) const {
    const auto fits = [&](const Vec3& p) { return (p - shift).allFinite(); };
    for (const auto& slot : bodies_) {
        const BodyState& b = slot.object;
        if (slot.live &&
            !(fits(b.body.start.position) && fits(b.body.target.position) && fits(b.before_jump.position)))
            return false;
    }
    for (const auto& c : colliders_) {
        if (c.live && c.object.body == UINT32_MAX && !fits(c.object.local.position)) return false;
    }
    return true;
}

void ContactWorld::shift_origin(const Vec3& shift) {
    for (auto& slot : bodies_) {
        if (!slot.live) continue;
        BodyState& b = slot.object;
        b.body.start.position -= shift;
        b.body.target.position -= shift;
        b.before_jump.position -= shift;
    }
    for (auto& c : colliders_) {
        if (c.live && c.object.body == UINT32_MAX) c.object.local.position -= shift;
    }
}

}  // namespace cloth
