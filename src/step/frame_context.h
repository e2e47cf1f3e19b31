// What one frame of one cloth carries from begin_frame to end_frame (as
// Jolt's SoftBodyUpdateContext): the decision it runs, the plan of the
// current substep and where the frame is in it. Nothing reads it between
// frames: end_frame leaves what the next frame and the stats read in a
// LastFrameRecord (frame_decision.h). Its buffers are sized once, with the
// cloth; the cloth's own state (positions, pins, settings) stays in
// ClothInstance.
#pragma once

#include <cstdint>

#include "base/host_allocator.h"
#include "base/math.h"
#include "base/soa.h"
#include "base/staged.h"
#include "collide/cloth_contact.h"
#include "solve/iterative_solve.h"
#include "solve/solver_settings.h"
#include "solve/strain_limit.h"
#include "step/frame_decision.h"
#include "step/limit_rounds.h"
#include "step/pair_rounds.h"
#include "step/step_stage.h"

namespace cloth {

class ClothInstance;

// Where the state a frame started from is kept, for a failed frame to go
// back to. Copying x and v every frame costs more than a step's smaller
// stages, so the copy is taken only when something rewrites them
// wholesale before integration (a carrier) or integrates in place
// (explicit). Otherwise the stages before integration change only the
// velocities of pinned particles (saved apart), the frame's first
// integration writes into the spare buffers and the buffers are swapped.
enum class FrameBackup : uint8_t {
    kCopied,            // the spare buffers hold a copy taken in begin_frame
    kFirstIntegration,  // x, v still hold it (but pinned v); integration writes to the spares
    kSwapped,           // the spare buffers hold it (but pinned v)
};

// One stage of the plan: `run` does one task of a round; `finish`, when
// set, is the serial work after each round's barrier; a stage with
// `rounds` is a staged algorithm (base/staged.h) whose rounds repeat the
// stage until it is done, otherwise the stage is one round.
struct PlannedStage {
    Stage stage;
    void (ClothInstance::*run)(const GroupTask& task);
    void (ClothInstance::*finish)();
    StagedAlgorithm* rounds;
};

struct FrameContext {
    static constexpr uint32_t kMaxPlannedStages = 16;
    // The most cloths one cloth is in contact with (World::set_cloth_contact).
    static constexpr uint32_t kMaxPairs = 4;

    explicit FrameContext(const HostMemory* memory)
        : pin_start(memory),
          pin_velocity_start(memory),
          backup_x(memory),
          backup_v(memory),
          group_finite(HostAllocator<uint8_t>(memory)),
          group_speed_squared(HostAllocator<float>(memory)),
          group_contacts(HostAllocator<uint32_t>(memory)) {}
    // Sizes the buffers once, at the cloth's creation (no allocation per step).
    void resize(uint32_t particles, uint32_t groups) {
        for (Vec3Soa* a : {&pin_start, &pin_velocity_start, &backup_x, &backup_v}) a->resize(particles);
        group_finite.assign(groups, 1);
        group_speed_squared.assign(groups, 0.0f);
        group_contacts.assign(groups, 0);
    }

    // What this frame runs (frame_decision.h), decided before it started.
    FrameDecision decision;

    float h = 0;   // substep length, s
    float dt = 0;  // frame length, s
    // The material's stiffness over the lightest free mass, which the
    // default's substep rule reads (solver_default.h).
    float stiffness_per_mass = 0;
    // The lightest free particle's mass, kg, when the solve stops in
    // physical units (SolverSettings::velocity_tolerance); else 0.
    float lightest_free_mass = 0;
    Vec3 gravity = Vec3::Zero();
    float theta = 1.0f;  // this substep's (integrate.h)
    // The strain the pins ask of this substep (Tethers::strain_pins_demand):
    // past the limit, the limit gives way to it in the solve and the passes.
    float strain_pins_demand = 0;
    bool strained = false;       // a substep of this frame ended past the strain limit's promise
    bool limit_held = false;     // a substep's strain limiter found a spring past the limit
    uint32_t strain_passes = 0;  // the strain limiter's passes, over the frame's substeps
    bool strain_capped = false;  // a substep's passes stopped at their cap (StrainLimiter::capped)
    bool collides = false;       // this frame runs the collision stage
    bool touching = false;       // this substep's collision stage found a contact
    // The colliders' pass of the current round between the strain limiter's
    // passes (ClothContact::Pass): the first records, the later ones test
    // the record, the one after the last pass every collider.
    ClothContact::Pass collider_pass = ClothContact::Pass::kEvery;
    bool colliders_recorded = false;  // this substep's colliders have a record
    bool converged = true;
    bool out_of_memory = false;  // set by the serial solve task
    FrameBackup backup = FrameBackup::kCopied;
    const Vec3Soa* solution = nullptr;  // the solver's dv, which integration reads

    // Per particle: where a pinned one was at the start of the frame, and
    // its velocity then; the spare buffers of the frame-start state (FrameBackup).
    Vec3Soa pin_start, pin_velocity_start;
    Vec3Soa backup_x, backup_v;
    // Per group: finite and the largest |v|^2 (written by the frame's last
    // round), and the contacts of this substep's collision stage.
    HostVector<uint8_t> group_finite;
    HostVector<float> group_speed_squared;
    HostVector<uint32_t> group_contacts;

    // The staged algorithms of the current substep.
    IterativeSolve iterative;  // JACOBI, PCG, CHEBYSHEV
    StrainLimiter strain_limiter;
    LimitRounds limit_rounds;  // the limiter's passes with the colliders between them
    // This frame's contact with other cloths: the cloth's side of each
    // pair, in the world's pair order (pair_rounds.h).
    PairRounds::Side* pairs[kMaxPairs] = {};
    uint32_t pair_count = 0;

    // The plan of the current substep, and where the frame is in it.
    PlannedStage plan[kMaxPlannedStages] = {};
    uint32_t plan_size = 0;
    uint32_t pins_move_at = 0;  // the plan entry before which the pins move (after the skinning)
    uint32_t substep = 0, entry = 0, round = 0;  // substep, entry of plan, round within it
    bool done = true;
};

}  // namespace cloth
