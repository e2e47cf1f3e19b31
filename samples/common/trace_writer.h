// Chrome trace-event JSON of a window of the run (opens in Perfetto and
// chrome://tracing): complete events ("ph": "X") on named tracks, times in
// microseconds from the start of the run. Every event is kept with the
// frame it belongs to; write() keeps the frames asked for, so a window
// around a moment found late in the run (the jump) can still be written.
#pragma once

#include <chrono>
#include <string>
#include <vector>

namespace cloth_samples {

class TraceWriter {
  public:
    TraceWriter() : origin_(std::chrono::steady_clock::now()) {}

    // Microseconds since the writer was made.
    double now_us() const;
    // A track (a "thread" row in the viewer); returns its id.
    int track(const std::string& name);
    // Events added from now on belong to this frame.
    void set_frame(int frame) { frame_ = frame; }
    void add(const char* name, int track, double start_us, double duration_us);

    // Writes the events of frames [first, last]; false if the file cannot
    // be written.
    bool write(const std::string& path, int first, int last);
    // Events the last write wrote.
    size_t written() const { return written_; }
    // Writes the frames `window` names ("FIRST:LAST"), or if it names none
    // the second of frames around `centre`, and says so on stdout; false
    // (with a message on stderr) if the file cannot be written.
    bool write_window(const std::string& path, const std::string& window, int centre);

  private:
    struct Event {
        const char* name;  // static strings only
        int track;
        int frame;
        double start_us, duration_us;
    };
    std::chrono::steady_clock::time_point origin_;
    std::vector<std::string> tracks_;
    std::vector<Event> events_;
    int frame_ = 0;
    size_t written_ = 0;
};

}  // namespace cloth_samples
