// The options every sample's run has, with the same names and meanings in
// each: --frames, --threads, --budget, --png, --video, --trace and
// --trace-frames (the solver's are in solver_options.h). Each sample sets
// its own defaults in RunOptions before adding them, and says in RunHelp
// what its run, its picture and its trace's window are.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>

namespace cloth_samples {

struct RunOptions {
    int frames = 0;            // 0: the whole run (the sample's course or clip)
    uint32_t threads = 1;      // cloth worker threads (1: the calling thread only)
    double budget_ms = 1.0;    // the cloth step's frame budget
    std::string png;           // the picture of a few moments (empty: none)
    std::string video;         // MP4 of the run at 30 fps (empty: none)
    std::string trace;         // Chrome trace-event JSON of a window of the run (empty: none)
    std::string trace_frames;  // "FIRST:LAST"; empty: the sample's own window
};

// What the options' help says of one sample.
struct RunHelp {
    std::string whole_run;     // what --frames 0 runs: "the whole course"
    std::string picture;       // what --png draws: "picture of four moments of the clip"
    std::string trace_window;  // the trace's window by default: "the second around the jump"
    std::string budget = "frame budget for the cloth step, ms (counts overruns)";
};

inline void add_run_options(CLI::App& app, RunOptions* o, const RunHelp& help) {
    app.add_option("--frames", o->frames, "frames at 60 Hz (0: " + help.whole_run + ")")
        ->check(CLI::Range(0, 1000000));
    app.add_option("--threads", o->threads, "cloth worker threads (1: the calling thread only)")
        ->check(CLI::Range(1, 256));
    app.add_option("--budget", o->budget_ms, help.budget)->check(CLI::PositiveNumber);
    app.add_option("--png", o->png, help.picture + " (empty: none)")
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
    app.add_option("--video", o->video, "MP4 of the run at 30 fps through ffmpeg (empty: none)")
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
    app.add_option("--trace", o->trace, "Chrome trace-event JSON of a window of the run (empty: none)")
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
    app.add_option("--trace-frames", o->trace_frames,
                   "frames the trace keeps, FIRST:LAST (default: " + help.trace_window + ")");
}

}  // namespace cloth_samples
