// The picture of a sample's run: a few moments, planned in order and kept
// as the run reaches them, each drawn after the run into a panel of one
// PNG (render_png.h). A Moment is the sample's own: whatever it needs to
// draw one, with a `label` and a `time` in seconds for the line that says
// the picture was written.
#pragma once

#include <cstddef>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "render_png.h"

namespace cloth_samples {

// Draws each moment with draw(moment, width, height, &rgb, &error) into a
// panel of panel_width x panel_height and writes them two to a row
// (write_panels_png); false with a message in *error.
template <class Moment, class Draw>
bool write_moment_panels(const std::string& path, const std::vector<Moment>& moments, int panel_width,
                         int panel_height, Draw draw, std::string* error) {
    std::vector<std::vector<uint8_t>> panels(moments.size());
    for (size_t i = 0; i < moments.size(); ++i) {
        if (!draw(moments[i], panel_width, panel_height, &panels[i], error)) return false;
    }
    return write_panels_png(path, panels, panel_width, panel_height, error);
}

template <class Moment>
class Picture {
  public:
    // `path`: the PNG to write (empty: none, and no moment is kept).
    explicit Picture(std::string path) : path_(std::move(path)) {}

    // The next moment of `plan` (the sample's, in order), once
    // reached(that plan entry) holds; null before then, after the last
    // one, and when no picture is asked for.
    template <class Plan, size_t N, class Reached>
    const Plan* due(const Plan (&plan)[N], Reached reached) const {
        if (path_.empty() || moments_.size() >= N || !reached(plan[moments_.size()])) return nullptr;
        return &plan[moments_.size()];
    }
    void add(Moment moment) { moments_.push_back(std::move(moment)); }
    const std::vector<Moment>& moments() const { return moments_; }

    // After the run: the moments, or the one last() makes if the run
    // reached none, written by write(path, moments, &error); then "wrote
    // PATH: [LABEL, t=T s] ..." or the error on stderr. False if it failed;
    // true without a picture.
    template <class Last, class Write>
    bool finish(Last last, Write write) {
        if (path_.empty()) return true;
        if (moments_.empty()) moments_.push_back(last());
        std::string error;
        if (!write(path_, moments_, &error)) {
            std::fprintf(stderr, "%s\n", error.c_str());
            return false;
        }
        print_written_moments(path_, moments_);
        return true;
    }

    // finish(), each moment drawn by draw(moment, width, height, &rgb,
    // &error) into a panel of panel_width x panel_height, two panels to a
    // row (write_moment_panels).
    template <class Last, class Draw>
    bool finish_panels(Last last, int panel_width, int panel_height, Draw draw) {
        return finish(last,
                      [&](const std::string& path, const std::vector<Moment>& moments, std::string* error) {
                          return write_moment_panels(path, moments, panel_width, panel_height, draw, error);
                      });
    }

  private:
    std::string path_;
    std::vector<Moment> moments_;
};

}  // namespace cloth_samples
