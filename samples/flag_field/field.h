// The field of flags beside the vehicle's course: flags of 48x32
// particles (1.2 x 0.8 m) on 3 m poles, at distances from 2 m to about
// 170 m from the course line and spread along it, in the cloth world of
// the vehicle's flag (one budget for all). Each flag's pole is a static
// capsule collider and its pole-side column is pinned; each has a
// gusting wind of its own. The classes (near, mid, far) are by distance
// from the course line; the budget decides by distance from the viewer
// (cloth_world_set_viewer, on the vehicle).
//
// The checks, on what a host reads back:
//  - max strain at most the bound, from cloth_get_stats (the state);
//  - no particle inside its pole (closer to the axis than the radius less
//    a tolerance), in the calls where the flag's state is what it reports;
//  - no jump at a change of update rate: in the first call at the new
//    rate no particle moves more than twice the most it moved in the two
//    calls before and the two after.
#pragma once

#include <cloth/cloth.h>

#include <array>
#include <string>
#include <vector>

#include "terrain.h"

namespace flag_field {

enum FlagClass { kNear, kMid, kFar, kClassCount };
const char* class_name(FlagClass c);

struct FieldFlag {
    cloth_id cloth{};
    FlagClass flag_class = kNear;
    float distance = 0;             // m from the course line
    double pole[3] = {};            // the pole's foot, Bullet's frame
    uint32_t rate = 1;              // the update rate in the last call
    std::vector<float> last;        // reported positions after the last call, Bullet's frame
    std::vector<float> moves;       // per call: the largest move of any particle
    std::vector<int> rate_changes;  // calls in which a new rate first showed
};

struct FieldChecks {
    float worst_strain = 0;
    long strain_frames = 0;  // flag-frames past the bound
    long inside_pole = 0;    // particle-frames inside a pole
    float deepest_in_pole = 0;
    long jumps = 0;              // rate changes with a jump
    long rate_changes = 0;       // rate changes seen
    float worst_jump_ratio = 0;  // move at a change over the most around it
};

class FlagField {
  public:
    static constexpr uint32_t kColumns = 48, kRows = 32;
    static constexpr float kPoleRadius = 0.04f, kPoleHeight = 3.0f;

    // `count` flags in `world` (whose origin is `origin` in Bullet's frame).
    bool create(cloth_world_id world, const double origin[3], const vehicle_flag::Terrain& terrain,
                uint32_t count, uint32_t max_update_rate, std::string* error);
    std::vector<FieldFlag>& flags() { return flags_; }
    const std::vector<uint32_t>& triangles() const { return triangles_; }

    // Gusts: a wind for each flag at `time`.
    void set_wind(float time);
    // After a call of cloth_step (`frame`: the world's count of calls);
    // `origin`: the cloth world's origin now. Updates each flag's rate,
    // reported positions and the checks.
    void observe(uint64_t frame, const double origin[3], float max_strain, float tolerance,
                 FieldChecks* checks);
    // After the run: the jump check over every change of rate.
    void check_jumps(FieldChecks* checks) const;

  private:
    std::vector<FieldFlag> flags_;
    std::vector<uint32_t> triangles_;
};

}  // namespace flag_field
