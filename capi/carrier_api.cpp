// C API: a cloth's carrier, the body it travels with (inertia scales,
// speed limit, teleports). Every argument is checked before anything changes.
#include <cloth/cloth.h>

#include <cmath>

#include "api_call.h"
#include "api_validation.h"

using namespace cloth;
using namespace cloth::api;

namespace {

Status check_unit_interval(float value, const char* what) {
    if (!std::isfinite(value)) return Status::error(CLOTH_ERROR_NOT_FINITE, "%s is not finite", what);
    if (value < 0 || value > 1)
        return Status::error(CLOTH_ERROR_INVALID_VALUE, "%s %g is not in 0..1", what, double(value));
    return {};
}

Status check_carrier(const cloth_carrier_desc& d) {
    Status s = check_desc(d.struct_size, sizeof(cloth_carrier_desc), d.internal_cookie, "cloth_carrier_desc");
    if (s.ok()) s = check_unit_interval(d.linear_inertia, "linear_inertia");
    if (s.ok()) s = check_unit_interval(d.angular_inertia, "angular_inertia");
    if (s.ok()) s = check_unit_interval(d.centrifugal_inertia, "centrifugal_inertia");
    if (s.ok()) s = check_non_negative(d.max_relative_speed, "max_relative_speed");
    if (s.ok()) s = check_non_negative(d.teleport_distance, "teleport_distance");
    if (s.ok()) s = check_non_negative(d.teleport_rotation, "teleport_rotation");
    const int32_t mode = enum_bits(d.teleport_mode);
    if (s.ok() && mode != CLOTH_TELEPORT_DEFAULT && mode != CLOTH_TELEPORT_MOVE &&
        mode != CLOTH_TELEPORT_AND_RESET) {
        return Status::error(CLOTH_ERROR_INVALID_VALUE, "unknown teleport_mode %d", mode);
    }
    return s;
}

}  // namespace

extern "C" {

CLOTH_API cloth_carrier_desc cloth_default_carrier_desc(void) {
    const CarrierParams core;
    cloth_carrier_desc d{};
    d.struct_size = sizeof(cloth_carrier_desc);
    d.linear_inertia = core.linear_inertia;
    d.angular_inertia = core.angular_inertia;
    d.centrifugal_inertia = core.centrifugal_inertia;
    d.max_relative_speed = core.max_relative_speed;
    d.teleport_distance = core.teleport_distance;
    d.teleport_rotation = core.teleport_rotation;
    d.teleport_mode = CLOTH_TELEPORT_DEFAULT;
    d.internal_cookie = kCookie;
    return d;
}

CLOTH_API cloth_result cloth_set_carrier(cloth_id id, cloth_body_id body_id, const cloth_carrier_desc* desc) {
    return with_cloth(__func__, id, [&](ClothInstance& cloth) -> Status {
        if (cloth_body_id_equal(body_id, cloth_null_body_id)) {
            cloth.contact().carrier().clear();
            return {};
        }
        const BodyState* body = nullptr;
        Status s = find_body_of_cloth(id, body_id, body);
        if (!s.ok()) return s;
        if (!desc) return null_error("desc");
        s = check_carrier(*desc);
        if (!s.ok()) return s;
        CarrierParams params;
        params.linear_inertia = desc->linear_inertia;
        params.angular_inertia = desc->angular_inertia;
        params.centrifugal_inertia = desc->centrifugal_inertia;
        params.max_relative_speed = desc->max_relative_speed;
        params.teleport_distance = desc->teleport_distance;
        params.teleport_rotation = desc->teleport_rotation;
        params.teleport_mode =
            desc->teleport_mode == CLOTH_TELEPORT_DEFAULT ? CLOTH_TELEPORT_MOVE : desc->teleport_mode;
        cloth.contact().carrier().set(body_id.index1 - 1u, body->body, params, cloth.positions());
        return {};
    });
}

CLOTH_API cloth_result cloth_get_teleported(cloth_id id, bool* out_teleported) {
    return with_cloth(__func__, id, [&](ClothInstance& cloth) -> Status {
        if (!out_teleported) return null_error("out_teleported");
        *out_teleported = cloth.contact().carrier().teleported();
        return {};
    });
}

}  // extern "C"
