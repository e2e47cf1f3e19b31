// C API: pins of a cloth's particles (kinematic particles the host moves).
#include <cloth/cloth.h>

#include "api_call.h"
#include "api_validation.h"

using namespace cloth;
using namespace cloth::api;

extern "C" {

CLOTH_API cloth_result cloth_pin(cloth_id id, const uint32_t* indices, uint32_t count) {
    return with_cloth(__func__, id, [&](ClothInstance& cloth) -> Status {
        Status s = check_indices(indices, count, cloth.particle_count());
        if (!s.ok()) return s;
        cloth.set_pinned(indices, count, true, /*vertex_indices=*/true);
        return {};
    });
}

CLOTH_API cloth_result cloth_unpin(cloth_id id, const uint32_t* indices, uint32_t count) {
    return with_cloth(__func__, id, [&](ClothInstance& cloth) -> Status {
        Status s = check_indices(indices, count, cloth.particle_count());
        if (!s.ok()) return s;
        cloth.set_pinned(indices, count, false, /*vertex_indices=*/true);
        return {};
    });
}

CLOTH_API cloth_result cloth_set_pin_targets(cloth_id id, const uint32_t* indices, const float* targets_xyz,
                                             uint32_t count) {
    return with_cloth(__func__, id, [&](ClothInstance& cloth) -> Status {
        Status s = check_indices(indices, count, cloth.particle_count());
        if (s.ok()) s = check_points(targets_xyz, count, "targets");
        if (!s.ok()) return s;
        const Fabric& fabric = cloth.fabric();
        for (uint32_t k = 0; k < count; ++k) {
            if (!cloth.is_pinned(fabric.particle(indices[k]))) {
                return Status::error(CLOTH_ERROR_INVALID_VALUE, "particle %u is not pinned", indices[k]);
            }
            if (cloth.skin_pins(fabric.particle(indices[k]))) {
                return Status::error(CLOTH_ERROR_INVALID_VALUE,
                                     "particle %u follows its skinned position (max distance 0)", indices[k]);
            }
            if (cloth.contact().is_attached(fabric.particle(indices[k]))) {
                return Status::error(CLOTH_ERROR_INVALID_VALUE, "particle %u is attached to a body",
                                     indices[k]);
            }
        }
        for (uint32_t k = 0; k < count; ++k) {
            const float* p = targets_xyz + 3 * k;
            cloth.set_pin_target(fabric.particle(indices[k]), Vec3(p[0], p[1], p[2]));
        }
        return {};
    });
}

CLOTH_API cloth_result cloth_is_pinned(cloth_id id, uint32_t index, bool* out_pinned) {
    return with_cloth(__func__, id, [&](ClothInstance& cloth) -> Status {
        if (!out_pinned) return null_error("out_pinned");
        if (index >= cloth.particle_count()) {
            return Status::error(CLOTH_ERROR_INDEX_OUT_OF_RANGE, "index %u, but the cloth has %u particles",
                                 index, cloth.particle_count());
        }
        *out_pinned = cloth.is_pinned(cloth.fabric().particle(index));
        return {};
    });
}

}  // extern "C"
