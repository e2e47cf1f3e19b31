// What a frame (one World::step) cost: per stage, per worker and per task,
// the budget and whether it was overrun; and its export as Chrome
// trace-event JSON. Filled by World::step from per-task timestamps taken
// on the workers into one slot per task (no shared counters).
#pragma once

#include <cstddef>
#include <cstdint>

#include "base/host_allocator.h"
#include "step/step_stage.h"

namespace cloth {

// Nanoseconds on a monotonic clock.
int64_t now_ns();

// One task of a round, timed by the worker that ran it.
struct TaskTime {
    int64_t start_ns = 0, end_ns = 0;
    uint32_t worker = 0;
};

struct TaskRecord {
    uint32_t cloth_slot;
    uint16_t cloth_generation;
    Stage stage;
    uint32_t group, worker, substep;
    int64_t start_ns, end_ns;
};

struct FrameProfile {
    explicit FrameProfile(const HostMemory* memory)
        : worker_busy_ns(HostAllocator<int64_t>(memory)), tasks(HostAllocator<TaskRecord>(memory)) {}

    uint64_t frame = 0;
    int64_t origin_ns = 0;  // the world's creation: trace times count from here
    int64_t start_ns = 0, end_ns = 0;
    double budget_ms = 0;
    bool overrun = false;
    uint32_t awake_cloths = 0, sleeping_cloths = 0;
    int64_t stage_ns[kStageCount] = {};
    int64_t stage_first_start_ns[kStageCount] = {};
    uint32_t stage_tasks[kStageCount] = {};
    HostVector<int64_t> worker_busy_ns;  // per worker
    HostVector<TaskRecord> tasks;        // capacity = the recording limit (0: off)
    uint32_t tasks_dropped = 0;

    double step_ms() const { return static_cast<double>(end_ns - start_ns) * 1e-6; }
    // Clear the per-frame values, keeping capacities.
    void begin(uint64_t frame_index, int64_t start, double budget);
};

// Writes the frame as Chrome trace-event JSON into buffer (at most
// capacity bytes, NUL included, nothing if it does not fit) and returns
// the bytes needed including the NUL.
size_t write_trace_json(const FrameProfile& profile, char* buffer, size_t capacity);

}  // namespace cloth
