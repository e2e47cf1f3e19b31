#include "scene/frame_profile.h"

#include <algorithm>
#include <chrono>
#include <cstdarg>
#include <cstdio>
#include <cstring>

namespace cloth {

int64_t now_ns() {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(
               std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

void FrameProfile::begin(uint64_t frame_index, int64_t start, double budget) {
    frame = frame_index;
    start_ns = end_ns = start;
    budget_ms = budget;
    overrun = false;
    awake_cloths = sleeping_cloths = 0;
    std::fill(std::begin(stage_ns), std::end(stage_ns), 0);
    std::fill(std::begin(stage_first_start_ns), std::end(stage_first_start_ns), 0);
    std::fill(std::begin(stage_tasks), std::end(stage_tasks), 0u);
    std::fill(worker_busy_ns.begin(), worker_busy_ns.end(), 0);
    tasks.clear();
    tasks_dropped = 0;
}

namespace {

// The format rules std::vsnprintf follows here. GCC's gnu_printf is C99's
// (%zu and friends), which MinGW-w64 builds get from __USE_MINGW_ANSI_STDIO
// (src/CMakeLists.txt); its printf archetype would check them by the
// Windows C runtime's older rules there. Clang knows only printf, which is
// C99's on every platform it builds this library for.
#if defined(__GNUC__) && !defined(__clang__)
#define CLOTH_FORMAT_PRINTF(format_index, first_arg) \
    __attribute__((format(gnu_printf, format_index, first_arg)))
#else
#define CLOTH_FORMAT_PRINTF(format_index, first_arg) __attribute__((format(printf, format_index, first_arg)))
#endif

// Appends formatted text while it fits; always counts what it would need.
class JsonOut {
  public:
    JsonOut(char* buffer, size_t capacity) : buffer_(buffer), capacity_(capacity) {}
    void printf(const char* format, ...) CLOTH_FORMAT_PRINTF(2, 3) {
        char piece[512];
        va_list args;
        va_start(args, format);
        const int n = std::vsnprintf(piece, sizeof piece, format, args);
        va_end(args);
        if (n <= 0) return;
        const size_t len = std::min(static_cast<size_t>(n), sizeof piece - 1);
        if (buffer_ && size_ + len < capacity_) std::memcpy(buffer_ + size_, piece, len);
        size_ += len;
    }
    size_t finish() {
        if (buffer_ && size_ < capacity_) buffer_[size_] = '\0';
        return size_ + 1;
    }

  private:
    char* buffer_;
    size_t capacity_;
    size_t size_ = 0;
};

double us(int64_t ns, int64_t origin) { return static_cast<double>(ns - origin) * 1e-3; }

constexpr int kStageTrackBase = 1000;  // tid of the stage tracks; workers use their index

void write(const FrameProfile& p, JsonOut& out) {
    out.printf("{\"displayTimeUnit\":\"ms\",\"traceEvents\":[\n");
    out.printf("{\"name\":\"process_name\",\"ph\":\"M\",\"pid\":1,\"args\":{\"name\":\"cloth\"}}");
    for (size_t w = 0; w < p.worker_busy_ns.size(); ++w) {
        out.printf(
            ",\n{\"name\":\"thread_name\",\"ph\":\"M\",\"pid\":1,\"tid\":%zu,\"args\":{\"name\":\"worker "
            "%zu\"}}",
            w, w);
    }
    out.printf(
        ",\n{\"name\":\"cloth_step\",\"cat\":\"frame\",\"ph\":\"X\",\"pid\":1,\"tid\":%d,\"ts\":%.3f,\"dur\":"
        "%.3f,"
        "\"args\":{\"frame\":%llu,\"budget_ms\":%.3f,\"overrun\":%s,\"awake_cloths\":%u,\"sleeping_cloths\":%"
        "u,"
        "\"tasks_dropped\":%u}}",
        kStageTrackBase - 1, us(p.start_ns, p.origin_ns), static_cast<double>(p.end_ns - p.start_ns) * 1e-3,
        static_cast<unsigned long long>(p.frame), p.budget_ms, p.overrun ? "true" : "false", p.awake_cloths,
        p.sleeping_cloths, p.tasks_dropped);
    for (uint32_t s = 0; s < kStageCount; ++s) {
        if (p.stage_tasks[s] == 0) continue;
        out.printf(
            ",\n{\"name\":\"%s\",\"cat\":\"stage\",\"ph\":\"X\",\"pid\":1,\"tid\":%u,\"ts\":%.3f,\"dur\":%."
            "3f,"
            "\"args\":{\"tasks\":%u}}",
            stage_name(static_cast<Stage>(s)), kStageTrackBase + s,
            us(p.stage_first_start_ns[s], p.origin_ns), static_cast<double>(p.stage_ns[s]) * 1e-3,
            p.stage_tasks[s]);
    }
    for (const TaskRecord& t : p.tasks) {
        out.printf(
            ",\n{\"name\":\"%s\",\"cat\":\"task\",\"ph\":\"X\",\"pid\":1,\"tid\":%u,\"ts\":%.3f,\"dur\":%.3f,"
            "\"args\":{\"cloth_slot\":%u,\"group\":%u,\"substep\":%u}}",
            stage_name(t.stage), t.worker, us(t.start_ns, p.origin_ns),
            static_cast<double>(t.end_ns - t.start_ns) * 1e-3, t.cloth_slot + 1, t.group, t.substep);
    }
    out.printf("\n]}\n");
}

}  // namespace

size_t write_trace_json(const FrameProfile& profile, char* buffer, size_t capacity) {
    JsonOut count(nullptr, 0);
    write(profile, count);
    const size_t needed = count.finish();
    if (buffer && capacity >= needed) {
        JsonOut out(buffer, capacity);
        write(profile, out);
        out.finish();
    }
    return needed;
}

}  // namespace cloth
