// The video of a sample's 60 Hz run: every other frame, at 30 fps,
// through VideoWriter (ffmpeg), if --video names a file.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "video_writer.h"

namespace cloth_samples {

class RunVideo {
  public:
    static constexpr int kFps = 30;
    // Draws a frame of the video: width x height RGB pixels into *rgb,
    // rows top to bottom; false with a message in *error.
    using Draw = std::function<bool(int width, int height, std::vector<uint8_t>* rgb, std::string* error)>;

    // Starts writing `path` in frames of width x height (nothing if the
    // path is empty); false, with the error on stderr, if it cannot.
    bool open(const std::string& path, int width, int height);
    bool is_open() const { return writer_.is_open(); }
    // Whether frame `frame` of the run goes into the video.
    bool due(int frame) const { return is_open() && frame % (60 / kFps) == 0; }
    // Adds the frame draw() draws; false, with "video WHERE: ERROR" on
    // stderr, if it cannot.
    bool add(const Draw& draw, const std::string& where);
    // Ends the video and says so ("wrote PATH (N frames at 30 fps)");
    // false, with the error on stderr, if ffmpeg failed. True without one.
    bool finish();

  private:
    VideoWriter writer_;
    std::string path_;
    int width_ = 0, height_ = 0;
};

}  // namespace cloth_samples
