// Times the parts of each frame of a sample's run (the Bullet step, the
// cloth step, the checks): a part's time goes into its row of the budget
// table and, as an event, onto its track of the trace. The frame itself
// is an event on the "frame" track from its start to the end of the last
// part timed, and a row of the table if the sample asks for one.
#pragma once

#include <type_traits>
#include <utility>
#include <vector>

#include "timing_table.h"
#include "trace_writer.h"

namespace cloth_samples {

class FrameTimer {
  public:
    // A part of the frame, timed by time() or by now_us() and end_part().
    struct Part {
        std::vector<double>* row;  // its row of the table, or null
        const char* event;         // a static string
        int track;
    };

    // Makes the trace's "frame" track.
    FrameTimer(TraceWriter* trace, TimingTable* table);

    // A part: a row named `row` in the table (null: none), made now, after
    // the rows already there, and the event `event` on a track `track`.
    Part part(const char* row, const char* event, const char* track);
    // A row named `row` with each frame's time, from its start to the end
    // of its last part.
    void add_frame_row(const char* row);

    // The frame starts: events from now on belong to it.
    void begin_frame(int frame);
    double now_us() const { return trace_->now_us(); }
    // When the last part timed ended (the trace's time, us).
    double last_end_us() const { return last_end_us_; }
    // `part`, begun at `start_us` (now_us() then), ends now.
    void end_part(const Part& part, double start_us);
    // Runs f() as `part`; returns what it returns.
    template <class F>
    auto time(const Part& part, F&& f) {
        const double start_us = now_us();
        if constexpr (std::is_void_v<decltype(f())>) {
            std::forward<F>(f)();
            end_part(part, start_us);
        } else {
            auto result = std::forward<F>(f)();
            end_part(part, start_us);
            return result;
        }
    }
    // The frame ends where its last part did.
    void end_frame();

  private:
    TraceWriter* trace_;
    TimingTable* table_;
    int frame_track_;
    std::vector<double>* frame_row_ = nullptr;
    double frame_start_us_ = 0, last_end_us_ = 0;
};

}  // namespace cloth_samples
