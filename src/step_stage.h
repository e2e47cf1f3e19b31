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
//   kPcgStart       PCG (solvers.h): r = b - W dv, z = P r, p = z, partial r.z
//   kPcgProduct     PCG: q = W p, partial p.q          } repeated while the
//   kPcgUpdate      PCG: dv += a p, r -= a q, z = P r  } iteration budget
//   kPcgDirection   PCG: p = z + beta p                } lasts and r.z is large
//   kChebyshevBound CHEBYSHEV: per group, the lower eigenvalue bound (min)
//   kChebyshevStart CHEBYSHEV: r = b - W dv, p = P r / theta
//   kChebyshevProduct   CHEBYSHEV: q = W p, dv += p    } `iterations` times
//   kChebyshevDirection CHEBYSHEV: r -= q, p = c1 p + c2 P r
//   kIntegrate      per particle: v += dv, x += h v; pins land
//   kExplicit       EXPLICIT (replaces kAssemble..kIntegrate): gather, Euler
//   -- after integration, where contact plugs in:
//   kStrainLimit    per particle: strain-limit corrections (strain_limit.h), when enabled
//   kStrainApply    per particle: x += c, v += c / h; both repeated `iterations` times
//   kCollisions     colliders and attachments (issue 6)
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
    kPcgStart,
    kPcgProduct,
    kPcgUpdate,
    kPcgDirection,
    kChebyshevBound,
    kChebyshevStart,
    kChebyshevProduct,
    kChebyshevDirection,
    kIntegrate,
    kExplicit,
    kStrainLimit,
    kStrainApply,
    kCollisions,
    kSelfCollision,
    kSelfSort,
    kSelfContacts,
    kSelfProject,
    kSelfRespond,
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
        case Stage::kPcgStart:
            return "pcg_start";
        case Stage::kPcgProduct:
            return "pcg_product";
        case Stage::kPcgUpdate:
            return "pcg_update";
        case Stage::kPcgDirection:
            return "pcg_direction";
        case Stage::kChebyshevBound:
            return "chebyshev_bound";
        case Stage::kChebyshevStart:
            return "chebyshev_start";
        case Stage::kChebyshevProduct:
            return "chebyshev_product";
        case Stage::kChebyshevDirection:
            return "chebyshev_direction";
        case Stage::kStrainLimit:
            return "strain_limit";
        case Stage::kStrainApply:
            return "strain_apply";
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
