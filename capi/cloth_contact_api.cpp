// C API: contact between two cloths of one world (turn on, change, turn
// off, read back, count). Every argument is checked before anything
// changes.
#include <cloth/cloth.h>

#include <algorithm>
#include <cmath>

#include "api_call.h"
#include "api_validation.h"
#include "collide/cloth_pair_contact.h"
#include "collide/self_collision.h"

using namespace cloth;
using namespace cloth::api;

namespace {

// Runs `body(world, a, b)` on the two live cloths of one world `a` and
// `b` name.
template <class Body>
cloth_result with_cloth_pair(const char* function, cloth_id a, cloth_id b, Body body) {
    return with_cloth(function, a, [&](ClothInstance& cloth_a, World& world) -> Status {
        Status s = check_same_world(b, cloth_world_id{a.world1, a.world_generation}, "cloth b", "cloth a");
        if (!s.ok()) return s;
        ClothInstance* cloth_b = world.find_cloth(b);
        if (!cloth_b) return no_object_error("cloth");
        return body(world, cloth_a, *cloth_b);
    });
}

Status check_cloth_contact(const cloth_cloth_contact_desc& d, const Fabric& a, const Fabric& b) {
    Status s = check_desc(d.struct_size, sizeof(cloth_cloth_contact_desc), d.internal_cookie,
                          "cloth_cloth_contact_desc");
    if (!s.ok() || !d.enabled) return s;  // turning it off needs no valid values
    if (!std::isfinite(d.thickness)) return Status::error(CLOTH_ERROR_NOT_FINITE, "thickness is not finite");
    if (!(d.thickness > 0))
        return Status::error(CLOTH_ERROR_INVALID_VALUE, "thickness %g must be > 0", double(d.thickness));
    // The hash's cells are as wide as the thickness: a thicker one than
    // the fabrics' edges would put whole patches of both cloths in a cell.
    const float max_thickness = 2.0f * std::max(mean_rest_edge(a), mean_rest_edge(b));
    if (d.thickness > max_thickness) {
        return Status::error(
            CLOTH_ERROR_INVALID_VALUE,
            "thickness %g is more than twice the larger fabric's mean rest edge (at most %g)",
            double(d.thickness), double(max_thickness));
    }
    s = check_non_negative(d.friction, "friction");
    if (!s.ok()) return s;
    if (d.passes < 1 || d.passes > CLOTH_MAX_SELF_COLLISION_PASSES) {
        return Status::error(CLOTH_ERROR_INVALID_VALUE, "passes %u is not in 1..%u", d.passes,
                             static_cast<uint32_t>(CLOTH_MAX_SELF_COLLISION_PASSES));
    }
    return {};
}

}  // namespace

extern "C" {

CLOTH_API cloth_cloth_contact_desc cloth_default_cloth_contact_desc(void) {
    const ClothPairSettings core;
    cloth_cloth_contact_desc d{};
    d.struct_size = sizeof(cloth_cloth_contact_desc);
    d.enabled = 0;
    d.thickness = core.thickness;
    d.friction = core.friction;
    d.passes = core.passes;
    d.internal_cookie = kCookie;
    return d;
}

CLOTH_API cloth_result cloth_set_cloth_contact(cloth_id a, cloth_id b, const cloth_cloth_contact_desc* desc) {
    return with_cloth_pair(__func__, a, b,
                           [&](World& world, ClothInstance& cloth_a, ClothInstance& cloth_b) -> Status {
                               if (!desc) return null_error("desc");
                               Status s = check_cloth_contact(*desc, cloth_a.fabric(), cloth_b.fabric());
                               if (!s.ok()) return s;
                               if (!desc->enabled) return world.set_cloth_contact(a, b, nullptr);
                               ClothPairSettings settings;
                               settings.thickness = desc->thickness;
                               settings.friction = desc->friction;
                               settings.passes = desc->passes;
                               return world.set_cloth_contact(a, b, &settings);
                           });
}

CLOTH_API cloth_result cloth_get_cloth_contact(cloth_id a, cloth_id b, cloth_cloth_contact_desc* out) {
    return with_cloth_pair(__func__, a, b, [&](World& world, ClothInstance&, ClothInstance&) -> Status {
        if (!out) return null_error("out_desc");
        cloth_cloth_contact_desc d = cloth_default_cloth_contact_desc();
        if (const ClothPairContact* contact = world.cloth_contact(a, b)) {
            d.enabled = 1;
            d.thickness = contact->settings().thickness;
            d.friction = contact->settings().friction;
            d.passes = contact->settings().passes;
        }
        *out = d;
        return {};
    });
}

CLOTH_API cloth_result cloth_get_cloth_contact_count(cloth_id a, cloth_id b, uint32_t* out_contacts,
                                                     uint32_t* out_passes) {
    return with_cloth_pair(__func__, a, b, [&](World& world, ClothInstance&, ClothInstance&) -> Status {
        if (!out_contacts) return null_error("out_contacts");
        if (!out_passes) return null_error("out_passes");
        const ClothPairContact* contact = world.cloth_contact(a, b);
        *out_contacts = contact ? contact->contacts() : 0;
        *out_passes = contact ? contact->passes() : 0;
        return {};
    });
}

}  // extern "C"
