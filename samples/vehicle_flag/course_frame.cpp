#include "course_frame.h"

#include <cmath>

namespace vehicle_flag {

Controls drive_course_frame(float time, CourseDriver& driver, VehicleWorld& vehicle, FlagRig& flag,
                            const std::function<void()>& step_bullet, int* failed_calls) {
    const Controls controls = driver.drive(time, vehicle);
    if (controls.teleport) {
        vehicle.teleport(vehicle.start_pose());
        if (flag.teleport_chassis() != CLOTH_OK) ++*failed_calls;
    }
    vehicle.set_controls(controls.engine, controls.brake, controls.steering);
    step_bullet();
    // Gusty wind from ahead-left of the course.
    const float wind[3] = {3.0f + 1.5f * std::sin(0.8f * time), 0.0f,
                           -4.0f + 2.0f * std::sin(1.7f * time + 1.0f)};
    flag.set_wind(wind);
    if (flag.sync() != CLOTH_OK) ++*failed_calls;
    return controls;
}

}  // namespace vehicle_flag
