#include "trace_writer.h"

#include <algorithm>
#include <cstdio>
#include <nlohmann/json.hpp>

namespace cloth_samples {

double TraceWriter::now_us() const {
    return std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - origin_).count();
}

int TraceWriter::track(const std::string& name) {
    tracks_.push_back(name);
    return static_cast<int>(tracks_.size());
}

void TraceWriter::add(const char* name, int track, double start_us, double duration_us) {
    events_.push_back({name, track, frame_, start_us, duration_us});
}

bool TraceWriter::write(const std::string& path, int first, int last) {
    // Written by hand rather than through a JSON library: times rounded to
    // a nanosecond keep the file near half the size a full double print
    // gives, and the names are fixed identifiers that need no escaping.
    std::FILE* out = std::fopen(path.c_str(), "w");
    if (!out) return false;
    std::fprintf(out, "{\"displayTimeUnit\":\"ms\",\"traceEvents\":[");
    const char* separator = "";
    for (size_t t = 0; t < tracks_.size(); ++t) {
        std::fprintf(out,
                     "%s{\"name\":\"thread_name\",\"ph\":\"M\",\"pid\":1,\"tid\":%zu,\"args\":{\"name\":%s}}",
                     separator, t + 1, nlohmann::json(tracks_[t]).dump().c_str());
        separator = ",\n";
    }
    written_ = 0;
    for (const Event& e : events_) {
        if (e.frame < first || e.frame > last) continue;
        ++written_;
        std::fprintf(out, "%s{\"name\":\"%s\",\"ph\":\"X\",\"pid\":1,\"tid\":%d,\"ts\":%.3f,\"dur\":%.3f}",
                     separator, e.name, e.track, e.start_us, e.duration_us);
        separator = ",\n";
    }
    std::fprintf(out, "]}\n");
    return std::fclose(out) == 0;
}

bool TraceWriter::write_window(const std::string& path, const std::string& window, int centre) {
    // A second of frames around the centre, none before the run's first.
    int first = std::max(0, centre - 30), last = first + 59;
    if (std::sscanf(window.c_str(), "%d:%d", &first, &last) != 2) {
        first = std::max(0, centre - 30);
        last = first + 59;
    }
    if (!write(path, first, last)) {
        std::fprintf(stderr, "cannot write %s\n", path.c_str());
        return false;
    }
    std::printf("wrote %s (frames %d to %d, %zu events)\n", path.c_str(), first, last, written_);
    return true;
}

}  // namespace cloth_samples
