#include "trace_writer.h"

#include <fstream>
#include <nlohmann/json.hpp>

namespace vehicle_flag {

double TraceWriter::now_us() const {
    return std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - origin_).count();
}

int TraceWriter::track(const std::string& name) {
    tracks_.push_back(name);
    return static_cast<int>(tracks_.size());
}

void TraceWriter::add(const char* name, int track, double start_us, double duration_us) {
    events_.push_back({name, track, start_us, duration_us});
}

bool TraceWriter::write(const std::string& path) const {
    nlohmann::json events = nlohmann::json::array();
    for (size_t t = 0; t < tracks_.size(); ++t) {
        events.push_back({{"name", "thread_name"},
                          {"ph", "M"},
                          {"pid", 1},
                          {"tid", static_cast<int>(t + 1)},
                          {"args", {{"name", tracks_[t]}}}});
    }
    for (const Event& e : events_) {
        events.push_back({{"name", e.name},
                          {"ph", "X"},
                          {"pid", 1},
                          {"tid", e.track},
                          {"ts", e.start_us},
                          {"dur", e.duration_us}});
    }
    std::ofstream out(path);
    out << nlohmann::json{{"traceEvents", events}, {"displayTimeUnit", "ms"}}.dump() << '\n';
    return static_cast<bool>(out);
}

}  // namespace vehicle_flag
