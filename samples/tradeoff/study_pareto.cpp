// pareto: every solver setting on the fixed scenes, against a converged
// reference (Eigen CG at a tight tolerance with 1/960 s steps, same
// simulated time). Writes one CSV row per (scene, setting) and a markdown
// fragment: the Pareto front of error against cost per scene and, per cost
// budget, the most accurate setting that holds.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "run_scene.h"
#include "study.h"

namespace tradeoff {

using cloth_samples::SceneConfig;
using cloth_samples::SceneKind;

namespace {

struct Row {
    std::string scene;
    cloth_solver_kind kind;
    uint32_t iterations, substeps;
    float dt;
    RunResult run;
    double error;        // RMS position error at the end, m
    double ms_per_60hz;  // wall time per 1/60 s of simulated time, ms
    double x_jacobi;     // ms_per_60hz over one JACOBI k=1 frame of 1/60 s of the scene
    bool kind_front;     // on the Pareto front of its solver kind in its scene
    bool holds;          // finite, max strain < 10 %, no energy gain (wind: no late rise)
};

std::string setting_name(const Row& r) {
    char buffer[96];
    if (r.kind == CLOTH_SOLVER_CG || r.kind == CLOTH_SOLVER_DEFAULT) {
        std::snprintf(buffer, sizeof buffer, "%s, dt 1/%.0f", kind_name(r.kind), 1.0 / r.dt);
    } else {
        std::snprintf(buffer, sizeof buffer, "%s k=%u, %u substep%s, dt 1/%.0f", kind_name(r.kind),
                      r.iterations, r.substeps, r.substeps > 1 ? "s" : "", 1.0 / r.dt);
    }
    return buffer;
}

// Whether another finite setting of the same scene (and, if same_kind, the
// same solver kind) is at least as good in both error and cost and better in one.
bool dominated_by_any(const std::vector<Row>& rows, const Row& r, bool same_kind) {
    for (const Row& other : rows) {
        if (other.scene != r.scene || !std::isfinite(other.error) || &other == &r) continue;
        if (same_kind && other.kind != r.kind) continue;
        if (other.error <= r.error && other.ms_per_60hz <= r.ms_per_60hz &&
            (other.error < r.error || other.ms_per_60hz < r.ms_per_60hz)) {
            return true;
        }
    }
    return false;
}

}  // namespace

int run_pareto(const ParetoOptions& o) {
    std::FILE* csv = o.csv.empty() ? nullptr : std::fopen(o.csv.c_str(), "w");
    if (!o.csv.empty() && !csv) {
        std::fprintf(stderr, "cannot write %s\n", o.csv.c_str());
        return 1;
    }
    if (csv) {
        std::fprintf(csv,
                     "scene,solver,iterations,substeps,dt,ms_per_frame,ms_per_60hz,error_m,max_strain,"
                     "mean_strain,energy_gain,late_energy_rise,holds,x_jacobi_k1,kind_front\n");
    }
    std::vector<Row> rows;
    const float dts[] = {1.0f / 30.0f, 1.0f / 60.0f, 1.0f / 120.0f};
    for (SceneKind scene :
         {SceneKind::kHanging, SceneKind::kFallingFlat, SceneKind::kFlagInWind, SceneKind::kDrapedSphere}) {
        if (!o.scenes.empty() &&
            std::find(o.scenes.begin(), o.scenes.end(), cloth_samples::scene_name(scene)) == o.scenes.end()) {
            continue;
        }
        SceneConfig base;
        base.kind = scene;
        base.resolution = o.resolution;
        base.stiffness = o.stiffness;

        SceneConfig reference_config = base;
        reference_config.solver.kind = CLOTH_SOLVER_CG;
        reference_config.solver.cg_tolerance = 1e-7f;
        reference_config.solver.cg_max_iterations = 20000;
        const uint32_t reference_frames = static_cast<uint32_t>(std::lround(o.seconds * 960.0f));
        const RunResult reference = run_scene(reference_config, 1.0f / 960.0f, reference_frames);
        std::fprintf(stderr, "%s: reference %s, %.1f ms/frame\n", cloth_samples::scene_name(scene),
                     reference.ok ? "ok" : reference.error.c_str(), reference.ms_per_frame);

        std::vector<Row> settings;
        for (float dt : dts) {
            if (o.default_only) {
                if (dt == 1.0f / 60.0f) {
                    settings.push_back(Row{cloth_samples::scene_name(scene),
                                           CLOTH_SOLVER_DEFAULT,
                                           1,
                                           1,
                                           dt,
                                           {},
                                           0,
                                           0,
                                           0,
                                           false,
                                           false});
                }
                continue;
            }
            for (cloth_solver_kind kind : {CLOTH_SOLVER_JACOBI, CLOTH_SOLVER_CHEBYSHEV, CLOTH_SOLVER_PCG}) {
                for (uint32_t iterations : {1u, 2u, 4u, 8u, 16u}) {
                    for (uint32_t substeps = 1; substeps <= 4; ++substeps) {
                        settings.push_back(Row{cloth_samples::scene_name(scene),
                                               kind,
                                               iterations,
                                               substeps,
                                               dt,
                                               {},
                                               0,
                                               0,
                                               0,
                                               false,
                                               false});
                    }
                }
            }
            settings.push_back(
                Row{cloth_samples::scene_name(scene), CLOTH_SOLVER_CG, 1, 1, dt, {}, 0, 0, 0, false, false});
            settings.push_back(Row{
                cloth_samples::scene_name(scene), CLOTH_SOLVER_DEFAULT, 1, 1, dt, {}, 0, 0, 0, false, false});
        }
        const double unit = jacobi_k1_ms(base, 1.0f / 60.0f);
        for (Row& row : settings) {
            SceneConfig config = base;
            config.solver.kind = row.kind;
            config.solver.iterations = row.iterations;
            config.solver.substeps = row.substeps;
            const uint32_t frames = static_cast<uint32_t>(std::lround(o.seconds / row.dt));
            row.run = run_scene(config, row.dt, frames);
            row.run.energy_gain = row.run.ok ? row.run.energy_gain : INFINITY;
            row.error = row.run.ok ? rms_distance(row.run.positions, reference.positions) : INFINITY;
            row.ms_per_60hz = row.run.ms_per_frame * (1.0 / 60.0) / row.dt;
            row.x_jacobi = row.ms_per_60hz / unit;
            const bool wind = scene == SceneKind::kFlagInWind;
            row.holds = row.run.ok && row.run.max_strain < 0.1 &&
                        (wind ? row.run.late_energy_rise < 0.5 : row.run.energy_gain < 1e-2);
            rows.push_back(row);
        }
    }
    // Each kind's own front in its scene, for the plot's lines.
    for (Row& r : rows) {
        r.kind_front = std::isfinite(r.error) && !dominated_by_any(rows, r, true);
    }
    if (csv) {
        for (const Row& row : rows) {
            std::fprintf(csv, "%s,%s,%u,%u,%.6f,%.4f,%.4f,%.6g,%.5g,%.5g,%.5g,%.5g,%d,%.2f,%d\n",
                         row.scene.c_str(), kind_name(row.kind), row.iterations, row.substeps, double(row.dt),
                         row.run.ms_per_frame, row.ms_per_60hz, row.error, row.run.max_strain,
                         row.run.mean_strain, row.run.energy_gain, row.run.late_energy_rise,
                         row.holds ? 1 : 0, row.x_jacobi, row.kind_front ? 1 : 0);
        }
        std::fclose(csv);
    }

    // Markdown: the Pareto front per scene (finite settings no other setting
    // beats in both error and cost), with whether each holds.
    std::printf("### Pareto front at %ux%u, k = %g N/m, %.2f s simulated\n\n", o.resolution, o.resolution,
                double(o.stiffness), double(o.seconds));
    std::printf(
        "| scene | setting | ms per 1/60 s | x JACOBI k=1 | RMS error (mm) | max strain | energy gain (J) | "
        "holds "
        "|\n");
    std::printf("| --- | --- | ---: | ---: | ---: | ---: | ---: | --- |\n");
    std::vector<const Row*> front;
    for (const Row& r : rows) {
        if (std::isfinite(r.error) && !dominated_by_any(rows, r, false)) front.push_back(&r);
    }
    // Scenes stay in study order; within a scene, cheapest first.
    auto order = [&](const Row* r) {
        return std::find_if(rows.begin(), rows.end(), [&](const Row& x) { return x.scene == r->scene; }) -
               rows.begin();
    };
    std::stable_sort(front.begin(), front.end(), [&](const Row* a, const Row* b) {
        const auto oa = order(a), ob = order(b);
        return oa != ob ? oa < ob : a->ms_per_60hz < b->ms_per_60hz;
    });
    std::string last_scene;
    for (const Row* r : front) {
        std::printf("| %s | %s | %.3f | %.1f | %.3g | %.3f | %.3g | %s |\n",
                    r->scene == last_scene ? "" : r->scene.c_str(), setting_name(*r).c_str(), r->ms_per_60hz,
                    r->x_jacobi, 1e3 * r->error, r->run.max_strain, r->run.energy_gain,
                    r->holds ? "yes" : "no");
        last_scene = r->scene;
    }
    return 0;
}

}  // namespace tradeoff
