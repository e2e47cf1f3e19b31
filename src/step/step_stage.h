// The named stages of one substep (algorithm.md 4; paper section III).
//
// Each stage is a loop over a cloth's particle groups (one task per group)
// that reads only what earlier stages wrote, so the end of a stage is a
// barrier and nothing inside one needs a lock or an atomic: every
// per-particle sum is a gather in the fabric's fixed order. The world runs
// the current stage of every cloth in one parallel_for (task_system.h), so
// many cloths share the workers within one cloth_step.
//
// The plan of one substep (ClothInstance::next_stage):
//
//   kAir            per triangle: wind drag and lift (only when the cloth has air)
//   kForces         per particle: external forces (air gather, gravity, drag);
//                   per spring: f~, J, A_s (paper Code 4)
//   -- solver dispatch on cloth_solver_kind (ClothInstance::next_stage):
//   kAssemble       per particle: W_ii, W_ii^-1, b_i, p_i (paper Code 1)
//   kJacobiSweep    JACOBI: one sweep per iteration (paper Code 2/3)
//   kSerialSolve    CG reference: one task for the whole cloth
//   kIterativeSolve PCG and CHEBYSHEV (solvers.h): a sequence of per-group
//                   passes, one round each, chosen after each barrier
//                   (ClothInstance::IterativeSolve::Phase):
//                     PCG: start (r = b - W dv, z = P r, p = z), then per
//                     iteration product (q = W p), update (dv, r, z) and
//                     direction (p = z + beta p), dot products per group;
//                     CHEBYSHEV: bound, start, then product / direction
//   kIntegrate      per particle: v += dv, x += h v; pins land
//   kExplicit       EXPLICIT (replaces kAssemble..kIntegrate): gather, Euler
//   -- after integration, where contact plugs in:
//   kCollisions     colliders and attachments (issue 6)
//   kStrainLimit    per particle, when enabled (strain_limit.h): rounds alternate
//                   corrections and x += c, v += c / h, `iterations` times each;
//                   each application is followed by the colliders' pass over
//                   the same particles, so contact and strain limit are
//                   resolved together (its time counts in this stage)
//   kSelfCollision  self-collision (issue 5, self_collision.h), in five stages:
//                   per group: region checks and hash keys;
//   kSelfSort       one task: counting sort into buckets;
//   kSelfContacts   per group: each particle's contact list;
//   kSelfProject    per group: one Jacobi projection pass (repeated while
//                   overlaps remain, at most `passes` times);
//   kSelfRespond    per group: velocity response (paper eq. 13), the last stage
//
// A new solver kind adds its stages here and its branch in next_stage();
// a serial one runs as a single task like kSerialSolve. A new post-
// integration pass gets a stage here, a body called from
// ClothInstance::run_task, and a condition in next_stage() that schedules
// it only when the feature is enabled (a feature that is off adds no pass).
#pragma once

#include <cstdint>

namespace cloth {

enum class Stage : uint8_t {
    kAir,
    kForces,
    kAssemble,
    kJacobiSweep,
    kSerialSolve,
    kIntegrate,
    kExplicit,
    kCollisions,
    kSelfCollision,
    kSelfSort,
    kSelfContacts,
    kSelfProject,
    kSelfRespond,
    kIterativeSolve,
    kStrainLimit,
    kCount
};

constexpr uint32_t kStageCount = static_cast<uint32_t>(Stage::kCount);

// Short stable names, for profiles and traces.
inline const char* stage_name(Stage stage) {
    switch (stage) {
        case Stage::kAir:
            return "air";
        case Stage::kForces:
            return "forces";
        case Stage::kAssemble:
            return "assemble";
        case Stage::kJacobiSweep:
            return "jacobi_sweep";
        case Stage::kSerialSolve:
            return "serial_solve";
        case Stage::kIterativeSolve:
            return "iterative_solve";
        case Stage::kStrainLimit:
            return "strain_limit";
        case Stage::kIntegrate:
            return "integrate";
        case Stage::kExplicit:
            return "explicit";
        case Stage::kCollisions:
            return "collisions";
        case Stage::kSelfCollision:
            return "self_hash";
        case Stage::kSelfSort:
            return "self_sort";
        case Stage::kSelfContacts:
            return "self_contacts";
        case Stage::kSelfProject:
            return "self_project";
        case Stage::kSelfRespond:
            return "self_respond";
        case Stage::kCount:
            break;
    }
    return "?";
}

}  // namespace cloth
