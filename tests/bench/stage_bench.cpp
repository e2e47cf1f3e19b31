// Per-stage cost of one JACOBI k=1 substep on the 64x64 flag, from the
// core's own stage functions: where the step's time goes, for tuning. What
// the tethers' plan costs after a change of the pin set. And what the skin
// costs per particle: skinning once a frame, its constraints per substep.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "forces/aerodynamics.h"
#include "forces/material.h"
#include "forces/spring_terms.h"
#include "solve/linear_system.h"
#include "solve/skin.h"
#include "solve/solver_settings.h"
#include "solve/solvers.h"
#include "solve/tethers.h"

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

// The tethers' plan after a change of the pin set: a grid's by straight
// distance against a search along the springs (the same cloth built as a
// mesh), with 2 pinned corners or a pinned top row. Sets
// Tethers::kSearchStepOverDistance: the counter `per_step` is the time per
// distance step (grid) or per search step (mesh, kAnchors * (n + 2 springs)).
void BM_Tethers_Plan(benchmark::State& state) {
    const uint32_t resolution = static_cast<uint32_t>(state.range(0));
    const bool mesh = state.range(1) != 0, row = state.range(2) != 0;
    HostMemory memory{};
    Fabric fabric(&memory);
    cloth_grid_desc grid = cloth_default_grid_desc();
    grid.columns = grid.rows = resolution;
    if (mesh) {
        Fabric flat(&memory);
        build_grid_fabric(grid, flat);
        std::vector<float> positions;
        for (const Vec3& p : flat.rest_positions) positions.insert(positions.end(), {p.x(), p.y(), p.z()});
        std::vector<uint32_t> triangles;
        for (uint32_t r = 0; r + 1 < resolution; ++r) {
            for (uint32_t c = 0; c + 1 < resolution; ++c) {
                const uint32_t a = r * resolution + c, b = a + 1, d = a + resolution, e = d + 1;
                triangles.insert(triangles.end(), {a, b, e, a, e, d});
            }
        }
        build_mesh_fabric(positions.data(), resolution * resolution, triangles.data(),
                          static_cast<uint32_t>(triangles.size() / 3), CLOTH_SPRING_ALL, fabric);
    } else {
        build_grid_fabric(grid, fabric);
    }
    const uint32_t n = fabric.particle_count();
    // Pins by rest position, so the grid and the mesh (stored in another
    // order) pin the same places: the top row, or its two ends.
    float top = -1e30f, left = 1e30f, right = -1e30f;
    for (const Vec3& p : fabric.rest_positions) {
        top = std::max(top, p.y());
        left = std::min(left, p.x());
        right = std::max(right, p.x());
    }
    std::vector<float> pinned(n, 0.0f);
    uint32_t pins = 0;
    for (uint32_t i = 0; i < n; ++i) {
        const Vec3& p = fabric.rest_positions[i];
        const bool on_top = p.y() == top, at_end = p.x() == left || p.x() == right;
        if (on_top && (row || at_end)) {
            pinned[i] = 1.0f;
            ++pins;
        }
    }
    Tethers tethers(&memory);
    tethers.resize(fabric);
    for (auto _ : state) tethers.plan(fabric, pinned.data());
    const double steps =
        mesh ? double{Tethers::kAnchors} * (n + 2.0 * fabric.spring_count()) : static_cast<double>(n) * pins;
    state.counters["per_step"] = benchmark::Counter(
        steps, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
    state.counters["pins"] = pins;
}

BENCHMARK(BM_Tethers_Plan)
    ->ArgNames({"res", "mesh", "row"})
    ->ArgsProduct({{64, 128}, {0, 1}, {0, 1}})
    ->Unit(benchmark::kMillisecond);

// A 64x64 cloth skinned to 16 joints, `influences` per particle, turned
// and moved; per particle, by range 1: 0 the skinning; 1 the max-distance
// and backstop projection of every particle (the skinned positions of a
// frame, the particles scattered about them); 2 the same from what
// prepare() kept (each run after a substep's first); 3 prepare() itself.
void BM_Skin(benchmark::State& state) {
    const uint32_t influences = static_cast<uint32_t>(state.range(0));
    const int64_t mode = state.range(1);
    const bool constraints = mode == 1 || mode == 2;
    StageFixture f(64);
    Skin skin(&f.memory);
    const uint32_t joints = 16;
    std::vector<uint32_t> joint(size_t{f.n} * influences);
    std::vector<float> weight(size_t{f.n} * influences, 1.0f / static_cast<float>(influences));
    for (size_t e = 0; e < joint.size(); ++e) joint[e] = static_cast<uint32_t>((e * 7) % joints);
    skin.bind(*f.fabric, joints, influences, joint.data(), weight.data());
    std::vector<float> m(size_t{joints} * Skin::kMatrixFloats);
    for (uint32_t j = 0; j < joints; ++j) {
        const float a = 0.1f * static_cast<float>(j), c = std::cos(a), s = std::sin(a);
        const float row[12] = {c, 0, s, 0.1f * j, 0, 1, 0, 0, -s, 0, c, 0};
        std::copy(row, row + 12, m.begin() + size_t{j} * Skin::kMatrixFloats);
    }
    skin.set_joint_matrices(m.data(), false);
    skin.begin_frame(false);
    skin.skin(0, f.n);
    skin.finish_skinning();
    for (uint32_t i = 0; i < f.n; ++i) {
        skin.set_max_distance(i, 0.05f);
        skin.set_backstop(i, 0.05f, 0.04f);
    }
    std::vector<float> pinned(f.n, 0.0f);
    Vec3Soa x(&f.memory), v(&f.memory);
    x.resize(f.n);
    v.resize(f.n);
    skin.prepare(0, f.n, 1.0f);
    for (auto _ : state) {
        if (mode == 3) {
            skin.prepare(0, f.n, 1.0f);
        } else if (constraints) {
            state.PauseTiming();
            for (uint32_t i = 0; i < f.n; ++i) {  // around the skin, some outside either sphere
                const float k = 0.02f * static_cast<float>(i % 7) - 0.06f;
                x.set(i, skin.position(i, 1.0f) + Vec3(k, -k, 0.5f * k));
            }
            state.ResumeTiming();
            skin.constrain(0, f.n, 1.0f, StageFixture::kH, pinned.data(), x, v, mode == 2);
        } else {
            skin.skin(0, f.n);
        }
        benchmark::DoNotOptimize(x.x.data());
    }
    state.counters["per_particle"] =
        benchmark::Counter(f.n, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

BENCHMARK(BM_Skin)
    ->ArgNames({"influences", "constraints"})
    ->Args({1, 0})
    ->Args({4, 0})
    ->Args({1, 1})
    ->Args({1, 2})
    ->Args({1, 3})
    ->Unit(benchmark::kMicrosecond);

BENCHMARK(BM_Stage_Air)->Arg(64)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Stage_AirGather)->Arg(64)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Stage_Springs)->Arg(64)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Stage_Assembly)->Arg(64)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Stage_JacobiSweep)->Arg(64)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace cloth
