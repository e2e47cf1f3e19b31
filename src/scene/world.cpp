#include "scene/world.h"

#include <algorithm>
#include <climits>
#include <cstdlib>

#include "step/frame_rounds.h"

namespace cloth {

World::World(const cloth_world_desc& desc, uint16_t index, uint16_t generation)
    : gravity(desc.gravity[0], desc.gravity[1], desc.gravity[2]),
      memory_{desc.alloc, desc.free, desc.user},
      log_(desc.log),
      index_(index),
      generation_(generation),
      fabrics_(&memory_, desc.max_fabrics),
      cloths_(&memory_, desc.max_cloths),
      contact_(&memory_),
      tasks_(&serial_tasks_),
      host_tasks_(desc.enqueue_task, desc.finish_task, desc.task_user, desc.worker_count),
      pool_(desc.enqueue_task ? 1 : desc.worker_count),
      stepping_(HostAllocator<uint32_t>(&memory_)),
      stepping_cloths_(HostAllocator<ClothInstance*>(&memory_)),
      stepping_index_(HostAllocator<uint32_t>(&memory_)),
      frame_inputs_(HostAllocator<FrameInputs>(&memory_)),
      decisions_(HostAllocator<FrameDecision>(&memory_)),
      unit_parent_(HostAllocator<uint32_t>(&memory_)),
      units_(HostAllocator<uint32_t>(&memory_)),
      unit_begin_(HostAllocator<uint32_t>(&memory_)),
      unit_cloths_(HostAllocator<ClothInstance*>(&memory_)),
      round_(HostAllocator<RoundTask>(&memory_)),
      round_times_(HostAllocator<TaskTime>(&memory_)),
      cloth_cost_ns_(HostAllocator<int64_t>(&memory_)),
      cloth_solve_ns_(HostAllocator<int64_t>(&memory_)),
      worker_tally_(HostAllocator<WorkerTally>(&memory_)),
      whole_records_(HostAllocator<TaskRecord>(&memory_)),
      profile_(&memory_),
      budget_(&memory_, desc.max_cloths),
      cloth_pairs_(HostAllocator<ClothPair>(&memory_)) {
    fabrics_.make_all_slots();
    cloths_.make_all_slots();
    stepping_.reserve(desc.max_cloths);
    stepping_cloths_.reserve(desc.max_cloths);
    stepping_index_.assign(desc.max_cloths, kNotStepping);
    frame_inputs_.reserve(desc.max_cloths);
    decisions_.reserve(desc.max_cloths);
    unit_parent_.reserve(desc.max_cloths);
    units_.reserve(desc.max_cloths);
    unit_begin_.reserve(size_t{desc.max_cloths} + 1);
    unit_cloths_.reserve(desc.max_cloths);
    cloth_cost_ns_.assign(desc.max_cloths, 0);
    cloth_solve_ns_.assign(desc.max_cloths, 0);
    profile_.origin_ns = now_ns();
    if (desc.enqueue_task) {
        tasks_ = &host_tasks_;
    } else if (desc.worker_count > 1) {
        tasks_ = &pool_;  // its threads keep their state on the C++ heap
    }
    profile_.worker_busy_ns.assign(tasks_->worker_count(), 0);
    worker_tally_.assign(tasks_->worker_count(), WorkerTally{});
}

void World::log(cloth_log_level level, cloth_result code, const char* message) const {
    if (log_) log_(level, code, message, memory_.user);
}

std::shared_ptr<const Fabric> World::find_fabric(cloth_fabric_id id) const {
    const uint32_t slot = fabrics_.find(id.index1, id.generation);
    return slot == fabrics_.kFull ? nullptr : fabrics_[slot].object;
}

Status World::destroy_fabric(cloth_fabric_id id) {
    const uint32_t slot = fabrics_.find(id.index1, id.generation);
    if (slot == fabrics_.kFull) {
        return Status::error(CLOTH_ERROR_INVALID_HANDLE,
                             "fabric handle names no live fabric in its world (destroyed, or never created)");
    }
    fabrics_.release(slot);
    return {};
}

Status World::create_cloth(std::shared_ptr<const Fabric> fabric, const Material& material,
                           const SolverSettings& solver, const AeroParams& aero,
                           const float* initial_positions, cloth_id* out) {
    const uint32_t slot = cloths_.free_slot();
    if (slot == cloths_.kFull) {
        return Status::error(CLOTH_ERROR_CAPACITY, "world has no free cloth slot (max_cloths = %u)",
                             cloths_.max_slots());
    }
    auto scene = std::allocate_shared<SceneCloth>(HostAllocator<SceneCloth>(&memory_), &memory_,
                                                  std::move(fabric), material, solver, aero);
    ClothInstance* cloth = &scene->cloth();
    if (initial_positions) {
        for (uint32_t i = 0; i < cloth->particle_count(); ++i) {
            const uint32_t v = cloth->fabric().vertex(i);  // the host's vertex order
            cloth->set_position(i, Vec3(initial_positions[3 * v], initial_positions[3 * v + 1],
                                        initial_positions[3 * v + 2]));
        }
    }
    reserve_round_tasks(cloth->group_count());
    cloth->contact().bind(&contact_);
    *out = cloth_id_of(slot, cloths_.occupy(slot, std::move(scene)));
    return {};
}

ClothInstance* World::find_cloth(cloth_id id) const {
    SceneCloth* scene = find_scene_cloth(id);
    return scene ? &scene->cloth() : nullptr;
}

SceneCloth* World::find_scene_cloth(cloth_id id) const {
    const uint32_t slot = cloths_.find(id.index1, id.generation);
    return slot == cloths_.kFull ? nullptr : cloths_[slot].object.get();
}

Status World::destroy_cloth(cloth_id id) {
    const uint32_t slot = cloths_.find(id.index1, id.generation);
    if (slot == cloths_.kFull) {
        return Status::error(CLOTH_ERROR_INVALID_HANDLE,
                             "cloth handle names no live cloth in its world (destroyed, or never created)");
    }
    drop_cloth_pairs(slot);
    cloths_.release(slot);
    return {};
}

// The step allocates nothing: a round holds at most one task per group
// of every cloth (a serial stage has one task).
void World::reserve_round_tasks(size_t extra_groups) {
    size_t groups = extra_groups;
    for (const auto& slot : cloths_) {
        if (slot.object) groups += slot.object->cloth().group_count();
    }
    round_.reserve(groups);
    round_times_.resize(std::max(round_times_.size(), groups));
}

void World::set_profiling(uint32_t max_tasks) {
    if (max_tasks == 0) {
        HostVector<TaskRecord>{HostAllocator<TaskRecord>(&memory_)}.swap(profile_.tasks);
        HostVector<TaskRecord>{HostAllocator<TaskRecord>(&memory_)}.swap(whole_records_);
    } else {
        // Whole cloths as tasks write their records here, at once.
        HostVector<TaskRecord> records{HostAllocator<TaskRecord>(&memory_)};
        HostVector<TaskRecord> concurrent{HostAllocator<TaskRecord>(&memory_)};
        records.reserve(max_tasks);
        concurrent.resize(max_tasks);
        profile_.tasks.swap(records);
        whole_records_.swap(concurrent);
    }
}

void World::set_zone_callbacks(cloth_zone_begin_fn* begin, cloth_zone_end_fn* end, void* user) {
    zone_begin_ = begin;
    zone_end_ = end;
    zone_user_ = user;
}

void World::run_round_range(uint32_t begin, uint32_t end, uint32_t worker) {
    if (!timing() && !zone_begin_) {
        for (uint32_t t = begin; t < end; ++t) round_[t].cloth->run_task(round_[t].task, worker);
        return;
    }
    // A host may pass any worker index; keep it inside the profile's arrays.
    worker = std::min(worker, static_cast<uint32_t>(profile_.worker_busy_ns.size()) - 1);
    if (!zone_begin_ && !zone_end_) {
        // One clock read per task: each task starts when the one before it
        // on this worker ended (a clock read costs about as much as the
        // vehicle flag's smallest tasks; docs/measurements.md, "One clock
        // read per timed task").
        int64_t start = now_ns();
        for (uint32_t t = begin; t < end; ++t) {
            round_[t].cloth->run_task(round_[t].task, worker);
            const int64_t done = now_ns();
            round_times_[t] = TaskTime{start, done, worker};
            start = done;
        }
        return;
    }
    for (uint32_t t = begin; t < end; ++t) {
        const char* name = stage_name(round_[t].stage);
        if (zone_begin_) zone_begin_(name, worker, zone_user_);
        const int64_t start = now_ns();
        round_[t].cloth->run_task(round_[t].task, worker);
        round_times_[t] = TaskTime{start, now_ns(), worker};
        if (zone_end_) zone_end_(name, worker, zone_user_);
    }
}

void World::account_round(uint32_t count) {
    int64_t first[kStageCount], last[kStageCount];
    std::fill(std::begin(first), std::end(first), INT64_MAX);
    std::fill(std::begin(last), std::end(last), INT64_MIN);
    for (uint32_t t = 0; t < count; ++t) {
        const RoundTask& task = round_[t];
        const TaskTime& time = round_times_[t];
        const uint32_t s = static_cast<uint32_t>(task.stage);
        const int64_t duration = time.end_ns - time.start_ns;
        cloth_cost_ns_[task.slot] += duration;
        if (is_solve_stage(task.stage)) cloth_solve_ns_[task.slot] += duration;
        profile_.worker_busy_ns[time.worker] += duration;
        profile_.stage_tasks[s] += 1;
        first[s] = std::min(first[s], time.start_ns);
        last[s] = std::max(last[s], time.end_ns);
        if (profile_.tasks.size() < profile_.tasks.capacity()) {
            profile_.tasks.push_back(TaskRecord{task.slot, cloths_[task.slot].generation, task.stage,
                                                task.task, time.worker, task.substep, time.start_ns,
                                                time.end_ns});
        } else if (profile_.tasks.capacity() > 0) {
            ++profile_.tasks_dropped;
        }
    }
    for (uint32_t s = 0; s < kStageCount; ++s) {
        if (first[s] > last[s]) continue;
        if (profile_.stage_ns[s] == 0) profile_.stage_first_start_ns[s] = first[s];
        profile_.stage_ns[s] += last[s] - first[s];
    }
}

void World::destroy_body(uint32_t body) {
    for (const auto& slot : cloths_) {
        if (!slot.object) continue;
        ClothInstance* cloth = &slot.object->cloth();
        ClothContact& contact = cloth->contact();
        if (contact.carrier().body() == body) contact.carrier().clear();
        for (uint32_t i = 0; i < cloth->particle_count(); ++i) {
            if (contact.is_attached(i) && contact.attached_body(i) == body) cloth->unpin(i);
        }
    }
    contact_.destroy_body(body);
}

// Tasks (particle groups of kGroupSize) a worker takes at least at a time.
// A round of a few groups runs on one thread: waking a second worker costs
// more than it saves there (Jobs/Overhead32; docs/measurements.md, "A
// round of a few groups on one thread").
constexpr uint32_t kMinTasksPerRange = 4;

Status World::shift_origin(const Vec3& shift) {
    bool fits = contact_.can_shift_origin(shift);
    for (const auto& slot : cloths_) fits = fits && (!slot.object || slot.object->can_shift_origin(shift));
    if (!fits) {
        return Status::error(CLOTH_ERROR_INVALID_VALUE,
                             "the shift would move a position out of float range; nothing was moved");
    }
    for (auto& slot : cloths_) {
        if (slot.object) slot.object->shift_origin(shift);
    }
    contact_.shift_origin(shift);
    return {};
}

Status World::step(float dt) {
    const int64_t start = now_ns();
    if (zone_begin_) zone_begin_("cloth_step", 0, zone_user_);
    profile_.begin(++frame_, start, budget_.ms());
    const bool timed = timing();
    stepping_.clear();
    stepping_cloths_.clear();
    frame_inputs_.clear();
    decisions_.clear();
    std::fill(stepping_index_.begin(), stepping_index_.end(), kNotStepping);
    for (uint32_t s = 0; s < cloths_.size(); ++s) {
        SceneCloth* scene = cloths_[s].object.get();
        if (!scene) continue;
        scene->levels().before_frame(scene->cloth(), in_cloth_pair(*scene));
        ClothInstance* cloth = &scene->stepped();
        cloth_cost_ns_[s] = cloth_solve_ns_[s] = 0;
        scene->set_world_frame(frame_);
        if (cloth->woken_by_bodies()) cloth->wake();
        if (cloth->sleeping()) {
            ++profile_.sleeping_cloths;
            continue;
        }
        // A body that carries the cloth moves frame by frame: back to rate 1.
        if (scene->update_rate().rate() > 1 && cloth->contact().rides_bodies()) scene->set_update_rate(1, 0);
        if (!scene->update_rate().due(frame_)) continue;  // between its steps (update_rate.h)
        // The frame's decision (frame_decision.h), made once before it starts.
        const float step_dt = dt * static_cast<float>(scene->begin_rate_step(frame_));
        const FrameInputs& in =
            frame_inputs_.emplace_back(cloth->frame_inputs(step_dt, scene->quality().bounds()));
        cloth->open_frame(step_dt, decisions_.emplace_back(decide_frame(in)));
        stepping_index_[s] = static_cast<uint32_t>(stepping_.size());
        stepping_.push_back(s);
        stepping_cloths_.push_back(cloth);
    }
    profile_.awake_cloths = static_cast<uint32_t>(stepping_.size());
    begin_cloth_pairs();
    for (uint32_t k = 0; k < stepping_.size(); ++k)
        stepping_cloths_[k]->begin_frame(frame_inputs_[k], decisions_[k], gravity);
    join_cloth_pairs();
    group_units();
    if (steps_whole_cloths()) {
        step_whole_cloths(timed);
    } else {
        auto run_range = [this](uint32_t begin, uint32_t end, uint32_t worker) {
            run_round_range(begin, end, worker);
        };
        // One round: the current stage of every cloth still in its frame.
        run_frames(stepping_cloths_.data(), static_cast<uint32_t>(stepping_cloths_.size()), [&] {
            round_.clear();
            for (uint32_t s : stepping_) {
                ClothInstance* cloth = &cloths_[s].object->stepped();
                if (cloth->frame_done()) continue;
                const uint32_t count = cloth->task_count();
                for (uint32_t t = 0; t < count; ++t) {
                    round_.push_back(RoundTask{cloth, t, s, cloth->stage(), cloth->substep()});
                }
            }
            const uint32_t count = static_cast<uint32_t>(round_.size());
            parallel_for(*tasks_, count, kMinTasksPerRange, run_range);
            if (timed) account_round(count);
        });
    }

    Status first_failure;
    for (uint32_t s : stepping_) {
        SceneCloth& scene = *cloths_[s].object;
        Status status = scene.stepped().end_frame();
        scene.levels().after_frame(scene.cloth());  // the full mesh from a coarse level
        if (status.ok()) continue;
        // A cloth that had to be restored outranks a solver warning.
        auto restored = [](cloth_result code) {
            return code == CLOTH_ERROR_NONFINITE_STATE || code == CLOTH_ERROR_OUT_OF_MEMORY;
        };
        if (restored(status.code)) cloths_[s].object->undo_rate_step();  // back at the step's start
        if (first_failure.ok() || (restored(status.code) && !restored(first_failure.code))) {
            first_failure = Status::error(status.code, "cloth slot %u: %.360s", s + 1, status.message);
        }
    }
    end_cloth_pairs();
    contact_.end_step();  // bodies start the next step where they are now
    profile_.end_ns = now_ns();
    if (budget_.ms() > 0) {
        // An overrun is reported in the profile and, unless a cloth failed
        // (which says more), by the step's result.
        profile_.overrun = budget_.count_frame(profile_.step_ms());
        if (profile_.overrun) {
            if (first_failure.ok()) {
                first_failure = Status::error(
                    CLOTH_ERROR_OVER_BUDGET,
                    "the step took %.3g ms, over the frame budget of %.3g ms; every cloth advanced",
                    profile_.step_ms(), budget_.ms());
            }
        }
        budget_.start_decision();
        for (uint32_t s : stepping_)
            budget_.add(cloths_[s].object.get(), cloth_cost_ns_[s], cloth_solve_ns_[s]);
        budget_.decide(profile_.step_ms(), frame_);
        // The rates it chose (their copies were sized with the policy: no allocation).
        for (const BudgetCloth& c : budget_.cloths()) {
            if (const uint32_t rate = c.cloth->quality().take_wanted_rate()) set_update_rate(*c.cloth, rate);
        }
    }
    if (zone_end_) zone_end_("cloth_step", 0, zone_user_);
    return first_failure;
}

void World::set_update_rate(SceneCloth& cloth, uint32_t rate) {
    uint32_t phase = 0;
    if (rate > 1) {
        // Cloths in contact step together: a partner's phase at the same rate.
        const SceneCloth* partner = nullptr;
        for (const ClothPair& pair : cloth_pairs_) {
            const SceneCloth* a = cloths_[pair.slot_a].object.get();
            const SceneCloth* b = cloths_[pair.slot_b].object.get();
            const SceneCloth* other = a == &cloth ? b : b == &cloth ? a : nullptr;
            if (other && other->update_rate().rate() == rate) partner = other;
            if (partner) break;
        }
        if (partner) {
            phase = partner->update_rate().phase();
        } else {
            // The phase with the fewest particles of this rate (the first of equals).
            uint64_t load[UpdateRate::kSlowest] = {};
            for (const auto& slot : cloths_) {
                const SceneCloth* other = slot.object.get();
                if (other && other != &cloth && other->update_rate().rate() == rate)
                    load[other->update_rate().phase()] += other->cloth().particle_count();
            }
            phase = static_cast<uint32_t>(std::min_element(load, load + rate) - load);
        }
    }
    cloth.set_update_rate(rate, phase);
}

}  // namespace cloth
