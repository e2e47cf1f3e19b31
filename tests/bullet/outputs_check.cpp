// Checks the files one vehicle_flag run wrote:
//   vehicle_flag_outputs_check PICTURE.png TRACE.json PANELS
// The picture decodes (stb_image), has PANELS panels of 480 x 360 two per
// row, and each panel shows the flag (enough of its red); the trace parses
// as JSON (nlohmann) with a "cloth_step" and a "bullet step" event for every
// "frame" event, each with a start and a non-negative duration.
// Prints what failed and exits 1, or exits 0.
#include <stb_image.h>

#include <cstdio>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

namespace {

int failures = 0;

void expect(bool ok, const std::string& what) {
    if (!ok) {
        std::fprintf(stderr, "FAILED: %s\n", what.c_str());
        ++failures;
    }
}

void check_picture(const char* path, int panels) {
    int width = 0, height = 0, channels = 0;
    unsigned char* pixels = stbi_load(path, &width, &height, &channels, 3);
    expect(pixels != nullptr, std::string(path) + " decodes as an image");
    if (!pixels) return;
    const int panel_w = 480, panel_h = 360, columns = panels > 1 ? 2 : 1;
    expect(width == columns * panel_w && height == (panels + columns - 1) / columns * panel_h,
           "picture size " + std::to_string(width) + "x" + std::to_string(height) + " fits " +
               std::to_string(panels) + " panels");
    for (int p = 0; p < panels && width >= columns * panel_w; ++p) {
        const int x0 = (p % columns) * panel_w, y0 = (p / columns) * panel_h;
        int red = 0;
        for (int y = y0; y < y0 + panel_h && y < height; ++y) {
            for (int x = x0; x < x0 + panel_w; ++x) {
                const unsigned char* c = pixels + (static_cast<size_t>(y) * width + x) * 3;
                red += c[0] > 40 && c[0] > 2 * c[1] && c[0] > 2 * c[2];
            }
        }
        // The flag covers a few thousand pixels of a panel; 300 rules out a
        // panel without it (nothing else in the scene is red).
        expect(red >= 300,
               "panel " + std::to_string(p) + " shows the flag (" + std::to_string(red) + " red pixels)");
    }
    stbi_image_free(pixels);
}

void check_trace(const char* path, long max_bytes) {
    std::ifstream in(path);
    expect(static_cast<bool>(in), std::string(path) + " opens");
    if (!in) return;
    const nlohmann::json trace = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
    expect(!trace.is_discarded(), std::string(path) + " parses as JSON");
    if (trace.is_discarded()) return;
    expect(trace.contains("traceEvents") && trace["traceEvents"].is_array(), "trace has a traceEvents array");
    if (!trace.contains("traceEvents") || !trace["traceEvents"].is_array()) return;
    std::map<std::string, int> counts;
    for (const auto& event : trace["traceEvents"]) {
        if (event.value("ph", "") != "X") continue;
        const std::string name = event.value("name", "");
        ++counts[name];
        const bool timed = event.contains("ts") && event["ts"].is_number() && event.contains("dur") &&
                           event["dur"].is_number() && event["dur"].get<double>() >= 0.0;
        if (!timed) {
            expect(false, "event '" + name + "' has a start and a non-negative duration");
            return;
        }
    }
    expect(counts["frame"] > 0, "trace has frame events");
    // A window a trace viewer opens comfortably (the whole course was 87 MB).
    if (max_bytes > 0) {
        in.clear();
        in.seekg(0, std::ios::end);
        expect(in.tellg() < max_bytes,
               std::string(path) + " is under " + std::to_string(max_bytes) + " bytes");
    }
    expect(counts["cloth_step"] == counts["frame"], "one cloth_step event per frame");
    expect(counts["bullet step"] == counts["frame"], "one bullet step event per frame");
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 4 && argc != 5) {
        std::fprintf(stderr, "usage: %s PICTURE.png TRACE.json PANELS [MAX_TRACE_BYTES]\n", argv[0]);
        return 2;
    }
    check_picture(argv[1], std::atoi(argv[2 + 1]));
    check_trace(argv[2], argc == 5 ? std::atol(argv[4]) : 0);
    if (failures == 0) std::printf("outputs valid\n");
    return failures == 0 ? 0 : 1;
}
