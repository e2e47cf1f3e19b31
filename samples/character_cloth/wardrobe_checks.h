// character_cloth's checks on what the character wears, after every frame
// of the clip, and their report after the run: each garment's particles
// within their max distances of the skin, outside their backstops and out
// of the body, its stretch bounded; the particles' speed bounded; the cape
// and the skirt apart, and the cape's folds apart (contact_check.h); the
// kinetic energy relative to the skin bounded and the cape's hem trailing
// (motion_checks.h). Each is a named check of the run's verdict.
#pragma once

#include <cloth/cloth.h>

#include <string>
#include <vector>

#include "motion_checks.h"
#include "skeleton.h"
#include "verdict.h"
#include "wardrobe.h"

namespace character_cloth {

// The checks' bounds (the sample's --max-strain, --max-speed, ...).
struct CheckBounds {
    float max_strain = 0.12f;
    float max_speed = 40.0f;           // m/s
    float energy_margin_speed = 1.0f;  // m/s: the energy bound's margin, 1/2 M v^2 (motion_checks.h)
    float hem_trailing = 0.9f;         // fraction of running frames with the cape's hem behind
    float tolerance = 1e-3f;           // m: a particle this far inside the body or past a constraint
};

// What the checks found in one garment over the run.
struct GarmentChecks {
    float worst_max_distance = 0, worst_backstop = 0, deepest = 0, worst_strain = 0;
    float worst_skin_strain = 0;  // the skinned positions' own, by the same measure
    long past_max_distance = 0, inside_backstop = 0, inside_body = 0;
};

class WardrobeChecks {
  public:
    // The checks' names, in the order they are reported (--require).
    static std::vector<std::string> names();

    // Checks `cape` and `skirt` (which outlive it). `garment_contact` and
    // `cape_self_collision`: the thicknesses they were given (0: off),
    // which the contact checks ask half of; `dt`: the frame's length, s.
    WardrobeChecks(const CheckBounds& bounds, const Garment& cape, const Garment& skirt,
                   float garment_contact, float cape_self_collision, float dt);

    // The garments at the end of frame `frame` in `phase` (`teleported`:
    // the root jumped in it; `step_ok`: its cloth_step returned CLOTH_OK);
    // counts the cloth calls that failed in *failed_calls. Whether every
    // check held in it.
    bool observe(const Pose& pose, Phase phase, int frame, bool teleported, bool step_ok, int* failed_calls);
    int bad_frames() const { return bad_frames_; }

    // The progress table's head, and its line for the frame just observed:
    // each garment's worst stretch so far with its skin's beside it, and
    // this frame's speed and kinetic energy relative to the skin over its
    // bound.
    static void print_head();
    void print_frame(int frame, float time, Phase phase, bool ok) const;
    // "checks over N frames:" and the findings, a line or two per check;
    // `clip` names the worst energy frame's phase.
    void print(int frames, int failed_calls, const Clip& clip) const;
    // Each named check's verdict over the run.
    void set_verdicts(int failed_calls, cloth_samples::Verdict* verdict) const;

  private:
    CheckBounds bounds_;
    const Garment *cape_, *skirt_;
    float dt_;
    GarmentChecks garments_[2];
    MotionChecks motion_;
    float speed_ = 0, worst_speed_ = 0;  // this frame's, the run's
    int bad_frames_ = 0;
    // The cape and the skirt: the closest two of their particles, and the
    // frames they came within half the contact thickness (1 cm with it off).
    float garment_contact_, garment_gap_, closest_garments_;
    int garments_touching_ = 0;
    // The cape against itself: particles at least three self-collision
    // thicknesses apart at rest (beyond its rest neighbours) closer than
    // half of one (1 cm when the cape's self-collision is off).
    float cape_self_collision_, cape_thickness_, cape_gap_, closest_folds_;
    int cape_folds_touching_ = 0;
};

}  // namespace character_cloth
