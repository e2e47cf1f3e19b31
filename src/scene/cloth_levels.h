// The level of detail a scene cloth steps at: a far cloth steps a coarser
// copy of itself (fabric/fabric_levels.h: a quarter, a sixteenth, ... of
// its particles) instead of the full cloth, and still shows the full mesh.
//
// The full cloth (SceneCloth::cloth()) stays the cloth the host talks to:
// its settings, pins, positions and sleep are what every call reads and
// writes. At a level k > 0 the world steps the level's ClothInstance
// instead (made on first use, kept while the cloth lives), and around each
// of its frames:
// - before: the coarse cloth takes the full one's settings (material,
//   solver, air, sleep, collision), its masses and pins restricted; a
//   state the host set on the full cloth (positions, a snapshot) since the
//   last frame is restricted anew; a full cloth the host woke wakes it;
// - after: its positions and velocities prolonged make the full cloth's
//   state (pinned particles on their targets), so readers, the update
//   rate's interpolation, snapshots and normals see the full mesh; a
//   coarse cloth that fell asleep leaves the full one held asleep.
// A change of level goes through the full state: down, the state is
// restricted (positions by rest area, velocities by mass: momentum kept),
// and the detail the level cannot hold (the full positions less the
// prolongation of their restriction) fades out of the full state over
// kMorphFrames frames instead of vanishing at once (a geomorph); up, the
// full state already holds the prolongation.
//
// What a coarse cloth cannot follow (a skin, attachments or a carrier,
// self-collision, contact with another cloth) keeps a cloth at level 0: a
// change of level is refused while the cloth has one, and a cloth that
// gets one goes back to level 0 at its next frame.
#pragma once

#include <cstdint>
#include <memory>

#include "base/host_allocator.h"
#include "base/soa.h"
#include "fabric/fabric_levels.h"
#include "step/cloth_instance.h"

namespace cloth {

class ClothLevels {
  public:
    static constexpr uint32_t kMorphFrames = 8;

    explicit ClothLevels(const HostMemory* memory);

    // Levels of `full`'s fabric, the full one included (1 on meshes).
    static uint32_t level_count(const ClothInstance& full) {
        return 1 + static_cast<uint32_t>(full.fabric().levels.size());
    }
    // Why `full` cannot step at a coarse level now, or null.
    static const char* unsupported(const ClothInstance& full, bool in_cloth_pair);

    uint32_t level() const { return level_; }
    // level < level_count(full). A first use of a level allocates its cloth
    // (an allocation failure throws before anything changed).
    void set_level(ClothInstance& full, uint32_t level);
    // The cloth the world steps at this level; null at level 0.
    ClothInstance* stepped() const { return level_ > 0 ? coarse_[level_ - 1].get() : nullptr; }

    // Around a world frame of the stepped cloth (see above).
    void before_frame(ClothInstance& full, bool in_cloth_pair);
    void after_frame(ClothInstance& full);

    // Origin rebasing of the coarse cloths.
    bool can_shift_origin(const Vec3& shift) const;
    void shift_origin(const Vec3& shift, const ClothInstance& full);

  private:
    const FabricLevel& fabric_level(const ClothInstance& full) const {
        return *full.fabric().levels[level_ - 1];
    }
    // The full cloth's settings, masses and pins onto the coarse one.
    void take_settings(const ClothInstance& full, ClothInstance& coarse);
    void take_pins(const ClothInstance& full, ClothInstance& coarse, bool exact);
    // The full state restricted onto the coarse cloth.
    void take_state(const ClothInstance& full, ClothInstance& coarse);
    static uint64_t state_hash(const ClothInstance& cloth);

    const HostMemory* memory_;
    std::shared_ptr<ClothInstance> coarse_[kMaxFabricLevels];
    uint32_t level_ = 0;
    uint64_t full_state_ = 0;  // hash of the full state the last prolongation left
    // Scratch for the restriction of masses and pins, sized for the level.
    HostVector<float> node_mass_, node_pinned_;
    Vec3Soa node_target_;
    HostVector<uint32_t> changed_;
    // The detail fading out after a change of level down, and the frames left.
    Vec3Soa detail_;
    uint32_t morph_frames_ = 0;
};

}  // namespace cloth
