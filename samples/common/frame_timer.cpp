#include "frame_timer.h"

namespace cloth_samples {

FrameTimer::FrameTimer(TraceWriter* trace, TimingTable* table)
    : trace_(trace), table_(table), frame_track_(trace->track("frame")) {}

FrameTimer::Part FrameTimer::part(const char* row, const char* event, const char* track) {
    return {row ? table_->add_row(row) : nullptr, event, trace_->track(track)};
}

void FrameTimer::add_frame_row(const char* row) { frame_row_ = table_->add_row(row); }

void FrameTimer::begin_frame(int frame) {
    trace_->set_frame(frame);
    frame_start_us_ = last_end_us_ = now_us();
}

void FrameTimer::end_part(const Part& part, double start_us) {
    last_end_us_ = now_us();
    if (part.row) part.row->push_back((last_end_us_ - start_us) * 1e-3);
    trace_->add(part.event, part.track, start_us, last_end_us_ - start_us);
}

void FrameTimer::end_frame() {
    if (frame_row_) frame_row_->push_back((last_end_us_ - frame_start_us_) * 1e-3);
    trace_->add("frame", frame_track_, frame_start_us_, last_end_us_ - frame_start_us_);
}

}  // namespace cloth_samples
