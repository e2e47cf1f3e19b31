// The world's pairs of cloths in contact (collide/cloth_pair_contact.h):
// turned on and off by the host; each frame, the pairs whose cloths can
// meet join both cloths' frames (step/pair_rounds.h).
#include <algorithm>

#include "scene/world.h"

namespace cloth {

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
    if (k == cloth_pairs_.size()) {
        for (uint32_t slot : {slot_a, slot_b}) {
            const auto pairs =
                std::count_if(cloth_pairs_.begin(), cloth_pairs_.end(),
                              [slot](const ClothPair& p) { return p.slot_a == slot || p.slot_b == slot; });
            if (pairs >= static_cast<ptrdiff_t>(FrameContext::kMaxPairs)) {
                return Status::error(CLOTH_ERROR_CAPACITY,
                                     "cloth slot %u is in contact with %u cloths already, the most", slot + 1,
                                     FrameContext::kMaxPairs);
            }
        }
    }
    // Built before anything changes, so an allocation failure changes nothing.
    auto contact = std::allocate_shared<ClothPairContact>(HostAllocator<ClothPairContact>(&memory_), &memory_,
                                                          cloth_at(slot_a).fabric(),
                                                          cloth_at(slot_b).fabric(), *settings);
    auto rounds = std::allocate_shared<PairRounds>(HostAllocator<PairRounds>(&memory_), contact.get());
    if (k < cloth_pairs_.size()) {
        cloth_pairs_[k].contact = std::move(contact);
        cloth_pairs_[k].rounds = std::move(rounds);
    } else {
        cloth_pairs_.push_back(ClothPair{slot_a, slot_b, std::move(contact), std::move(rounds)});
    }
    cloth_at(slot_a).wake();
    cloth_at(slot_b).wake();
    return {};
}

const ClothPairContact* World::cloth_contact(cloth_id a, cloth_id b) const {
    uint32_t slot_a = cloths_.find(a.index1, a.generation), slot_b = cloths_.find(b.index1, b.generation);
    if (slot_a == cloths_.kFull || slot_b == cloths_.kFull) return nullptr;
    if (slot_a > slot_b) std::swap(slot_a, slot_b);
    const size_t k = find_cloth_pair(slot_a, slot_b);
    return k < cloth_pairs_.size() ? cloth_pairs_[k].contact.get() : nullptr;
}

bool World::in_cloth_pair(const SceneCloth& cloth) const {
    for (const ClothPair& pair : cloth_pairs_) {
        if (cloths_[pair.slot_a].object.get() == &cloth || cloths_[pair.slot_b].object.get() == &cloth)
            return true;
    }
    return false;
}

void World::drop_cloth_pairs(uint32_t slot) {
    cloth_pairs_.erase(
        std::remove_if(cloth_pairs_.begin(), cloth_pairs_.end(),
                       [slot](const ClothPair& p) { return p.slot_a == slot || p.slot_b == slot; }),
        cloth_pairs_.end());
}

void World::begin_cloth_pairs() {
    for (ClothPair& pair : cloth_pairs_) {
        ClothInstance& a = cloth_at(pair.slot_a);
        ClothInstance& b = cloth_at(pair.slot_b);
        const bool a_steps = steps(pair.slot_a), b_steps = steps(pair.slot_b);
        // Both step to the same frame (update_rate.h: cloths of one rate
        // in contact share a phase), or one steps beside the other asleep.
        const bool together = a_steps && b_steps &&
                              cloths_[pair.slot_a].object->update_rate().state_frame() ==
                                  cloths_[pair.slot_b].object->update_rate().state_frame();
        const bool beside_sleeper =
            (a_steps && !b_steps && b.sleeping()) || (b_steps && !a_steps && a.sleeping());
        const ParticleView va = a.particle_view(a_steps), vb = b.particle_view(b_steps);
        const float dt = frame_inputs_[stepping_index_[a_steps ? pair.slot_a : pair.slot_b]].dt;
        pair.active = (together || beside_sleeper) && pair.contact->near(va, vb, dt);
        if (!pair.active) {
            pair.contact->clear();
            continue;
        }
        pair.rounds->begin_frame(va, vb);
    }
    // The cloths of a pair share their substeps: the most of any cloth they
    // are in contact with, directly or through others.
    for (bool raised = true; raised;) {
        raised = false;
        for (const ClothPair& pair : cloth_pairs_) {
            if (!pair.active || !steps(pair.slot_a) || !steps(pair.slot_b)) continue;
            const uint32_t ia = stepping_index_[pair.slot_a], ib = stepping_index_[pair.slot_b];
            const uint32_t most = std::max(decisions_[ia].solver.substeps, decisions_[ib].solver.substeps);
            raised = raised || decisions_[ia].solver.substeps != decisions_[ib].solver.substeps;
            decisions_[ia] = share_substeps(decisions_[ia], most, frame_inputs_[ia]);
            decisions_[ib] = share_substeps(decisions_[ib], most, frame_inputs_[ib]);
        }
    }
}

void World::join_cloth_pairs() {
    for (ClothPair& pair : cloth_pairs_) {
        if (!pair.active) continue;
        if (steps(pair.slot_a)) cloth_at(pair.slot_a).join_pair(&pair.rounds->side(0));
        if (steps(pair.slot_b)) cloth_at(pair.slot_b).join_pair(&pair.rounds->side(1));
    }
}

void World::end_cloth_pairs() {
    for (ClothPair& pair : cloth_pairs_) {
        if (!pair.active || pair.contact->contacts() == 0) continue;
        for (uint32_t slot : {pair.slot_a, pair.slot_b}) {
            ClothInstance& cloth = cloth_at(slot);
            if (cloth.sleeping()) cloth.wake();  // touched by a cloth that stepped
        }
    }
}

}  // namespace cloth
