// Self-collision cost per step on a folded cloth (an N x N grid folded like
// an accordion every 0.3 m, across regions, into four layers 0.6 theta_c apart, theta_c = 0.9 mean rest
// edge), single thread:
//
//   SelfCollision/BruteForce/N   contact search over all n^2 / 2 pairs
//   SelfCollision/HashOnly/N     hash search, regions off: region check (a
//                                no-op), keys, sort, per-particle contacts
//   SelfCollision/HashRegions/N  the same with collision-free regions
//   SelfCollision/Stage/N        the whole self-collision stage with regions
//                                (search, projection passes, velocity response)
//
// `per_particle` is time per particle per step: flat in N means O(n).
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <vector>

#include "collide/self_collision.h"

namespace cloth {
namespace {

struct FoldedCloth {
    HostMemory memory{};
    Fabric fabric{&memory};
    Vec3Soa x{&memory}, v{&memory};
    std::vector<float> mass, pinned;
    std::unique_ptr<SelfCollision> collision;
    uint32_t n = 0;

    FoldedCloth(uint32_t resolution, bool regions) {
        cloth_grid_desc grid = cloth_default_grid_desc();
        grid.columns = grid.rows = resolution;
        build_grid_fabric(grid, fabric);
        n = fabric.particle_count();
        SelfCollisionSettings settings;
        settings.thickness = 0.9f * mean_rest_edge(fabric);
        settings.use_regions = regions;
        collision = std::make_unique<SelfCollision>(&memory, fabric, settings);
        x.resize(n);
        v.resize(n);
        const float period = 0.3f, gap = 0.6f * settings.thickness;
        for (uint32_t i = 0; i < n; ++i) {
            const Vec3& p = fabric.rest_positions[i];
            const float layer = std::floor(p.x() / period), t = p.x() - layer * period;
            const float folded = static_cast<int>(layer) % 2 ? period - t : t;
            // A small ripple so the layers are not exactly flat.
            x.set(i, Vec3(folded, p.y(), layer * gap + 0.1f * gap * std::sin(40.0f * p.y())));
            v.set(i, Vec3(0.0f, 0.0f, -0.1f));
        }
        mass.assign(n, 1.0f / static_cast<float>(n));
        pinned.assign(n, 0.0f);
    }

    void search() {
        collision->check_regions(x, 0, collision->region_count());
        collision->compute_keys(x, 0, n);
        collision->sort_into_buckets(x);
        collision->find_contacts(x, 0, n);
    }

    // All pairs closer than theta_c that are not rest neighbours.
    uint32_t brute_force() const {
        const float theta = collision->settings().thickness, theta2 = theta * theta;
        uint32_t pairs = 0;
        for (uint32_t i = 0; i < n; ++i) {
            const float xi = x.x[i], yi = x.y[i], zi = x.z[i];
            for (uint32_t j = i + 1; j < n; ++j) {
                const float dx = xi - x.x[j], dy = yi - x.y[j], dz = zi - x.z[j];
                if (dx * dx + dy * dy + dz * dz < theta2 && !collision->is_rest_neighbour(i, j)) ++pairs;
            }
        }
        return pairs;
    }
};

void per_particle(benchmark::State& state, const FoldedCloth& f) {
    state.counters["per_particle"] =
        benchmark::Counter(f.n, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void BM_SelfCollision_BruteForce(benchmark::State& state) {
    FoldedCloth f(static_cast<uint32_t>(state.range(0)), false);
    uint32_t pairs = 0;
    for (auto _ : state) benchmark::DoNotOptimize(pairs = f.brute_force());
    per_particle(state, f);
    state.counters["contacts"] = pairs;
}

void BM_SelfCollision_HashOnly(benchmark::State& state) {
    FoldedCloth f(static_cast<uint32_t>(state.range(0)), false);
    for (auto _ : state) f.search();
    per_particle(state, f);
    state.counters["contacts"] = f.collision->stats().contacts;
}

void BM_SelfCollision_HashRegions(benchmark::State& state) {
    FoldedCloth f(static_cast<uint32_t>(state.range(0)), true);
    for (auto _ : state) f.search();
    per_particle(state, f);
    const SelfCollisionStats stats = f.collision->stats();
    state.counters["contacts"] = stats.contacts;
    state.counters["valid_regions"] = stats.valid_regions;
    state.counters["regions"] = stats.regions;
}

void BM_SelfCollision_Stage(benchmark::State& state) {
    FoldedCloth f(static_cast<uint32_t>(state.range(0)), true);
    const Vec3Soa x0 = f.x, v0 = f.v;
    for (auto _ : state) {
        // Each iteration starts from the same folded state (a copy of two
        // arrays, small next to the stage).
        f.x = x0;
        f.v = v0;
        f.collision->run_serially(f.x, f.v, f.mass.data(), f.pinned.data());
    }
    per_particle(state, f);
    state.counters["passes"] = f.collision->stats().passes;
}

BENCHMARK(BM_SelfCollision_BruteForce)->Arg(32)->Arg(64)->Arg(128)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_SelfCollision_HashOnly)->Arg(32)->Arg(64)->Arg(128)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_SelfCollision_HashRegions)->Arg(32)->Arg(64)->Arg(128)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_SelfCollision_Stage)->Arg(32)->Arg(64)->Arg(128)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace cloth
