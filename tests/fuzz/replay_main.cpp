// Replays fuzz inputs through the harness without libFuzzer (any compiler):
// the seed corpus and every input that ever crashed the library are
// regression tests (ctest cloth_fuzz_replay).
//
//   cloth_fuzz_replay DIR_OR_FILE...   run every file; fails if none is found
//   cloth_fuzz_replay --write-seeds DIR   write the hand-written seeds
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "api_sequence.h"

namespace fs = std::filesystem;

namespace {

int write_seeds(const fs::path& dir) {
    fs::create_directories(dir);
    const auto seeds = cloth_fuzz::seed_inputs();
    for (size_t i = 0; i < seeds.size(); ++i) {
        char name[32];
        std::snprintf(name, sizeof name, "seed-%02zu", i);
        std::ofstream out(dir / name, std::ios::binary);
        out.write(reinterpret_cast<const char*>(seeds[i].data()),
                  static_cast<std::streamsize>(seeds[i].size()));
    }
    std::printf("wrote %zu seeds to %s\n", seeds.size(), dir.c_str());
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc == 3 && std::string(argv[1]) == "--write-seeds") return write_seeds(argv[2]);
    std::vector<fs::path> files;
    for (int i = 1; i < argc; ++i) {
        const fs::path arg = argv[i];
        if (fs::is_directory(arg)) {
            for (const auto& entry : fs::directory_iterator(arg))
                if (entry.is_regular_file() && entry.path().filename().string()[0] != '.')
                    files.push_back(entry.path());
        } else if (fs::is_regular_file(arg)) {
            files.push_back(arg);
        }
    }
    std::sort(files.begin(), files.end());
    if (files.empty()) {
        std::fprintf(stderr, "cloth_fuzz_replay: no input files\n");
        return 1;
    }
    cloth_fuzz::RunStats total;
    for (const fs::path& file : files) {
        std::ifstream in(file, std::ios::binary);
        const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                                         std::istreambuf_iterator<char>());
        std::fprintf(stderr, "%s\n", file.c_str());  // names the input if it crashes
        const cloth_fuzz::RunStats s = cloth_fuzz::run_api_sequence(bytes.data(), bytes.size());
        total.calls += s.calls;
        total.rejected += s.rejected;
        total.steps += s.steps;
    }
    std::printf("replayed %zu inputs: %llu C API calls, %llu rejected with an error code, %llu steps\n",
                files.size(), static_cast<unsigned long long>(total.calls),
                static_cast<unsigned long long>(total.rejected),
                static_cast<unsigned long long>(total.steps));
    return 0;
}
