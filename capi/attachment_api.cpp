// C API: attachments, particles fixed to a body at local offsets. Every
// argument is checked before anything changes.
#include <cloth/cloth.h>

#include "api_call.h"
#include "api_validation.h"

using namespace cloth;
using namespace cloth::api;

extern "C" {

CLOTH_API cloth_result cloth_attach(cloth_id id, cloth_body_id body_id, const uint32_t* indices,
                                    const float* local_offsets_xyz, uint32_t count) {
    return with_scene_cloth(__func__, id, [&](SceneCloth& scene) -> Status {
        ClothInstance& cloth = scene.cloth();
        const BodyState* body = nullptr;
        Status s = find_body_of_cloth(id, body_id, body);
        if (s.ok()) s = check_indices(indices, count, cloth.particle_count());
        if (s.ok() && local_offsets_xyz) s = check_points(local_offsets_xyz, count, "local_offsets");
        if (!s.ok()) return s;
        ClothContact& contact = cloth.contact();
        contact.reserve_attachments(cloth.particle_count());  // may throw; nothing changed then
        const uint32_t slot = body_id.index1 - 1u;
        // A particle attached now sits at its target from the start of the
        // next step: the body's pose at the start of that step.
        const Pose& pose = body->body.start;
        const Fabric& fabric = cloth.fabric();
        for (uint32_t k = 0; k < count; ++k) {
            const uint32_t i = fabric.particle(indices[k]);
            const Vec3 offset = local_offsets_xyz
                                    ? Vec3(local_offsets_xyz[3 * k], local_offsets_xyz[3 * k + 1],
                                           local_offsets_xyz[3 * k + 2])
                                    : pose.apply_inverse(cloth.positions().get(i));
            contact.attach(i, slot, offset);
        }
        cloth.set_pinned(indices, count, true, /*vertex_indices=*/true);
        for (uint32_t k = 0; k < count; ++k) {
            const uint32_t i = fabric.particle(indices[k]);
            cloth.set_position(i, pose.apply(contact.attached_offset(i)));
        }
        scene.settle();
        return {};
    });
}

CLOTH_API cloth_result cloth_detach(cloth_id id, const uint32_t* indices, uint32_t count) {
    return with_cloth(__func__, id, [&](ClothInstance& cloth) -> Status {
        Status s = check_indices(indices, count, cloth.particle_count());
        if (!s.ok()) return s;
        for (uint32_t k = 0; k < count; ++k) {
            if (!cloth.contact().is_attached(cloth.fabric().particle(indices[k])))
                return Status::error(CLOTH_ERROR_INVALID_VALUE, "particle %u is not attached", indices[k]);
        }
        cloth.set_pinned(indices, count, false, /*vertex_indices=*/true);
        return {};
    });
}

CLOTH_API cloth_result cloth_get_attachment(cloth_id id, uint32_t index, cloth_body_id* out_body,
                                            float out_local_offset[3]) {
    return with_cloth(__func__, id, [&](ClothInstance& cloth) -> Status {
        if (!out_body) return null_error("out_body");
        if (index >= cloth.particle_count()) {
            return Status::error(CLOTH_ERROR_INDEX_OUT_OF_RANGE, "index %u, but the cloth has %u particles",
                                 index, cloth.particle_count());
        }
        const ClothContact& contact = cloth.contact();
        const uint32_t particle = cloth.fabric().particle(index);
        if (!contact.is_attached(particle)) {
            *out_body = cloth_body_id{};
            if (out_local_offset) out_local_offset[0] = out_local_offset[1] = out_local_offset[2] = 0.0f;
            return {};
        }
        const uint32_t slot = contact.attached_body(particle);
        *out_body = cloth_body_id{static_cast<uint16_t>(slot + 1), id.world1,
                                  contact.world()->body_generation(slot), id.world_generation};
        if (out_local_offset) {
            const Vec3 offset = contact.attached_offset(particle);
            for (int k = 0; k < 3; ++k) out_local_offset[k] = offset[k];
        }
        return {};
    });
}

}  // extern "C"
