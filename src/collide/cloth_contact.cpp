#include "collide/cloth_contact.h"

#include <algorithm>
#include <cmath>

#include "base/staged.h"

namespace cloth {

void ClothContact::reserve_attachments(uint32_t particle_count) {
    if (!attached_body_.empty()) return;
    Vec3Soa offsets(attached_offset_.x.get_allocator().memory());
    offsets.resize(particle_count);
    HostVector<uint32_t> bodies(particle_count, UINT32_MAX, attached_body_.get_allocator());
    attached_offset_ = std::move(offsets);
    attached_body_ = std::move(bodies);
}

void ClothContact::attach(uint32_t particle, uint32_t body_slot, const Vec3& offset) {
    attached_body_[particle] = body_slot;
    attached_offset_.set(particle, offset);
}

void ClothContact::detach(uint32_t particle) {
    if (!attached_body_.empty()) attached_body_[particle] = UINT32_MAX;
}

Pose ClothContact::body_pose(uint32_t body_slot, float fraction) const {
    const Body& body = world_->body(body_slot).body;
    // A carrier teleport takes the carrier's attachments to the new pose at
    // once (the cloth moved there before the substeps).
    if (carrier_.teleported() && body_slot == carrier_.body()) return body.target;
    return body.pose_at(fraction);
}

Vec3 ClothContact::attached_position(uint32_t particle, float fraction) const {
    return body_pose(attached_body_[particle], fraction).apply(attached_offset_.get(particle));
}

void ClothContact::fall_asleep() {
    catch_up_on_ = UINT32_MAX;
    slept_on_ = carrier_.active() ? carrier_.body() : UINT32_MAX;
    if (slept_on_ == UINT32_MAX) return;
    slept_generation_ = world_->body_generation(slept_on_);
    const BodyState& carrier = world_->body(slept_on_);
    slept_at_ =
        carrier.jumped ? carrier.before_jump : carrier.body.start;  // where the cloth last followed it
}

void ClothContact::wake_up() {
    catch_up_on_ = slept_on_;
    slept_on_ = UINT32_MAX;
}

void ClothContact::begin_step(float dt, const float* pinned, Vec3Soa& x, Vec3Soa& v) {
    const uint32_t catch_up_on = catch_up_on_;
    catch_up_on_ = UINT32_MAX;
    if (!carrier_.active()) return;
    const BodyState& carrier = world_->body(carrier_.body());
    // A carrier changed while the cloth slept has nothing to catch up with.
    const bool same =
        carrier_.body() == catch_up_on && world_->body_generation(catch_up_on) == slept_generation_;
    const Pose* jumped_from = same ? &slept_at_ : carrier.jumped ? &carrier.before_jump : nullptr;
    carrier_.begin_step(carrier.body, jumped_from, dt, pinned,
                        attached_body_.empty() ? nullptr : &attached_body_, x, v);
}

void ClothContact::size_record(uint32_t particle_count) {
    recorded_collider_.assign(size_t{particle_count} * kRecordedColliders, 0);
    recorded_count_.assign(particle_count, kEveryCollider);
}

uint32_t ClothContact::collide(float h, float from, float to, const float* kinematic, uint32_t begin,
                               uint32_t end, Vec3Soa& x, Vec3Soa& v, Pass pass) {
    const bool records = !recorded_count_.empty();
    if (pass == Pass::kRecorded && records) return collide_recorded(h, from, to, kinematic, begin, end, x, v);
    // Culled by bounds before any per-particle work: the range's first (a
    // flag high above a terrain or beside a box needs nothing for it), then
    // each chunk's (a flag beside its pole touches it only near the pole).
    // A chunk's bounds are taken once per collision pass and shared by the
    // colliders, and taken again after a collider moved its particles.
    constexpr uint32_t kMaxChunks = (kGroupSize + kCollisionChunk - 1) / kCollisionChunk;
    RangeBounds chunks[kMaxChunks];
    const uint32_t chunk_count = std::min((end - begin + kCollisionChunk - 1) / kCollisionChunk, kMaxChunks);
    const auto chunk_end = [&](uint32_t k) {
        return k + 1 == chunk_count ? end : begin + (k + 1) * kCollisionChunk;
    };
    const bool recording = pass == Pass::kRecord && records;
    RangeBounds range;
    bool bounded = false;  // bounds taken (at the first collider)
    if (recording) std::fill(&recorded_count_[begin], &recorded_count_[begin] + (end - begin), uint8_t{0});
    uint32_t contacts = 0;
    const auto& colliders = world_->colliders();
    for (uint32_t slot_index = 0; slot_index < colliders.size(); ++slot_index) {
        const auto& slot = colliders[slot_index];
        const Collider& c = slot.object;
        if (!slot.live || !(c.group_bits & collision_.collider_mask)) continue;
        const MovingCollider moving = moving_collider(c, from, to);
        if (!bounded) {
            range = RangeBounds{};
            for (uint32_t k = 0; k < chunk_count; ++k) {
                chunks[k] = range_bounds(h, kinematic, begin + k * kCollisionChunk, chunk_end(k), x, v);
                range.merge(chunks[k]);
            }
            bounded = true;
        }
        if (recording) {
            // Every chunk the collider may reach in the rest of the substep,
            // with at least the margin record() takes.
            CollisionParams reach = collision_;
            reach.thickness += collision_.thickness + 2.0f * range.travel;
            if (!range_is_clear(moving, reach, range)) {
                for (uint32_t k = 0; k < chunk_count; ++k) {
                    if (range_is_clear(moving, reach, chunks[k])) continue;
                    record(moving, static_cast<uint16_t>(slot_index), h, kinematic,
                           begin + k * kCollisionChunk, chunk_end(k), x, v);
                }
            }
        }
        if (range_is_clear(moving, collision_, range)) continue;
        for (uint32_t k = 0; k < chunk_count; ++k) {
            if (range_is_clear(moving, collision_, chunks[k])) continue;
            const uint32_t chunk_contacts = collide_particles(
                moving, collision_, h, kinematic, begin + k * kCollisionChunk, chunk_end(k), x, v);
            if (chunk_contacts > 0) bounded = false;  // particles moved: the next collider takes bounds anew
            contacts += chunk_contacts;
        }
    }
    return contacts;
}

MovingCollider ClothContact::moving_collider(const Collider& c, float from, float to) const {
    const bool on_body = c.body != UINT32_MAX;
    return MovingCollider(c.shape.get(), on_body ? body_pose(c.body, from) * c.local : c.local,
                          on_body ? body_pose(c.body, to) * c.local : c.local,
                          on_body ? &world_->body(c.body).body : nullptr);
}

void ClothContact::record(const MovingCollider& collider, uint16_t slot, float h, const float* kinematic,
                          uint32_t begin, uint32_t end, const Vec3Soa& x, const Vec3Soa& v) {
    // Before this collider's own pass moved them. A particle's path over
    // the substep, in the collider's moving frame, touches the collider
    // only if its end is within the thickness plus the path's length of
    // it; the passes after it may take it about twice its own path
    // further, and one the collision stage left at the thickness back in.
    for (uint32_t i = begin; i < end; ++i) {
        if (kinematic[i] != 0.0f) continue;
        uint8_t& count = recorded_count_[i];
        if (count == kEveryCollider) continue;
        const Vec3 x_end = x.get(i), step = v.get(i) * h;
        const Vec3 local_end = collider.end.apply_inverse(x_end);
        const float path = (local_end - collider.start.apply_inverse(Vec3(x_end - step))).norm();
        const float reach = 2.0f * collision_.thickness + path + 2.0f * step.norm();
        if (!(query_shape(*collider.shape, local_end, reach).distance < reach)) continue;
        if (count == kRecordedColliders) {
            count = kEveryCollider;
            continue;
        }
        recorded_collider_[size_t{i} * kRecordedColliders + count++] = slot;
    }
}

uint32_t ClothContact::collide_recorded(float h, float from, float to, const float* kinematic, uint32_t begin,
                                        uint32_t end, Vec3Soa& x, Vec3Soa& v) {
    // The group's recorded colliders over this substep, each taken once.
    constexpr uint32_t kMost = 16;
    uint16_t slots[kMost];
    MovingCollider moving[kMost];
    uint32_t distinct = 0;
    for (uint32_t i = begin; i < end; ++i) {
        const uint8_t count = recorded_count_[i];
        if (count == 0) continue;
        if (count == kEveryCollider) return collide(h, from, to, kinematic, begin, end, x, v);
        for (uint32_t c = 0; c < count; ++c) {
            const uint16_t slot = recorded_collider_[size_t{i} * kRecordedColliders + c];
            if (std::find(slots, slots + distinct, slot) != slots + distinct) continue;
            if (distinct == kMost) return collide(h, from, to, kinematic, begin, end, x, v);
            slots[distinct] = slot;
            moving[distinct++] = moving_collider(world_->colliders()[slot].object, from, to);
        }
    }
    uint32_t contacts = 0;
    for (uint32_t i = begin; i < end; ++i) {
        const uint8_t count = recorded_count_[i];
        for (uint32_t c = 0; c < count; ++c) {
            const uint16_t slot = recorded_collider_[size_t{i} * kRecordedColliders + c];
            const uint32_t k = static_cast<uint32_t>(std::find(slots, slots + distinct, slot) - slots);
            contacts += collide_particles(moving[k], collision_, h, kinematic, i, i + 1, x, v);
        }
    }
    return contacts;
}

}  // namespace cloth
