// Field/*: a scene of many cloths in one world, what it costs and what a
// frame budget holds of it. 32 flags of 48x32 particles (1.2 x 0.8 m,
// pinned along one side, 8-12 m/s wind, CLOTH_SOLVER_DEFAULT, sleep off):
//
//   Field/W1/Full, Field/W2/Full      every flag at its own quality, 1 or 2 workers
//   Field/W1/Budget4, Field/W2/Budget4  a 4 ms frame budget, every flag's
//                                     policy allowing rate 8, importance
//                                     falling with the flag's index
//   Field/W1/Lone                     one such flag (10 m/s) alone in its world
//
// Counters (medians of the timed frames): step_ms, and what it held:
// flags_per_ms and particles_per_ms (all the flags' particles over the
// frame's time), and over_budget (the share of frames over 4 ms). A flag
// of the field costs step_ms x workers / 32 of worker time, against
// Field/W1/Lone's step_ms alone.
#include <benchmark/benchmark.h>
#include <cloth/cloth.h>

#include <algorithm>
#include <chrono>
#include <string>
#include <vector>

namespace {

constexpr uint32_t kFlags = 32, kColumns = 48, kRows = 32;
constexpr float kDt = 1.0f / 60.0f;
constexpr float kBudgetMs = 4.0f;

// The field; false with the benchmark skipped.
bool make_field(benchmark::State& state, uint32_t flags, uint32_t workers, bool budget, cloth_world_id* out) {
    cloth_world_desc wd = cloth_default_world_desc();
    wd.worker_count = workers;
    wd.max_cloths = flags;
    cloth_world_id world{};
    cloth_fabric_id fabric{};
    cloth_grid_desc grid = cloth_default_grid_desc();
    grid.columns = kColumns;
    grid.rows = kRows;
    grid.u[0] = 1.2f;
    grid.v[1] = -0.8f;
    if (cloth_world_create(&wd, &world) != CLOTH_OK ||
        cloth_fabric_create_grid(world, &grid, &fabric) != CLOTH_OK) {
        state.SkipWithError(cloth_get_last_error());
        *out = world;
        return false;
    }
    *out = world;
    std::vector<uint32_t> pole_side;
    for (uint32_t r = 0; r < kRows; ++r) pole_side.push_back(r * kColumns);
    for (uint32_t k = 0; k < flags; ++k) {
        cloth_desc cd = cloth_default_desc();
        cd.fabric = fabric;
        cloth_id flag{};
        cloth_sleep_params sleep = cloth_default_sleep_params();
        sleep.enabled = 0;
        const float wind[3] = {flags == 1 ? 10.0f : 8.0f + static_cast<float>(k % 5), 0.0f, 1.0f};
        bool ok = cloth_create(world, &cd, &flag) == CLOTH_OK &&
                  cloth_pin(flag, pole_side.data(), kRows) == CLOTH_OK &&
                  cloth_set_wind(flag, wind) == CLOTH_OK && cloth_set_sleep(flag, &sleep) == CLOTH_OK;
        if (ok && budget) {
            cloth_quality_policy policy = cloth_default_quality_policy();
            policy.enabled = 1;
            policy.max_update_rate = 8;
            ok = cloth_set_quality_policy(flag, &policy) == CLOTH_OK &&
                 cloth_set_importance(flag, 1.0f / static_cast<float>(1 + k)) == CLOTH_OK;
        }
        if (!ok) {
            state.SkipWithError(cloth_get_last_error());
            return false;
        }
    }
    if (budget) cloth_world_set_frame_budget(world, kBudgetMs);
    return true;
}

void field(benchmark::State& state, uint32_t workers, bool budget, uint32_t flags = kFlags) {
    cloth_world_id world{};
    if (!make_field(state, flags, workers, budget, &world)) {
        cloth_world_destroy(world);
        return;
    }
    auto step = [&] {
        const cloth_result r = cloth_step(world, kDt);
        return r == CLOTH_OK || r == CLOTH_ERROR_OVER_BUDGET;
    };
    bool ok = true;
    for (int i = 0; i < 60 && ok; ++i) ok = step();  // the flags unfold, the budget settles
    std::vector<double> ms;
    for (auto _ : state) {
        const auto start = std::chrono::steady_clock::now();
        ok = step() && ok;
        const double t =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        ms.push_back(t);
        state.SetIterationTime(t * 1e-3);
    }
    cloth_world_destroy(world);
    if (!ok) {
        state.SkipWithError("a step failed");
        return;
    }
    const double over =
        static_cast<double>(std::count_if(ms.begin(), ms.end(), [](double t) { return t > kBudgetMs; }));
    std::nth_element(ms.begin(), ms.begin() + ms.size() / 2, ms.end());
    const double median = ms[ms.size() / 2];
    state.counters["step_ms"] = median;
    state.counters["flags_per_ms"] = flags / median;
    state.counters["particles_per_ms"] = flags * kColumns * kRows / median;
    state.counters["over_budget"] = over / static_cast<double>(ms.size());
}

void BM_FieldW1Full(benchmark::State& state) { field(state, 1, false); }
void BM_FieldW2Full(benchmark::State& state) { field(state, 2, false); }
void BM_FieldW1Budget(benchmark::State& state) { field(state, 1, true); }
void BM_FieldW2Budget(benchmark::State& state) { field(state, 2, true); }
void BM_FieldW1Lone(benchmark::State& state) { field(state, 1, false, 1); }

}  // namespace

BENCHMARK(BM_FieldW1Full)
    ->Name("Field/W1/Full")
    ->UseManualTime()
    ->Iterations(120)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FieldW2Full)
    ->Name("Field/W2/Full")
    ->UseManualTime()
    ->Iterations(120)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FieldW1Lone)
    ->Name("Field/W1/Lone")
    ->UseManualTime()
    ->Iterations(120)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FieldW1Budget)
    ->Name("Field/W1/Budget4")
    ->UseManualTime()
    ->Iterations(600)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FieldW2Budget)
    ->Name("Field/W2/Budget4")
    ->UseManualTime()
    ->Iterations(600)
    ->Unit(benchmark::kMillisecond);
