#include "world_profile.h"

#include <string>

namespace cloth_samples {

WorldProfile::WorldProfile(TraceWriter* trace, double world_zero_us, uint32_t max_tasks)
    : trace_(trace), world_zero_us_(world_zero_us), tasks_(max_tasks) {}

void WorldProfile::add_stage_rows(TimingTable* table) {
    for (int stage = 0; stage < kStageCount; ++stage) {
        const std::string name = std::string("  ") + cloth_stage_name(static_cast<cloth_stage>(stage));
        stage_rows_.push_back(table->add_row(name, /*only_if_ran=*/true));
    }
}

TaskRecords WorldProfile::record(cloth_world_id world) {
    for (size_t stage = 0; stage < stage_rows_.size(); ++stage) {
        double ms = 0.0;
        uint32_t tasks = 0;
        if (cloth_world_get_stage_profile(world, static_cast<cloth_stage>(stage), &ms, &tasks) == CLOTH_OK &&
            tasks > 0)
            stage_rows_[stage]->push_back(ms);
    }
    TaskRecords records{tasks_.data(), 0};
    if (cloth_world_read_task_records(world, tasks_.data(), static_cast<uint32_t>(tasks_.size()),
                                      &records.count) != CLOTH_OK)
        records.count = 0;
    for (const cloth_task_record& task : records) {
        while (worker_tracks_.size() <= task.worker)
            worker_tracks_.push_back(trace_->track("cloth worker " + std::to_string(worker_tracks_.size())));
        trace_->add(cloth_stage_name(task.stage), worker_tracks_[task.worker], world_zero_us_ + task.start_us,
                    task.end_us - task.start_us);
    }
    return records;
}

}  // namespace cloth_samples
