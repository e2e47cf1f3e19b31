#include "sample_run.h"

namespace cloth_samples {

SampleRun::SampleRun(const RunOptions& options, uint32_t max_tasks)
    : options_(options), timer_(&trace_, &table_), profile_(&trace_, trace_.now_us(), max_tasks) {}

bool SampleRun::write_trace(int trace_centre) {
    return options_.trace.empty() || trace_.write_window(options_.trace, options_.trace_frames, trace_centre);
}

}  // namespace cloth_samples
