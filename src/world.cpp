#include "world.h"

#include <cstdlib>

namespace cloth {

void* HostMemory::allocate(size_t size, size_t alignment) const {
    if (alignment < alignof(std::max_align_t)) alignment = alignof(std::max_align_t);
    void* p = nullptr;
    if (alloc) {
        p = alloc(size, alignment, user);
    } else {
        // aligned_alloc needs a size that is a multiple of the alignment.
        p = std::aligned_alloc(alignment, (size + alignment - 1) / alignment * alignment);
    }
    if (!p) throw std::bad_alloc();
    return p;
}

void HostMemory::deallocate(void* ptr, size_t size) const {
    if (!ptr) return;
    if (free) {
        free(ptr, size, user);
    } else {
        std::free(ptr);
    }
}

World::World(const cloth_world_desc& desc, uint16_t index, uint16_t generation)
    : gravity(desc.gravity[0], desc.gravity[1], desc.gravity[2]),
      memory_{desc.alloc, desc.free, desc.user},
      log_(desc.log),
      index_(index),
      generation_(generation),
      fabrics_(HostAllocator<Slot<Fabric>>(&memory_)),
      cloths_(HostAllocator<Slot<ClothInstance>>(&memory_)),
      tasks_(&serial_tasks_),
      host_tasks_(desc.enqueue_task, desc.finish_task, desc.task_user, desc.worker_count),
      pool_(desc.enqueue_task ? 1 : desc.worker_count),
      stepping_(HostAllocator<ClothInstance*>(&memory_)),
      round_(HostAllocator<RoundTask>(&memory_)) {
    fabrics_.resize(desc.max_fabrics);
    cloths_.resize(desc.max_cloths);
    stepping_.reserve(desc.max_cloths);
    if (desc.enqueue_task) {
        tasks_ = &host_tasks_;
    } else if (desc.worker_count > 1) {
        tasks_ = &pool_;  // its threads keep their state on the C++ heap
    }
}

void World::log(cloth_log_level level, cloth_result code, const char* message) const {
    if (log_) log_(level, code, message, memory_.user);
}

namespace {

template <class T, class Id>
T* lookup(const HostVector<Slot<T>>& slots, Id id) {
    if (id.index1 == 0 || id.index1 > slots.size()) return nullptr;
    const Slot<T>& slot = slots[id.index1 - 1];
    if (!slot.object || slot.generation != id.generation) return nullptr;
    return slot.object.get();
}

template <class T>
void release(Slot<T>& slot) {
    slot.object.reset();
    slot.generation = static_cast<uint16_t>(slot.generation + 1 == 0 ? 1 : slot.generation + 1);
}

}  // namespace

std::shared_ptr<const Fabric> World::find_fabric(cloth_fabric_id id) const {
    if (!lookup(fabrics_, id)) return nullptr;
    return fabrics_[id.index1 - 1].object;
}

Status World::destroy_fabric(cloth_fabric_id id) {
    if (!lookup(fabrics_, id)) return Status::error(CLOTH_ERROR_INVALID_HANDLE, "fabric handle is not live");
    release(fabrics_[id.index1 - 1]);
    return {};
}

Status World::create_cloth(std::shared_ptr<const Fabric> fabric, const Material& material,
                           const SolverSettings& solver, const AeroParams& aero,
                           const float* initial_positions, cloth_id* out) {
    const uint32_t slot = find_free_slot(cloths_);
    if (slot == UINT32_MAX) {
        return Status::error(CLOTH_ERROR_CAPACITY, "world has no free cloth slot (max_cloths = %zu)",
                             cloths_.size());
    }
    auto cloth = std::allocate_shared<ClothInstance>(HostAllocator<ClothInstance>(&memory_), &memory_,
                                                     std::move(fabric), material, solver, aero);
    if (initial_positions) {
        for (uint32_t i = 0; i < cloth->particle_count(); ++i) {
            cloth->set_position(i, Vec3(initial_positions[3 * i], initial_positions[3 * i + 1],
                                        initial_positions[3 * i + 2]));
        }
    }
    reserve_round_tasks(cloth->group_count());
    cloths_[slot].object = std::move(cloth);
    *out = cloth_id{static_cast<uint16_t>(slot + 1), static_cast<uint16_t>(index_ + 1),
                    cloths_[slot].generation, generation_};
    return {};
}

ClothInstance* World::find_cloth(cloth_id id) const { return lookup(cloths_, id); }

Status World::destroy_cloth(cloth_id id) {
    if (!lookup(cloths_, id)) return Status::error(CLOTH_ERROR_INVALID_HANDLE, "cloth handle is not live");
    release(cloths_[id.index1 - 1]);
    return {};
}

// The step allocates nothing: a round holds at most one task per group
// of every cloth (a serial stage has one task).
void World::reserve_round_tasks(size_t extra_groups) {
    size_t groups = extra_groups;
    for (const Slot<ClothInstance>& slot : cloths_) {
        if (slot.object) groups += slot.object->group_count();
    }
    round_.reserve(groups);
}

Status World::step(float dt) {
    stepping_.clear();
    for (Slot<ClothInstance>& slot : cloths_) {
        if (!slot.object) continue;
        slot.object->begin_frame(dt, gravity);
        stepping_.push_back(slot.object.get());
    }
    auto run_range = [this](uint32_t begin, uint32_t end, uint32_t worker) {
        for (uint32_t t = begin; t < end; ++t) round_[t].cloth->run_task(round_[t].task, worker);
    };
    for (;;) {
        round_.clear();
        for (ClothInstance* cloth : stepping_) {
            if (cloth->frame_done()) continue;
            cloth->prepare_stage();
            const uint32_t count = cloth->task_count();
            for (uint32_t t = 0; t < count; ++t) round_.push_back(RoundTask{cloth, t});
        }
        if (round_.empty()) break;
        parallel_for(*tasks_, static_cast<uint32_t>(round_.size()), 1, run_range);
        for (ClothInstance* cloth : stepping_) {
            if (!cloth->frame_done()) cloth->finish_stage();
        }
    }

    Status first_failure;
    for (uint32_t s = 0; s < cloths_.size(); ++s) {
        ClothInstance* cloth = cloths_[s].object.get();
        if (!cloth) continue;
        Status status = cloth->end_frame();
        if (status.ok()) continue;
        // A cloth that had to be restored outranks a solver warning.
        auto restored = [](cloth_result code) {
            return code == CLOTH_ERROR_NONFINITE_STATE || code == CLOTH_ERROR_OUT_OF_MEMORY;
        };
        if (first_failure.ok() || (restored(status.code) && !restored(first_failure.code))) {
            first_failure = Status::error(status.code, "cloth slot %u: %.360s", s + 1, status.message);
        }
    }
    return first_failure;
}

}  // namespace cloth
