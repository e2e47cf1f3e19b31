#include "video_writer.h"

namespace cloth_samples {

VideoWriter::~VideoWriter() {
    if (pipe_) pclose(pipe_);
}

bool VideoWriter::open(const std::string& path, int width, int height, int fps, std::string* error) {
    // The path is quoted for the shell; a path with a quote in it is refused.
    if (path.find('\'') != std::string::npos) {
        *error = "video path must not contain a single quote: " + path;
        return false;
    }
    const std::string command = "chrt --idle 0 ffmpeg -loglevel error -y -f rawvideo -pix_fmt rgb24 -s " +
                                std::to_string(width) + "x" + std::to_string(height) + " -r " +
                                std::to_string(fps) + " -i - -c:v libx264 -preset veryfast -crf 23 " +
                                "-pix_fmt yuv420p -movflags +faststart '" + path + "'";
    pipe_ = popen(command.c_str(), "w");
    if (!pipe_) {
        *error = "cannot start ffmpeg (scripts/demo installs it): " + command;
        return false;
    }
    frame_bytes_ = static_cast<size_t>(width) * height * 3;
    return true;
}

bool VideoWriter::add(const std::vector<uint8_t>& rgb) {
    if (!pipe_ || rgb.size() != frame_bytes_) return false;
    if (std::fwrite(rgb.data(), 1, rgb.size(), pipe_) != rgb.size()) return false;
    ++frames_;
    return true;
}

bool VideoWriter::close(std::string* error) {
    if (!pipe_) return false;
    const int status = pclose(pipe_);
    pipe_ = nullptr;
    if (status != 0) {
        *error = "ffmpeg failed (exit status " + std::to_string(status) + ")";
        return false;
    }
    return true;
}

bool VideoWriter::close_and_report(const std::string& path, int fps) {
    const int written = frames_;
    std::string error;
    if (!close(&error)) {
        std::fprintf(stderr, "%s\n", error.c_str());
        return false;
    }
    std::printf("wrote %s (%d frames at %d fps)\n", path.c_str(), written, fps);
    return true;
}

}  // namespace cloth_samples
