#include "motion_checks.h"

#include <algorithm>
#include <cmath>

namespace character_cloth {

namespace {

// The mean position of the given particles.
Eigen::Vector3f mean_of(const std::vector<float>& x, const std::vector<uint32_t>& particles) {
    Eigen::Vector3f sum = Eigen::Vector3f::Zero();
    for (uint32_t i : particles) sum += Eigen::Vector3f(x[3 * i], x[3 * i + 1], x[3 * i + 2]);
    return sum / static_cast<float>(std::max<size_t>(particles.size(), 1));
}

}  // namespace

double MotionChecks::relative_energy(int k, const Garment& g, bool teleported) {
    std::vector<float> v(3 * g.count), skinned(3 * g.count), normals(3 * g.count);
    if (cloth_read_velocities(g.cloth, v.data(), 3 * g.count) != CLOTH_OK ||
        cloth_read_skinned_positions(g.cloth, skinned.data(), normals.data(), 3 * g.count) != CLOTH_OK)
        return INFINITY;
    std::vector<float>& last = last_skinned_[k];
    double sum = 0;
    if (!teleported && last.size() == skinned.size()) {
        for (uint32_t i = 0; i < 3 * g.count; ++i) {
            const double relative = v[i] - (skinned[i] - last[i]) / dt_;
            sum += relative * relative;
        }
    }
    last.swap(skinned);
    return 0.5 * g.particle_mass * sum;
}

bool MotionChecks::observe(const Pose& pose, Phase phase, float time, bool teleported, const Garment& cape,
                           const Garment& skirt) {
    const double energy = relative_energy(0, cape, teleported) + relative_energy(1, skirt, teleported);

    // The steady walk: its frames after its first second.
    bool ok = true;
    if (phase == Phase::kWalk) {
        if (walk_start_ < 0.0f) walk_start_ = time;
        if (time >= walk_start_ + 1.0f) walk_energy_ = std::max(walk_energy_, energy), walked_ = true;
    } else if (walked_ && phase != Phase::kIdle) {
        const double ratio = walk_energy_ > 0.0 ? energy / walk_energy_ : INFINITY;
        worst_ratio_ = std::max(worst_ratio_, ratio);
        ok = ratio <= energy_factor_;
    }

    // The hem behind the shoulders while running: against the facing.
    if (phase == Phase::kRun && !cape.hem.empty()) {
        std::vector<float> x(3 * cape.count);
        if (cloth_read_positions(cape.cloth, x.data(), 3 * cape.count) == CLOTH_OK) {
            Eigen::Vector3f facing = pose.world[kPelvis].linear() * Eigen::Vector3f::UnitZ();
            facing.y() = 0.0f;
            const Eigen::Vector3f trail = mean_of(x, cape.hem) - mean_of(x, cape.top);
            ++running_;
            hem_behind_ += trail.dot(facing) < 0.0f;
        }
    }
    return ok;
}

}  // namespace character_cloth
