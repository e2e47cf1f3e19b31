// World: owns the fabrics and cloths of one host scene, the host's
// callbacks, gravity, and the step over all its cloths.
//
// Fabrics and cloths live in id pools (base/id_pool.h) sized once at
// creation (capacity from the description); a handle is a slot index plus
// the slot's generation, so a stale handle is detected and never followed.
#pragma once

#include <cloth/cloth.h>

#include <atomic>
#include <memory>

#include "base/host_allocator.h"
#include "base/id_pool.h"
#include "base/status.h"
#include "collide/cloth_pair_contact.h"
#include "collide/contact_world.h"
#include "fabric/fabric.h"
#include "jobs/host_tasks.h"
#include "jobs/task_system.h"
#include "jobs/thread_pool.h"
#include "scene/frame_budget.h"
#include "scene/frame_profile.h"
#include "scene/scene_cloth.h"
#include "step/cloth_instance.h"
#include "step/pair_rounds.h"

namespace cloth {

class World {
  public:
    World(const cloth_world_desc& desc, uint16_t index, uint16_t generation);

    const HostMemory* memory() const { return &memory_; }
    TaskSystem& tasks() { return *tasks_; }
    uint16_t index() const { return index_; }

    Vec3 gravity = Vec3(0.0f, -9.81f, 0.0f);

    // Fabrics. `build` fills a fresh Fabric and returns its status.
    template <class Build>
    Status create_fabric(Build build, cloth_fabric_id* out);
    std::shared_ptr<const Fabric> find_fabric(cloth_fabric_id id) const;
    Status destroy_fabric(cloth_fabric_id id);

    Status create_cloth(std::shared_ptr<const Fabric> fabric, const Material& material,
                        const SolverSettings& solver, const AeroParams& aero, const float* initial_positions,
                        cloth_id* out);
    ClothInstance* find_cloth(cloth_id id) const;
    // The cloth with the scene's record of it (scene_cloth.h).
    SceneCloth* find_scene_cloth(cloth_id id) const;
    // Wake every cloth (gravity changed).
    void wake_all() {
        for (auto& slot : cloths_) {
            if (slot.object) slot.object->cloth().wake();
        }
    }
    Status destroy_cloth(cloth_id id);
    // Origin rebasing (cloth_world_shift_origin): subtract `shift` from
    // every world-frame position of the world's cloths, bodies and static
    // colliders. A shift that would take one of them out of float range
    // is refused and changes nothing.
    Status shift_origin(const Vec3& shift);

    // Step every cloth; a cloth that goes non-finite is restored and
    // reported, the others advance. With no more cloths to step than
    // workers, all cloths advance together, stage by stage: each round
    // runs the current stage of every unfinished cloth as one parallel_for
    // over all their groups (cloths with fewer stages finish in fewer
    // rounds), so a few cloths share the workers. With more, each worker
    // runs whole cloths (world_whole_cloths.cpp). The bits are the same.
    Status step(float dt);

    void log(cloth_log_level level, cloth_result code, const char* message) const;

    // Profiling (frame_profile.h). Recording keeps up to max_tasks task
    // records per frame (0: off, frees them).
    void set_profiling(uint32_t max_tasks);
    // cloth_world_set_worker_spin: the built-in pool's polling time.
    void set_worker_spin(uint32_t microseconds) { pool_.set_spin(microseconds); }
    const FrameProfile& frame_profile() const { return profile_; }
    // The frame budget, its overruns and the viewer (frame_budget.h).
    FrameBudget& budget() { return budget_; }
    const FrameBudget& budget() const { return budget_; }
    void set_zone_callbacks(cloth_zone_begin_fn* begin, cloth_zone_end_fn* end, void* user);
    // The id of the cloth in `slot` (for task records).
    cloth_id cloth_id_of(uint32_t slot, uint16_t generation) const {
        return cloth_id{static_cast<uint16_t>(slot + 1), static_cast<uint16_t>(index_ + 1), generation,
                        generation_};
    }
    // A cloth's update rate (update_rate.h), with the phase that staggers
    // it: a cloth in contact with another of the same rate takes its
    // phase (contact runs where both step to one frame), any other the
    // phase with the fewest particles of that rate. Allocates for a rate
    // above 1 (a failure changes nothing).
    void set_update_rate(SceneCloth& cloth, uint32_t rate);

    // Contact between two of the world's cloths (cloth_pair_contact.h;
    // world_cloth_pairs.cpp), resolved inside both cloths' substeps
    // (pair_rounds.h). settings null: off. Turning a pair on allocates;
    // an allocation failure changes nothing; a cloth is in at most
    // FrameContext::kMaxPairs pairs (CLOTH_ERROR_CAPACITY).
    Status set_cloth_contact(cloth_id a, cloth_id b, const ClothPairSettings* settings);
    // Whether the cloth is in contact with another (a pair is on).
    bool in_cloth_pair(const SceneCloth& cloth) const;
    // The pair's contact, or null while it is off.
    const ClothPairContact* cloth_contact(cloth_id a, cloth_id b) const;

    // Bodies and colliders (contact_world.h). Destroying a body detaches
    // every particle attached to it and removes it as a carrier first.
    ContactWorld& contact() { return contact_; }
    const ContactWorld& contact() const { return contact_; }
    void destroy_body(uint32_t slot);

