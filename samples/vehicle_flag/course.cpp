#include "course.h"

#include <algorithm>
#include <cmath>

namespace vehicle_flag {
namespace {

constexpr float kTopSpeed = 30.0f;      // m/s, the course's fastest stretch
constexpr float kRampSpeed = 21.0f;     // m/s at the kicker
constexpr float kMaxEngine = 2600.0f;   // N per driven wheel (two driven wheels, 800 kg: ~6.5 m/s^2)
constexpr float kHardBrake = 40.0f;     // per wheel, Bullet's per-step brake impulse limit
constexpr float kSlalomSeconds = 5.0f;  // two and a half periods...
constexpr float kSlalomPeriod = 2.0f;   // ...of a sinusoidal steer...
constexpr float kSlalomSteer = 0.045f;  // ...of this amplitude (rad)
constexpr float kPi = 3.14159265f;

// Engine force (and a light brake when too fast) to track a target speed.
void track_speed(float target, float speed, Controls* controls) {
    const float error = target - speed;
    controls->engine = std::clamp(900.0f * error, 0.0f, kMaxEngine);
    controls->brake = error < -1.0f ? 2.0f : 0.0f;
}

// Steer back towards the line x = 0, heading +z; gentler at speed.
float hold_line(const VehicleWorld& vehicle) {
    const btTransform pose = vehicle.chassis_pose();
    const float x = pose.getOrigin().x();
    const float heading_x = pose.getBasis().getColumn(2).x();
    const float speed = std::max(5.0f, std::fabs(vehicle.forward_speed()));
    return std::clamp(-(0.6f * x + 6.0f * heading_x) / speed, -0.3f, 0.3f);
}

}  // namespace

const char* phase_name(Phase phase) {
    switch (phase) {
        case Phase::kAccelerate:
            return "accelerate";
        case Phase::kCruise:
            return "cruise";
        case Phase::kSlalom:
            return "slalom";
        case Phase::kBrake:
            return "hard brake";
        case Phase::kToRamp:
            return "to ramp";
        case Phase::kAirborne:
            return "airborne";
        case Phase::kLanding:
            return "landing";
        case Phase::kRestart:
            return "after teleport";
        case Phase::kDone:
            return "done";
    }
    return "?";
}

void CourseDriver::enter(Phase phase, float time) {
    phase_ = phase;
    phase_start_ = time;
}

Controls CourseDriver::drive(float time, const VehicleWorld& vehicle) {
    const float speed = vehicle.forward_speed();
    const float z = vehicle.chassis_pose().getOrigin().z();
    top_speed_ = std::max(top_speed_, speed);
    const float t = phase_time(time);
    Controls c;
    c.steering = hold_line(vehicle);
    switch (phase_) {
        case Phase::kAccelerate:
            track_speed(kTopSpeed + 2.0f, speed, &c);
            if (speed >= kTopSpeed) enter(Phase::kCruise, time);
            break;
        case Phase::kCruise:
            track_speed(kTopSpeed, speed, &c);
            if (t >= 1.0f) enter(Phase::kSlalom, time);
            break;
        case Phase::kSlalom:
            track_speed(kTopSpeed, speed, &c);
            c.steering = kSlalomSteer * std::sin(2.0f * kPi * t / kSlalomPeriod);
            if (t >= kSlalomSeconds) enter(Phase::kBrake, time);
            break;
        case Phase::kBrake:
            c.brake = kHardBrake;
            if (speed < 0.5f) enter(Phase::kToRamp, time);
            break;
        case Phase::kToRamp:
            track_speed(kRampSpeed, speed, &c);
            if (z > ramp_start_z_ && vehicle.wheels_in_contact() == 0) enter(Phase::kAirborne, time);
            break;
        case Phase::kAirborne:
            c.steering = 0.0f;
            if (vehicle.wheels_in_contact() >= 2) {
                longest_airtime_ = std::max(longest_airtime_, t);
                enter(Phase::kLanding, time);
            }
            break;
        case Phase::kLanding:
            c.brake = t > 0.5f ? 0.5f * kHardBrake : 0.0f;
            if (t >= 2.5f) {
                c.teleport = true;
                ++teleports_;
                enter(Phase::kRestart, time);
            }
            break;
        case Phase::kRestart:
            track_speed(12.0f, speed, &c);
            if (t >= 2.5f) enter(Phase::kDone, time);
            break;
        case Phase::kDone:
            c.brake = kHardBrake;
            break;
    }
    return c;
}

}  // namespace vehicle_flag
