// C API: snapshots (save and restore a cloth's dynamic state).
#include <cloth/cloth.h>

#include "api_call.h"
#include "api_validation.h"

using namespace cloth;
using namespace cloth::api;

extern "C" {

CLOTH_API cloth_result cloth_get_snapshot_size(cloth_id id, size_t* out_size) {
    return with_cloth(__func__, id, [&](ClothInstance& cloth) -> Status {
        if (!out_size) return null_error("out_size");
        *out_size = cloth.snapshot_size();
        return {};
    });
}

CLOTH_API cloth_result cloth_save_snapshot(cloth_id id, void* buffer, size_t capacity) {
    return with_cloth(__func__, id, [&](ClothInstance& cloth) -> Status {
        if (!buffer) return null_error("buffer");
        if (capacity < cloth.snapshot_size()) {
            return Status::error(CLOTH_ERROR_INVALID_COUNT, "capacity %zu is less than the %zu bytes needed",
                                 capacity, cloth.snapshot_size());
        }
        cloth.save_snapshot(buffer);
        return {};
    });
}

CLOTH_API cloth_result cloth_restore_snapshot(cloth_id id, const void* buffer, size_t size) {
    return with_scene_cloth(__func__, id, [&](SceneCloth& scene) -> Status {
        if (!buffer) return null_error("buffer");
        Status s = scene.cloth().restore_snapshot(buffer, size);
        if (s.ok()) scene.settle();  // reports show the restored state at once
        return s;
    });
}

}  // extern "C"
