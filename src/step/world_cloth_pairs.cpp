// The world's pairs of cloths in contact (collide/cloth_pair_contact.h):
// turned on and off by the host, resolved after every cloth's frame.
#include <algorithm>

#include "step/world.h"

namespace cloth {

namespace {

// Particles per task of a contact round: a round's work per particle is
// a few dozen flops, so smaller ranges cost more to hand out than to run.
constexpr uint32_t kMinParticlesPerRange = 256;

}  // namespace

size_t World::find_cloth_pair(uint32_t slot_a, uint32_t slot_b) const {
    for (size_t k = 0; k < cloth_pairs_.size(); ++k) {
        if (cloth_pairs_[k].slot_a == slot_a && cloth_pairs_[k].slot_b == slot_b) return k;
    }
    return cloth_pairs_.size();
}

Status World::set_cloth_contact(cloth_id a, cloth_id b, const ClothPairSettings* settings) {
    uint32_t slot_a = cloths_.find(a.index1, a.generation), slot_b = cloths_.find(b.index1, b.generation);
    if (slot_a == cloths_.kFull || slot_b == cloths_.kFull) {
        return Status::error(CLOTH_ERROR_INVALID_HANDLE,
                             "cloth handle names no live cloth in its world (destroyed, or never created)");
    }
    if (slot_a == slot_b) {
        return Status::error(CLOTH_ERROR_INVALID_VALUE,
                             "a cloth and itself: its contact with itself is cloth_set_self_collision");
    }
    if (slot_a > slot_b) std::swap(slot_a, slot_b);
    const size_t k = find_cloth_pair(slot_a, slot_b);
    if (!settings) {
        if (k < cloth_pairs_.size()) cloth_pairs_.erase(cloth_pairs_.begin() + static_cast<ptrdiff_t>(k));
        return {};
    }
    // Built before anything changes, so an allocation failure changes nothing.
    auto contact = std::allocate_shared<ClothPairContact>(HostAllocator<ClothPairContact>(&memory_), &memory_,
                                                          cloths_[slot_a].object->fabric(),
                                                          cloths_[slot_b].object->fabric(), *settings);
    if (k < cloth_pairs_.size()) {
        cloth_pairs_[k].contact = std::move(contact);
    } else {
        cloth_pairs_.push_back(ClothPair{slot_a, slot_b, std::move(contact)});
    }
    cloths_[slot_a].object->wake();
    cloths_[slot_b].object->wake();
    return {};
}

const ClothPairContact* World::cloth_contact(cloth_id a, cloth_id b) const {
    uint32_t slot_a = cloths_.find(a.index1, a.generation), slot_b = cloths_.find(b.index1, b.generation);
    if (slot_a == cloths_.kFull || slot_b == cloths_.kFull) return nullptr;
    if (slot_a > slot_b) std::swap(slot_a, slot_b);
    const size_t k = find_cloth_pair(slot_a, slot_b);
    return k < cloth_pairs_.size() ? cloth_pairs_[k].contact.get() : nullptr;
}

void World::drop_cloth_pairs(uint32_t slot) {
    cloth_pairs_.erase(
        std::remove_if(cloth_pairs_.begin(), cloth_pairs_.end(),
                       [slot](const ClothPair& p) { return p.slot_a == slot || p.slot_b == slot; }),
        cloth_pairs_.end());
}

namespace {

// Whether contact between two cloths runs after this frame: each stepped
// in it or sleeps, and the awake ones' states end at the same frame
// (update_rate.h: cloths of one rate in contact share a phase).
bool in_step(const ClothInstance& a, const ClothInstance& b, uint64_t frame) {
    auto stepped = [frame](const ClothInstance& c) { return c.update_rate().stepped_in(frame); };
    if (a.sleeping() || b.sleeping()) return a.sleeping() ? stepped(b) : stepped(a);
    return stepped(a) && stepped(b) && a.update_rate().state_frame() == b.update_rate().state_frame();
}

}  // namespace

void World::resolve_cloth_pairs() {
    for (ClothPair& pair : cloth_pairs_) {
        ClothInstance& a = *cloths_[pair.slot_a].object;
        ClothInstance& b = *cloths_[pair.slot_b].object;
        ClothPairContact& contact = *pair.contact;
        if ((a.sleeping() && b.sleeping()) || !in_step(a, b, frame_) || !contact.near(a, b)) {
            contact.clear();
            continue;
        }
        const uint32_t n = contact.count();
        auto gather = [&](uint32_t begin, uint32_t end, uint32_t) { contact.gather(a, b, begin, end); };
        parallel_for(*tasks_, n, kMinParticlesPerRange, gather);
        contact.sort();
        auto find = [&](uint32_t begin, uint32_t end, uint32_t) { contact.find_contacts(begin, end); };
        parallel_for(*tasks_, n, kMinParticlesPerRange, find);
        auto project = [&](uint32_t begin, uint32_t end, uint32_t) { contact.project(begin, end); };
        do {
            parallel_for(*tasks_, n, kMinParticlesPerRange, project);
        } while (contact.apply_positions());
        auto respond = [&](uint32_t begin, uint32_t end, uint32_t) { contact.respond(begin, end); };
        parallel_for(*tasks_, n, kMinParticlesPerRange, respond);
        contact.apply_velocities();
        auto scatter = [&](uint32_t begin, uint32_t end, uint32_t) { contact.scatter(a, b, begin, end); };
        parallel_for(*tasks_, n, kMinParticlesPerRange, scatter);
        contact.finish_frame();
        if (contact.contacts() == 0) continue;
        for (ClothInstance* cloth : {&a, &b}) {
            // A sleeping cloth that was touched moves again; an awake one
            // has its strain limit and skin held again.
            if (cloth->sleeping()) {
                cloth->wake();
            } else {
                cloth->settle_after_contact();
            }
        }
    }
}

}  // namespace cloth
