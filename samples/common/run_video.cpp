#include "run_video.h"

#include <cstdio>

namespace cloth_samples {

bool RunVideo::open(const std::string& path, int width, int height) {
    if (path.empty()) return true;
    std::string error;
    if (!writer_.open(path, width, height, kFps, &error)) {
        std::fprintf(stderr, "%s\n", error.c_str());
        return false;
    }
    path_ = path;
    width_ = width;
    height_ = height;
    return true;
}

bool RunVideo::add(const Draw& draw, const std::string& where) {
    std::vector<uint8_t> rgb;
    std::string error;
    if (!draw(width_, height_, &rgb, &error) || !writer_.add(rgb)) {
        std::fprintf(stderr, "video %s: %s\n", where.c_str(), error.c_str());
        return false;
    }
    return true;
}

bool RunVideo::finish() { return !is_open() || writer_.close_and_report(path_, kFps); }

}  // namespace cloth_samples
