// cloth_bench: step cost per solver kind and grid size (Google Benchmark,
// single thread), preceded by the accuracy table that shows where the
// paper's one-iteration step stands against the full solve
// (algorithm.md section 6).
//
//   cloth_bench [--accuracy=full|quick|off] [Google Benchmark flags]
//
// Step scene: the flag in 10 m/s wind, 1 m x 1 m, 1 kg, every spring kind
// at 1e3 N/m, 1/60 s, after 30 warm-up frames. Counter per_particle is the
// wall time per particle per step.
//
// Frame/DEFAULT/N: the default holding a cloth falling flat (1 m, 1 kg,
// 1e3 N/m, awake throughout); counter x_jacobi_k1 is its frame time over
// the median JACOBI k=1 step of the same scene, timed in the same run just
// before: the cost of holding cloth as a multiple of the paper's step.
// Frame/DEFAULT_MESH/64: the same cloth built as a mesh fabric
// (cloth_fabric_create_mesh, index-pair springs), the same counter (over
// the grid's JACOBI k=1 step). Frame/DEFAULT_2_WORKERS/N: the default on a
// world of two workers; counter x_faster_than_1_worker is the median
// one-worker frame of the same scene, timed in the same run just before,
// over its frame time.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "scenes.h"

namespace {

using cloth_samples::Scene;
using cloth_samples::SceneConfig;
using cloth_samples::SceneKind;

constexpr float kDt = 1.0f / 60.0f;

void BM_Step(benchmark::State& state, cloth_solver_kind kind, uint32_t iterations) {
    SceneConfig config;
    config.kind = SceneKind::kFlagInWind;
    config.resolution = static_cast<uint32_t>(state.range(0));
    config.solver.kind = kind;
    config.solver.iterations = iterations;
    Scene scene(config);
    if (!scene.ok()) {
        state.SkipWithError(scene.error().c_str());
        return;
    }
    for (int i = 0; i < 30; ++i) scene.step(kDt);
    int64_t failed = 0;
    for (auto _ : state) {
        failed += scene.step(kDt) != CLOTH_OK;
    }
    // Steps that went non-finite and were undone: the time of such a step is
    // the cost of computing and discarding it (EXPLICIT at 60 Hz, mostly).
    state.counters["failed_steps"] =
        benchmark::Counter(static_cast<double>(failed), benchmark::Counter::kAvgIterations);
    state.counters["particles"] = scene.particle_count();
    // Wall time per particle per step (printed with its SI prefix, e.g. "90ns").
    state.counters["per_particle"] =
        benchmark::Counter(static_cast<double>(scene.particle_count()),
                           benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
    state.counters["max_strain"] = scene.stats().max_strain;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

SceneConfig falling_flat(uint32_t resolution, cloth_solver_kind kind) {
    SceneConfig config;
    config.kind = SceneKind::kFallingFlat;
    config.resolution = resolution;
    config.stiffness = 1000.0f;
    config.solver.kind = kind;
    return config;
}

void keep_awake(const Scene& scene) {
    cloth_sleep_params awake = cloth_default_sleep_params();
    awake.enabled = 0;
    for (cloth_id cloth : scene.cloths()) cloth_set_sleep(cloth, &awake);
}

double median(std::vector<double> times) {
    std::nth_element(times.begin(), times.begin() + times.size() / 2, times.end());
    return times[times.size() / 2];
}

// Median frame of the falling-flat scene over `frames` frames after 30
// warm-up frames, awake throughout.
double median_frame_seconds(const SceneConfig& config, int frames) {
    Scene scene(config);
    keep_awake(scene);
    for (int i = 0; i < 30; ++i) scene.step(kDt);
    std::vector<double> times;
    for (int i = 0; i < frames; ++i) {
        const auto start = std::chrono::steady_clock::now();
        scene.step(kDt);
        times.push_back(seconds_since(start));
    }
    return median(times);
}

// Median JACOBI k=1 step of the falling-flat scene.
double jacobi_step_seconds(uint32_t resolution) {
    return median_frame_seconds(falling_flat(resolution, CLOTH_SOLVER_JACOBI), 61);
}

SceneConfig default_on_workers(uint32_t resolution, uint32_t workers) {
    SceneConfig config = falling_flat(resolution, CLOTH_SOLVER_DEFAULT);
    config.world.worker_count = workers;
    return config;
}

void BM_FrameTwoWorkers(benchmark::State& state) {
    const uint32_t resolution = static_cast<uint32_t>(state.range(0));
    const double one_worker = median_frame_seconds(default_on_workers(resolution, 1), 31);
    Scene scene(default_on_workers(resolution, 2));
    if (!scene.ok()) {
        state.SkipWithError(scene.error().c_str());
        return;
    }
    keep_awake(scene);
    for (int i = 0; i < 30; ++i) scene.step(kDt);
    std::vector<double> times;
    for (auto _ : state) {
        const auto start = std::chrono::steady_clock::now();
        scene.step(kDt);
        times.push_back(seconds_since(start));
    }
    state.counters["x_faster_than_1_worker"] = one_worker / median(times);
    state.counters["one_worker_ms"] = one_worker * 1e3;
}

void BM_Frame(benchmark::State& state, cloth_solver_kind kind, bool mesh) {
    const uint32_t resolution = static_cast<uint32_t>(state.range(0));
    const double jacobi = jacobi_step_seconds(resolution);
    SceneConfig config = falling_flat(resolution, kind);
    config.mesh = mesh;
    Scene scene(config);
    if (!scene.ok()) {
        state.SkipWithError(scene.error().c_str());
        return;
    }
    keep_awake(scene);
    for (int i = 0; i < 30; ++i) scene.step(kDt);
    double total = 0;
    float max_strain = 0;
    for (auto _ : state) {
        const auto start = std::chrono::steady_clock::now();
        scene.step(kDt);
        total += seconds_since(start);
        max_strain = std::max(max_strain, scene.stats().max_strain);
    }
    state.counters["x_jacobi_k1"] = total / static_cast<double>(state.iterations()) / jacobi;
    state.counters["jacobi_k1_ms"] = jacobi * 1e3;
    state.counters["max_strain"] = max_strain;
}

void register_step_benchmarks() {
    struct Variant {
        const char* name;
        cloth_solver_kind kind;
        uint32_t iterations;
    };
    const Variant variants[] = {{"EXPLICIT", CLOTH_SOLVER_EXPLICIT, 1},
                                {"JACOBI_k1", CLOTH_SOLVER_JACOBI, 1},
                                {"JACOBI_k2", CLOTH_SOLVER_JACOBI, 2},
                                {"JACOBI_k4", CLOTH_SOLVER_JACOBI, 4},
                                {"CG", CLOTH_SOLVER_CG, 1}};
    for (const Variant& v : variants) {
        auto* b = benchmark::RegisterBenchmark((std::string("Step/") + v.name).c_str(), BM_Step, v.kind,
                                               v.iterations);
        b->Arg(32)->Arg(64)->Arg(128)->Unit(benchmark::kMillisecond);
    }
    benchmark::RegisterBenchmark("Frame/DEFAULT", BM_Frame, CLOTH_SOLVER_DEFAULT, false)
        ->Arg(64)
        ->Arg(128)
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark("Frame/DEFAULT_MESH", BM_Frame, CLOTH_SOLVER_DEFAULT, true)
        ->Arg(64)
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark("Frame/DEFAULT_2_WORKERS", BM_FrameTwoWorkers)
        ->Arg(64)
        ->Arg(128)
        ->Unit(benchmark::kMillisecond);
}

// Max strain over the run and the largest energy gain above the start, for
// a cloth falling flat from horizontal, pinned at two corners.
void accuracy_row(uint32_t resolution, const char* label, cloth_solver_kind kind, bool compression_safe,
                  int steps) {
    SceneConfig config;
    config.kind = SceneKind::kFallingFlat;
    config.resolution = resolution;
    config.stiffness = 1000.0f;
    config.solver.kind = kind;
    config.solver.compression_safe_jacobian = compression_safe;
    Scene scene(config);
    if (!scene.ok()) {
        std::printf("%s\n", scene.error().c_str());
        return;
    }
    auto energy = [](const cloth_stats& s) { return s.kinetic_energy + s.gravity_energy + s.elastic_energy; };
    const double e0 = energy(scene.stats());
    double max_gain = 0;
    float max_strain = 0;
    int failures = 0;
    for (int i = 0; i < steps; ++i) {
        if (scene.step(kDt) != CLOTH_OK) ++failures;
        const cloth_stats s = scene.stats();
        max_gain = std::max(max_gain, energy(s) - e0);
        max_strain = std::max(max_strain, s.max_strain);
    }
    const cloth_stats end = scene.stats();
    // gamma of an interior particle: mass = 1 kg/m^2 times one cell, (1/(N-1))^2 m^2.
    const double cell = 1.0 / (resolution - 1);
    const double gamma = double(kDt) * kDt * config.stiffness / (cell * cell);
    std::printf("%4ux%-4u %7.0f %-26s %10.4g %14.4g %14.4g %8d\n", resolution, resolution, gamma, label,
                max_strain, max_gain, energy(end) - e0, failures);
}

void print_accuracy(bool quick) {
    const int steps = quick ? 20 : 300;
    std::printf(
        "Falling flat, 1 m / 1 kg, k = 1e3 N/m, 1/60 s, %d steps. strain: max over the run of\n"
        "(L - l0) / l0; max_gain_J: largest energy above the start; failures: steps undone as non-finite\n",
        steps);
    std::printf("%-9s %7s %-26s %10s %14s %14s %8s\n", "grid", "gamma", "solver", "strain", "max_gain_J",
                "end_change_J", "failures");
    for (uint32_t resolution : {32u, 64u}) {
        if (quick && resolution > 32) break;
        accuracy_row(resolution, "JACOBI k=1", CLOTH_SOLVER_JACOBI, true, steps);
        accuracy_row(resolution, "JACOBI k=1, exact Jacobian", CLOTH_SOLVER_JACOBI, false, steps);
        accuracy_row(resolution, "CG", CLOTH_SOLVER_CG, true, steps);
    }
    std::printf("\n");
    std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
    std::string accuracy = "full";
    int kept = 1;
    for (int i = 1; i < argc; ++i) {
        if (std::strncmp(argv[i], "--accuracy=", 11) == 0) {
            accuracy = argv[i] + 11;
        } else {
            argv[kept++] = argv[i];
        }
    }
    argc = kept;
    if (accuracy != "off") print_accuracy(accuracy == "quick");
    register_step_benchmarks();
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
