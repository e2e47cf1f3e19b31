// Chrome trace-event JSON of the whole run (opens in Perfetto and
// chrome://tracing): complete events ("ph": "X") on named tracks, times in
// microseconds from the start of the run.
#pragma once

#include <chrono>
#include <string>
#include <vector>

namespace vehicle_flag {

class TraceWriter {
  public:
    TraceWriter() : origin_(std::chrono::steady_clock::now()) {}

    // Microseconds since the writer was made.
    double now_us() const;
    // A track (a "thread" row in the viewer); returns its id.
    int track(const std::string& name);
    void add(const char* name, int track, double start_us, double duration_us);

    // Writes the events; false if the file cannot be written.
    bool write(const std::string& path) const;
    size_t event_count() const { return events_.size(); }

  private:
    struct Event {
        const char* name;  // static strings only
        int track;
        double start_us, duration_us;
    };
    std::chrono::steady_clock::time_point origin_;
    std::vector<std::string> tracks_;
    std::vector<Event> events_;
};

}  // namespace vehicle_flag
