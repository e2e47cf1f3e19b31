// C API: what a cloth costs in a scene: its importance under a frame
// budget, the world's viewer, the cloth's update rate, and the level of
// detail it steps at (scene/cloth_levels.h).
#include <cloth/cloth.h>

#include "api_call.h"
#include "api_validation.h"
#include "scene/update_rate.h"

using namespace cloth;
using namespace cloth::api;

extern "C" {

CLOTH_API cloth_result cloth_set_importance(cloth_id id, float importance) {
    return with_scene_cloth(__func__, id, [&](SceneCloth& cloth) -> Status {
        Status s = check_non_negative(importance, "importance");
        if (!s.ok()) return s;
        cloth.set_importance(importance);
        return {};
    });
}

CLOTH_API cloth_result cloth_get_importance(cloth_id id, float* out_importance) {
    return with_scene_cloth(__func__, id, [&](SceneCloth& cloth) -> Status {
        if (!out_importance) return null_error("out_importance");
        *out_importance = cloth.importance();
        return {};
    });
}

CLOTH_API cloth_result cloth_world_set_viewer(cloth_world_id id, const float position[3]) {
    return with_world(__func__, id, [&](World& world) -> Status {
        if (!position) {
            world.budget().set_viewer(nullptr);
            return {};
        }
        Vec3 viewer;
        Status s = check_position(position, "position", &viewer);
        if (!s.ok()) return s;
        world.budget().set_viewer(&viewer);
        return {};
    });
}

CLOTH_API cloth_result cloth_set_update_rate(cloth_id id, uint32_t rate) {
    return with_scene_cloth(__func__, id, [&](SceneCloth& cloth, World& world) -> Status {
        if (!UpdateRate::valid(rate))
            return Status::error(CLOTH_ERROR_INVALID_VALUE, "rate %u is not 1, 2, 4 or 8", rate);
        if (rate > 1 && cloth.cloth().contact().rides_bodies()) {
            return Status::error(
                CLOTH_ERROR_INVALID_VALUE,
                "rate %u: the cloth is attached to or carried by a body, and steps every frame", rate);
        }
        world.set_update_rate(cloth, rate);
        return {};
    });
}

CLOTH_API cloth_result cloth_get_update_rate(cloth_id id, uint32_t* out_rate, uint32_t* out_phase) {
    return with_scene_cloth(__func__, id, [&](SceneCloth& cloth) -> Status {
        if (!out_rate && !out_phase) return null_error("out_rate and out_phase");
        if (out_rate) *out_rate = cloth.update_rate().rate();
        if (out_phase) *out_phase = cloth.update_rate().phase();
        return {};
    });
}

CLOTH_API cloth_result cloth_set_lod_level(cloth_id id, uint32_t level) {
    return with_scene_cloth(__func__, id, [&](SceneCloth& cloth, World& world) -> Status {
        ClothInstance& full = cloth.cloth();
        const uint32_t count = ClothLevels::level_count(full);
        if (level > 0 && count == 1) {
            return Status::error(CLOTH_ERROR_INVALID_VALUE,
                                 "level %u: the cloth's fabric has no coarser level (a mesh, or a grid "
                                 "under %u x %u particles); its only level is 0",
                                 level, kLevelMinExtent, kLevelMinExtent);
        }
        if (level >= count) {
            return Status::error(CLOTH_ERROR_INDEX_OUT_OF_RANGE,
                                 "level %u, but the cloth's fabric has levels 0..%u", level, count - 1);
        }
        if (level > 0) {
            if (const char* why = ClothLevels::unsupported(full, world.in_cloth_pair(cloth))) {
                return Status::error(CLOTH_ERROR_INVALID_VALUE, "level %u: %s, and steps at level 0", level,
                                     why);
            }
        }
        cloth.levels().set_level(full, level);
        return {};
    });
}

CLOTH_API cloth_result cloth_get_lod_level(cloth_id id, uint32_t* out_level, uint32_t* out_level_count) {
    return with_scene_cloth(__func__, id, [&](SceneCloth& cloth) -> Status {
        if (!out_level && !out_level_count) return null_error("out_level and out_level_count");
        if (out_level) *out_level = cloth.levels().level();
        if (out_level_count) *out_level_count = ClothLevels::level_count(cloth.cloth());
        return {};
    });
}

}  // extern "C"
