// cloth_bench: step cost per solver kind and grid size (Google Benchmark,
// single thread), preceded by the accuracy table that shows where the
// paper's one-iteration step stands against the full solve
// (docs/method.md, "Where one iteration stops holding").
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
// over its frame time. Frame/DEFAULT_AT_REST/N: the default holding a
// cloth hanging still (the hanging scene, 1e3 N/m, its top edge pinned,
// awake, after 300 frames of settling); counter x_falling is its frame time over the median
// frame of Frame/DEFAULT's falling cloth, timed in the same run just
// before: what a quiet cloth costs against a moving one.
//
// Exit code 1 when a scene failed (what the ctest cloth_bench_smoke checks):
// a benchmark that could not build its scene or whose step returned what it
// does not expect (reported as the benchmark's error, ERROR OCCURRED), or an
// accuracy row whose scene was not built, whose step returned an error other
// than an undone non-finite step, or whose figures are not finite.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "scenes.h"

namespace {

using cloth_samples::Scene;
using cloth_samples::SceneConfig;
using cloth_samples::SceneKind;

constexpr float kDt = 1.0f / 60.0f;

// The steps of one benchmark's scene, checked. A kind that is not stable
// at every step (EXPLICIT at 60 Hz, JACOBI k=1 on a fine grid falling flat)
// may diverge: the library undoes such a step and says so
// (CLOTH_ERROR_NONFINITE_STATE), and the benchmark counts it. Any other
// result is a failure, reported as the benchmark's error by report().
struct CheckedSteps {
    bool may_diverge = false;
    int64_t undone = 0;
    cloth_result failure = CLOTH_OK;
    cloth_result step(Scene& scene) {
        const cloth_result r = scene.step(kDt);
        if (r == CLOTH_ERROR_NONFINITE_STATE && may_diverge) {
            ++undone;
        } else if (r != CLOTH_OK && failure == CLOTH_OK) {
            failure = r;
        }
        return r;
    }
    // false (and the benchmark's error set) when a step failed.
    bool report(benchmark::State& state) const {
        if (failure == CLOTH_OK) return true;
        state.SkipWithError((std::string("a step returned ") + cloth_result_name(failure)).c_str());
        return false;
    }
};

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
    CheckedSteps steps;
    steps.may_diverge = kind == CLOTH_SOLVER_EXPLICIT;
    for (int i = 0; i < 30; ++i) steps.step(scene);
    const int64_t undone_in_warm_up = steps.undone;
    for (auto _ : state) steps.step(scene);
    if (!steps.report(state)) return;
    // Steps that went non-finite and were undone: the time of such a step is
    // the cost of computing and discarding it (EXPLICIT at 60 Hz).
    state.counters["failed_steps"] = benchmark::Counter(static_cast<double>(steps.undone - undone_in_warm_up),
                                                        benchmark::Counter::kAvgIterations);
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

// Sleep off for every cloth of the scene; false (and the benchmark's error
// set) when that failed.
bool keep_awake(benchmark::State& state, const Scene& scene) {
    cloth_sleep_params awake = cloth_default_sleep_params();
    awake.enabled = 0;
    for (cloth_id cloth : scene.cloths()) {
        if (cloth_set_sleep(cloth, &awake) != CLOTH_OK) {
            state.SkipWithError(cloth_get_last_error());
            return false;
        }
    }
    return true;
}

double median(std::vector<double> times) {
    std::nth_element(times.begin(), times.begin() + times.size() / 2, times.end());
    return times[times.size() / 2];
}

// Median frame of the falling-flat scene over `frames` frames after 30
// warm-up frames, awake throughout; 0 (and the benchmark's error set) when
// the scene or a step failed.
double median_frame_seconds(benchmark::State& state, const SceneConfig& config, int frames) {
    Scene scene(config);
    if (!scene.ok()) {
        state.SkipWithError(scene.error().c_str());
        return 0;
    }
    if (!keep_awake(state, scene)) return 0;
    CheckedSteps steps;
    steps.may_diverge = config.solver.kind == CLOTH_SOLVER_JACOBI;
    for (int i = 0; i < 30; ++i) steps.step(scene);
    std::vector<double> times;
    for (int i = 0; i < frames; ++i) {
        const auto start = std::chrono::steady_clock::now();
        steps.step(scene);
        times.push_back(seconds_since(start));
    }
    return steps.report(state) ? median(times) : 0;
}

// Median JACOBI k=1 step of the falling-flat scene (at 128 x 128 it
// diverges after about 45 frames: those steps are timed as computed and undone).
double jacobi_step_seconds(benchmark::State& state, uint32_t resolution) {
    return median_frame_seconds(state, falling_flat(resolution, CLOTH_SOLVER_JACOBI), 61);
}

SceneConfig default_on_workers(uint32_t resolution, uint32_t workers) {
    SceneConfig config = falling_flat(resolution, CLOTH_SOLVER_DEFAULT);
    config.world.worker_count = workers;
    return config;
}

void BM_FrameTwoWorkers(benchmark::State& state) {
    const uint32_t resolution = static_cast<uint32_t>(state.range(0));
    const double one_worker = median_frame_seconds(state, default_on_workers(resolution, 1), 31);
    if (state.error_occurred()) return;
    Scene scene(default_on_workers(resolution, 2));
    if (!scene.ok()) {
        state.SkipWithError(scene.error().c_str());
        return;
    }
    if (!keep_awake(state, scene)) return;
    CheckedSteps steps;
    for (int i = 0; i < 30; ++i) steps.step(scene);
    std::vector<double> times;
    for (auto _ : state) {
        const auto start = std::chrono::steady_clock::now();
        steps.step(scene);
        times.push_back(seconds_since(start));
    }
    if (!steps.report(state)) return;
    state.counters["x_faster_than_1_worker"] = one_worker / median(times);
    state.counters["one_worker_ms"] = one_worker * 1e3;
}

void BM_FrameAtRest(benchmark::State& state) {
    const uint32_t resolution = static_cast<uint32_t>(state.range(0));
    const double falling = median_frame_seconds(state, falling_flat(resolution, CLOTH_SOLVER_DEFAULT), 31);
    if (state.error_occurred()) return;
    SceneConfig config = falling_flat(resolution, CLOTH_SOLVER_DEFAULT);
    config.kind = SceneKind::kHanging;
    Scene scene(config);
    if (!scene.ok()) {
        state.SkipWithError(scene.error().c_str());
        return;
    }
    if (!keep_awake(state, scene)) return;
    // Its whole top edge pinned, the cloth hangs straight down and stills.
    std::vector<uint32_t> top(resolution);
    for (uint32_t i = 0; i < resolution; ++i) top[i] = i;
    if (cloth_pin(scene.cloth(), top.data(), resolution) != CLOTH_OK) {
        state.SkipWithError(cloth_get_last_error());
        return;
    }
    CheckedSteps steps;
    for (int i = 0; i < 300; ++i) steps.step(scene);
    std::vector<double> times;
    float max_speed = 0;
    for (auto _ : state) {
        const auto start = std::chrono::steady_clock::now();
        steps.step(scene);
        times.push_back(seconds_since(start));
        max_speed = std::max(max_speed, scene.stats().max_speed);
    }
    if (!steps.report(state)) return;
    state.counters["x_falling"] = median(times) / falling;
    state.counters["falling_ms"] = falling * 1e3;
    state.counters["max_speed"] = max_speed;
}

void BM_Frame(benchmark::State& state, cloth_solver_kind kind, bool mesh) {
    const uint32_t resolution = static_cast<uint32_t>(state.range(0));
    const double jacobi = jacobi_step_seconds(state, resolution);
    if (state.error_occurred()) return;
    SceneConfig config = falling_flat(resolution, kind);
    config.mesh = mesh;
    Scene scene(config);
    if (!scene.ok()) {
        state.SkipWithError(scene.error().c_str());
        return;
    }
    if (!keep_awake(state, scene)) return;
    CheckedSteps steps;
    for (int i = 0; i < 30; ++i) steps.step(scene);
    double total = 0;
    float max_strain = 0;
    for (auto _ : state) {
        const auto start = std::chrono::steady_clock::now();
        steps.step(scene);
        total += seconds_since(start);
        max_strain = std::max(max_strain, scene.stats().max_strain);
    }
    if (!steps.report(state)) return;
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
    benchmark::RegisterBenchmark("Frame/DEFAULT_AT_REST", BM_FrameAtRest)
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
// a cloth falling flat from horizontal, pinned at two corners. false when
// the scene was not built, a step returned an error other than an undone
// non-finite step (counted in the row), or a figure is not finite.
bool accuracy_row(uint32_t resolution, const char* label, cloth_solver_kind kind, bool compression_safe,
                  int steps) {
    SceneConfig config;
    config.kind = SceneKind::kFallingFlat;
    config.resolution = resolution;
    config.stiffness = 1000.0f;
    config.solver.kind = kind;
    config.solver.compression_safe_jacobian = compression_safe;
    Scene scene(config);
    if (!scene.ok()) {
        std::printf("%s: the scene was not built: %s\n", label, scene.error().c_str());
        return false;
    }
    auto energy = [](const cloth_stats& s) { return s.kinetic_energy + s.gravity_energy + s.elastic_energy; };
    const double e0 = energy(scene.stats());
    double max_gain = 0;
    float max_strain = 0;
    int failures = 0;
    cloth_result error = CLOTH_OK;
    for (int i = 0; i < steps; ++i) {
        const cloth_result r = scene.step(kDt);
        if (r == CLOTH_ERROR_NONFINITE_STATE) ++failures;
        if (r != CLOTH_OK && r != CLOTH_ERROR_NONFINITE_STATE && error == CLOTH_OK) error = r;
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
    if (error != CLOTH_OK) std::printf("%s: a step returned %s\n", label, cloth_result_name(error));
    // std::max keeps its first argument against a NaN: test every figure.
    const bool finite = std::isfinite(e0) && std::isfinite(max_gain) && std::isfinite(max_strain) &&
                        std::isfinite(energy(end)) && std::isfinite(end.max_strain);
    if (!finite) std::printf("%s: a figure is not finite\n", label);
    return error == CLOTH_OK && finite;
}

// false when a row failed (accuracy_row).
bool print_accuracy(bool quick) {
    const int steps = quick ? 20 : 300;
    std::printf(
        "Falling flat, 1 m / 1 kg, k = 1e3 N/m, 1/60 s, %d steps. strain: max over the run of\n"
        "(L - l0) / l0; max_gain_J: largest energy above the start; failures: steps undone as non-finite\n",
        steps);
    std::printf("%-9s %7s %-26s %10s %14s %14s %8s\n", "grid", "gamma", "solver", "strain", "max_gain_J",
                "end_change_J", "failures");
    bool ok = true;
    for (uint32_t resolution : {32u, 64u}) {
        if (quick && resolution > 32) break;
        ok &= accuracy_row(resolution, "JACOBI k=1", CLOTH_SOLVER_JACOBI, true, steps);
        ok &= accuracy_row(resolution, "JACOBI k=1, exact Jacobian", CLOTH_SOLVER_JACOBI, false, steps);
        ok &= accuracy_row(resolution, "CG", CLOTH_SOLVER_CG, true, steps);
    }
    std::printf("\n");
    std::fflush(stdout);
    return ok;
}

// The display reporter the flags ask for (--benchmark_format), counting
// the benchmarks that reported an error (SkipWithError: a scene not built,
// a step that failed).
class CountingReporter : public benchmark::BenchmarkReporter {
  public:
    CountingReporter() : display_(benchmark::CreateDefaultDisplayReporter()) {}
    bool ReportContext(const Context& context) override { return display_->ReportContext(context); }
    void ReportRuns(const std::vector<Run>& runs) override {
        for (const Run& run : runs) {
            if (run.error_occurred) ++errors_;
        }
        display_->ReportRuns(runs);
    }
    void Finalize() override { display_->Finalize(); }
    int errors() const { return errors_; }

  private:
    std::unique_ptr<benchmark::BenchmarkReporter> display_;
    int errors_ = 0;
};

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
    const bool accuracy_ok = accuracy == "off" || print_accuracy(accuracy == "quick");
    register_step_benchmarks();
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    CountingReporter reporter;
    benchmark::RunSpecifiedBenchmarks(&reporter);
    benchmark::Shutdown();
    if (!accuracy_ok) std::fprintf(stderr, "cloth_bench: an accuracy row failed (above)\n");
    if (reporter.errors() > 0) std::fprintf(stderr, "cloth_bench: %d benchmarks failed\n", reporter.errors());
    return accuracy_ok && reporter.errors() == 0 ? 0 : 1;
}
