// The plan of a frame, written once: plan_substep lists a substep's stages
// in run order, and the machine below runs them.
//
// A frame of `dt` runs `substeps` substeps of h = dt / substeps. Each stage
// is a loop over the cloth's particle groups (one task per group, on any
// worker) that reads only what earlier stages wrote, so the end of a stage
// is a barrier and nothing inside one needs a lock or an atomic: every
// per-particle sum is a gather in the fabric's fixed order. That makes the
// step parallel and bit-identical for any split of the groups over
// workers. The world runs the current stage of every cloth in one round
// (World::step), so many cloths share the workers.
//
// A new stage gets a line in plan_substep, behind the condition that
// enables it (a feature that is off adds no pass), and a body in
// cloth_stages.cpp that starts with expect_stage.
#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "collide/self_collision.h"
#include "solve/solver_default.h"
#include "step/cloth_instance.h"
#include "step/frame_rounds.h"

namespace cloth {

// A staged reduction writes one partial sum per particle group into the
// block-ordered arrays of solvers.h: a group must be exactly one block.
static_assert(kGroupSize == kReductionBlock, "one particle group per reduction block");

using C = ClothInstance;

// ---------------------------------------------------------------- the plan

// One substep, top to bottom (docs/method.md, "One substep, in order").
// Before the first stage, move_pins gives pinned particles their substep
// velocity.
void ClothInstance::plan_substep() {
    frame_.plan_size = 0;
    frame_.solution = &system_.dv;  // where the solver leaves dv (JACOBI: record_iterative_result says)
    frame_.theta = frame_.strained ? 1.0f : frame_.decision.solver.theta;
    frame_.touching = false;
    frame_.colliders_recorded = false;
    const cloth_solver_kind kind = frame_.decision.solver.kind;
    if (frame_.substep == 0 && skin_.active())
        plan(Stage::kSkinning, &C::skin_particles, &C::finish_skinning);
    frame_.pins_move_at = frame_.plan_size;  // the skin gives its pins their targets first
    if (has_air()) plan(Stage::kAir, &C::apply_air);
    plan(Stage::kForces, &C::evaluate_forces);
    if (kind == CLOTH_SOLVER_EXPLICIT) {
        plan(Stage::kExplicit, &C::integrate_explicitly, &C::report_explicit_solve);
    } else {
        plan(Stage::kAssemble, &C::assemble_system);
        if (kind == CLOTH_SOLVER_CG) {
            plan(Stage::kSerialSolve, &C::solve_by_cg, &C::record_cg_result);
        } else {
            const Stage stage = kind == CLOTH_SOLVER_JACOBI ? Stage::kJacobiSweep : Stage::kIterativeSolve;
            plan(stage, &C::iterate_solver, &C::record_iterative_result, begin_iterative_solve());
        }
        plan(Stage::kIntegrate, &C::integrate_implicitly, &C::adopt_first_integration);
    }
    // After integration, where contact plugs in.
    if (frame_.collides) plan(Stage::kCollisions, &C::collide_stage, &C::note_contacts);
    // Self-collision before the strain limiter, which projects its contacts
    // again between its passes and then responds (limit_rounds.h).
    if (self_collision_) {
        self_collision_->begin(x_, v_, mass_.data(), pins_.pinned.data(), !limits_strain());
        plan(Stage::kSelfCollision, &C::resolve_self_contacts, nullptr, self_collision_.get());
    }
    // Contact with other cloths, where both cloths wait (pair_rounds.h),
    // before the strain limiter, whose passes take back the stretch its
    // pushes make; each cloth's response after them (projected again
    // after the passes, the contacts' pushes leave the cloth stretched:
    // docs/measurements.md, "Contact between cloths inside the substeps").
    for (uint32_t k = 0; k < frame_.pair_count; ++k)
        plan(Stage::kClothContact, &C::run_pair_contact, nullptr, frame_.pairs[k]);
    if (limits_strain()) plan(Stage::kStrainLimit, &C::limit_strain, &C::note_strain, begin_strain_limit());
    if (frame_.pair_count > 0) plan(Stage::kClothContactRespond, &C::respond_to_pairs);
    // Last: max distance and backstop are promises after every substep.
    if (skin_.active() && skin_.constrains()) plan(Stage::kSkinConstraints, &C::constrain_to_skin);
}

StagedAlgorithm* ClothInstance::begin_iterative_solve() {
    // The physical stop (SolverSettings::velocity_tolerance) in r.z's units.
    const double v_tol = frame_.decision.solver.velocity_tolerance;
    frame_.iterative.begin(frame_.decision.solver.kind, frame_.decision.solver.iterations,
                           frame_.decision.solver.cg_tolerance,
                           {system(), assembly(), &system_.dv, &system_.work, &system_.dv_scratch,
                            frame_.decision.solver.multigrid ? &system_.multigrid : nullptr},
                           frame_.lightest_free_mass * v_tol * v_tol);
    return &frame_.iterative;
}

bool ClothInstance::limits_strain() const {
    const StrainLimit& limit = frame_.decision.solver.strain_limit;
    return limit.max_strain > 0 && limit.iterations > 0;
}

StagedAlgorithm* ClothInstance::begin_strain_limit() {
    const StrainLimit& limit = frame_.decision.solver.strain_limit;
    const StrainLimitPass pass{fabric_.get(),
                               mass_.data(),
                               pins_.pinned.data(),
                               limit.max_strain,
                               strain_.maybe_over.data(),
                               strain_.pull.data(),
                               holds_compression()};
    const bool accelerate = frame_.decision.solver.kind != CLOTH_SOLVER_EXPLICIT;  // strain_limit.h
    frame_.strain_limiter.begin(pass, limit.iterations, frame_.h, x_, v_, system_.work.r, system_.work.z,
                                accelerate, &strain_.grid_terms, &strain_.tethers, strain_.counts.data(),
                                frame_.decision.strain_passes_cap);
    frame_.limit_rounds.begin(&frame_.strain_limiter, frame_.collides, &frame_.touching,
                              self_collision_.get(), &x_, &v_);
    return &frame_.limit_rounds;
}

void ClothInstance::plan(Stage stage, void (C::*run)(const GroupTask&), void (C::*finish)(),
                         StagedAlgorithm* rounds) {
    assert(frame_.plan_size < FrameContext::kMaxPlannedStages);
    frame_.plan[frame_.plan_size++] = PlannedStage{stage, run, finish, rounds};
}

// ---------------------------------------------------------------- the machine

Status ClothInstance::step(float dt, const Vec3& gravity, TaskSystem* tasks, const BudgetBounds& bounds) {
    SerialTasks serial;
    TaskSystem& runner = tasks ? *tasks : serial;
    if (woken_by_bodies()) wake();
    if (sleep_.sleeping) return {};
    begin_frame_alone(dt, gravity, bounds);
    ClothInstance* self = this;
    auto body = [this](uint32_t begin, uint32_t end, uint32_t worker) {
        for (uint32_t t = begin; t < end; ++t) run_task(t, worker);
    };
    run_frames(&self, 1, [&] { parallel_for(runner, task_count(), 1, body); });
    return end_frame();
}

void ClothInstance::begin_frame_alone(float dt, const Vec3& gravity, const BudgetBounds& bounds) {
    const FrameInputs in = frame_inputs(dt, bounds);
    const FrameDecision decision = decide_frame(in);
    open_frame(dt, decision);
    begin_frame(in, decision, gravity);
}

FrameInputs ClothInstance::frame_inputs(float dt, const BudgetBounds& budget) const {
    FrameInputs in;
    in.host = solver_;
    in.dt = dt;
    const bool by_default = solver_.kind == CLOTH_SOLVER_DEFAULT;
    // Only the default solver's choice depends on k / m (a pass over every particle).
    const float lightest =
        by_default ? lightest_free_mass(mass_.data(), pins_.pinned.data(), particle_count()) : 0.0f;
    in.stiffness_per_mass = stiffness_over_mass(material_, lightest);
    in.multigrid = !system_.multigrid.empty();
    in.budget = budget;
    in.last = last_;
    // Each scan of the particles only where the decision reads it.
    in.starts_slow = by_default && may_be_quiet() && free_particles_slower_than(kDefaultQuietSpeed);
    in.pins_slow = last_.quiet && in.starts_slow && pins_slower_than(kDefaultQuietSpeed, dt);
    if (by_default && budget.substeps > 0) in.fastest_free_speed = fastest_free_speed_relative_to_pins();
    in.mean_rest_length = mean_structural_rest_length_;
    in.lightest_free_mass = lightest;
    return in;
}

void ClothInstance::open_frame(float dt, const FrameDecision& decision) {
    if (contact_.carrier().active() || decision.solver.kind == CLOTH_SOLVER_EXPLICIT) {
        frame_.backup = FrameBackup::kCopied;
        frame_.backup_x = x_;
        frame_.backup_v = v_;
    } else {
        frame_.backup = FrameBackup::kFirstIntegration;
        for (uint32_t i : pins_.list) frame_.pin_velocity_start.set(i, v_.get(i));
    }
    contact_.begin_step(dt, pins_.pinned.data(), x_, v_);  // carrier (no pass without one)
    frame_.collides = contact_.collides();
    for (uint32_t i : pins_.list) frame_.pin_start.set(i, x_.get(i));
    // A teleport of the carrier is one of the character the skin is on.
    if (skin_.active()) skin_.begin_frame(contact_.carrier().teleported());
    frame_.dt = dt;
    frame_.pair_count = 0;
}

void ClothInstance::begin_frame(const FrameInputs& in, const FrameDecision& decision, const Vec3& gravity) {
    frame_.decision = decision;
    frame_.stiffness_per_mass = in.stiffness_per_mass;
    frame_.lightest_free_mass = decision.solver.velocity_tolerance > 0 ? in.lightest_free_mass : 0.0f;
    frame_.strained = last_.strained;
    if (frame_.decision.solver.strain_limit.max_strain > 0 && !strain_.tethers_follow_pins) {
        strain_.tethers.plan(*fabric_, pins_.pinned.data());
        strain_.tethers_follow_pins = true;
    }
    frame_.h = decision.h;
    frame_.gravity = gravity;
    frame_.converged = true;
    frame_.limit_held = false;
    frame_.strain_passes = 0;
    frame_.strain_capped = false;
    frame_.out_of_memory = false;
    std::fill(frame_.group_finite.begin(), frame_.group_finite.end(), uint8_t{1});
    frame_.substep = frame_.entry = frame_.round = 0;
    plan_substep();
    frame_.done = false;
}

void ClothInstance::join_pair(PairRounds::Side* side) {
    assert(frame_.pair_count < FrameContext::kMaxPairs && frame_.substep == 0 && frame_.entry == 0);
    frame_.pairs[frame_.pair_count++] = side;
    plan_substep();
}

float ClothInstance::fastest_free_speed_relative_to_pins() const {
    const uint32_t n = particle_count();
    Vec3 mean = Vec3::Zero();
    if (!pins_.list.empty()) {
        for (uint32_t i : pins_.list) mean += v_.get(i);
        mean /= static_cast<float>(pins_.list.size());
    } else {
        for (uint32_t i = 0; i < n; ++i) mean += v_.get(i);
        mean /= static_cast<float>(std::max(n, 1u));
    }
    float most = 0;
    for (uint32_t i = 0; i < n; ++i) {
        if (pins_.pinned[i] == 0.0f) most = std::max(most, (v_.get(i) - mean).squaredNorm());
    }
    return std::sqrt(most);
}

bool ClothInstance::free_particles_slower_than(float speed) const {
    const float most = speed * speed;
    for (uint32_t i = 0; i < particle_count(); ++i) {
        if (pins_.pinned[i] == 0.0f && v_.get(i).squaredNorm() > most) return false;
    }
    return true;
}

bool ClothInstance::pins_slower_than(float speed, float dt) const {
    const float farthest = speed * speed * dt * dt;
    for (uint32_t i : pins_.list) {
        if ((pins_.target.get(i) - x_.get(i)).squaredNorm() > farthest) return false;
    }
    return true;
}

Stage ClothInstance::stage() const {
    const PlannedStage& s = planned();
    if (s.stage == Stage::kStrainLimit) {
        switch (frame_.limit_rounds.round()) {  // the rounds between its passes have stages of their own
            case LimitRounds::Round::kColliders:
                return Stage::kLimitCollisions;
            case LimitRounds::Round::kProject:
                return Stage::kSelfProject;
            case LimitRounds::Round::kRespond:
                return Stage::kSelfRespond;
            case LimitRounds::Round::kPass:
                return s.stage;
        }
    }
    if (s.stage != Stage::kSelfCollision) return s.stage;
    switch (self_collision_->round()) {  // self-collision's rounds have stages of their own
        case SelfCollision::Round::kSort:
            return Stage::kSelfSort;
        case SelfCollision::Round::kContacts:
            return Stage::kSelfContacts;
        case SelfCollision::Round::kProject:
            return Stage::kSelfProject;
        case SelfCollision::Round::kRespond:
            return Stage::kSelfRespond;
        default:
            return Stage::kSelfCollision;
    }
}

bool ClothInstance::pair_stage() const { return planned().stage == Stage::kClothContact; }

PairRounds::Side& ClothInstance::planned_pair() const {
    assert(pair_stage());
    return *static_cast<PairRounds::Side*>(planned().rounds);
}

void ClothInstance::prepare_stage() {
    if (frame_.entry == frame_.pins_move_at && frame_.round == 0) move_pins();
    if (pair_stage() && frame_.round == 0) planned_pair().arrive(frame_.h);
    if (planned().stage == Stage::kStrainLimit && frame_.round == 0)
        frame_.strain_limiter.hold_at_least(frame_.strain_pins_demand);
    if (planned().stage == Stage::kStrainLimit &&
        frame_.limit_rounds.round() == LimitRounds::Round::kColliders) {
        // Between the passes the colliders each particle can reach, found
        // in the first such round; after the last, every one (cloth_contact.h).
        using Pass = ClothContact::Pass;
        frame_.collider_pass = frame_.strain_limiter.done() ? Pass::kEvery
                               : frame_.colliders_recorded  ? Pass::kRecorded
                                                            : Pass::kRecord;
        frame_.colliders_recorded = frame_.colliders_recorded || frame_.collider_pass == Pass::kRecord;
    }
}

uint32_t ClothInstance::task_count() const {
    const PlannedStage& s = planned();
    if (pair_stage()) return planned_pair().task_count();
    const bool one_task = s.stage == Stage::kSerialSolve || (s.rounds && s.rounds->single_task());
    return one_task ? 1 : group_count_;
}

bool ClothInstance::final_round() const {
    const PlannedStage& s = planned();
    return frame_.substep + 1 == frame_.decision.solver.substeps && frame_.entry + 1 == frame_.plan_size &&
           (!s.rounds || s.rounds->last_round());
}

// Always on: one comparison per task. A mismatch is a bug in this file
// (a body wired to the wrong stage), never the caller's doing.
void ClothInstance::expect_stage(Stage stage) const {
    if (planned().stage == stage) return;
    std::fprintf(stderr, "cloth: stage body %s ran as planned stage %s\n", stage_name(stage),
                 stage_name(planned().stage));
    std::abort();
}

void ClothInstance::run_task(uint32_t task, uint32_t) {
    if (pair_stage()) {
        // A task over both cloths' particles (pair_rounds.h).
        ClothPairContact& contact = planned_pair().pair().contact();
        const uint32_t tasks = contact.task_count();
        run_pair_contact(tasks == 1 ? GroupTask{0, 1, 0, contact.count()}
                                    : GroupTask::of(task, tasks, contact.count()));
        return;
    }
    (this->*planned().run)(group_task(task));
    // The last round of the frame checks its group for NaN and Inf.
    if (final_round()) check_finite(task);
}

void ClothInstance::finish_stage() {
    if (frame_.out_of_memory) {
        frame_.done = true;
        return;
    }
    const PlannedStage& s = planned();
    if (s.rounds) s.rounds->finish_round();
    if (s.finish) (this->*s.finish)();
    if (s.rounds && !s.rounds->done()) {
        ++frame_.round;  // the staged algorithm's next round
        return;
    }
    frame_.round = 0;
    if (++frame_.entry < frame_.plan_size) return;
    if (++frame_.substep == frame_.decision.solver.substeps) {
        frame_.done = true;
        return;
    }
    frame_.entry = 0;
    plan_substep();
}

Status ClothInstance::end_frame() {
    frame_.done = true;
    last_.decision = frame_.decision;
    last_.strain_passes = frame_.strain_passes;
    last_.strain_capped = frame_.strain_capped;
    if (frame_.out_of_memory) {
        // Only the CG reference solver allocates during a step.
        restore_frame_start();
        last_step_result_ = CLOTH_ERROR_OUT_OF_MEMORY;
        return Status::error(
            CLOTH_ERROR_OUT_OF_MEMORY,
            "the solver could not allocate; the cloth was restored to its state before the step");
    }
    if (!state_is_finite()) {
        restore_frame_start();
        last_step_result_ = CLOTH_ERROR_NONFINITE_STATE;
        return Status::error(
            CLOTH_ERROR_NONFINITE_STATE,
            "the step produced a non-finite state; the cloth was restored to its state before "
            "the step (lower dt, raise substeps or iterations, or use a sturdier solver)");
    }
    last_step_result_ = frame_.converged ? CLOTH_OK : CLOTH_ERROR_SOLVER_FAILED;
    last_.strained = frame_.strained;
    last_.quiet = frame_.decision.started_slow && !frame_.limit_held;
    update_sleep();
    if (!frame_.converged) {
        return Status::error(CLOTH_ERROR_SOLVER_FAILED,
                             "conjugate gradient stopped at its iteration limit (residual %g)",
                             static_cast<double>(last_solve_.residual));
    }
    return {};
}

}  // namespace cloth
