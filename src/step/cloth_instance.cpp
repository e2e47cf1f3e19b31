// A cloth's state and its setters, snapshots apart (cloth_snapshot.cpp):
// construction, material, pins, positions, self-collision, sleep, origin
// shifts, and putting back a failed frame's start. What a frame does is in
// frame_plan.cpp and cloth_stages.cpp.
#include "step/cloth_instance.h"

#include <algorithm>

#include "collide/self_collision.h"
#include "forces/spring_terms.h"

namespace cloth {

ClothInstance::ClothInstance(const HostMemory* memory, std::shared_ptr<const Fabric> fabric,
                             const Material& material, const SolverSettings& solver, const AeroParams& aero)
    : fabric_(std::move(fabric)),
      material_(material),
      solver_(solver),
      aero_(aero),
      x_(memory),
      v_(memory),
      mass_(HostAllocator<float>(memory)),
      pins_(memory),
      springs_(make_spring_terms(memory, fabric_, material)),
      system_(memory),
      strain_(memory),
      frame_(memory),
      contact_(memory),
      skin_(memory) {
    const Fabric& f = *fabric_;
    const uint32_t n = f.particle_count();
    for (Vec3Soa* a : {&x_, &v_, &system_.external_force, &system_.rhs, &system_.dv, &system_.dv_scratch,
                       &system_.normals}) {
        a->resize(n);
    }
    for (uint32_t i = 0; i < n; ++i) x_.set(i, f.rest_positions[i]);
    mean_structural_rest_length_ = mean_structural_rest_length(f);
    pins_.target = x_;
    mass_.resize(n);
    pins_.pinned.assign(n, 0.0f);
    pins_.list.reserve(n);
    pins_.by_skin.assign(n, 0);
    system_.triangle_force.resize(air_storage_size(f));
    system_.diagonal.resize(n);
    system_.diagonal_inverse.resize(n);
    system_.work.resize(n);
    group_count_ = (n + kGroupSize - 1) / kGroupSize;
    frame_.resize(n, group_count_);
    contact_.size_record(n);
    strain_.counts.assign(group_count_, StretchCount{});
    strain_.maybe_over.assign(n, 0);
    strain_.pull.assign(n, 0.0f);
    set_material(material);
    system_.multigrid.plan(f, *springs_);
    if (!f.grid_families.empty()) strain_.grid_terms.resize(f);
    strain_.tethers.resize(f);
}

void ClothInstance::set_material(const Material& material) {
    wake();
    // The masses follow the mass parameters only when those change (at
    // creation): new spring parameters keep masses the host set.
    const bool new_masses = material.particle_mass != material_.particle_mass ||
                            material.area_density != material_.area_density || !masses_set_;
    material_ = material;
    const Fabric& f = *fabric_;
    if (new_masses) {
        for (uint32_t i = 0; i < f.particle_count(); ++i) {
            mass_[i] =
                material.particle_mass > 0 ? material.particle_mass : material.area_density * f.rest_area[i];
        }
        masses_set_ = true;
    }
    springs_->set_material(material);
}

void ClothInstance::set_mass(uint32_t particle, float mass) {
    wake();
    mass_[particle] = mass;
}

void ClothInstance::set_pinned(const uint32_t* indices, uint32_t count, bool pinned, bool vertex_indices) {
    wake();
    for (uint32_t k = 0; k < count; ++k) {
        const uint32_t i = vertex_indices ? fabric_->particle(indices[k]) : indices[k];
        if (pinned) pins_.target.set(i, x_.get(i));
        pins_.pinned[i] = pinned ? 1.0f : 0.0f;
        if (!pinned) contact_.detach(i);
    }
    strain_.tethers_follow_pins = false;
    pins_.list.clear();  // keeps its capacity of one entry per particle
    for (uint32_t i = 0; i < particle_count(); ++i) {
        if (pins_.pinned[i] != 0.0f) pins_.list.push_back(i);
    }
}

void ClothInstance::set_position(uint32_t particle, const Vec3& x) {
    wake();
    contact_.forget_sleep();
    x_.set(particle, x);
    v_.set(particle, Vec3::Zero());
    pins_.target.set(particle, x);
}

void ClothInstance::set_self_collision(const SelfCollisionSettings* settings) {
    wake();
    if (!settings) {
        self_collision_.reset();
        return;
    }
    // The cloth's own allocator (the world's host memory), as for its other buffers.
    const HostMemory* memory = x_.x.get_allocator().memory();
    self_collision_ = std::allocate_shared<SelfCollision>(HostAllocator<SelfCollision>(memory), memory,
                                                          *fabric_, *settings);
}

const Vec3Soa& ClothInstance::normals(const Vec3Soa& positions) const {
    compute_vertex_normals(*fabric_, positions, 0, particle_count(), system_.normals);
    return system_.normals;
}

void ClothInstance::set_solver(const SolverSettings& settings) {
    solver_ = settings;
    wake();
}

// ---------------------------------------------------------------- sleep

void ClothInstance::set_sleep(const SleepSettings& settings) {
    sleep_.settings = settings;
    wake();
}

void ClothInstance::wake() {
    end_sleep();
    last_.quiet = false;
}

void ClothInstance::end_sleep() {
    if (sleep_.held) contact_.wake_up();
    sleep_.held = false;
    sleep_.sleeping = false;
    sleep_.rest_frames = 0;
}

void ClothInstance::hold_asleep() {
    sleep_.sleeping = sleep_.held = true;
    contact_.fall_asleep();
}

bool ClothInstance::can_shift_origin(const Vec3& shift) const {
    for (const Vec3Soa* a : {&x_, &pins_.target}) {
        for (size_t i = 0; i < a->size(); ++i) {
            if (!(a->get(i) - shift).allFinite()) return false;
        }
    }
    return true;
}

void ClothInstance::shift_origin(const Vec3& shift) {
    for (Vec3Soa* a : {&x_, &pins_.target}) {
        for (float& c : a->x) c -= shift.x();
        for (float& c : a->y) c -= shift.y();
        for (float& c : a->z) c -= shift.z();
    }
    skin_.shift_origin(shift);
}

void ClothInstance::bind_skin(uint32_t joint_count, uint32_t influences, const uint32_t* joints,
                              const float* weights) {
    skin_.bind(*fabric_, joint_count, influences, joints, weights);
    wake();
}

void ClothInstance::set_joint_matrices(const float* matrices, bool column_major_4x4) {
    skin_.set_joint_matrices(matrices, column_major_4x4);
    wake();
}

void ClothInstance::set_skinned(const float* positions, const float* normals) {
    skin_.set_skinned(*fabric_, positions, normals);
    wake();
}

void ClothInstance::set_max_distances(const float* distances) {
    const uint32_t n = particle_count();
    // Everything allocated before anything changes: an allocation failure changes nothing.
    HostVector<uint32_t> pins(HostAllocator<uint32_t>(fabric_->memory)), releases(pins.get_allocator());
    pins.reserve(n);
    releases.reserve(n);
    skin_.size_for(n);
    for (uint32_t i = 0; i < n; ++i) {
        const bool was_pin = skin_pins(i), pin = distances[i] == 0.0f;
        // A 0 is the pin's alone (PinSet::by_skin): the skin constrains no pinned particle.
        skin_.set_max_distance(i, pin ? kNoMaxDistance : distances[i]);
        pins_.by_skin[i] = pin ? 1 : 0;
        if (pin && !is_pinned(i)) pins.push_back(i);
        if (!pin && was_pin && is_pinned(i)) releases.push_back(i);
    }
    if (!pins.empty()) set_pinned(pins.data(), static_cast<uint32_t>(pins.size()), true);
    if (!releases.empty()) set_pinned(releases.data(), static_cast<uint32_t>(releases.size()), false);
    wake();
}

void ClothInstance::set_backstops(const float* distances, const float* radii) {
    const uint32_t n = particle_count();
    skin_.size_for(n);
    for (uint32_t i = 0; i < n; ++i) skin_.set_backstop(i, distances[i], radii[i]);
    wake();
}

float ClothInstance::moved_speed_squared() const {
    if (frame_.backup == FrameBackup::kFirstIntegration) return -1.0f;
    const float frame = frame_.h * static_cast<float>(frame_.decision.solver.substeps);
    if (!(frame > 0)) return -1.0f;
    float most = 0;
    for (uint32_t i = 0; i < particle_count(); ++i) {
        const float dx = x_.x[i] - frame_.backup_x.x[i], dy = x_.y[i] - frame_.backup_x.y[i],
                    dz = x_.z[i] - frame_.backup_x.z[i];
        most = std::max(most, dx * dx + dy * dy + dz * dz);
    }
    return most / (frame * frame);
}

void ClothInstance::update_sleep() {
    float speed_squared = 0;
    for (float s : frame_.group_speed_squared) speed_squared = std::max(speed_squared, s);
    const float max_squared = sleep_.settings.max_speed * sleep_.settings.max_speed;
    // A cloth held at its strain limit keeps velocities that do not move
    // it: each substep the limiter's projection turns its correction into
    // velocity (Provot), and against the theta step's x' = x + h (v + theta
    // dv), v' = v + dv, the particles it holds still end with
    // (1 - theta) dv. Such a cloth is at rest when no particle moved
    // farther than max_speed allows over the frame and no velocity is far
    // above it (kPhantomSpeed).
    constexpr float kPhantomSpeed = 10.0f;
    if (sleep_.settings.enabled && speed_squared > max_squared &&
        speed_squared <= kPhantomSpeed * kPhantomSpeed * max_squared) {
        const float moved = moved_speed_squared();
        if (moved >= 0) speed_squared = moved;
    }
    const bool at_rest = speed_squared <= max_squared && !contact_.follows_bodies();
    sleep_.rest_frames = at_rest ? sleep_.rest_frames + 1 : 0;
    if (sleep_.settings.enabled && sleep_.rest_frames >= sleep_.settings.frames) {
        // At rest: stop, and cost nothing until something changes.
        sleep_.sleeping = true;
        v_.fill(Vec3::Zero());
    }
}

void ClothInstance::restore_frame_start() {
    switch (frame_.backup) {
        case FrameBackup::kCopied:
            x_ = frame_.backup_x;
            v_ = frame_.backup_v;
            return;
        case FrameBackup::kSwapped:
            x_.swap_buffers(frame_.backup_x);
            v_.swap_buffers(frame_.backup_v);
            break;
        case FrameBackup::kFirstIntegration:
            break;
    }
    // Only pinned velocities changed before the first integration.
    for (uint32_t i : pins_.list) v_.set(i, frame_.pin_velocity_start.get(i));
}

}  // namespace cloth
