// A video of the run: RGB frames piped to Debian's ffmpeg, which encodes
// them as H.264 in an MP4 (a flag's motion cannot be judged from stills).
// Written through ffmpeg's command line rather than its libraries: the
// sample only needs "frames in, file out", and a pipe keeps the encoder's
// cost and its dependencies out of the process being timed. The encoder
// runs at idle priority (SCHED_IDLE), so it takes only the time the cloth
// step leaves: at normal priority it shared the cores with the step's
// workers and its time showed in the step's p99.
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace cloth_samples {

class VideoWriter {
  public:
    VideoWriter() = default;
    ~VideoWriter();
    VideoWriter(const VideoWriter&) = delete;
    VideoWriter& operator=(const VideoWriter&) = delete;

    // Starts ffmpeg writing `path` at `fps` frames per second; false (with
    // a message) if it cannot be started.
    bool open(const std::string& path, int width, int height, int fps, std::string* error);
    bool is_open() const { return pipe_ != nullptr; }
    // One frame of width x height RGB pixels, rows top to bottom.
    bool add(const std::vector<uint8_t>& rgb);
    // Ends the stream and waits for ffmpeg; false if it failed.
    bool close(std::string* error);
    // close(), then "wrote PATH (N frames at F fps)" on stdout, or the
    // error on stderr; false if it failed.
    bool close_and_report(const std::string& path, int fps);
    int frames() const { return frames_; }

  private:
    std::FILE* pipe_ = nullptr;
    size_t frame_bytes_ = 0;
    int frames_ = 0;
};

}  // namespace cloth_samples