  private:
    // Whether tasks are timed this frame (profiling or a budget needs it).
    bool timing() const { return profile_.tasks.capacity() > 0 || budget_.ms() > 0; }
    // Run tasks [begin, end) of the current round, as `worker`.
    void run_round_range(uint32_t begin, uint32_t end, uint32_t worker);
    // After a round's barrier: fold its task times into the profile and
    // the per-cloth costs.
    void account_round(uint32_t count);
    // Whole cloths as tasks (world_whole_cloths.cpp): whether this frame
    // runs that way, the frame, one cloth's frame as `worker`, and the
    // per-worker times folded into the profile after it.
    bool steps_whole_cloths() const;
    void step_whole_cloths(bool timed);
    void run_whole_unit(uint32_t unit, uint32_t worker, bool timed);
    void account_whole_cloths();
    // Cloths in contact step as one unit: units_ lists the stepping
    // cloths' indices unit by unit (each unit's in stepping order, units by
    // their first), unit_begin_ where each unit starts, unit_cloths_ the
    // cloths in that order (world_whole_cloths.cpp).
    void group_units();
    uint32_t unit_count() const { return static_cast<uint32_t>(unit_begin_.size()) - 1; }
    // What one worker timed while it ran whole cloths.
    struct WorkerTally {
        int64_t stage_ns[kStageCount] = {};
        int64_t first_start_ns[kStageCount] = {};
        uint32_t stage_tasks[kStageCount] = {};
    };

    HostMemory memory_;
    cloth_log_fn* log_ = nullptr;
    uint16_t index_;
    uint16_t generation_;
    IdPool<std::shared_ptr<Fabric>> fabrics_;
    IdPool<std::shared_ptr<SceneCloth>> cloths_;
    ClothInstance& cloth_at(uint32_t slot) const { return cloths_[slot].object->cloth(); }
    ContactWorld contact_;

    // One task of a round: group `task` of `cloth`'s current stage.
    struct RoundTask {
        ClothInstance* cloth;
        uint32_t task;
        uint32_t slot;
        Stage stage;
        uint32_t substep;
    };
    void reserve_round_tasks(size_t extra_groups);

    struct ClothPair {
        uint32_t slot_a, slot_b;  // slot_a < slot_b
        std::shared_ptr<ClothPairContact> contact;
        std::shared_ptr<PairRounds> rounds;  // where the two frames meet (pair_rounds.h)
        bool active = false;                 // in this frame's substeps
    };
    // The pair of a and b's slots in cloth_pairs_, or its size.
    size_t find_cloth_pair(uint32_t slot_a, uint32_t slot_b) const;
    // After every stepping cloth's open_frame: the pairs whose cloths can
    // meet this frame, and the substeps they share (share_substeps on the
    // decisions); after their begin_frame, the pairs join both frames.
    void begin_cloth_pairs();
    void join_cloth_pairs();
    bool steps(uint32_t slot) const { return stepping_index_[slot] != kNotStepping; }
    // After the frame: a sleeping cloth another one touched wakes.
    void end_cloth_pairs();
    void drop_cloth_pairs(uint32_t slot);
    TaskSystem* tasks_ = nullptr;  // never null after construction: one of the three below
    SerialTasks serial_tasks_;
    HostTasks host_tasks_;
    ThreadPool pool_;  // starts no thread unless the world asked for workers and has no host callbacks
    HostVector<uint32_t> stepping_;               // slots of the cloths of the frame in progress
    HostVector<ClothInstance*> stepping_cloths_;  // and those cloths, in the same order
    static constexpr uint32_t kNotStepping = UINT32_MAX;
    HostVector<uint32_t> stepping_index_;  // per cloth slot: its index in stepping_, or kNotStepping
    // Per stepping cloth: what its frame is decided on, and the decision.
    HostVector<FrameInputs> frame_inputs_;
    HostVector<FrameDecision> decisions_;
    HostVector<uint32_t> unit_parent_;         // per stepping index: union-find over active pairs
    HostVector<uint32_t> units_, unit_begin_;  // group_units()
    HostVector<ClothInstance*> unit_cloths_;
    HostVector<RoundTask> round_;           // sized for every group of every cloth
    HostVector<TaskTime> round_times_;      // one slot per task of the round, written by its worker
    HostVector<int64_t> cloth_cost_ns_;     // per cloth slot: task time of the last frame
    HostVector<int64_t> cloth_solve_ns_;    // per cloth slot: the part of it in solve stages
    HostVector<WorkerTally> worker_tally_;  // per worker (whole cloths as tasks)
    // Task records of whole cloths as tasks, in the order the workers
    // claimed their slots (whole_record_count_: claims this frame).
    HostVector<TaskRecord> whole_records_;
    std::atomic<uint32_t> whole_record_count_{0};

    FrameProfile profile_;
    uint64_t frame_ = 0;
    FrameBudget budget_;
    HostVector<ClothPair> cloth_pairs_;
    cloth_zone_begin_fn* zone_begin_ = nullptr;
    cloth_zone_end_fn* zone_end_ = nullptr;
    void* zone_user_ = nullptr;
};

template <class Build>
Status World::create_fabric(Build build, cloth_fabric_id* out) {
    const uint32_t slot = fabrics_.free_slot();
    if (slot == fabrics_.kFull) {
        return Status::error(CLOTH_ERROR_CAPACITY, "world has no free fabric slot (max_fabrics = %u)",
                             fabrics_.max_slots());
    }
    auto fabric = std::allocate_shared<Fabric>(HostAllocator<Fabric>(&memory_), &memory_);
    Status status = build(*fabric);
    if (!status.ok()) return status;
    fabric->identity = fabric_identity(*fabric);
    const uint16_t generation = fabrics_.occupy(slot, std::move(fabric));
    *out = cloth_fabric_id{static_cast<uint16_t>(slot + 1), static_cast<uint16_t>(index_ + 1), generation,
                           generation_};
    return {};
}

}  // namespace cloth
