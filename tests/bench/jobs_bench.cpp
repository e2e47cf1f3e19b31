// Jobs/*: what the task system buys and costs, each as two configurations
// stepped alternately in the same benchmark so that both see the same
// machine load, reported as medians and their ratio:
//
//   Jobs/Speedup128      one 128 x 128 flag: 1 worker vs 2 (ratio = speed-up)
//   Jobs/Speedup16x32    16 flags of 32 x 32 in one world: 1 vs 2 workers
//   .../Polling          the same with the second worker polling for 2 ms
//                        after a step (cloth_world_set_worker_spin) instead
//                        of the default 0.5 ms: here each world waits for
//                        the other's step (over 1 ms), so at the default
//                        its worker sleeps and every step pays its wake-up
//   Jobs/Overhead32      one 32 x 32 flag: 1 worker vs 2 (ratio > 1: 2 workers faster)
//   Jobs/FeaturesOff     a 64 x 64 cloth with bend springs, air and
//                        self-collision off, stepped through the world and
//                        the C API, vs the bare solver (ClothInstance::step
//                        on the calling thread): ratio ~ 1 means the unused
//                        features and the task system cost nothing
//   Jobs/Sleeping        one sleeping 64 x 64 cloth: cost of cloth_step
//
// The flags are in 10 m/s wind, JACOBI one sweep, 1/60 s. Every step must
// return CLOTH_OK: else the benchmark reports an error (and cloth_bench
// exits 1).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "scenes.h"
#include "step/cloth_instance.h"

