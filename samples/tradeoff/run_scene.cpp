#include "run_scene.h"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace tradeoff {

const char* kind_name(cloth_solver_kind kind) {
    switch (kind) {
        case CLOTH_SOLVER_DEFAULT:
            return "DEFAULT";
        case CLOTH_SOLVER_JACOBI:
            return "JACOBI";
        case CLOTH_SOLVER_CG:
            return "CG";
        case CLOTH_SOLVER_EXPLICIT:
            return "EXPLICIT";
        case CLOTH_SOLVER_PCG:
            return "PCG";
        case CLOTH_SOLVER_CHEBYSHEV:
            return "CHEBYSHEV";
        default:
            return "?";
    }
}

RunResult run_scene(const cloth_samples::SceneConfig& config, float dt, uint32_t frames) {
    RunResult out;
    cloth_samples::Scene scene(config);
    if (!scene.ok()) {
        out.ok = false;
        out.error = scene.error();
        return out;
    }
    // The study times the solver: a cloth at rest must not go to sleep and
    // report the cost of sleeping (a few microseconds) as its step.
    cloth_sleep_params awake = cloth_default_sleep_params();
    awake.enabled = false;
    for (cloth_id cloth : scene.cloths()) cloth_set_sleep(cloth, &awake);
    auto energy = [](const cloth_stats& s) { return s.kinetic_energy + s.gravity_energy + s.elastic_energy; };
    const double e0 = energy(scene.stats());
    double first_half_max = e0, second_half_max = -1e300, e = e0;
    std::vector<double> ms;
    ms.reserve(frames);
    for (uint32_t f = 0; f < frames; ++f) {
        const auto start = std::chrono::steady_clock::now();
        const cloth_result r = scene.step(dt);
        ms.push_back(
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
        if (r != CLOTH_OK && r != CLOTH_ERROR_SOLVER_FAILED) {
            out.ok = false;
            out.error = std::string(cloth_result_name(r)) + ": " + cloth_get_last_error();
            break;
        }
        const cloth_stats s = scene.stats();
        e = energy(s);
        if (!std::isfinite(e)) {
            out.ok = false;
            out.error = "non-finite energy";
            break;
        }
        out.max_strain = std::max(out.max_strain, static_cast<double>(s.max_strain));
        if (!config.mesh)
            out.max_abs_strain =
                std::max(out.max_abs_strain, grid_abs_strain(scene.positions(), config.resolution));
        out.mean_strain = std::max(out.mean_strain, static_cast<double>(s.mean_strain));
        out.energy_gain = std::max(out.energy_gain, e - e0);
        if (2 * f < frames) {
            first_half_max = std::max(first_half_max, e);
        } else {
            second_half_max = std::max(second_half_max, e);
        }
        ++out.frames;
    }
    out.energy_change = e - e0;
    out.late_energy_rise = second_half_max - first_half_max;
    if (!ms.empty()) {
        std::nth_element(ms.begin(), ms.begin() + ms.size() / 2, ms.end());
        out.ms_per_frame = ms[ms.size() / 2];
    }
    out.positions = scene.positions();
    if (!out.ok) out.max_strain = out.max_abs_strain = std::max(out.max_strain, 1e9);
    return out;
}

double jacobi_k1_ms(const cloth_samples::SceneConfig& config, float dt) {
    cloth_samples::SceneConfig jacobi = config;
    jacobi.solver = cloth_default_solver_settings();
    jacobi.solver.kind = CLOTH_SOLVER_JACOBI;
    jacobi.solver.iterations = 1;
    jacobi.solver.substeps = 1;
    jacobi.strain_limit = 0;
    constexpr uint32_t kFrames = 60;
    return run_scene(jacobi, dt, kFrames).ms_per_frame;
}

double grid_abs_strain(const std::vector<float>& x, uint32_t n) {
    const double rest = 1.0 / (n - 1);
    double worst = 0;
    const auto pair = [&](uint32_t a, uint32_t b) {
        const double dx = x[3 * b] - x[3 * a], dy = x[3 * b + 1] - x[3 * a + 1],
                     dz = x[3 * b + 2] - x[3 * a + 2];
        worst = std::max(worst, std::fabs(std::sqrt(dx * dx + dy * dy + dz * dz) - rest) / rest);
    };
    for (uint32_t p = 0; p < n * n; ++p) {
        if (p % n + 1 < n) pair(p, p + 1);
        if (p + n < n * n) pair(p, p + n);
    }
    return worst;
}

double rms_distance(const std::vector<float>& a, const std::vector<float>& b) {
    if (a.size() != b.size() || a.empty()) return INFINITY;
    double sum = 0;
    for (size_t i = 0; i < a.size(); i += 3) {
        double d2 = 0;
        for (int c = 0; c < 3; ++c) d2 += (static_cast<double>(a[i + c]) - b[i + c]) * (a[i + c] - b[i + c]);
        sum += d2;
    }
    return std::sqrt(sum / static_cast<double>(a.size() / 3));
}

}  // namespace tradeoff
