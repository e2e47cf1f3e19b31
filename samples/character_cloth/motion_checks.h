// Two checks of how the garments move with the character, made over the
// whole clip: their kinetic energy relative to the character (each
// particle's velocity less its skinned position's, so the body's own turn
// and travel count for nothing) never passes a multiple of its peak in the
// steady walk (no blow-up through the spin and the teleport), and the
// cape's hem trails behind the shoulders (against the character's facing)
// in most running frames.
#pragma once

#include <cloth/cloth.h>

#include <Eigen/Core>
#include <vector>

#include "skeleton.h"
#include "wardrobe.h"

namespace character_cloth {

class MotionChecks {
  public:
    // `dt`: the frame's length, s; `energy_factor`: the multiple of the
    // steady walk's peak allowed after the walk.
    MotionChecks(float dt, float energy_factor) : dt_(dt), energy_factor_(energy_factor) {}

    // The state at the end of a frame at `time` in `phase` (`teleported`:
    // the root jumped within it). False if the energy check failed.
    bool observe(const Pose& pose, Phase phase, float time, bool teleported, const Garment& cape,
                 const Garment& skirt);

    double walk_energy() const { return walk_energy_; }         // J, the steady walk's peak
    double worst_energy_ratio() const { return worst_ratio_; }  // after the walk, of walk_energy()
    int running_frames() const { return running_; }
    int hem_behind_frames() const { return hem_behind_; }
    // The hem trailed in at least `fraction` of the running frames.
    bool hem_trails(double fraction) const { return running_ > 0 && hem_behind_ >= fraction * running_; }

  private:
    // Kinetic energy of garment k relative to its skinned positions' motion
    // over the frame, J (0 on the first frame and across the teleport,
    // where the skin's motion is not known).
    double relative_energy(int k, const Garment& g, bool teleported);

    float dt_, energy_factor_;
    std::vector<float> last_skinned_[2];
    bool walked_ = false;
    float walk_start_ = -1.0f;
    double walk_energy_ = 0, worst_ratio_ = 0;
    int running_ = 0, hem_behind_ = 0;
};

}  // namespace character_cloth
