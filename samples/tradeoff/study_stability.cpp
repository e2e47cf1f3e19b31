// stability: where each solver kind stays stable, over spring stiffness,
// step, particle mass and resolution, on the falling-flat scene (the
// hardest of the standard scenes: large motion, pinned at two corners).
// Each cell runs for 0.5 s of simulated time (20..200 frames) and is
//   3 holds      finite, no energy gain, max strain < 10 %
//   2 stretches  finite, no energy gain, max strain >= 10 %
//   1 gains      finite but gains energy (more than 1 % of m g over 1 m)
//   0 blows up   non-finite (the library restores the state and reports it)
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "run_scene.h"
#include "study.h"

namespace tradeoff {

using cloth_samples::SceneConfig;
using cloth_samples::SceneKind;

int classify(const RunResult& r, double total_mass) {
    if (!r.ok) return 0;
    if (r.energy_gain > 1e-2 * total_mass * 9.81) return 1;
    return r.max_strain < 0.1 ? 3 : 2;
}

int run_stability(const StabilityOptions& o) {
    std::FILE* csv = o.csv.empty() ? nullptr : std::fopen(o.csv.c_str(), "w");
    if (!o.csv.empty() && !csv) {
        std::fprintf(stderr, "cannot write %s\n", o.csv.c_str());
        return 1;
    }
    if (csv)
        std::fprintf(
            csv,
            "solver,iterations,resolution,stiffness,dt,particle_mass,gamma,max_strain,energy_gain,class\n");
    struct Kind {
        cloth_solver_kind kind;
        uint32_t iterations;
    };
    const Kind kinds[] = {{CLOTH_SOLVER_EXPLICIT, 1},
                          {CLOTH_SOLVER_JACOBI, 1},
                          {CLOTH_SOLVER_CHEBYSHEV, 16},
                          {CLOTH_SOLVER_PCG, 16},
                          {CLOTH_SOLVER_DEFAULT, 1}};
    const float stiffnesses[] = {1e1f, 1e2f, 1e3f, 1e4f, 1e5f, 1e6f, 1e7f};
    const float steps[] = {1.0f / 1000.0f, 1.0f / 300.0f, 1.0f / 100.0f, 1.0f / 30.0f, 1.0f / 10.0f};
    const float masses[] = {1e-4f, 1e-2f, 1.0f};
    const uint32_t resolutions[] = {16, 32};
    for (const Kind& kind : kinds) {
        uint32_t counts[4] = {};
        for (uint32_t n : resolutions) {
            for (float mass : masses) {
                for (float k : stiffnesses) {
                    for (float dt : steps) {
                        SceneConfig config;
                        config.kind = SceneKind::kFallingFlat;
                        config.resolution = n;
                        config.total_mass = mass * float(n * n);
                        config.stiffness = k;
                        config.solver.kind = kind.kind;
                        config.solver.iterations = kind.iterations;
                        const uint32_t frames =
                            std::clamp<uint32_t>(static_cast<uint32_t>(std::lround(0.5f / dt)), 20, o.frames);
                        const RunResult r = run_scene(config, dt, frames);
                        const int c = classify(r, config.total_mass);
                        ++counts[c];
                        if (csv) {
                            std::fprintf(csv, "%s,%u,%u,%g,%g,%g,%.4g,%.4g,%.4g,%d\n", kind_name(kind.kind),
                                         kind.iterations, n, double(k), double(dt), double(mass),
                                         double(dt) * dt * k / mass, r.max_strain, r.energy_gain, c);
                            std::fflush(csv);
                        }
                    }
                }
            }
        }
        std::printf("%-10s k=%-2u holds %3u  stretches %3u  gains %3u  blows up %3u\n", kind_name(kind.kind),
                    kind.iterations, counts[3], counts[2], counts[1], counts[0]);
        std::fflush(stdout);
    }
    if (csv) std::fclose(csv);
    return 0;
}

}  // namespace tradeoff
