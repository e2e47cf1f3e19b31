// C API: solver options beyond cloth_solver_settings (strain limiting).
#include <cloth/cloth.h>

#include "api_call.h"
#include "api_validation.h"

using namespace cloth;
using namespace cloth::api;

extern "C" {

CLOTH_API cloth_strain_limit cloth_default_strain_limit(void) {
    const StrainLimit core;
    cloth_strain_limit l{};
    l.struct_size = sizeof(cloth_strain_limit);
    l.max_strain = core.max_strain;
    l.iterations = core.iterations;
    return l;
}

CLOTH_API cloth_result cloth_set_strain_limit(cloth_id id, const cloth_strain_limit* limit) {
    return api_call(__func__, [&](const World*& log_world) -> Status {
        ClothInstance* cloth;
        Status s = get_cloth(id, cloth, log_world);
        if (!s.ok()) return s;
        if (!limit) return null_error("limit");
        s = check_strain_limit(*limit);
        if (!s.ok()) return s;
        cloth->solver().strain_limit = StrainLimit{limit->max_strain, limit->iterations};
        return {};
    });
}

CLOTH_API cloth_result cloth_get_strain_limit(cloth_id id, cloth_strain_limit* out) {
    return api_call(__func__, [&](const World*& log_world) -> Status {
        ClothInstance* cloth;
        Status s = get_cloth(id, cloth, log_world);
        if (!s.ok()) return s;
        if (!out) return null_error("out_limit");
        *out = cloth_default_strain_limit();
        out->max_strain = cloth->solver().strain_limit.max_strain;
        out->iterations = cloth->solver().strain_limit.iterations;
        return {};
    });
}

}  // extern "C"
