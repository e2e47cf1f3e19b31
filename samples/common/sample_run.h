// One run of a sample around its scene, what vehicle_flag,
// character_cloth and flag_field share: the frame loop timed into the
// budget table and the trace (FrameTimer), the cloth world's profile
// (WorldProfile), the video (RunVideo) and the trace's window written at
// the end. Each sample keeps its scene, its checks (their verdict in a
// Verdict, verdict.h) and its picture (picture.h):
//
//   SampleRun run(options.run, kProfileTasks);  // just before the world is made
//   const auto cloth = run.timer().part("cloth step", "cloth_step", "cloth");
//   for (int frame = 0; run.more_frames(frame, scene_done); ++frame) {
//       run.begin_frame(frame);
//       ... the scene's frame ...
//       run.timer().time(cloth, [&] { return cloth_step(world, dt); });
//       run.profile().record(world);
//       run.end_frame();
//       ... the checks, the picture's moments, the video's frames ...
//   }
//   run.print_timings("frame timings", "stage", 18);
//   ... the checks' report, then run.write_trace(centre),
//   run.video().finish(), the picture and verdict.finish() ...
#pragma once

#include <cloth/cloth.h>

#include <cstdint>
#include <string>

#include "frame_timer.h"
#include "run_options.h"
#include "run_video.h"
#include "timing_table.h"
#include "trace_writer.h"
#include "world_profile.h"

namespace cloth_samples {

class SampleRun {
  public:
    // Made just before the sample creates its cloth world: the world's
    // task records count from then. `max_tasks`: the task records the
    // world keeps a frame.
    SampleRun(const RunOptions& options, uint32_t max_tasks);
    SampleRun(const SampleRun&) = delete;
    SampleRun& operator=(const SampleRun&) = delete;

    TraceWriter& trace() { return trace_; }
    TimingTable& table() { return table_; }
    FrameTimer& timer() { return timer_; }
    WorldProfile& profile() { return profile_; }
    RunVideo& video() { return video_; }

    // Starts the video (--video) in frames of width x height; false, with
    // the error on stderr, if it cannot.
    bool open_video(int width, int height) { return video_.open(options_.video, width, height); }
    // Whether the loop runs frame `frame`: below --frames, or with
    // --frames 0 until the scene is done.
    bool more_frames(int frame, bool scene_done) const {
        return options_.frames == 0 ? !scene_done : frame < options_.frames;
    }
    void begin_frame(int frame) { timer_.begin_frame(frame); }
    void end_frame() { timer_.end_frame(); }

    // The budget table under "TITLE, ms ...; budget B ms" (--budget).
    void print_timings(const std::string& title, const char* first_column, int name_width) const {
        table_.print(title, first_column, options_.budget_ms, name_width);
    }
    // Writes the trace (--trace) of the frames --trace-frames names, or of
    // the second around frame `trace_centre`, and says so; false, with the
    // error on stderr, if it cannot. True without one.
    bool write_trace(int trace_centre);

  private:
    RunOptions options_;
    TraceWriter trace_;
    TimingTable table_;
    FrameTimer timer_;
    WorldProfile profile_;
    RunVideo video_;
};

}  // namespace cloth_samples
