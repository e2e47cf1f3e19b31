// One simulated cloth: per-instance state over a shared Fabric (Jolt's
// SoftBodyMotionProperties, NvCloth's Cloth). Owns its material, solver
// settings and scratch buffers. A frame is a sequence of named stages, each
// a loop over the cloth's particle groups, in the order frame_plan.cpp
// writes down once; the world runs the stages of all its cloths together on
// one task system (World::step), and step() runs one cloth alone.
//
// The code of a cloth: cloth_instance.cpp (state, setters, sleep),
// frame_plan.cpp (the plan of a substep and the machine that runs it),
// cloth_stages.cpp (each stage's body), cloth_snapshot.cpp.
#pragma once

#include <cloth/cloth.h>

#include <algorithm>
#include <memory>

#include "base/host_allocator.h"
#include "base/math.h"
#include "base/soa.h"
#include "base/staged.h"
#include "base/status.h"
#include "collide/cloth_contact.h"
#include "fabric/fabric.h"
#include "forces/aerodynamics.h"
#include "forces/material.h"
#include "forces/springs.h"
#include "jobs/task_system.h"
#include "solve/skin.h"
#include "solve/solver_settings.h"
#include "solve/solvers.h"
#include "solve/strain_limit.h"
#include "step/cloth_parts.h"
#include "step/frame_context.h"
#include "step/step_stage.h"

namespace cloth {

class SpringTerms;
class SelfCollision;
struct SelfCollisionSettings;

class ClothInstance {
  public:
    ClothInstance(const HostMemory* memory, std::shared_ptr<const Fabric> fabric, const Material& material,
                  const SolverSettings& solver, const AeroParams& aero);

    const Fabric& fabric() const { return *fabric_; }
    uint32_t particle_count() const { return fabric_->particle_count(); }

    // Advance by one frame of `dt` seconds (settings().substeps substeps),
    // running the stages on `tasks` (serially if null), within a budget's
    // `bounds` (none by default). Returns CLOTH_ERROR_NONFINITE_STATE after
    // restoring the state from before the call if the result was not finite.
    Status step(float dt, const Vec3& gravity, TaskSystem* tasks = nullptr, const BudgetBounds& bounds = {});

    // The frame protocol (frame_plan.cpp), driven by run_frames
    // (frame_rounds.h) for one cloth here and for all of a world's cloths in
    // World::step. Serial calls are made on the stepping thread; run_task
    // on any worker, concurrently for different tasks of one stage:
    //   in = frame_inputs(dt, budget)                      // what the frame is decided on
    //   decision = decide_frame(in)                         // frame_decision.h: pure
    //   open_frame(dt, decision)                            // the state it starts from (carrier)
    //   [cloths in contact: share_substeps(decision, ...)] // the world, before the frame starts
    //   begin_frame(in, decision, gravity)
    //   while (!frame_done()) {
    //       prepare_stage();                               // serial
    //       run_task(t, worker) for t in [0, task_count()) // parallel
    //       finish_stage();                                // serial, after the barrier
    //   }
    //   end_frame()
    FrameInputs frame_inputs(float dt, const BudgetBounds& budget) const;
    void open_frame(float dt, const FrameDecision& decision);
    void begin_frame(const FrameInputs& in, const FrameDecision& decision, const Vec3& gravity);
    // The first four for a cloth in no pair (step()).
    void begin_frame_alone(float dt, const Vec3& gravity, const BudgetBounds& bounds);
    bool frame_done() const { return frame_.done; }
    Stage stage() const;  // the stage the current round belongs to
    uint32_t substep() const { return frame_.substep; }
    void prepare_stage();
    uint32_t task_count() const;
    void run_task(uint32_t task, uint32_t worker);
    void finish_stage();
    Status end_frame();

    // Sleep: a cloth whose particles all stay below sleep().max_speed for
    // sleep().frames frames stops (velocities zero) and is skipped by the
    // step until wake(). Everything that changes what the cloth would do
    // wakes it: pins and their targets, positions, material, and (through
    // the C API) solver, air and wind, gravity, self-collision; contact
    // features call wake() when their colliders or attachments move.
    void set_sleep(const SleepSettings& settings);
    const SleepSettings& sleep() const { return sleep_.settings; }
    bool sleeping() const { return sleep_.sleeping; }
    void wake();
    // The host puts the cloth to sleep now (an unseen cloth): it keeps its
    // velocities, so waking continues its motion, and moving bodies do not
    // wake it (a cloth on a carrier catches up with it when it wakes).
    void hold_asleep();
    bool held_asleep() const { return sleep_.held; }
    // Whether the step wakes the sleeping cloth: bodies it follows move
    // without a call on the cloth, unless the host holds it asleep.
    bool woken_by_bodies() const { return sleep_.sleeping && !sleep_.held && contact_.follows_bodies(); }
    // Origin rebasing: subtract `shift` from the positions and pin targets
    // (between frames; everything else is relative or per frame);
    // can_shift_origin: whether every result stays finite.
    bool can_shift_origin(const Vec3& shift) const;
    void shift_origin(const Vec3& shift);

