// The names of a substep's stages, for profiles and traces. The order in
// which they run is written in one place, ClothInstance::plan_substep
// (frame_plan.cpp); what each does is the body of the same name in
// cloth_stages.cpp. The values match cloth_stage in cloth.h, which is ABI:
// they are numbered in the order the stages were added, not in run order.
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
    kLimitCollisions,
    kSkinning,
    kSkinConstraints,
    kClothContact,
    kClothContactRespond,
    kCount
};

constexpr uint32_t kStageCount = static_cast<uint32_t>(Stage::kCount);

// The stages whose work grows with the solver's iterations (the frame-budget
// policy's cost model, budget_policy.h).
inline bool is_solve_stage(Stage stage) {
    return stage == Stage::kJacobiSweep || stage == Stage::kSerialSolve || stage == Stage::kIterativeSolve;
}

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
        case Stage::kLimitCollisions:
            return "limit_collisions";
        case Stage::kSkinning:
            return "skinning";
        case Stage::kSkinConstraints:
            return "skin_constraints";
        case Stage::kIntegrate:
            return "integrate";
        case Stage::kExplicit:
            return "explicit";
        case Stage::kCollisions:
            return "collisions";
        case Stage::kSelfCollision:
            return "self_collision";
        case Stage::kSelfSort:
            return "self_sort";
        case Stage::kSelfContacts:
            return "self_contacts";
        case Stage::kSelfProject:
            return "self_project";
        case Stage::kSelfRespond:
            return "self_respond";
        case Stage::kClothContact:
            return "cloth_contact";
        case Stage::kClothContactRespond:
            return "cloth_contact_respond";
        case Stage::kCount:
            break;
    }
    return "?";
}

}  // namespace cloth
