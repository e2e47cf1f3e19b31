// The one id pool behind every handle kind of the C API (worlds, fabrics,
// cloths, bodies, colliders): a table of slots, each holding an object and
// the slot's generation. A public handle is (slot index + 1, generation), so
// all-zero is null; destroying an object bumps its slot's generation, so an
// old handle to a reused slot is refused instead of followed.
//
// Written here rather than taken from a library because it is a few lines
// and has rules of its own: every byte goes through the host's allocator
// (HostVector); a new object takes the lowest free slot, since handle
// values and the order in which a step visits cloths and colliders depend
// on it; and a generation skips 0 when it wraps, so no live handle is null.
// Not synchronised: each owner guards it as it guards the rest of its state.
#pragma once

#include <cstdint>
#include <utility>

#include "base/host_allocator.h"

namespace cloth {

template <class T>
class IdPool {
  public:
    struct Slot {
        T object{};
        uint16_t generation = 1;  // of the live object, or of the next one while free
        bool live = false;
    };
    static constexpr uint32_t kFull = UINT32_MAX;

    // At most `max_slots` (<= 65535, the range of a handle's index) slots.
    IdPool(const HostMemory* memory, uint32_t max_slots)
        : slots_(HostAllocator<Slot>(memory)), max_slots_(max_slots) {}

    // Make every slot now, so that taking one later allocates nothing.
    void make_all_slots() { slots_.resize(max_slots_); }

    // The lowest free slot, adding one if all are live and fewer than
    // max_slots exist; kFull if max_slots are live. Adding may throw
    // std::bad_alloc; nothing has changed then.
    uint32_t free_slot() {
        for (uint32_t i = 0; i < slots_.size(); ++i) {
            if (!slots_[i].live) return i;
        }
        if (slots_.size() >= max_slots_) return kFull;
        slots_.emplace_back();
        return static_cast<uint32_t>(slots_.size() - 1);
    }

    // Put `object` in free slot `index`; returns the generation of its handle.
    uint16_t occupy(uint32_t index, T object) {
        Slot& slot = slots_[index];
        slot.object = std::move(object);
        slot.live = true;
        return slot.generation;
    }

    // The slot index a handle names if its object is live, else kFull.
    uint32_t find(uint16_t index1, uint16_t generation) const {
        if (index1 == 0 || index1 > slots_.size()) return kFull;
        const Slot& slot = slots_[index1 - 1u];
        return slot.live && slot.generation == generation ? index1 - 1u : kFull;
    }
    T* get(uint16_t index1, uint16_t generation) {
        const uint32_t index = find(index1, generation);
        return index == kFull ? nullptr : &slots_[index].object;
    }

    // Empty a live slot and retire every handle to it.
    void release(uint32_t index) {
        Slot& slot = slots_[index];
        slot.object = T{};
        slot.live = false;
        slot.generation = static_cast<uint16_t>(slot.generation == UINT16_MAX ? 1 : slot.generation + 1);
    }

    uint32_t size() const { return static_cast<uint32_t>(slots_.size()); }
    uint32_t max_slots() const { return max_slots_; }
    Slot& operator[](uint32_t index) { return slots_[index]; }
    const Slot& operator[](uint32_t index) const { return slots_[index]; }
    auto begin() { return slots_.begin(); }
    auto end() { return slots_.end(); }
    auto begin() const { return slots_.begin(); }
    auto end() const { return slots_.end(); }

  private:
    HostVector<Slot> slots_;
    uint32_t max_slots_;
};

}  // namespace cloth
