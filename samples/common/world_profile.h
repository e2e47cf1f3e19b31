// The cloth world's profile of each frame of a sample's run: each stage's
// time into its row of the budget table, and each task as an event on
// its worker's track of the trace ("cloth worker N").
#pragma once

#include <cloth/cloth.h>

#include <cstdint>
#include <vector>

#include "timing_table.h"
#include "trace_writer.h"

namespace cloth_samples {

// Every stage the library has (cloth_frame_profile holds only the first
// CLOTH_MAX_STAGES; cloth_world_get_stage_profile reads each one).
constexpr int kStageCount = CLOTH_STAGE_CLOTH_CONTACT_RESPOND + 1;

// The task records of one frame, for a range-for.
struct TaskRecords {
    const cloth_task_record* first;
    uint32_t count;
    const cloth_task_record* begin() const { return first; }
    const cloth_task_record* end() const { return first + count; }
};

class WorldProfile {
  public:
    // `world_zero_us`: the trace's time when the world was created (task
    // records count from it); `max_tasks`: the task records read a frame,
    // as many as the world keeps (cloth_world_set_profiling).
    WorldProfile(TraceWriter* trace, double world_zero_us, uint32_t max_tasks);

    // A row in `table` for each stage ("  NAME"), made now, after the rows
    // already there, and left out of the table for stages that never ran.
    void add_stage_rows(TimingTable* table);
    // After a cloth step: the stages' times into their rows (if made) and
    // the tasks onto the trace; returns the tasks (valid until the next call).
    TaskRecords record(cloth_world_id world);

  private:
    TraceWriter* trace_;
    double world_zero_us_;
    std::vector<std::vector<double>*> stage_rows_;
    std::vector<int> worker_tracks_;
    std::vector<cloth_task_record> tasks_;
};

}  // namespace cloth_samples
