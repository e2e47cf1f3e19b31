#include "wardrobe_checks.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "body.h"
#include "contact_check.h"

namespace character_cloth {
namespace {

// The largest stretch of the pairs (the triangles' edges) at positions
// `x`, max of |a - b| / rest - 1 (0 when none is stretched), the measure
// the stretch check applies to the garment and the line beside it to the
// skin; infinite when a position is not finite.
float max_stretch(const std::vector<float>& x, const std::vector<std::pair<uint32_t, uint32_t>>& pairs,
                  const std::vector<float>& rest_length) {
    float stretch = 0;
    for (size_t k = 0; k < pairs.size(); ++k) {
        const Eigen::Vector3f a(&x[3 * pairs[k].first]), b(&x[3 * pairs[k].second]);
        const float s = (a - b).norm() / rest_length[k] - 1.0f;
        if (!std::isfinite(s)) return INFINITY;
        stretch = std::max(stretch, s);
    }
    return stretch;
}

// Checks one garment at the end of a frame; returns whether every check
// held (false, counted in `failed_calls`, if it cannot be read).
bool check_garment(const Garment& g, const Pose& pose, const CheckBounds& o, GarmentChecks* c,
                   int* failed_calls) {
    std::vector<float> x(3 * g.count), s(3 * g.count), n(3 * g.count);
    if (cloth_read_positions(g.cloth, x.data(), 3 * g.count) != CLOTH_OK ||
        cloth_read_skinned_positions(g.cloth, s.data(), n.data(), 3 * g.count) != CLOTH_OK) {
        ++*failed_calls;
        return false;
    }
    c->worst_skin_strain = std::max(c->worst_skin_strain, max_stretch(s, g.structural, g.rest_length));
    const float stretch =
        max_stretch(x, g.structural, g.rest_length);  // this frame's; infinite if not finite
    c->worst_strain = std::max(c->worst_strain, stretch);
    if (!std::isfinite(stretch)) return false;
    bool ok = true;
    for (uint32_t i = 0; i < g.count; ++i) {
        const Eigen::Vector3f p(&x[3 * i]), skinned(&s[3 * i]), normal(&n[3 * i]);
        const float past = (p - skinned).norm() - g.max_distance[i];
        c->worst_max_distance = std::max(c->worst_max_distance, past);
        if (past > o.tolerance) ++c->past_max_distance, ok = false;
        if (g.back_radius[i] > 0.0f) {
            const float inside = g.back_radius[i] - (p - (skinned - g.back_distance[i] * normal)).norm();
            c->worst_backstop = std::max(c->worst_backstop, inside);
            if (inside > o.tolerance) ++c->inside_backstop, ok = false;
        }
        if (g.max_distance[i] > 0.0f) {
            const float depth = -CharacterBody::distance(pose, &x[3 * i], g.collider_mask);
            c->deepest = std::max(c->deepest, depth);
            if (depth > o.tolerance) ++c->inside_body, ok = false;
        }
    }
    return ok && stretch <= o.max_strain;
}

std::vector<float> positions(const Garment& g) {
    std::vector<float> x(3 * g.count);
    cloth_read_positions(g.cloth, x.data(), 3 * g.count);
    return x;
}

}  // namespace

std::vector<std::string> WardrobeChecks::names() {
    return {"calls", "max_distance",    "backstop",   "body",   "stretch",
            "speed", "garment_contact", "cape_folds", "energy", "hem_trailing"};
}

WardrobeChecks::WardrobeChecks(const CheckBounds& bounds, const Garment& cape, const Garment& skirt,
                               float garment_contact, float cape_self_collision, float dt)
    : bounds_(bounds),
      cape_(&cape),
      skirt_(&skirt),
      dt_(dt),
      motion_(dt, bounds.energy_margin_speed),
      garment_contact_(garment_contact),
      garment_gap_(0.5f * (garment_contact > 0.0f ? garment_contact : 0.02f)),
      closest_garments_(INFINITY),
      cape_self_collision_(cape_self_collision),
      cape_thickness_(cape_self_collision > 0.0f ? cape_self_collision : 0.01f),
      cape_gap_(0.5f * cape_thickness_),
      closest_folds_(INFINITY) {}

bool WardrobeChecks::observe(const Pose& pose, Phase phase, int frame, bool teleported, bool step_ok,
                             int* failed_calls) {
    const Garment &cape = *cape_, &skirt = *skirt_;
    const Garment* garments[] = {cape_, skirt_};
    bool ok = step_ok;
    speed_ = 0.0f;
    for (int k = 0; k < 2; ++k) {
        ok = check_garment(*garments[k], pose, bounds_, &garments_[k], failed_calls) && ok;
        cloth_stats stats{};
        stats.struct_size = sizeof stats;
        cloth_get_stats(garments[k]->cloth, &stats);
        speed_ = std::max(speed_, std::isfinite(stats.max_speed) ? stats.max_speed : INFINITY);
    }
    worst_speed_ = std::max(worst_speed_, speed_);
    const float gap = closest_between(positions(cape), positions(skirt), 4.0f * garment_gap_);
    closest_garments_ = std::min(closest_garments_, gap);
    if (gap < garment_gap_) ++garments_touching_, ok = false;
    const float fold = closest_within(positions(cape), cape.rest, 3.0f * cape_thickness_, 4.0f * cape_gap_);
    closest_folds_ = std::min(closest_folds_, fold);
    if (fold < cape_gap_) ++cape_folds_touching_, ok = false;
    ok = motion_.observe(pose, phase, frame, teleported, cape, skirt) && ok;
    ok = ok && speed_ <= bounds_.max_speed;
    bad_frames_ += !ok;
    return ok;
}

void WardrobeChecks::print_head() {
    std::printf("%6s %7s %-11s %10s %10s %10s %10s %9s %8s\n", "frame", "time_s", "phase", "cape_str",
                "cape_skin", "skirt_str", "skirt_skin", "max_speed", "energy");
}

void WardrobeChecks::print_frame(int frame, float time, Phase phase, bool ok) const {
    std::printf("%6d %7.2f %-11s %10.3f %10.3f %10.3f %10.3f %9.2f %8.3f%s\n", frame, time, phase_name(phase),
                garments_[0].worst_strain, garments_[0].worst_skin_strain, garments_[1].worst_strain,
                garments_[1].worst_skin_strain, speed_, motion_.energy_ratio(), ok ? "" : "  CHECK FAILED");
}

void WardrobeChecks::print(int frames, int failed_calls, const Clip& clip) const {
    std::printf("\nchecks over %d frames:\n", frames);
    const Garment* garments[] = {cape_, skirt_};
    for (int k = 0; k < 2; ++k) {
        const GarmentChecks& c = garments_[k];
        std::printf(
            "  %-5s: past its max distance %ld (worst %.2g m), inside its backstop %ld (worst %.2g m), "
            "inside "
            "the body %ld (deepest %.2g m), max stretch %.3f (limit %.3g; its skin's own %.3f)\n",
            garments[k]->name.c_str(), c.past_max_distance, c.worst_max_distance, c.inside_backstop,
            c.worst_backstop, c.inside_body, c.deepest, c.worst_strain, bounds_.max_strain,
            c.worst_skin_strain);
    }
    std::printf(
        "  the cape and the skirt closer than %.3g m in %d frames (closest %.3g m; contact thickness %.3g "
        "m)\n",
        garment_gap_, garments_touching_, closest_garments_, garment_contact_);
    std::printf(
        "  the cape with itself (particles %.3g m apart at rest or more) closer than %.3g m in %d frames "
        "(closest %.3g m; self-collision thickness %.3g m)\n",
        3.0f * cape_thickness_, cape_gap_, cape_folds_touching_, closest_folds_, cape_self_collision_);
    std::printf(
        "  max speed %.2f m/s (limit %.3g); cloth calls that failed: %d; frames failing a check: %d\n",
        worst_speed_, bounds_.max_speed, failed_calls, bad_frames_);
    const int worst_energy_frame = motion_.worst_energy_frame();
    std::printf(
        "  kinetic energy relative to the skin: at most %.3f of its bound (limit 1; past it in %d frames), "
        "in frame %d (%.2f s, %s): %.3g J against %.3g J (the skin's own peak over the last second %.3g J + "
        "1/2 M (%.3g m/s)^2 %.3g J)\n",
        motion_.worst_energy_ratio(), motion_.energy_failed_frames(), worst_energy_frame,
        worst_energy_frame * dt_,
        worst_energy_frame >= 0 ? phase_name(clip.phase(worst_energy_frame * dt_)) : "none",
        motion_.worst_energy(), motion_.worst_bound(), motion_.worst_skin_energy(),
        bounds_.energy_margin_speed, motion_.margin_energy());
    std::printf(
        "  the cape's hem behind the shoulders in %d of %d running frames (%.1f %%, at least %.0f %% "
        "asked)%s\n",
        motion_.hem_behind_frames(), motion_.running_frames(),
        100.0 * motion_.hem_behind_frames() / std::max(motion_.running_frames(), 1),
        100.0 * bounds_.hem_trailing, motion_.hem_trails(bounds_.hem_trailing) ? "" : "  CHECK FAILED");
}

void WardrobeChecks::set_verdicts(int failed_calls, cloth_samples::Verdict* verdict) const {
    const GarmentChecks &cape = garments_[0], &skirt = garments_[1];
    verdict->set("calls", failed_calls == 0);
    verdict->set("max_distance", cape.past_max_distance == 0 && skirt.past_max_distance == 0);
    verdict->set("backstop", cape.inside_backstop == 0 && skirt.inside_backstop == 0);
    verdict->set("body", cape.inside_body == 0 && skirt.inside_body == 0);
    verdict->set("stretch",
                 cape.worst_strain <= bounds_.max_strain && skirt.worst_strain <= bounds_.max_strain);
    verdict->set("speed", worst_speed_ <= bounds_.max_speed);
    verdict->set("garment_contact", garments_touching_ == 0);
    verdict->set("cape_folds", cape_folds_touching_ == 0);
    verdict->set("energy", motion_.energy_holds());
    verdict->set("hem_trailing", motion_.hem_trails(bounds_.hem_trailing));
}

}  // namespace character_cloth
