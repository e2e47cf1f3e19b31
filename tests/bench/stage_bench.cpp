// Per-stage cost of one JACOBI k=1 substep on the 64x64 flag, from the
// core's own stage functions: where the step's time goes, for tuning.
#include <benchmark/benchmark.h>

#include <memory>
#include <vector>

#include "forces/aerodynamics.h"
#include "forces/material.h"
#include "forces/spring_terms.h"
#include "solve/linear_system.h"
#include "solve/solver_settings.h"
#include "solve/solvers.h"

namespace cloth {
namespace {

struct StageFixture {
    static constexpr float kH = 1.0f / 60.0f;
    HostMemory memory{};
    std::shared_ptr<Fabric> fabric = std::make_shared<Fabric>(&memory);
    Material material;
    AeroParams air;
    Vec3Soa x{&memory}, v{&memory}, external{&memory}, rhs{&memory}, dv{&memory}, next{&memory},
        corner{&memory};
    Sym3Soa diagonal{&memory}, inverse{&memory};
    std::vector<float> mass, pinned;
    std::shared_ptr<SpringTerms> springs;
    uint32_t n = 0;

    explicit StageFixture(uint32_t resolution) {
        cloth_grid_desc grid = cloth_default_grid_desc();
        grid.columns = grid.rows = resolution;
        build_grid_fabric(grid, *fabric);
        n = fabric->particle_count();
        for (SpringParams& s : material.springs) s = {1000.0f, 0.1f};
        air.wind = Vec3(10.0f, 0.0f, 1.0f);
        for (Vec3Soa* a : {&x, &v, &external, &rhs, &dv, &next}) a->resize(n);
        corner.resize(air_storage_size(*fabric));
        diagonal.resize(n);
        inverse.resize(n);
        mass.assign(n, 1.0f / static_cast<float>(n));
        pinned.assign(n, 0.0f);
        for (uint32_t i = 0; i < n; ++i) {
            x.set(i, fabric->rest_positions[i] + Vec3(0.0f, 0.0f, 0.01f * static_cast<float>(i % 5)));
            v.set(i, Vec3(0.01f * static_cast<float>(i % 3), 0.0f, 0.0f));
        }
        springs = make_spring_terms(&memory, fabric, material);
        springs->evaluate(x, v, kH, SpringModel::make(true), 0, springs->item_count());
        assemble();
    }
    AssemblyPass assembly() const {
        return {springs.get(), &external, mass.data(), pinned.data(), kH, 0.02f};
    }
    void assemble() { assemble_particles(assembly(), 0, n, diagonal, inverse, rhs, dv); }
    LinearSystem system() const { return {springs.get(), n, &diagonal, &inverse, &rhs, pinned.data()}; }
};

template <class Stage>
void run_stage(benchmark::State& state, Stage stage) {
    StageFixture f(static_cast<uint32_t>(state.range(0)));
    for (auto _ : state) stage(f);
    state.counters["per_particle"] =
        benchmark::Counter(f.n, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void BM_Stage_Air(benchmark::State& s) {
    run_stage(s, [](StageFixture& f) {
        evaluate_air(*f.fabric, f.air, f.x, f.v, 0, air_item_count(*f.fabric), f.corner);
    });
}
void BM_Stage_AirGather(benchmark::State& s) {
    run_stage(s, [](StageFixture& f) { gather_air(*f.fabric, f.corner, 0, f.n, f.external); });
}
void BM_Stage_Springs(benchmark::State& s) {
    run_stage(s, [](StageFixture& f) {
        f.springs->evaluate(f.x, f.v, StageFixture::kH, SpringModel::make(true), 0, f.springs->item_count());
    });
}
void BM_Stage_Assembly(benchmark::State& s) {
    run_stage(s, [](StageFixture& f) { f.assemble(); });
}
void BM_Stage_JacobiSweep(benchmark::State& s) {
    run_stage(s, [](StageFixture& f) { jacobi_sweep(f.system(), f.dv, 0, f.n, f.next); });
}

BENCHMARK(BM_Stage_Air)->Arg(64)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Stage_AirGather)->Arg(64)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Stage_Springs)->Arg(64)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Stage_Assembly)->Arg(64)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Stage_JacobiSweep)->Arg(64)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace cloth
