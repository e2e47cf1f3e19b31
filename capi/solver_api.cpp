// C API: how a cloth is solved (cloth_solver_settings) and its strain limit.
#include <cloth/cloth.h>

#include "api_call.h"
#include "api_validation.h"

using namespace cloth;
using namespace cloth::api;

extern "C" {

CLOTH_API cloth_solver_settings cloth_default_solver_settings(void) {
    const SolverSettings core;
    cloth_solver_settings s{};
    s.struct_size = sizeof(cloth_solver_settings);
    s.kind = CLOTH_SOLVER_DEFAULT;  // resolved per frame from gamma (src/solve/solver_default.h)
    s.iterations = core.iterations;
    s.substeps = core.substeps;
    s.cg_tolerance = core.cg_tolerance;
    s.cg_max_iterations = core.cg_max_iterations;
    s.compression_safe_jacobian = core.compression_safe_jacobian;
    return s;
}

CLOTH_API cloth_result cloth_set_solver(cloth_id id, const cloth_solver_settings* settings) {
    return with_scene_cloth(__func__, id, [&](SceneCloth& cloth) -> Status {
        if (!settings) return null_error("settings");
        Status s = check_solver(*settings);
        if (!s.ok()) return s;
        cloth.set_solver(to_core(*settings, cloth.cloth().solver()));
        return {};
    });
}

CLOTH_API cloth_result cloth_get_solver(cloth_id id, cloth_solver_settings* out) {
    return with_scene_cloth(__func__, id, [&](SceneCloth& cloth) -> Status {
        if (!out) return null_error("out_settings");
        // The host's settings, and for a kind other than the default the
        // iterations and substeps a budget gave it (cloth.h, "Frame budget").
        const SolverSettings& host = cloth.cloth().solver();
        const SolverSettings core = host.kind == CLOTH_SOLVER_DEFAULT ? host : cloth.quality().settings();
        *out = cloth_default_solver_settings();
        out->kind = core.kind;
        out->iterations = core.iterations;
        out->substeps = core.substeps;
        out->cg_tolerance = core.cg_tolerance;
        out->cg_max_iterations = core.cg_max_iterations;
        out->compression_safe_jacobian = core.compression_safe_jacobian;
        return {};
    });
}

CLOTH_API cloth_strain_limit cloth_default_strain_limit(void) {
    const StrainLimit core;
    cloth_strain_limit l{};
    l.struct_size = sizeof(cloth_strain_limit);
    l.max_strain = core.max_strain;
    l.iterations = core.iterations;
    return l;
}

CLOTH_API cloth_result cloth_set_strain_limit(cloth_id id, const cloth_strain_limit* limit) {
    return with_scene_cloth(__func__, id, [&](SceneCloth& cloth) -> Status {
        if (!limit) return null_error("limit");
        Status s = check_strain_limit(*limit);
        if (!s.ok()) return s;
        cloth.set_strain_limit(StrainLimit{limit->max_strain, limit->iterations, true});
        return {};
    });
}

CLOTH_API cloth_result cloth_get_strain_limit(cloth_id id, cloth_strain_limit* out) {
    return with_cloth(__func__, id, [&](ClothInstance& cloth) -> Status {
        if (!out) return null_error("out_limit");
        *out = cloth_default_strain_limit();
        out->max_strain = cloth.solver().strain_limit.max_strain;
        out->iterations = cloth.solver().strain_limit.iterations;
        return {};
    });
}

}  // extern "C"
