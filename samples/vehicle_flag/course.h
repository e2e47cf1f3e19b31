// The scripted driver of the sample's course: accelerate to 30 m/s, a
// slalom, a hard brake, a run at the kicker ramp and a jump, a landing, then
// one teleport back to the start and a short drive away. The driver reads the
// vehicle's state each frame and returns its controls; a lateral controller
// keeps the vehicle on the line x = 0 except where the slalom steers it off.
#pragma once

#include "vehicle_world.h"

namespace vehicle_flag {

enum class Phase { kAccelerate, kCruise, kSlalom, kBrake, kToRamp, kAirborne, kLanding, kRestart, kDone };

const char* phase_name(Phase phase);

struct Controls {
    float engine = 0.0f;    // N per driven wheel
    float brake = 0.0f;     // per wheel
    float steering = 0.0f;  // rad, front wheels
    bool teleport = false;  // move the vehicle back to its start pose before this frame's step
};

class CourseDriver {
  public:
    explicit CourseDriver(float ramp_start_z) : ramp_start_z_(ramp_start_z) {}

    // Controls for the frame at time `time` (s) given the vehicle's state
    // after the previous frame. Advances the phase as the course goes.
    Controls drive(float time, const VehicleWorld& vehicle);

    Phase phase() const { return phase_; }
    float phase_time(float time) const { return time - phase_start_; }
    bool done() const { return phase_ == Phase::kDone; }
    float top_speed() const { return top_speed_; }
    float longest_airtime() const { return longest_airtime_; }
    int teleports() const { return teleports_; }

  private:
    void enter(Phase phase, float time);

    float ramp_start_z_;
    Phase phase_ = Phase::kAccelerate;
    float phase_start_ = 0.0f;
    float top_speed_ = 0.0f;
    float longest_airtime_ = 0.0f;
    int teleports_ = 0;
};

}  // namespace vehicle_flag
