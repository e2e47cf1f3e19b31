// C API: self-collision of a cloth (enable, change, disable, read back,
// stats). Every argument is checked before anything changes.
#include <cloth/cloth.h>

#include <cmath>

#include "api_call.h"
#include "api_validation.h"
#include "collide/self_collision.h"

using namespace cloth;
using namespace cloth::api;

namespace {

constexpr uint32_t kMaxPasses = CLOTH_MAX_SELF_COLLISION_PASSES;

Status check_self_collision(const cloth_self_collision_desc& d, const Fabric& fabric) {
    Status s = check_desc(d.struct_size, sizeof(cloth_self_collision_desc), d.internal_cookie,
                          "cloth_self_collision_desc");
    if (!s.ok() || !d.enabled) return s;  // turning it off needs no valid values
    if (!std::isfinite(d.thickness)) return Status::error(CLOTH_ERROR_NOT_FINITE, "thickness is not finite");
    if (!(d.thickness > 0))
        return Status::error(CLOTH_ERROR_INVALID_VALUE, "thickness %g must be > 0", double(d.thickness));
    const float max_thickness = max_self_collision_thickness(fabric);
    if (d.thickness > max_thickness) {
        return Status::error(CLOTH_ERROR_INVALID_VALUE,
                             "thickness %g is more than twice the fabric's mean rest edge (at most %g)",
                             double(d.thickness), double(max_thickness));
    }
    s = check_non_negative(d.friction, "friction");
    if (!s.ok()) return s;
    if (d.passes < 1 || d.passes > kMaxPasses) {
        return Status::error(CLOTH_ERROR_INVALID_VALUE, "passes %u is not in 1..%u", d.passes, kMaxPasses);
    }
    return {};
}

SelfCollisionSettings to_core(const cloth_self_collision_desc& d) {
    SelfCollisionSettings s;
    s.thickness = d.thickness;
    s.friction = d.friction;
    s.use_regions = d.use_regions;
    s.passes = d.passes;
    return s;
}

}  // namespace

extern "C" {

CLOTH_API cloth_self_collision_desc cloth_default_self_collision_desc(void) {
    const SelfCollisionSettings core;
    cloth_self_collision_desc d{};
    d.struct_size = sizeof(cloth_self_collision_desc);
    d.enabled = false;
    d.thickness = core.thickness;
    d.friction = core.friction;
    d.use_regions = core.use_regions;
    d.passes = core.passes;
    d.internal_cookie = kCookie;
    return d;
}

CLOTH_API cloth_result cloth_set_self_collision(cloth_id id, const cloth_self_collision_desc* desc) {
    return with_cloth(__func__, id, [&](ClothInstance& cloth) -> Status {
        if (!desc) return null_error("desc");
        Status s = check_self_collision(*desc, cloth.fabric());
        if (!s.ok()) return s;
        if (!desc->enabled) {
            cloth.set_self_collision(nullptr);
            return {};
        }
        const SelfCollisionSettings settings = to_core(*desc);
        cloth.set_self_collision(&settings);  // builds the new state before replacing the old
        return {};
    });
}

CLOTH_API cloth_result cloth_get_self_collision(cloth_id id, cloth_self_collision_desc* out) {
    return with_cloth(__func__, id, [&](ClothInstance& cloth) -> Status {
        if (!out) return null_error("out_desc");
        cloth_self_collision_desc d = cloth_default_self_collision_desc();
        if (const SelfCollision* c = cloth.self_collision()) {
            const SelfCollisionSettings& core = c->settings();
            d.enabled = true;
            d.thickness = core.thickness;
            d.friction = core.friction;
            d.use_regions = core.use_regions;
            d.passes = core.passes;
        }
        *out = d;
        return {};
    });
}

CLOTH_API cloth_result cloth_get_self_collision_stats(cloth_id id, cloth_self_collision_stats* out) {
    return with_cloth(__func__, id, [&](ClothInstance& cloth) -> Status {
        if (!out) return null_error("out_stats");
        if (out->struct_size != sizeof(cloth_self_collision_stats)) {
            return Status::error(CLOTH_ERROR_INVALID_DESC,
                                 "cloth_self_collision_stats.struct_size is %u, expected %zu",
                                 out->struct_size, sizeof(cloth_self_collision_stats));
        }
        cloth_self_collision_stats r{};
        r.struct_size = sizeof(cloth_self_collision_stats);
        if (const SelfCollision* c = cloth.self_collision()) {
            const SelfCollisionStats core = c->stats();
            r.contacts = core.contacts;
            r.regions = core.regions;
            r.valid_regions = core.valid_regions;
            r.overflowed_particles = core.overflowed_particles;
            r.passes = core.passes;
        }
        *out = r;
        return {};
    });
}

}  // extern "C"