    // The strain limiter's passes over the last step's substeps, and
    // whether a substep's passes stopped at their cap.
    uint32_t last_strain_passes() const { return last_.strain_passes; }
    bool last_strain_capped() const { return last_.strain_capped; }
    // Whether a step has run.
    bool last_step_ran() const { return last_.decision.h > 0; }
    // The strain limit the last step ran with (0: none).
    float ran_strain_limit() const {
        const StrainLimit& limit = last_.decision.solver.strain_limit;
        return limit.iterations > 0 ? limit.max_strain : 0.0f;
    }

    // Whether the strain limit holds structural springs against compression
    // as well as stretch: for the default, whose theta step rebounds a
    // spring the passes pulled in, past the limit the other way unless held
    // (docs/measurements.md, "Structural springs held against compression").
    // The other kinds integrate every substep with backward Euler, which
    // does not rebound; there compression terms only fight the stretch
    // terms where a load shears the cloth ("The course's PCG and JACOBI
    // kinds with compression held").
    bool holds_compression() const { return solver_.kind == CLOTH_SOLVER_DEFAULT; }

    // Snapshots (cloth_snapshot.cpp): the dynamic state in a flat buffer.
    size_t snapshot_size() const;
    void save_snapshot(void* out) const;
    // Validates everything before changing anything.
    Status restore_snapshot(const void* in, size_t size);
    // Whether a snapshot of the cloth carries its skin's state.
    bool snapshot_has_skin() const;

    // Particle groups: [group * kGroupSize, min(n, (group + 1) * kGroupSize)).
    // Every per-particle stage runs one task per group, so tasks carry about
    // the same work; a group is a row band on grids (row-major order).
    static constexpr uint32_t kGroupSize = cloth::kGroupSize;
    uint32_t group_count() const { return group_count_; }

    // Recomputes the masses when the material's mass parameters change.
    void set_material(const Material& material);
    // One particle's mass (kg, > 0), replacing what the material gave it.
    void set_mass(uint32_t particle, float mass);
    const Material& material() const { return material_; }
    // How the last frame shaped its springs (compression-safe Jacobian,
    // strain cable: springs.h).
    SpringModel spring_model() const;
    SolverSettings& solver() { return solver_; }
    const SolverSettings& solver() const { return solver_; }
    // What the last frame ran: CLOTH_SOLVER_DEFAULT's choice, caps and theta.
    const SolverSettings& last_frame_solver() const { return last_.decision.solver; }
    // The last frame's decision (frame_decision.h).
    const FrameDecision& last_frame_decision() const { return last_.decision; }
    // New solver settings from the host (wakes the cloth).
    void set_solver(const SolverSettings& settings);
    AeroParams& aero() { return aero_; }
    const AeroParams& aero() const { return aero_; }

    // Pin (kinematic, at their current positions) or release particles,
    // given by particle index or (as the C API does) by the host's vertex
    // index (Fabric::particle). Allocates nothing: the pinned list has room
    // for every particle.
    void set_pinned(const uint32_t* indices, uint32_t count, bool pinned, bool vertex_indices = false);
    void pin(uint32_t particle) { set_pinned(&particle, 1, true); }
    void unpin(uint32_t particle) { set_pinned(&particle, 1, false); }
    bool is_pinned(uint32_t particle) const { return pins_.pinned[particle] != 0.0f; }
    void set_pin_target(uint32_t particle, const Vec3& target) {
        pins_.target.set(particle, target);
        end_sleep();  // the pin's move is measured when the frame starts (starts_quiet)
    }
    // Teleport a particle: new position, zero velocity (and pin target).
    void set_position(uint32_t particle, const Vec3& x);

