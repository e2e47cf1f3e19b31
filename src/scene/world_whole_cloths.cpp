// Whole cloths as tasks. Where a world steps more cloths than it has
// workers, each worker takes whole cloths (cloths in contact together, as
// one unit) and runs each one's frame from its first stage to its last:
// the cloth's particles stay in that worker's cache through its substeps,
// and no barrier separates its stages. The
// rounds of World::step instead run the current stage of every cloth at
// once, streaming all the cloths' particles through the cache once per
// stage (a field of 32 flags cost 1.8 times the sum of its flags alone
// that way: docs/measurements.md, "Whole cloths as tasks"). A cloth's
// frame does not depend on how its groups are split over workers, so the
// bits are the rounds'. Times are kept per worker, and task records in
// slots the workers claim from one atomic counter, while the cloths run;
// both are folded into the profile after the frame.
#include <algorithm>

#include "scene/world.h"
#include "step/frame_rounds.h"

namespace cloth {

bool World::steps_whole_cloths() const { return unit_count() > tasks_->worker_count(); }

void World::group_units() {
    const uint32_t n = static_cast<uint32_t>(stepping_.size());
    unit_parent_.resize(n);
    for (uint32_t i = 0; i < n; ++i) unit_parent_[i] = i;
    auto root = [this](uint32_t i) {
        while (unit_parent_[i] != i) i = unit_parent_[i] = unit_parent_[unit_parent_[i]];
        return i;
    };
    for (const ClothPair& pair : cloth_pairs_) {
        if (!pair.active) continue;
        const auto a = std::find(stepping_.begin(), stepping_.end(), pair.slot_a);
        const auto b = std::find(stepping_.begin(), stepping_.end(), pair.slot_b);
        if (a == stepping_.end() || b == stepping_.end()) continue;  // one side asleep
        const uint32_t ra = root(static_cast<uint32_t>(a - stepping_.begin()));
        const uint32_t rb = root(static_cast<uint32_t>(b - stepping_.begin()));
        unit_parent_[std::max(ra, rb)] = std::min(ra, rb);  // a unit's root is its first cloth
    }
    units_.clear();
    unit_begin_.clear();
    unit_cloths_.clear();
    for (uint32_t first = 0; first < n; ++first) {
        if (root(first) != first) continue;
        unit_begin_.push_back(static_cast<uint32_t>(units_.size()));
        for (uint32_t i = first; i < n; ++i) {
            if (root(i) != first) continue;
            units_.push_back(i);
            unit_cloths_.push_back(stepping_cloths_[i]);
        }
    }
    unit_begin_.push_back(n);
}

void World::step_whole_cloths(bool timed) {
    std::fill(worker_tally_.begin(), worker_tally_.end(), WorkerTally{});
    whole_record_count_.store(0, std::memory_order_relaxed);
    auto run = [this, timed](uint32_t begin, uint32_t end, uint32_t worker) {
        for (uint32_t u = begin; u < end; ++u) run_whole_unit(u, worker, timed);
    };
    parallel_for(*tasks_, unit_count(), 1, run);
    if (timed) account_whole_cloths();
}

void World::run_whole_unit(uint32_t unit, uint32_t worker, bool timed) {
    const uint32_t first = unit_begin_[unit], count = unit_begin_[unit + 1] - first;
    ClothInstance* const* cloths = unit_cloths_.data() + first;
    if (!timed && !zone_begin_ && !zone_end_) {
        run_frames(cloths, count, [&] {
            for (uint32_t c = 0; c < count; ++c) {
                if (cloths[c]->frame_done()) continue;
                for (uint32_t t = 0, n = cloths[c]->task_count(); t < n; ++t) cloths[c]->run_task(t, worker);
            }
        });
        return;
    }
    // A host may pass any worker index; keep it inside the per-worker arrays.
    worker = std::min(worker, static_cast<uint32_t>(worker_tally_.size()) - 1);
    WorkerTally& tally = worker_tally_[worker];
    run_frames(cloths, count, [&] {
        for (uint32_t c = 0; c < count; ++c) {
            ClothInstance* cloth = cloths[c];
            if (cloth->frame_done()) continue;
            const uint32_t slot = stepping_[units_[first + c]];
            const Stage stage = cloth->stage();
            const uint32_t s = static_cast<uint32_t>(stage), substep = cloth->substep();
            const char* name = stage_name(stage);
            // One clock read per task without zones, as run_round_range.
            int64_t start = now_ns();
            for (uint32_t t = 0, n = cloth->task_count(); t < n; ++t) {
                if (zone_begin_) {
                    zone_begin_(name, worker, zone_user_);
                    start = now_ns();
                }
                cloth->run_task(t, worker);
                const int64_t end = now_ns();
                if (zone_end_) zone_end_(name, worker, zone_user_);
                if (timed) {
                    const int64_t duration = end - start;
                    cloth_cost_ns_[slot] += duration;
                    if (is_solve_stage(stage)) cloth_solve_ns_[slot] += duration;
                    profile_.worker_busy_ns[worker] += duration;
                    if (tally.stage_tasks[s] == 0) tally.first_start_ns[s] = start;
                    tally.stage_ns[s] += duration;
                    tally.stage_tasks[s] += 1;
                    // Workers claim record slots from one counter: a profile keeps
                    // the first tasks up to its capacity, whichever worker ran them.
                    if (!whole_records_.empty()) {
                        const uint32_t at = whole_record_count_.fetch_add(1, std::memory_order_relaxed);
                        if (at < whole_records_.size())
                            whole_records_[at] = TaskRecord{
                                slot, cloths_[slot].generation, stage, t, worker, substep, start, end};
                    }
                }
                start = end;
            }
        }
    });
}

void World::account_whole_cloths() {
    for (uint32_t w = 0; w < worker_tally_.size(); ++w) {
        const WorkerTally& tally = worker_tally_[w];
        for (uint32_t s = 0; s < kStageCount; ++s) {
            if (tally.stage_tasks[s] == 0) continue;
            if (profile_.stage_tasks[s] == 0 || tally.first_start_ns[s] < profile_.stage_first_start_ns[s])
                profile_.stage_first_start_ns[s] = tally.first_start_ns[s];
            profile_.stage_ns[s] += tally.stage_ns[s];
            profile_.stage_tasks[s] += tally.stage_tasks[s];
        }
    }
    // After the parallel_for's barrier: every claim is written.
    const uint32_t claimed = whole_record_count_.load(std::memory_order_relaxed);
    for (uint32_t r = 0; r < claimed; ++r) {
        if (r < whole_records_.size() && profile_.tasks.size() < profile_.tasks.capacity()) {
            profile_.tasks.push_back(whole_records_[r]);
        } else {
            ++profile_.tasks_dropped;
        }
    }
}

}  // namespace cloth
