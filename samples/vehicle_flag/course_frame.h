// A frame of the course up to the cloth step, as vehicle_flag and
// flag_field drive it: the driver's controls (its teleport passed on to
// the flag's chassis body), the Bullet step, the course's gusty wind on
// the vehicle's flag and the chassis body synced into the cloth world.
#pragma once

#include <functional>

#include "course.h"
#include "flag_rig.h"

namespace vehicle_flag {

// The frame at `time` (s): step_bullet() steps the vehicle's world (timed
// by the caller, if it likes). Counts the cloth calls that failed in
// *failed_calls; returns the driver's controls.
Controls drive_course_frame(float time, CourseDriver& driver, VehicleWorld& vehicle, FlagRig& flag,
                            const std::function<void()>& step_bullet, int* failed_calls);

}  // namespace vehicle_flag