    const Vec3Soa& positions() const { return x_; }
    // The cloth's particles as contact with another cloth sees them
    // (collide/cloth_pair_contact.h); `steps`: it steps this frame.
    ParticleView particle_view(bool steps) {
        return ParticleView{fabric_.get(), &x_, &v_, mass_.data(), pins_.pinned.data(), steps};
    }
    // Contact with other cloths this frame (World::step, between
    // begin_frame and the first round): the cloth's side of each pair, in
    // the world's pair order (step/pair_rounds.h).
    void join_pair(PairRounds::Side* side);
    const Vec3Soa& velocities() const { return v_; }
    const HostVector<float>& masses() const { return mass_; }
    // The state and pins as they are, for a level of detail
    // (scene/cloth_levels.h), which moves the state between a cloth and its
    // coarser copy between frames: writing through these wakes nothing.
    Vec3Soa& level_positions() { return x_; }
    Vec3Soa& level_velocities() { return v_; }
    const PinSet& pin_set() const { return pins_; }
    // Unit area-weighted vertex normals of `positions` (the state, or what
    // the scene reports between steps: scene/scene_cloth.h).
    const Vec3Soa& normals(const Vec3Soa& positions) const;

    // Self-collision (self_collision.h): off (null, nothing allocated) until
    // enabled; `settings` null turns it off and frees it. Allocates when on.
    void set_self_collision(const SelfCollisionSettings* settings);
    const SelfCollision* self_collision() const { return self_collision_.get(); }
    // Collision settings, attachments and carrier (cloth_contact.h).
    ClothContact& contact() { return contact_; }
    const ClothContact& contact() const { return contact_; }

    const SolveReport& last_solve() const { return last_solve_; }
    cloth_result last_step_result() const { return last_step_result_; }

    // The skin (skin.h): skinned positions, max distances and backstops.
    // Setters that change what the cloth would do wake it.
    const Skin& skin() const { return skin_; }
    void bind_skin(uint32_t joint_count, uint32_t influences, const uint32_t* joints, const float* weights);
    void set_joint_matrices(const float* matrices, bool column_major_4x4);
    // By vertex, as the C API takes them.
    void set_skinned(const float* positions, const float* normals);
    // Max distances in particle order: 0 pins the particle to its skinned
    // position; a particle leaving 0 is unpinned.
    void set_max_distances(const float* distances);
    void set_backstops(const float* distances, const float* radii);
    // Whether particle i is a pin whose target the skin writes (max distance 0).
    bool skin_pins(uint32_t i) const {
        return skin_.active() && skin_.sized_for(particle_count()) && pins_.by_skin[i] != 0;
    }

  private:
    // ---- The plan of a substep and the machine that runs it (frame_plan.cpp)
    // Writes this substep's stages into frame_.plan, in run order.
    void plan_substep();
    // Set up a staged stage of the substep for its rounds.
    StagedAlgorithm* begin_iterative_solve();
    StagedAlgorithm* begin_strain_limit();
    bool limits_strain() const;
    void plan(Stage stage, void (ClothInstance::*run)(const GroupTask&),
              void (ClothInstance::*finish)() = nullptr, StagedAlgorithm* rounds = nullptr);
    const PlannedStage& planned() const { return frame_.plan[frame_.entry]; }
    // Whether the round about to run is the last of the frame (it checks the state).
    bool final_round() const;
    // Box2D-style order check: a stage body runs only as its planned stage.
    void expect_stage(Stage stage) const;

