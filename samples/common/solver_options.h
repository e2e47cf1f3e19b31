// The solver options the samples share (vehicle_flag, character_cloth),
// with the same names and meanings in each: --solver, --iterations,
// --substeps, --quality-policy and --policy-max-substeps. What iterations
// and substeps a kind gets when they are left at 0 is each sample's own
// plan (its cloth, its motion), a SolverPlan. Header-only: only the
// samples, which link CLI11, include it.
#pragma once

#include <cloth/cloth.h>

#include <CLI/CLI.hpp>
#include <cstdint>
#include <cstdio>
#include <string>

namespace cloth_samples {

struct SolverOptions {
    std::string solver = "default";
    uint32_t iterations = 0;           // 0: the solver kind's own (the sample's plan)
    uint32_t substeps = 0;             // 0: what the solver kind needs (the sample's plan)
    bool quality_policy = false;       // hand the budget to the library (cloth_set_quality_policy)
    uint32_t policy_max_substeps = 0;  // 0: the policy's default
};

// The kind a --solver name stands for (the option accepts only these names).
inline cloth_solver_kind solver_kind(const std::string& name) {
    if (name == "jacobi") return CLOTH_SOLVER_JACOBI;
    if (name == "cg") return CLOTH_SOLVER_CG;
    if (name == "explicit") return CLOTH_SOLVER_EXPLICIT;
    if (name == "pcg") return CLOTH_SOLVER_PCG;
    if (name == "chebyshev") return CLOTH_SOLVER_CHEBYSHEV;
    return CLOTH_SOLVER_DEFAULT;
}

// What a sample gives a solver kind when --iterations or --substeps is 0,
// and why (printed).
struct SolverPlan {
    uint32_t iterations, substeps;
    const char* why;
};

// The solver settings the options ask for, the plan's where they are 0.
inline cloth_solver_settings solver_settings(const SolverOptions& o, const SolverPlan& plan) {
    cloth_solver_settings solver = cloth_default_solver_settings();
    solver.kind = solver_kind(o.solver);
    solver.iterations = o.iterations > 0 ? o.iterations : plan.iterations;
    solver.substeps = o.substeps > 0 ? o.substeps : plan.substeps;
    return solver;
}

// " (WHY)" when the plan chose the substeps, to follow them when printed;
// empty when --substeps did.
inline std::string plan_note(const SolverOptions& o, const SolverPlan& plan) {
    return o.substeps > 0 ? "" : std::string(" (") + plan.why + ")";
}

// --solver, --iterations and --substeps.
inline void add_solver_options(CLI::App& app, SolverOptions* o) {
    app.add_option("--solver", o->solver, "jacobi, cg, explicit, pcg, chebyshev or default")
        ->check(CLI::IsMember({"jacobi", "cg", "explicit", "pcg", "chebyshev", "default"}));
    app.add_option("--iterations", o->iterations,
                   "solver iterations per substep (0: the solver kind's own, printed)")
        ->check(CLI::Range(0, 256));
    app.add_option("--substeps", o->substeps,
                   "cloth substeps per frame (0: what the solver kind needs, printed)")
        ->check(CLI::Range(0, 64));
}

// --quality-policy and --policy-max-substeps; `cloths` names whose policy
// it is in the help ("the flag's").
inline void add_quality_policy_options(CLI::App& app, SolverOptions* o, const std::string& cloths) {
    app.add_flag("--quality-policy", o->quality_policy,
                 "give the budget to the cloth world with " + cloths +
                     " quality policy on: the library lowers iterations and substeps in frames over it");
    app.add_option("--policy-max-substeps", o->policy_max_substeps,
                   "the quality policy's most substeps (0: its default)")
        ->check(CLI::Range(0, 64));
}

// The quality policy --quality-policy and --policy-max-substeps ask for
// (enabled only with --quality-policy).
inline cloth_quality_policy quality_policy(const SolverOptions& o) {
    cloth_quality_policy policy = cloth_default_quality_policy();
    policy.enabled = o.quality_policy ? 1 : 0;
    if (o.policy_max_substeps > 0) policy.max_substeps = o.policy_max_substeps;
    return policy;
}

// With --quality-policy: the world's frame budget and the policy on each
// of `count` cloths; false, with the error on stderr, if a call failed.
// Without it, nothing.
inline bool apply_quality_policy(const SolverOptions& o, cloth_world_id world, double budget_ms,
                                 const cloth_id* cloths, size_t count) {
    if (!o.quality_policy) return true;
    const cloth_quality_policy policy = quality_policy(o);
    bool ok = cloth_world_set_frame_budget(world, static_cast<float>(budget_ms)) == CLOTH_OK;
    for (size_t k = 0; k < count && ok; ++k) ok = cloth_set_quality_policy(cloths[k], &policy) == CLOTH_OK;
    if (!ok) std::fprintf(stderr, "quality policy: %s\n", cloth_get_last_error());
    return ok;
}

}  // namespace cloth_samples
