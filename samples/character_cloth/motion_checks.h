// Two checks of how the garments move with the character, made over the
// whole clip: the free particles' kinetic energy relative to the skin
// (each particle's velocity less its skinned position's, so the body's own
// turn and travel count for nothing) stays within a bound that follows the
// skin's own motion (no blow-up, no tearing, through the run, the spin and
// the teleport), and the cape's hem trails behind the shoulders (against
// the character's facing) in most running frames.
#pragma once

#include <cloth/cloth.h>

#include <Eigen/Core>
#include <deque>
#include <vector>

#include "skeleton.h"
#include "wardrobe.h"

namespace character_cloth {

class MotionChecks {
  public:
    // `dt`: the frame's length, s; `margin_speed`: the speed of the bound's
    // margin, m/s (see energy_bound).
    MotionChecks(float dt, float margin_speed) : dt_(dt), margin_speed_(margin_speed) {}

    // The state at the end of frame `frame` in `phase`
    // (`teleported`: the root jumped within it). False if the energy check
    // failed in it.
    bool observe(const Pose& pose, Phase phase, int frame, bool teleported, const Garment& cape,
                 const Garment& skirt);

    // The energy check, at every frame but the first and the teleport's
    // (where the skin's velocity is not known): the free particles'
    // kinetic energy relative to the skin, sum of 1/2 m |v - v_skin|^2,
    // at most the bound B = the largest kinetic energy of the skin's own
    // motion over the same particles (sum of 1/2 m |v_skin|^2) in the last
    // second of frames, this one included, plus 1/2 M margin_speed^2 with
    // M the garments' total mass: cloth that swings, flaps and lags as far
    // as the character moves passes; cloth that tears or blows up gains
    // more than its skin brings.
    double energy() const { return energy_; }  // J, this frame's relative energy
    double bound() const { return bound_; }    // J, this frame's bound
    double energy_ratio() const { return bound_ > 0.0 ? energy_ / bound_ : 0.0; }
    double worst_energy_ratio() const { return worst_ratio_; }   // of the clip, energy / bound
    int worst_energy_frame() const { return worst_frame_; }      // -1: no frame measured
    double worst_energy() const { return worst_energy_; }        // J, at that frame
    double worst_bound() const { return worst_bound_; }          // J, at that frame
    double worst_skin_energy() const { return worst_skin_; }     // J, the bound's skin part at that frame
    double margin_energy() const { return margin_; }             // J, the bound's margin
    int energy_failed_frames() const { return energy_failed_; }  // frames past the bound
    bool energy_holds() const { return worst_ratio_ <= 1.0; }

    int running_frames() const { return running_; }
    int hem_behind_frames() const { return hem_behind_; }
    // The hem trailed in at least `fraction` of the running frames.
    bool hem_trails(double fraction) const { return running_ > 0 && hem_behind_ >= fraction * running_; }

  private:
    // Garment k's free particles' kinetic energy relative to their skinned
    // positions' motion over the frame, and that motion's own, J; false on
    // the first frame and across the teleport, where the skin's motion is
    // not known (infinite energy if the cloth cannot be read).
    bool energies(int k, const Garment& g, bool teleported, double* relative, double* skin);

    float dt_, margin_speed_;
    std::vector<float> last_skinned_[2];
    std::deque<double> skin_window_;  // the skin's energy in the last second's measured frames
    double energy_ = 0, bound_ = 0, margin_ = 0;
    double worst_ratio_ = 0, worst_energy_ = 0, worst_bound_ = 0, worst_skin_ = 0;
    int worst_frame_ = -1, energy_failed_ = 0;
    int running_ = 0, hem_behind_ = 0;
};

}  // namespace character_cloth