namespace {

using cloth_samples::Scene;
using cloth_samples::SceneConfig;
using cloth_samples::SceneKind;
using Clock = std::chrono::steady_clock;

constexpr float kDt = 1.0f / 60.0f;

double median(std::vector<double> v) {
    if (v.empty()) return 0;
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
}

// Runs `step` (which returns a cloth_result) and adds its time in ms to
// `ms`; keeps the first result other than CLOTH_OK in `failure`.
template <class Step>
double time_ms(Step step, cloth_result& failure) {
    const auto start = Clock::now();
    const cloth_result r = step();
    const double ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    if (r != CLOTH_OK && failure == CLOTH_OK) failure = r;
    return ms;
}

// Steps a and b alternately; counters a_ms, b_ms (medians) and ratio = a / b.
template <class A, class B>
void run_pair(benchmark::State& state, A step_a, B step_b) {
    cloth_result failure = CLOTH_OK;
    for (int i = 0; i < 20; ++i) {  // warm-up
        time_ms(step_a, failure);
        time_ms(step_b, failure);
    }
    std::vector<double> a, b;
    for (auto _ : state) {
        const double ta = time_ms(step_a, failure), tb = time_ms(step_b, failure);
        a.push_back(ta);
        b.push_back(tb);
        state.SetIterationTime((ta + tb) * 1e-3);
    }
    if (failure != CLOTH_OK) {
        state.SkipWithError((std::string("a step returned ") + cloth_result_name(failure)).c_str());
        return;
    }
    const double ma = median(a), mb = median(b);
    state.counters["a_ms"] = ma;
    state.counters["b_ms"] = mb;
    state.counters["ratio"] = mb > 0 ? ma / mb : 0;
}

SceneConfig flags(uint32_t resolution, uint32_t copies, uint32_t workers) {
    SceneConfig config;
    config.kind = SceneKind::kFlagInWind;
    config.resolution = resolution;
    config.copies = copies;
    config.world.worker_count = workers;
    config.solver.kind = CLOTH_SOLVER_JACOBI;  // one sweep (the default solver is PCG)
    return config;
}

// A worker polling time that spans the other world's step in run_pair.
constexpr uint32_t kPollingSpinMicroseconds = 2000;

void workers_1_vs_2(benchmark::State& state, uint32_t resolution, uint32_t copies, uint32_t spin_us = 0) {
    Scene one(flags(resolution, copies, 1)), two(flags(resolution, copies, 2));
    if (!one.ok() || !two.ok()) {
        state.SkipWithError("scene");
        return;
    }
    if (spin_us > 0 && cloth_world_set_worker_spin(two.world(), spin_us) != CLOTH_OK) {
        state.SkipWithError("cloth_world_set_worker_spin");
        return;
    }
    run_pair(
        state, [&] { return one.step(kDt); }, [&] { return two.step(kDt); });
}

void BM_Speedup128(benchmark::State& state) { workers_1_vs_2(state, 128, 1); }
void BM_Speedup16x32(benchmark::State& state) { workers_1_vs_2(state, 32, 16); }
void BM_Overhead32(benchmark::State& state) { workers_1_vs_2(state, 32, 1); }
void BM_Speedup128Polling(benchmark::State& state) {
    workers_1_vs_2(state, 128, 1, kPollingSpinMicroseconds);
}
void BM_Speedup16x32Polling(benchmark::State& state) {
    workers_1_vs_2(state, 32, 16, kPollingSpinMicroseconds);
}

void BM_FeaturesOff(benchmark::State& state) {
    // Through the world: structural and shear springs only, still air, no
    // self-collision (off by default), one worker.
    SceneConfig config;
    config.kind = SceneKind::kHanging;
    config.resolution = 64;
    config.spring_kinds = CLOTH_SPRING_STRUCTURAL | CLOTH_SPRING_SHEAR;
    config.damping = 0.1f;
    config.solver.kind = CLOTH_SOLVER_JACOBI;  // as the bare ClothInstance below
    Scene world_scene(config);
    if (!world_scene.ok()) {
        state.SkipWithError(world_scene.error().c_str());
        return;
    }
    cloth_aero_params still{};
    still.air_density = 0;
    cloth_sleep_params awake = cloth_default_sleep_params();
    awake.enabled = false;
    const uint32_t pins[2] = {0, 63};
    if (cloth_set_aero(world_scene.cloth(), &still) != CLOTH_OK ||
        cloth_set_sleep(world_scene.cloth(), &awake) != CLOTH_OK ||
        cloth_pin(world_scene.cloth(), pins, 2) != CLOTH_OK) {
        state.SkipWithError(cloth_get_last_error());
        return;
    }

    // The bare solver: the same cloth as a core object, stepped directly.
    static const cloth::HostMemory heap{};
    auto fabric = std::make_shared<cloth::Fabric>(&heap);
    cloth_grid_desc grid = cloth_default_grid_desc();
    grid.columns = grid.rows = 64;
    grid.spring_kinds = config.spring_kinds;
    grid.origin[1] = 1.5f;
    cloth::build_grid_fabric(grid, *fabric);
    cloth::Material material;
    for (auto& s : material.springs) s = {config.stiffness, config.damping};
    material.area_density = config.total_mass;
    cloth::AeroParams air;
    air.air_density = 0;
    air.linear_drag = 0;
    cloth::ClothInstance bare(&heap, fabric, material, cloth::SolverSettings{}, air);
    cloth::SleepSettings never;
    never.enabled = false;
    bare.set_sleep(never);
    bare.pin(0);
    bare.pin(63);
    const cloth::Vec3 gravity(0.0f, -9.81f, 0.0f);
    run_pair(
        state, [&] { return world_scene.step(kDt); }, [&] { return bare.step(kDt, gravity).code; });
}

void BM_Sleeping(benchmark::State& state) {
    SceneConfig config;
    config.kind = SceneKind::kHanging;
    config.resolution = 64;
    Scene scene(config);
    if (!scene.ok()) {
        state.SkipWithError(scene.error().c_str());
        return;
    }
    cloth_sleep_params sleep = cloth_default_sleep_params();
    sleep.max_speed = 1e9f;  // asleep after one frame, whatever it does
    sleep.frames = 1;
    bool sleeping = false;
    if (cloth_set_sleep(scene.cloth(), &sleep) != CLOTH_OK || scene.step(kDt) != CLOTH_OK ||
        cloth_is_sleeping(scene.cloth(), &sleeping) != CLOTH_OK || !sleeping) {
        state.SkipWithError("the cloth did not fall asleep");
        return;
    }
    cloth_result failure = CLOTH_OK;
    for (auto _ : state) {
        const cloth_result r = scene.step(kDt);
        if (r != CLOTH_OK && failure == CLOTH_OK) failure = r;
    }
    if (failure != CLOTH_OK)
        state.SkipWithError((std::string("a step returned ") + cloth_result_name(failure)).c_str());
}

}  // namespace

BENCHMARK(BM_Speedup128)->Name("Jobs/Speedup128")->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Speedup16x32)->Name("Jobs/Speedup16x32")->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Speedup128Polling)
    ->Name("Jobs/Speedup128/Polling")
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Speedup16x32Polling)
    ->Name("Jobs/Speedup16x32/Polling")
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Overhead32)->Name("Jobs/Overhead32")->UseManualTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_FeaturesOff)->Name("Jobs/FeaturesOff")->UseManualTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Sleeping)->Name("Jobs/Sleeping")->Unit(benchmark::kNanosecond);
