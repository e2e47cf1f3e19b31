#include "step_effort.h"

#include <cloth/cloth.h>

#include <algorithm>
#include <cstdio>

#include "timing_table.h"

namespace character_cloth {

using cloth_samples::percentile;

void StepEffort::observe(Phase phase, double step_ms) {
    for (int k = 0; k < 2; ++k) {
        cloth_stats stats{};
        stats.struct_size = sizeof stats;
        cloth_get_stats(garments_[k]->cloth, &stats);
        strain_passes_[k].push_back(stats.last_strain_passes);
        capped_frames_[k] += stats.last_strain_pass_cap_hit;
    }
    if (phase == Phase::kIdle) idle_ms_.push_back(step_ms);
    if (phase == Phase::kTeleported) still_ms_.push_back(step_ms);
}

void StepEffort::print(const std::vector<double>& step_ms, uint32_t free_particles, int frames) const {
    const double per_particle_us = 1e3 * percentile(step_ms, 0.5) / free_particles;
    std::printf(
        "cost per free particle: %.3f us a frame at p50 (Kim, Chentanez and Mueller 2012: a 1,500-vertex "
        "dress at 0.67 us a vertex on one 2012 core)\n",
        per_particle_us);
    for (int k = 0; k < 2; ++k) {
        std::printf(
            "strain passes of the %s: p50 %.0f, max %.0f a frame; stopped at their cap in %d frames (%.1f "
            "%%)\n",
            garments_[k]->name.c_str(), percentile(strain_passes_[k], 0.5),
            percentile(strain_passes_[k], 1.0), capped_frames_[k],
            100.0 * capped_frames_[k] / std::max(frames, 1));
    }
    if (!idle_ms_.empty() && !still_ms_.empty()) {
        std::printf(
            "standing still after the teleport: cloth step p50 %.3f ms, %.2fx the idle start's %.3f ms\n",
            percentile(still_ms_, 0.5), percentile(still_ms_, 0.5) / percentile(idle_ms_, 0.5),
            percentile(idle_ms_, 0.5));
    }
}

}  // namespace character_cloth
