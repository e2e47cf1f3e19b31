// A scene cloth's level of detail (cloth_levels.h): the coarse cloths, and
// what moves between them and the full cloth around each frame.
#include "scene/cloth_levels.h"

#include <cmath>

#include "base/hash.h"

namespace cloth {
namespace {

// A coarse cloth follows its full cloth's pin targets once they move
// further than this (m): closer, it keeps its target and can fall asleep
// (a free particle's place in a pinned node's target moves by a trace
// each frame while the cloth settles).
constexpr float kTargetTolerance = 1e-4f;

bool same_material(const Material& a, const Material& b) {
    for (int k = 0; k < kSpringKindCount; ++k) {
        if (a.springs[k].stiffness != b.springs[k].stiffness || a.springs[k].damping != b.springs[k].damping)
            return false;
    }
    return a.area_density == b.area_density && a.particle_mass == b.particle_mass;
}

bool same_sleep(const SleepSettings& a, const SleepSettings& b) {
    return a.enabled == b.enabled && a.max_speed == b.max_speed && a.frames == b.frames;
}

}  // namespace

ClothLevels::ClothLevels(const HostMemory* memory)
    : memory_(memory),
      node_mass_(HostAllocator<float>(memory)),
      node_pinned_(HostAllocator<float>(memory)),
      node_target_(memory),
      changed_(HostAllocator<uint32_t>(memory)),
      detail_(memory) {}

const char* ClothLevels::unsupported(const ClothInstance& full, bool in_cloth_pair) {
    if (full.skin().active()) return "the cloth has a skin";
    if (full.contact().rides_bodies()) return "the cloth is attached to or carried by a body";
    if (full.self_collision()) return "the cloth collides with itself";
    if (in_cloth_pair) return "the cloth is in contact with another cloth";
    return nullptr;
}

void ClothLevels::set_level(ClothInstance& full, uint32_t level) {
    if (level == level_) return;
    if (level == 0) {
        level_ = 0;
        morph_frames_ = 0;
        // The full cloth's own record is from before it went down.
        if (!full.sleeping()) full.wake();
        return;
    }
    const FabricLevel& target = *full.fabric().levels[level - 1];
    const uint32_t nodes = target.node_count();
    // What may throw first: nothing has changed yet.
    std::shared_ptr<ClothInstance>& slot = coarse_[level - 1];
    if (!slot) {
        auto made =
            std::allocate_shared<ClothInstance>(HostAllocator<ClothInstance>(memory_), memory_, target.fabric,
                                                full.material(), full.solver(), full.aero());
        made->contact().bind(full.contact().world());
        slot = std::move(made);
    }
    if (node_mass_.size() < nodes) {
        HostVector<float> mass(nodes, 0.0f, HostAllocator<float>(memory_)),
            pinned(nodes, 0.0f, HostAllocator<float>(memory_));
        Vec3Soa pin_target(memory_);
        pin_target.resize(nodes);
        HostVector<uint32_t> changed{HostAllocator<uint32_t>(memory_)};
        changed.reserve(nodes);
        node_mass_.swap(mass);
        node_pinned_.swap(pinned);
        node_target_.swap_buffers(pin_target);
        changed_.swap(changed);
    }
    if (detail_.size() != full.particle_count()) {
        Vec3Soa detail(memory_);
        detail.resize(full.particle_count());
        detail_.swap_buffers(detail);
    }
    level_ = level;
    ClothInstance& coarse = *slot;
    take_settings(full, coarse);
    take_state(full, coarse);
    take_pins(full, coarse, true);
    // The detail the level loses: what its first frames fade out.
    prolong(target, coarse.positions(), detail_);
    const Vec3Soa& x = full.positions();
    for (uint32_t i = 0; i < full.particle_count(); ++i) detail_.set(i, x.get(i) - detail_.get(i));
    morph_frames_ = kMorphFrames;
    if (full.sleeping()) {
        coarse.hold_asleep();
    } else {
        coarse.wake();
    }
}

void ClothLevels::before_frame(ClothInstance& full, bool in_cloth_pair) {
    if (level_ == 0) return;
    if (unsupported(full, in_cloth_pair)) {
        set_level(full, 0);
        return;
    }
    ClothInstance& coarse = *stepped();
    if (!full.sleeping() && coarse.sleeping()) {
        coarse.wake();  // the host woke the full cloth
    } else if (full.sleeping() && !coarse.sleeping()) {
        coarse.hold_asleep();  // the host put it to sleep
    }
    if (coarse.sleeping()) return;
    if (state_hash(full) != full_state_) {  // the host set it: shown as it is, no fade
        take_state(full, coarse);
        morph_frames_ = 0;
    }
    take_settings(full, coarse);
    take_pins(full, coarse, false);
}

void ClothLevels::after_frame(ClothInstance& full) {
    if (level_ == 0) return;
    const ClothInstance& coarse = *stepped();
    const FabricLevel& level = fabric_level(full);
    Vec3Soa& x = full.level_positions();
    prolong(level, coarse.positions(), x);
    prolong(level, coarse.velocities(), full.level_velocities());
    if (morph_frames_ > 0) {
        const float weight = static_cast<float>(--morph_frames_) / static_cast<float>(kMorphFrames);
        for (uint32_t i = 0; i < full.particle_count(); ++i) {
            x.x[i] += weight * detail_.x[i];
            x.y[i] += weight * detail_.y[i];
            x.z[i] += weight * detail_.z[i];
        }
    }
    const PinSet& pins = full.pin_set();
    for (uint32_t i = 0; i < full.particle_count(); ++i) {
        if (pins.pinned[i] != 0.0f) x.set(i, pins.target.get(i));
    }
    full_state_ = state_hash(full);
    if (coarse.sleeping() && !full.sleeping()) full.hold_asleep();
}

void ClothLevels::take_settings(const ClothInstance& full, ClothInstance& coarse) {
    if (!same_material(full.material(), coarse.material())) coarse.set_material(full.material());
    restrict_masses(fabric_level(full), full.masses().data(), node_mass_.data());
    for (uint32_t node = 0; node < coarse.particle_count(); ++node) {
        if (coarse.masses()[node] != node_mass_[node]) coarse.set_mass(node, node_mass_[node]);
    }
    coarse.solver() = full.solver();  // as set_solver, which only adds a wake
    coarse.aero() = full.aero();
    if (!same_sleep(full.sleep(), coarse.sleep())) coarse.set_sleep(full.sleep());
    coarse.contact().collision() = full.contact().collision();
}

void ClothLevels::take_pins(const ClothInstance& full, ClothInstance& coarse, bool exact) {
    const PinSet& pins = full.pin_set();
    restrict_pins(fabric_level(full), pins.pinned.data(), pins.target, full.positions(), node_pinned_.data(),
                  node_target_);
    const uint32_t nodes = coarse.particle_count();
    for (float pinned : {1.0f, 0.0f}) {
        changed_.clear();
        for (uint32_t node = 0; node < nodes; ++node) {
            if (node_pinned_[node] == pinned && coarse.is_pinned(node) != (pinned != 0.0f))
                changed_.push_back(node);
        }
        if (!changed_.empty())
            coarse.set_pinned(changed_.data(), static_cast<uint32_t>(changed_.size()), pinned != 0.0f);
    }
    const Vec3Soa& target = coarse.pin_set().target;
    for (uint32_t node = 0; node < nodes; ++node) {
        if (node_pinned_[node] == 0.0f) continue;
        const Vec3 to = node_target_.get(node);
        const float off = (to - target.get(node)).squaredNorm();
        if (exact ? off > 0.0f : off > kTargetTolerance * kTargetTolerance) coarse.set_pin_target(node, to);
    }
}

void ClothLevels::take_state(const ClothInstance& full, ClothInstance& coarse) {
    const FabricLevel& level = fabric_level(full);
    restrict_positions(level, full.positions(), coarse.level_positions());
    restrict_velocities(level, full.masses().data(), full.velocities(), coarse.level_velocities());
}

uint64_t ClothLevels::state_hash(const ClothInstance& cloth) {
    uint64_t h = 0;
    for (const Vec3Soa* a : {&cloth.positions(), &cloth.velocities()}) {
        for (const HostVector<float>* c : {&a->x, &a->y, &a->z})
            h = hash_bytes(c->data(), c->size() * sizeof(float), h);
    }
    return h;
}

bool ClothLevels::can_shift_origin(const Vec3& shift) const {
    for (const auto& coarse : coarse_) {
        if (coarse && !coarse->can_shift_origin(shift)) return false;
    }
    return true;
}

void ClothLevels::shift_origin(const Vec3& shift, const ClothInstance& full) {
    for (const auto& coarse : coarse_) {
        if (coarse) coarse->shift_origin(shift);
    }
    // The full cloth moved with them: its state is still the prolongation.
    if (level_ > 0) full_state_ = state_hash(full);
}

}  // namespace cloth
