#include "flag_checks.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace vehicle_flag {

FlagChecks::FlagChecks(const CheckBounds& bounds, const FlagRig& flag, uint32_t columns, uint32_t rows)
    : bounds_(bounds), columns_(columns), rows_(rows), skip_(flag.particle_count(), false) {
    for (uint32_t index : flag.attached()) skip_[index] = true;
}

FrameCheck FlagChecks::observe(FlagRig& flag, const VehicleWorld& vehicle, const Terrain& terrain,
                               Phase phase, bool course_teleported) {
    FrameCheck f;
    f.attach = static_cast<float>(flag.attachment_error(vehicle.chassis_pose()));
    const Penetrations p = count_penetrations(flag.positions(), skip_, vehicle.chassis_pose(),
                                              vehicle.layout(), terrain, bounds_.tolerance);
    const int through_pole = count_springs_through_pole(flag.positions(), columns_, rows_,
                                                        vehicle.chassis_pose(), vehicle.layout());
    springs_through_pole_ += through_pole;
    f.stats.struct_size = sizeof f.stats;
    cloth_get_stats(flag.cloth(), &f.stats);
    const bool finite = std::isfinite(f.stats.max_strain) && std::isfinite(f.stats.max_speed);
    // The carrier must see the course's teleport, and nothing else, as one.
    const bool teleported = flag.teleported();
    carrier_teleports_ += teleported;
    const bool teleport_wrong = teleported != course_teleported;
    missed_teleports_ += teleport_wrong;
    f.bad = !finite || f.attach > bounds_.max_attach_error || p.total() > 0 || through_pole > 0 ||
            f.stats.max_strain > bounds_.max_strain || f.stats.max_speed > bounds_.max_speed ||
            teleport_wrong;
    bad_frames_ += f.bad;
    penetrations_.add(p);
    const bool on_the_straight = phase == Phase::kAccelerate || phase == Phase::kCruise ||
                                 phase == Phase::kSlalom || phase == Phase::kToRamp;
    if (on_the_straight && std::abs(vehicle.forward_speed()) > bounds_.trail_speed) {
        trailing_.add(trailing_angle_degrees(flag.positions(), columns_, rows_, vehicle.chassis_velocity()),
                      bounds_.trail_degrees);
    }
    worst_attach_ = std::max(worst_attach_, f.attach);
    worst_strain_ = finite ? std::max(worst_strain_, f.stats.max_strain) : INFINITY;
    worst_speed_ = finite ? std::max(worst_speed_, f.stats.max_speed) : INFINITY;
    return f;
}

void FlagChecks::print(int frames, int course_teleports, int failed_calls) const {
    std::printf("\nchecks over %d frames:\n", frames);
    std::printf("  attached particles: worst distance to target %.3g m (limit %.3g)\n", worst_attach_,
                bounds_.max_attach_error);
    std::printf("  particles inside (deeper than %.3g m): chassis %d, pole %d, terrain %d (deepest %.3g m)\n",
                bounds_.tolerance, penetrations_.chassis, penetrations_.pole, penetrations_.terrain,
                penetrations_.deepest);
    std::printf("  springs through the pole (within half its radius of its axis), summed over frames: %d\n",
                springs_through_pole_);
    std::printf("  max strain %.3f (limit %.3g), max speed %.2f m/s (limit %.3g)\n", worst_strain_,
                bounds_.max_strain, worst_speed_, bounds_.max_speed);
    std::printf("  carrier teleports: %d for %d course teleport(s); frames where they disagree: %d\n",
                carrier_teleports_, course_teleports, missed_teleports_);
    std::printf(
        "  looks like a flag: above %.0f m/s on the straight and in the slalom, the free edge trails the "
        "pole "
        "within %.0f degrees of the reverse travel direction in %d of %d frames (%.1f %%, at least %.0f %% "
        "asked), worst %.1f degrees%s\n",
        bounds_.trail_speed, bounds_.trail_degrees, trailing_.trailing, trailing_.frames,
        100.0 * trailing_.fraction(), 100.0 * bounds_.trail_fraction, trailing_.worst,
        trails() ? "" : "  CHECK FAILED");
    std::printf("  cloth calls that failed: %d; frames failing a check: %d\n", failed_calls, bad_frames_);
}

}  // namespace vehicle_flag
