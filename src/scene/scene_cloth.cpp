#include "scene/scene_cloth.h"

namespace cloth {

SceneCloth::SceneCloth(const HostMemory* memory, std::shared_ptr<const Fabric> fabric,
                       const Material& material, const SolverSettings& solver, const AeroParams& aero)
    : cloth_(memory, std::move(fabric), material, solver, aero),
      previous_x_(memory),
      reported_x_(memory),
      levels_(memory) {}

void SceneCloth::set_update_rate(uint32_t rate, uint32_t phase) {
    if (rate > 1) size_interpolation();
    rate_.set(rate, phase);
    if (rate == 1 && rate_.fraction(world_frame_) == 1.0f && !rates_by_budget()) free_interpolation();
}

bool SceneCloth::rates_by_budget() const {
    return quality_.policy().enabled && quality_.policy().max_update_rate > 1;
}

void SceneCloth::size_interpolation() {
    const uint32_t n = cloth_.particle_count();
    if (previous_x_.size() == n) return;
    const HostMemory* memory = previous_x_.x.get_allocator().memory();
    Vec3Soa previous(memory), reported(memory);
    previous.resize(n);
    reported.resize(n);
    previous = cloth_.positions();
    previous_x_.swap_buffers(previous);
    reported_x_.swap_buffers(reported);
}

void SceneCloth::free_interpolation() {
    const HostMemory* memory = previous_x_.x.get_allocator().memory();
    Vec3Soa previous(memory), reported(memory);
    previous_x_.swap_buffers(previous);
    reported_x_.swap_buffers(reported);
}

uint32_t SceneCloth::begin_rate_step(uint64_t frame) {
    const uint32_t frames = rate_.begin_step(frame);
    // A one-frame step ends at the world's frame: nothing to interpolate,
    // and back at rate 1 the copies are not needed again.
    if (frames > 1) {
        previous_x_ = cloth_.positions();
    } else if (rate_.rate() == 1 && previous_x_.size() > 0 && !rates_by_budget()) {
        free_interpolation();
    }
    return frames;
}

const Vec3Soa& SceneCloth::reported_positions() const {
    const Vec3Soa& x = cloth_.positions();
    const float t = rate_.fraction(world_frame_);
    if (t == 1.0f || previous_x_.size() != x.size()) return x;
    for (uint32_t i = 0; i < cloth_.particle_count(); ++i) {
        reported_x_.x[i] = previous_x_.x[i] + t * (x.x[i] - previous_x_.x[i]);
        reported_x_.y[i] = previous_x_.y[i] + t * (x.y[i] - previous_x_.y[i]);
        reported_x_.z[i] = previous_x_.z[i] + t * (x.z[i] - previous_x_.z[i]);
    }
    return reported_x_;
}

void SceneCloth::set_quality_policy(const QualityPolicy& policy) {
    const bool rate_was_cut = quality_.rate_cut();
    if (policy.enabled && policy.max_update_rate > 1) size_interpolation();
    quality_.set_policy(policy);
    if (rate_was_cut) set_update_rate(1, 0);
    cloth_.wake();
}

void SceneCloth::set_solver(const SolverSettings& settings) {
    cloth_.set_solver(settings);
    quality_.host_set_solver();
}

void SceneCloth::set_strain_limit(const StrainLimit& limit) {
    SolverSettings settings = cloth_.solver();
    settings.strain_limit = limit;
    cloth_.set_solver(settings);
    quality_.costs().clear();
}

bool SceneCloth::can_shift_origin(const Vec3& shift) const {
    for (size_t i = 0; i < previous_x_.size(); ++i) {
        if (!(previous_x_.get(i) - shift).allFinite()) return false;
    }
    return cloth_.can_shift_origin(shift) && levels_.can_shift_origin(shift);
}

void SceneCloth::shift_origin(const Vec3& shift) {
    for (float& c : previous_x_.x) c -= shift.x();
    for (float& c : previous_x_.y) c -= shift.y();
    for (float& c : previous_x_.z) c -= shift.z();
    cloth_.shift_origin(shift);
    levels_.shift_origin(shift, cloth_);
}

}  // namespace cloth
