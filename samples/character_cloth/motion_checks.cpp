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

bool MotionChecks::energies(int k, const Garment& g, bool teleported, double* relative, double* skin) {
    std::vector<float> v(3 * g.count), skinned(3 * g.count), normals(3 * g.count);
    if (cloth_read_velocities(g.cloth, v.data(), 3 * g.count) != CLOTH_OK ||
        cloth_read_skinned_positions(g.cloth, skinned.data(), normals.data(), 3 * g.count) != CLOTH_OK) {
        *relative = INFINITY;
        *skin = 0;
        return true;
    }
    std::vector<float>& last = last_skinned_[k];
    const bool known = !teleported && last.size() == skinned.size();
    double sum_relative = 0, sum_skin = 0;
    if (known) {
        for (uint32_t i = 0; i < g.count; ++i) {
            if (g.max_distance[i] <= 0.0f) continue;  // sewn on: moves with the skin
            for (uint32_t d = 3 * i; d < 3 * i + 3; ++d) {
                const double skin_velocity = (skinned[d] - last[d]) / dt_;
                const double difference = v[d] - skin_velocity;
                sum_relative += difference * difference;
                sum_skin += skin_velocity * skin_velocity;
            }
        }
    }
    last.swap(skinned);
    *relative = 0.5 * g.particle_mass * sum_relative;
    *skin = 0.5 * g.particle_mass * sum_skin;
    return known;
}

bool MotionChecks::observe(const Pose& pose, Phase phase, int frame, bool teleported, const Garment& cape,
                           const Garment& skirt) {
    double cape_relative = 0, cape_skin = 0, skirt_relative = 0, skirt_skin = 0;
    const bool cape_known = energies(0, cape, teleported, &cape_relative, &cape_skin);
    const bool skirt_known = energies(1, skirt, teleported, &skirt_relative, &skirt_skin);
    const double mass = cape.particle_mass * cape.count + skirt.particle_mass * skirt.count;
    margin_ = 0.5 * mass * margin_speed_ * margin_speed_;

    bool ok = true;
    if (cape_known && skirt_known) {
        // The last second of frames, this one included.
        const size_t window = static_cast<size_t>(std::lround(1.0 / dt_));
        skin_window_.push_back(cape_skin + skirt_skin);
        while (skin_window_.size() > window) skin_window_.pop_front();
        const double skin_peak = *std::max_element(skin_window_.begin(), skin_window_.end());
        energy_ = cape_relative + skirt_relative;
        bound_ = skin_peak + margin_;
        const double ratio = std::isfinite(energy_) ? energy_ / bound_ : INFINITY;
        if (worst_frame_ < 0 || ratio > worst_ratio_) {
            worst_ratio_ = ratio;
            worst_frame_ = frame;
            worst_energy_ = energy_;
            worst_bound_ = bound_;
            worst_skin_ = skin_peak;
        }
        ok = ratio <= 1.0;
        energy_failed_ += !ok;
    } else {
        energy_ = bound_ = 0;  // not measured in this frame
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