    // ---- The stages (cloth_stages.cpp), in plan order; each runs one group.
    /// Pinned particles get the velocity that lands them on this substep's targets (serial).
    void move_pins();
    /// The frame's skinned positions and normals (first substep only); the
    /// skin's pins get them as targets.
    void skin_particles(const GroupTask& task);
    void finish_skinning();
    /// Wind drag and lift per triangle, a share for each corner.
    void apply_air(const GroupTask& task);
    /// External forces (air gather, gravity, linear drag), then each spring's f~, J and A_s.
    void evaluate_forces(const GroupTask& task);
    /// EXPLICIT: gather spring forces, symplectic Euler; pins land.
    void integrate_explicitly(const GroupTask& task);
    void report_explicit_solve();
    /// W_ii, W_ii^-1, b_i and the first iterate p_i = W_ii^-1 b_i (paper Code 1).
    void assemble_system(const GroupTask& task);
    /// CG reference: the whole system on one task (Eigen).
    void solve_by_cg(const GroupTask& task);
    void record_cg_result();
    /// JACOBI, PCG, CHEBYSHEV: one round of the iterative solve (iterative_solve.h).
    void iterate_solver(const GroupTask& task);
    void record_iterative_result();
    /// v += dv, x += h v; pins land (the frame's first integration writes the spare buffers).
    void integrate_implicitly(const GroupTask& task);
    void adopt_first_integration();
    /// The collision stage: particles against the world's colliders over
    /// this substep, and whether any touched one (frame_.group_contacts).
    void collide_stage(const GroupTask& task);
    void note_contacts();
    void collide(const GroupTask& task, ClothContact::Pass pass, uint32_t* contacts = nullptr);
    /// One round of strain limiting, or of what runs between its passes: the
    /// self-collision's projection or response, the colliders (limit_rounds.h).
    void limit_strain(const GroupTask& task);
    /// The self-collision's projection (with `limiter` told of its move) or
    /// response between a strain limiter's passes (limit_rounds.h).
    void self_between_passes(LimitRounds::Round round, StrainLimiter& limiter, const GroupTask& task);
    /// After the strain limiter's last round: whether it ended past its promise.
    void note_strain();
    /// Contact with other cloths: a round of a pair's projections (a task
    /// over both cloths' particles, pair_rounds.h), and this cloth's
    /// velocities after them.
    void run_pair_contact(const GroupTask& task);
    void respond_to_pairs(const GroupTask& task);
    bool pair_stage() const;
    PairRounds::Side& planned_pair() const;
    /// Free particles into their max distances, out of their backstops
    /// (after the colliders, so the skin wins; also after each strain-limit pass).
    void constrain_to_skin(const GroupTask& task);
    void hold_to_skin(const GroupTask& task, bool prepared);
    // The fraction of the frame at this substep's end.
    float substep_end_fraction() const;
    /// One round of self-collision (hash, sort, contacts, project, respond).
    void resolve_self_contacts(const GroupTask& task);
    /// Checks the group's new state for NaN and Inf (in the frame's last round).
    void check_finite(uint32_t group);

    LinearSystem system() const;
    AssemblyPass assembly() const;
    void land_pins(uint32_t begin, uint32_t end, Vec3Soa& x);
    // Puts back the state the frame started from (end_frame, on failure).
    void restore_frame_start();
    // Where the integration stage writes: the spare buffers while the
    // frame-start state is still in x_ and v_ (FrameBackup::kFirstIntegration).
    Vec3Soa& integration_x() {
        return frame_.backup == FrameBackup::kFirstIntegration ? frame_.backup_x : x_;
    }
    Vec3Soa& integration_v() {
        return frame_.backup == FrameBackup::kFirstIntegration ? frame_.backup_v : v_;
    }
    GroupTask group_task(uint32_t group) const {
        return GroupTask::of(group, group_count_, particle_count());
    }
    bool has_air() const;
    bool state_is_finite() const;
    // Where pinned particle i is at `frame_fraction` of the current frame.
    Vec3 pin_position(uint32_t i, float frame_fraction) const;

    std::shared_ptr<const Fabric> fabric_;
    float mean_structural_rest_length_ = 0;  // m
    Material material_;
    SolverSettings solver_;
    AeroParams aero_;

    // State.
    Vec3Soa x_, v_;
    HostVector<float> mass_;
    bool masses_set_ = false;  // mass_ holds the material's (or the host's) masses
    PinSet pins_;

    std::shared_ptr<SpringTerms> springs_;  // per-spring f~ and A_s, in the layout that suits the fabric
    mutable SystemBuffers system_;          // mutable: normals() fills its normals
    StrainLimitParts strain_;
    std::shared_ptr<SelfCollision> self_collision_;  // null while off

    SolveReport last_solve_;
    cloth_result last_step_result_ = CLOTH_OK;
    LastFrameRecord last_;  // what the last frame left (frame_decision.h)
    uint32_t group_count_ = 0;
    FrameContext frame_;  // the frame in progress (nothing reads it between frames)

    void update_sleep();  // end of a successful frame
    // Bodies move without a call on the cloth, and a skin moves it each
    // frame: such a cloth is never quiet, and pays for no speed check.
    bool may_be_quiet() const { return !contact_.follows_bodies() && !skin_.active(); }
    bool free_particles_slower_than(float speed) const;
    // Whether no pin moves faster than `speed` to its target over a frame of `dt`.
    bool pins_slower_than(float speed, float dt) const;
    // The largest speed of a free particle relative to the mean velocity
    // of the pinned particles (of all, without pins): its motion within
    // the cloth, whatever carries it.
    float fastest_free_speed_relative_to_pins() const;
    void end_sleep();  // wake(), but a quiet cloth stays quiet
    // The largest squared speed of a particle's move over the frame, from
    // the frame's start positions (in frame_.backup_x); -1 when they are
    // not kept.
    float moved_speed_squared() const;
    SleepState sleep_;

    ClothContact contact_;  // colliders, attachments, carrier
    Skin skin_;             // sized only once the host gives the cloth a skin
};

}  // namespace cloth
