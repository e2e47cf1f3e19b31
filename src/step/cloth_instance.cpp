// One frame of one cloth, as a sequence of named stages (step_stage.h has
// the plan): per substep h = dt / substeps, the kinematic velocities of
// pinned particles (serial, tiny), then air, forces and springs, assembly,
// the solver's stages and integration, each a loop over particle groups.
//
// Every stage reads the previous stages' output only, with a barrier
// between stages; all sums are gathers in the fabric's fixed order. That
// makes the step parallel without atomics and bit-identical for any
// split of the groups over workers.
#include "step/cloth_instance.h"

#include <algorithm>
#include <cmath>

#include "base/lanes.h"
#include "collide/self_collision.h"
#include "forces/aerodynamics.h"
#include "forces/spring_terms.h"
#include "forces/springs.h"
#include "solve/integrate.h"
#include "solve/solver_default.h"
#include "solve/solvers.h"
#include "solve/strain_limit.h"

namespace cloth {

// A staged reduction writes one partial sum per particle group into the
// block-ordered arrays of solvers.h: a group must be exactly one block.
static_assert(ClothInstance::kGroupSize == kReductionBlock, "one particle group per reduction block");

ClothInstance::ClothInstance(const HostMemory* memory, std::shared_ptr<const Fabric> fabric,
                             const Material& material, const SolverSettings& solver, const AeroParams& aero)
    : fabric_(std::move(fabric)),
      material_(material),
      solver_(solver),
      aero_(aero),
      x_(memory),
      v_(memory),
      mass_(HostAllocator<float>(memory)),
      pinned_(HostAllocator<float>(memory)),
      pinned_list_(HostAllocator<uint32_t>(memory)),
      pin_target_(memory),
      pin_start_(memory),
      external_force_(memory),
      triangle_force_(memory),
      springs_(make_spring_terms(memory, fabric_, material)),
      diagonal_(memory),
      diagonal_inverse_(memory),
      rhs_(memory),
      dv_(memory),
      dv_scratch_(memory),
      solver_work_(memory),
      normals_(memory),
      backup_x_(memory),
      backup_v_(memory),
      pin_velocity_start_(memory),
      group_finite_(HostAllocator<uint8_t>(memory)),
      group_speed_squared_(HostAllocator<float>(memory)),
      contact_(memory) {
    const Fabric& f = *fabric_;
    const uint32_t n = f.particle_count();
    for (Vec3Soa* a : {&x_, &v_, &pin_target_, &pin_start_, &external_force_, &rhs_, &dv_, &dv_scratch_,
                       &normals_, &backup_x_, &backup_v_, &pin_velocity_start_}) {
        a->resize(n);
    }
    for (uint32_t i = 0; i < n; ++i) x_.set(i, f.rest_positions[i]);
    pin_target_ = x_;
    mass_.resize(n);
    pinned_.assign(n, 0.0f);
    pinned_list_.reserve(n);
    triangle_force_.resize(air_storage_size(f));
    diagonal_.resize(n);
    diagonal_inverse_.resize(n);
    solver_work_.resize(n);
    group_count_ = (n + kGroupSize - 1) / kGroupSize;
    group_finite_.assign(group_count_, 1);
    group_speed_squared_.assign(group_count_, 0.0f);
    set_material(material);
}

void ClothInstance::set_material(const Material& material) {
    wake();
    material_ = material;
    const Fabric& f = *fabric_;
    for (uint32_t i = 0; i < f.particle_count(); ++i) {
        mass_[i] =
            material.particle_mass > 0 ? material.particle_mass : material.area_density * f.rest_area[i];
    }
    springs_->set_material(material);
}

void ClothInstance::set_pinned(const uint32_t* indices, uint32_t count, bool pinned, bool vertex_indices) {
    wake();
    for (uint32_t k = 0; k < count; ++k) {
        const uint32_t i = vertex_indices ? fabric_->particle(indices[k]) : indices[k];
        if (pinned) pin_target_.set(i, x_.get(i));
        pinned_[i] = pinned ? 1.0f : 0.0f;
        if (!pinned) contact_.detach(i);
    }
    pinned_list_.clear();  // keeps its capacity of one entry per particle
    for (uint32_t i = 0; i < particle_count(); ++i) {
        if (pinned_[i] != 0.0f) pinned_list_.push_back(i);
    }
}

void ClothInstance::set_position(uint32_t particle, const Vec3& x) {
    wake();
    x_.set(particle, x);
    v_.set(particle, Vec3::Zero());
    pin_target_.set(particle, x);
}

void ClothInstance::set_self_collision(const SelfCollisionSettings* settings) {
    wake();
    if (!settings) {
        self_collision_.reset();
        return;
    }
    // The cloth's own allocator (the world's host memory), as for its other buffers.
    const HostMemory* memory = x_.x.get_allocator().memory();
    self_collision_ = std::allocate_shared<SelfCollision>(HostAllocator<SelfCollision>(memory), memory,
                                                          *fabric_, *settings);
}

const Vec3Soa& ClothInstance::normals() const {
    compute_vertex_normals(*fabric_, x_, 0, particle_count(), normals_);
    return normals_;
}

namespace {

// Exchanges the buffers of a and b (no copy).
void swap_buffers(Vec3Soa& a, Vec3Soa& b) {
    a.x.swap(b.x);
    a.y.swap(b.y);
    a.z.swap(b.z);
}

// Whether x and v are finite on [begin, end) (x * 0 is 0 for finite x and
// NaN otherwise; NaN survives any sum), and the largest squared speed
// there, in one pass. The maximum does not depend on the order.
CLOTH_HOT_LOOP bool range_is_finite(const Vec3Soa& x, const Vec3Soa& v, uint32_t begin, uint32_t end,
                                    float& max_speed_squared) {
    float sum[VectorLanes::width] = {}, top[VectorLanes::width] = {};
    for_each_lane_group(begin, end, begin, end, [&](auto lanes, uint32_t i) {
        using L = decltype(lanes);
        using T = typename L::type;
        const T vx = L::load(&v.x[i]), vy = L::load(&v.y[i]), vz = L::load(&v.z[i]);
        T acc = L::load(sum);
        acc += L::load(&x.x[i]) * 0.0f + L::load(&x.y[i]) * 0.0f + L::load(&x.z[i]) * 0.0f;
        acc += vx * 0.0f + vy * 0.0f + vz * 0.0f;
        L::store(sum, acc);
        const T speed_squared = vx * vx + vy * vy + vz * vz, m = L::load(top);
        L::store(top, m < speed_squared ? speed_squared : m);
    });
    float total = 0, m = 0;
    for (uint32_t lane = 0; lane < VectorLanes::width; ++lane) {
        total += sum[lane];
        m = std::max(m, top[lane]);
    }
    max_speed_squared = m;
    return std::isfinite(total);
}

}  // namespace

bool ClothInstance::state_is_finite() const {
    for (uint8_t finite : group_finite_) {
        if (!finite) return false;
    }
    return true;
}

void ClothInstance::check_finite(uint32_t group) {
    // The state the last stage wrote, which becomes x_, v_ after the barrier:
    // self-collision's response velocities, or the first integration's output.
    const bool integrated = cursor_.stage == Stage::kIntegrate;
    const Vec3Soa& x = integrated ? integration_x() : x_;
    const Vec3Soa& v = cursor_.stage == Stage::kSelfRespond ? self_collision_->next_velocities()
                       : integrated                         ? integration_v()
                                                            : v_;
    float speed_squared = 0;
    group_finite_[group] = range_is_finite(x, v, group_begin(group), group_end(group), speed_squared) ? 1 : 0;
    group_speed_squared_[group] = speed_squared;
}

void ClothInstance::set_quality_policy(const QualityPolicy& policy) {
    quality_ = policy;
    if (!policy.enabled) return;
    solver_.iterations = std::clamp(solver_.iterations, policy.min_iterations, policy.max_iterations);
    solver_.substeps = std::clamp(solver_.substeps, policy.min_substeps, policy.max_substeps);
    wake();
}

// ---------------------------------------------------------------- sleep

void ClothInstance::set_sleep(const SleepSettings& settings) {
    sleep_ = settings;
    wake();
}

void ClothInstance::wake() {
    sleeping_ = false;
    rest_frames_ = 0;
}

bool ClothInstance::can_shift_origin(const Vec3& shift) const {
    for (const Vec3Soa* a : {&x_, &pin_target_}) {
        for (size_t i = 0; i < a->size(); ++i) {
            if (!(a->get(i) - shift).allFinite()) return false;
        }
    }
    return true;
}

void ClothInstance::shift_origin(const Vec3& shift) {
    for (Vec3Soa* a : {&x_, &pin_target_}) {
        for (float& c : a->x) c -= shift.x();
        for (float& c : a->y) c -= shift.y();
        for (float& c : a->z) c -= shift.z();
    }
}

void ClothInstance::update_sleep() {
    float speed_squared = 0;
    for (float s : group_speed_squared_) speed_squared = std::max(speed_squared, s);
    const bool at_rest = speed_squared <= sleep_.max_speed * sleep_.max_speed && !contact_.follows_bodies();
    rest_frames_ = at_rest ? rest_frames_ + 1 : 0;
    if (sleep_.enabled && rest_frames_ >= sleep_.frames) {
        // At rest: stop, and cost nothing until something changes.
        sleeping_ = true;
        v_.fill(Vec3::Zero());
    }
}

// ---------------------------------------------------------------- frame

Status ClothInstance::step(float dt, const Vec3& gravity, TaskSystem* tasks) {
    SerialTasks serial;
    TaskSystem& runner = tasks ? *tasks : serial;
    if (sleeping_ && contact_.follows_bodies()) wake();  // bodies move without a call on the cloth
    if (sleeping_) return {};
    begin_frame(dt, gravity);
    while (!frame_done()) {
        prepare_stage();
        auto body = [this](uint32_t begin, uint32_t end, uint32_t worker) {
            for (uint32_t t = begin; t < end; ++t) run_task(t, worker);
        };
        parallel_for(runner, task_count(), 1, body);
        finish_stage();
    }
    return end_frame();
}

SpringModel ClothInstance::spring_model() const {
    SpringModel model = SpringModel::make(frame_solver_.compression_safe_jacobian);
    // The strain cable (springs.h) with a strain limit and an implicit
    // solver; the explicit integrator, whose step a spring 100 times
    // stiffer would blow up, relies on the projection passes alone.
    if (frame_solver_.strain_limit.max_strain > 0 && frame_solver_.kind != CLOTH_SOLVER_EXPLICIT) {
        model.cable_stretch = 1.0f + frame_solver_.strain_limit.max_strain;
        model.cable_factor = kStrainCableStiffness;
    }
    return model;
}

bool ClothInstance::has_air() const {
    return aero_.air_density > 0 && (aero_.drag_coefficient > 0 || aero_.lift_coefficient > 0);
}

void ClothInstance::begin_frame(float dt, const Vec3& gravity) {
    // Only the default solver's choice depends on k / m (a pass over every particle).
    const float stiffness_per_mass =
        solver_.kind == CLOTH_SOLVER_DEFAULT
            ? stiffness_over_mass(material_, mass_.data(), pinned_.data(), particle_count())
            : 0.0f;
    frame_solver_ = resolve_solver(solver_, dt, stiffness_per_mass);
    if (contact_.carrier().active() || frame_solver_.kind == CLOTH_SOLVER_EXPLICIT) {
        backup_ = Backup::kCopied;
        backup_x_ = x_;
        backup_v_ = v_;
    } else {
        backup_ = Backup::kFirstIntegration;
        for (uint32_t i : pinned_list_) pin_velocity_start_.set(i, v_.get(i));
    }
    contact_.begin_step(dt, pinned_.data(), x_, v_);  // carrier (no pass without one)
    collides_ = contact_.collides();
    for (uint32_t i : pinned_list_) pin_start_.set(i, x_.get(i));
    substeps_ = frame_solver_.substeps;
    h_ = dt / static_cast<float>(substeps_);
    gravity_ = gravity;
    frame_converged_ = true;
    frame_out_of_memory_ = false;
    std::fill(group_finite_.begin(), group_finite_.end(), uint8_t{1});
    cursor_ = Cursor{};
    cursor_.stage = first_stage_of_substep();
    frame_done_ = false;
}

Stage ClothInstance::first_stage_of_substep() const { return has_air() ? Stage::kAir : Stage::kForces; }

// The plan of a substep (step_stage.h). The solver dispatch is the branch
// after kForces; post-integration stages are scheduled only when enabled.
Stage ClothInstance::next_stage(Stage current) const {
    switch (current) {
        case Stage::kAir:
            return Stage::kForces;
        case Stage::kForces:
            // Solver dispatch: the explicit baseline needs no system.
            return frame_solver_.kind == CLOTH_SOLVER_EXPLICIT ? Stage::kExplicit : Stage::kAssemble;
        case Stage::kAssemble:
            // Solver dispatch: the stages that turn the assembled system into dv.
            if (frame_solver_.kind == CLOTH_SOLVER_CG) return Stage::kSerialSolve;
            if (frame_solver_.kind == CLOTH_SOLVER_PCG || frame_solver_.kind == CLOTH_SOLVER_CHEBYSHEV)
                return Stage::kIterativeSolve;
            return Stage::kJacobiSweep;
        case Stage::kJacobiSweep:
            return cursor_.sweep + 1 < frame_solver_.iterations ? Stage::kJacobiSweep : Stage::kIntegrate;
        case Stage::kSerialSolve:
            return Stage::kIntegrate;
        case Stage::kIterativeSolve:
            return iterative_.go_on ? Stage::kIterativeSolve : Stage::kIntegrate;
        case Stage::kIntegrate:
        case Stage::kExplicit:
            if (collides_) return Stage::kCollisions;  // issue 6
            return stage_after_collisions();
        case Stage::kCollisions:
            return stage_after_collisions();
        case Stage::kStrainLimit:
            // Rounds alternate corrections (even) and their application (odd).
            if (cursor_.sweep + 1 < 2 * frame_solver_.strain_limit.iterations) return Stage::kStrainLimit;
            return self_collision_ ? Stage::kSelfCollision : Stage::kCount;
        case Stage::kSelfCollision:
            return Stage::kSelfSort;
        case Stage::kSelfSort:
            return Stage::kSelfContacts;
        case Stage::kSelfContacts:
            return Stage::kSelfProject;
        case Stage::kSelfProject:
            // Another pass while overlaps remain (known after the barrier).
            return self_overlapping_ && cursor_.sweep + 1 < self_collision_->settings().passes
                       ? Stage::kSelfProject
                       : Stage::kSelfRespond;
        case Stage::kSelfRespond:
        case Stage::kCount:
            break;
    }
    return Stage::kCount;  // kCount: the substep is over
}

// Where a substep goes once dv is integrated and the colliders have had
// their pass. Post-integration passes plug in here, each behind its feature.
Stage ClothInstance::stage_after_collisions() const {
    if (frame_solver_.strain_limit.max_strain > 0) return Stage::kStrainLimit;
    return self_collision_ ? Stage::kSelfCollision : Stage::kCount;
}

void ClothInstance::prepare_stage() {
    if (cursor_.stage == first_stage_of_substep()) {
        // Pinned particles move linearly towards their frame-end targets.
        const float fraction_end = static_cast<float>(cursor_.substep + 1) / static_cast<float>(substeps_);
        for (uint32_t i : pinned_list_) v_.set(i, (pin_position(i, fraction_end) - x_.get(i)) / h_);
    }
    if (cursor_.stage == Stage::kAssemble) {
        // Assembly writes p = W^-1 b (the first iterate) to dv_; a solver
        // leaves its dv in *sweep_current_.
        sweep_current_ = &dv_;
        sweep_next_ = &dv_scratch_;
    }
}

uint32_t ClothInstance::task_count() const {
    return cursor_.stage == Stage::kSerialSolve || cursor_.stage == Stage::kSelfSort ? 1 : group_count_;
}

void ClothInstance::finish_stage() {
    if (frame_out_of_memory_) {
        frame_done_ = true;
        return;
    }
    switch (cursor_.stage) {
        case Stage::kJacobiSweep:
            std::swap(sweep_current_, sweep_next_);
            break;
        case Stage::kIntegrate:
            if (backup_ == Backup::kFirstIntegration) {
                // The new state is in the backups, the frame-start state in x_, v_: swap.
                swap_buffers(x_, backup_x_);
                swap_buffers(v_, backup_v_);
                backup_ = Backup::kSwapped;
            }
            break;
        case Stage::kSerialSolve:
            frame_converged_ = frame_converged_ && last_solve_.converged;
            break;
        case Stage::kExplicit:
            last_solve_ = SolveReport{};
            break;
        case Stage::kSelfProject:
            self_collision_->apply_positions(x_);
            self_overlapping_ = self_collision_->any_overlapping();
            break;
        case Stage::kSelfRespond:
            self_collision_->apply_velocities(v_);
            break;
        case Stage::kAssemble:
            iterative_.phase = frame_solver_.kind == CLOTH_SOLVER_PCG
                                   ? IterativeSolve::Phase::kPcgStart
                                   : IterativeSolve::Phase::kChebyshevBound;
            break;
        case Stage::kIterativeSolve:
            finish_iterative_stage();
            break;
        default:
            break;
    }
    Stage next = next_stage(cursor_.stage);
    if (cursor_.stage == Stage::kIterativeSolve && next == Stage::kIterativeSolve)
        iterative_.phase = iterative_.next;
    if (cursor_.stage == Stage::kStrainLimit)
        cursor_.sweep = next == Stage::kStrainLimit ? cursor_.sweep + 1 : 0;
    if (cursor_.stage == Stage::kSelfProject)
        cursor_.sweep = next == Stage::kSelfProject ? cursor_.sweep + 1 : 0;
    if (cursor_.stage == Stage::kJacobiSweep) {
        if (next == Stage::kJacobiSweep) {
            ++cursor_.sweep;
        } else {
            last_solve_ = SolveReport{};
            last_solve_.iterations = frame_solver_.iterations;
            cursor_.sweep = 0;
        }
    }
    if (next == Stage::kCount) {
        ++cursor_.substep;
        if (cursor_.substep == substeps_) {
            frame_done_ = true;
            return;
        }
        next = first_stage_of_substep();
    }
    cursor_.stage = next;
}

void ClothInstance::run_task(uint32_t task, uint32_t) {
    switch (cursor_.stage) {
        case Stage::kAir:
            run_air(task);
            break;
        case Stage::kForces:
            run_forces(task);
            break;
        case Stage::kAssemble:
            run_assemble(task);
            break;
        case Stage::kJacobiSweep:
            run_jacobi_sweep(task);
            break;
        case Stage::kSerialSolve:
            run_serial_solve();
            return;
        case Stage::kIterativeSolve:
            run_iterative_solver(task);
            break;
        case Stage::kStrainLimit:
            run_strain_limit(task);
            break;
        case Stage::kIntegrate:
            run_integrate(task);
            break;
        case Stage::kExplicit:
            run_explicit(task);
            break;
        case Stage::kCollisions:
            run_collisions(task);
            break;
        case Stage::kSelfCollision:
        case Stage::kSelfSort:
        case Stage::kSelfContacts:
        case Stage::kSelfProject:
        case Stage::kSelfRespond:
            run_self_collision(task);
            break;
        case Stage::kCount:
            break;
    }
    // The last stage of the frame checks its group for NaN and Inf.
    if (next_stage(cursor_.stage) == Stage::kCount && cursor_.substep + 1 == substeps_) {
        check_finite(task);
    }
}

Status ClothInstance::end_frame() {
    frame_done_ = true;
    if (frame_out_of_memory_) {
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
    last_step_result_ = frame_converged_ ? CLOTH_OK : CLOTH_ERROR_SOLVER_FAILED;
    update_sleep();
    if (!frame_converged_) {
        return Status::error(CLOTH_ERROR_SOLVER_FAILED,
                             "conjugate gradient stopped at its iteration limit (residual %g)",
                             static_cast<double>(last_solve_.residual));
    }
    return {};
}

void ClothInstance::restore_frame_start() {
    switch (backup_) {
        case Backup::kCopied:
            x_ = backup_x_;
            v_ = backup_v_;
            return;
        case Backup::kSwapped:
            swap_buffers(x_, backup_x_);
            swap_buffers(v_, backup_v_);
            break;
        case Backup::kFirstIntegration:
            break;
    }
    // Only pinned velocities changed before the first integration.
    for (uint32_t i : pinned_list_) v_.set(i, pin_velocity_start_.get(i));
}

Vec3 ClothInstance::pin_position(uint32_t i, float frame_fraction) const {
    if (contact_.is_attached(i)) return contact_.attached_position(i, frame_fraction);
    return pin_start_.get(i) + (pin_target_.get(i) - pin_start_.get(i)) * frame_fraction;
}

void ClothInstance::group_items(uint32_t group, uint32_t items, uint32_t& begin, uint32_t& end) const {
    begin = static_cast<uint32_t>(static_cast<uint64_t>(items) * group / group_count_);
    end = static_cast<uint32_t>(static_cast<uint64_t>(items) * (group + 1) / group_count_);
}

// ---------------------------------------------------------------- stages

void ClothInstance::run_air(uint32_t group) {
    uint32_t begin, end;
    group_items(group, air_item_count(*fabric_), begin, end);
    evaluate_air(*fabric_, aero_, x_, v_, begin, end, triangle_force_);
}

CLOTH_HOT_LOOP void ClothInstance::run_forces(uint32_t group) {
    const uint32_t begin = group_begin(group), end = group_end(group);
    // External forces: air (only when the scene has air), gravity, linear drag.
    if (has_air()) {
        gather_air(*fabric_, triangle_force_, begin, end, external_force_);
    } else {
        for (HostVector<float>* a : {&external_force_.x, &external_force_.y, &external_force_.z}) {
            std::fill(a->begin() + begin, a->begin() + end, 0.0f);
        }
    }
    const float linear_drag = aero_.linear_drag;
    const Vec3 gravity = gravity_;
    for_each_lane_group(begin, end, begin, end, [&](auto lanes, uint32_t i) {
        using L = decltype(lanes);
        const typename L::type m = L::load(&mass_[i]), drag = m * linear_drag;
        L::store(&external_force_.x[i],
                 L::load(&external_force_.x[i]) + m * gravity.x() - L::load(&v_.x[i]) * drag);
        L::store(&external_force_.y[i],
                 L::load(&external_force_.y[i]) + m * gravity.y() - L::load(&v_.y[i]) * drag);
        L::store(&external_force_.z[i],
                 L::load(&external_force_.z[i]) + m * gravity.z() - L::load(&v_.z[i]) * drag);
    });
    // Springs: each spring (grid: each first particle) belongs to one group.
    uint32_t spring_begin, spring_end;
    group_items(group, springs_->item_count(), spring_begin, spring_end);
    const float h = frame_solver_.kind == CLOTH_SOLVER_EXPLICIT ? 0.0f : h_;  // h = 0: plain forces
    springs_->evaluate(x_, v_, h, spring_model(), spring_begin, spring_end);
}

void ClothInstance::run_assemble(uint32_t group) {
    // dv_ = p on exit.
    const AssemblyPass assembly{springs_.get(),   &external_force_, mass_.data(), pinned_.data(), h_,
                                aero_.linear_drag};
    assemble_particles(assembly, group_begin(group), group_end(group), diagonal_, diagonal_inverse_, rhs_,
                       dv_);
}

void ClothInstance::run_jacobi_sweep(uint32_t group) {
    const LinearSystem system{springs_.get(), particle_count(), &diagonal_, &diagonal_inverse_,
                              &rhs_,          pinned_.data()};
    jacobi_sweep(system, *sweep_current_, group_begin(group), group_end(group), *sweep_next_);
}

void ClothInstance::run_serial_solve() {
    const LinearSystem system{springs_.get(), particle_count(), &diagonal_, &diagonal_inverse_,
                              &rhs_,          pinned_.data()};
    try {
        last_solve_ =
            solve_cg(system, frame_solver_.cg_tolerance, frame_solver_.cg_max_iterations, *sweep_current_);
    } catch (const std::bad_alloc&) {
        frame_out_of_memory_ = true;  // end_frame restores the cloth
    }
}

LinearSystem ClothInstance::system() const {
    return LinearSystem{springs_.get(), particle_count(), &diagonal_, &diagonal_inverse_,
                        &rhs_,          pinned_.data()};
}

// One group of a PCG or Chebyshev stage (solvers.h). Groups are the
// reduction blocks (kGroupSize == kReductionBlock), so each group writes its
// own partial sum and the sums do not depend on the workers.
void ClothInstance::run_iterative_solver(uint32_t group) {
    const LinearSystem sys = system();
    const uint32_t begin = group_begin(group), end = group_end(group);
    switch (iterative_.phase) {
        case IterativeSolve::Phase::kPcgStart:
            pcg_start(sys, dv_, begin, end, solver_work_);
            break;
        case IterativeSolve::Phase::kPcgProduct:
            pcg_product(sys, begin, end, solver_work_);
            break;
        case IterativeSolve::Phase::kPcgUpdate:
            pcg_update(sys, iterative_.alpha, begin, end, dv_, solver_work_);
            break;
        case IterativeSolve::Phase::kPcgDirection:
            pcg_direction(iterative_.beta, begin, end, solver_work_);
            break;
        case IterativeSolve::Phase::kChebyshevBound: {
            const AssemblyPass assembly{springs_.get(),   &external_force_, mass_.data(), pinned_.data(), h_,
                                        aero_.linear_drag};
            solver_work_.partial[group] = chebyshev_lower_bound(sys, assembly, begin, end);
            break;
        }
        case IterativeSolve::Phase::kChebyshevStart:
            chebyshev_start(sys, dv_, static_cast<float>(1.0 / (iterative_.sigma * iterative_.delta)), begin,
                            end, solver_work_);
            break;
        case IterativeSolve::Phase::kChebyshevProduct:
            chebyshev_product(sys, begin, end, dv_, solver_work_);
            break;
        case IterativeSolve::Phase::kChebyshevEnergy:
            chebyshev_energy(sys, dv_, begin, end, solver_work_);
            break;
        case IterativeSolve::Phase::kChebyshevScale:
            chebyshev_scale(static_cast<float>(iterative_.step_scale), begin, end, dv_);
            break;
        case IterativeSolve::Phase::kChebyshevDirection: {
            const double rho_next = 1.0 / (2.0 * iterative_.sigma - iterative_.rho);
            chebyshev_direction(sys, static_cast<float>(rho_next * iterative_.rho),
                                static_cast<float>(2.0 * rho_next / iterative_.delta), begin, end,
                                solver_work_);
            break;
        }
    }
}

// After the barrier of an iterative solver's stage: the scalars of the
// next stage (the same sequence solve_pcg / solve_chebyshev run).
void ClothInstance::finish_iterative_stage() {
    IterativeSolve& it = iterative_;
    const uint32_t budget = frame_solver_.iterations;
    const double tolerance = frame_solver_.cg_tolerance;
    switch (iterative_.phase) {
        case IterativeSolve::Phase::kPcgStart:
            it.rz0 = it.rz = sum_partials(solver_work_);
            cursor_.sweep = 0;
            it.go_on = budget > 0 && it.rz > 0 && it.rz > tolerance * tolerance * it.rz0;
            it.next = IterativeSolve::Phase::kPcgProduct;
            break;
        case IterativeSolve::Phase::kPcgProduct: {
            const double pq = sum_partials(solver_work_);
            it.go_on = pq > 0;  // W is positive definite; pq <= 0 only from round-off at convergence
            if (it.go_on) it.alpha = it.rz / pq;
            it.next = IterativeSolve::Phase::kPcgUpdate;
            break;
        }
        case IterativeSolve::Phase::kPcgUpdate: {
            const double rz_next = sum_partials(solver_work_);
            ++cursor_.sweep;
            it.go_on = cursor_.sweep < budget && rz_next > tolerance * tolerance * it.rz0;
            it.beta = rz_next / it.rz;
            it.rz = rz_next;
            it.next = IterativeSolve::Phase::kPcgDirection;
            break;
        }
        case IterativeSolve::Phase::kChebyshevBound: {
            double a = 1.0;
            for (double partial : solver_work_.partial) a = std::min(a, partial);
            const double theta = 0.5 * (2.0 + a);
            it.delta = 0.5 * (2.0 - a);
            it.sigma = theta / it.delta;
            it.rho = 1.0 / it.sigma;
            cursor_.sweep = 0;
            it.go_on = true;
            it.next = IterativeSolve::Phase::kChebyshevStart;
            break;
        }
        case IterativeSolve::Phase::kChebyshevStart:
            it.go_on = true;
            it.next = IterativeSolve::Phase::kChebyshevProduct;
            break;
        case IterativeSolve::Phase::kChebyshevProduct:
            ++cursor_.sweep;
            it.go_on = true;  // another iteration, or the line search (solvers.h)
            if (cursor_.sweep < budget) {
                if (cursor_.sweep > 1) it.rho = 1.0 / (2.0 * it.sigma - it.rho);
                it.next = IterativeSolve::Phase::kChebyshevDirection;
            } else {
                it.next = IterativeSolve::Phase::kChebyshevEnergy;
            }
            break;
        case IterativeSolve::Phase::kChebyshevEnergy:
            it.step_scale = chebyshev_step_scale(solver_work_);
            it.go_on = it.step_scale != 1.0;
            it.next = IterativeSolve::Phase::kChebyshevScale;
            break;
        case IterativeSolve::Phase::kChebyshevScale:
            it.go_on = false;
            break;
        case IterativeSolve::Phase::kPcgDirection:
            it.go_on = true;
            it.next = IterativeSolve::Phase::kPcgProduct;
            break;
        case IterativeSolve::Phase::kChebyshevDirection:
            it.go_on = true;
            it.next = IterativeSolve::Phase::kChebyshevProduct;
            break;
    }
    if (!it.go_on) {
        last_solve_ = SolveReport{};
        last_solve_.iterations = cursor_.sweep;
        if (frame_solver_.kind == CLOTH_SOLVER_PCG && it.rz0 > 0) {
            last_solve_.residual = static_cast<float>(std::sqrt(std::max(it.rz, 0.0) / it.rz0));
        }
        cursor_.sweep = 0;
    }
}

void ClothInstance::run_strain_limit(uint32_t group) {
    const StrainLimitPass pass{fabric_.get(), mass_.data(), pinned_.data(),
                               frame_solver_.strain_limit.max_strain};
    const uint32_t begin = group_begin(group), end = group_end(group);
    if (cursor_.sweep % 2 == 0) {
        strain_limit_corrections(pass, x_, begin, end, solver_work_.r);
    } else {
        // Contact and strain limit are resolved together: each round's
        // moves (along straight springs) are taken back out of the
        // colliders at once, so the next round sees where the particles
        // really are. Limiting after the colliders alone would pull a
        // spring that wraps a thin collider (the flag round its pole)
        // through it; colliders after the limiter alone would push both
        // ends back out on their own sides every substep, undoing the limit.
        strain_limit_apply(solver_work_.r, h_, begin, end, x_, v_);
        if (collides_) run_collisions(group);
    }
}

CLOTH_HOT_LOOP void ClothInstance::run_integrate(uint32_t group) {
    // dv is zero on pinned particles; they are placed below. Writes to x_, v_
    // or, on the frame's first integration, to the spare buffers.
    const Vec3Soa& dv = *sweep_current_;
    Vec3Soa& x_out = integration_x();
    Vec3Soa& v_out = integration_v();
    const uint32_t begin = group_begin(group), end = group_end(group);
    const float h = h_;
    for_each_lane_group(begin, end, begin, end, [&](auto lanes, uint32_t i) {
        using L = decltype(lanes);
        const typename L::type vx = L::load(&v_.x[i]) + L::load(&dv.x[i]);
        const typename L::type vy = L::load(&v_.y[i]) + L::load(&dv.y[i]);
        const typename L::type vz = L::load(&v_.z[i]) + L::load(&dv.z[i]);
        store_vec3<L>(x_out, i, L::load(&x_.x[i]) + vx * h, L::load(&x_.y[i]) + vy * h,
                      L::load(&x_.z[i]) + vz * h);
        store_vec3<L>(v_out, i, vx, vy, vz);
    });
    land_pins(begin, end, x_out);
}

void ClothInstance::run_explicit(uint32_t group) {
    // Plain spring forces (evaluated with h = 0), then symplectic Euler.
    const uint32_t begin = group_begin(group), end = group_end(group);
    springs_->gather(begin, end, external_force_, nullptr);
    integrate_explicit(external_force_, mass_.data(), pinned_.data(), h_, begin, end, v_, x_);
    land_pins(begin, end, x_);
}

void ClothInstance::run_self_collision(uint32_t group) {
    SelfCollision& c = *self_collision_;
    const uint32_t begin = group_begin(group), end = group_end(group);
    switch (cursor_.stage) {
        case Stage::kSelfCollision: {
            uint32_t region_begin, region_end;
            group_items(group, c.region_count(), region_begin, region_end);
            c.check_regions(x_, region_begin, region_end);
            c.compute_keys(x_, begin, end);
            break;
        }
        case Stage::kSelfSort:
            c.sort_into_buckets(x_);
            break;
        case Stage::kSelfContacts:
            c.find_contacts(x_, begin, end);
            c.compute_inverse_mass(mass_.data(), pinned_.data(), begin, end);
            break;
        case Stage::kSelfProject:
            c.project(x_, begin, end);
            break;
        case Stage::kSelfRespond:
            c.respond_velocities(x_, v_, begin, end);
            break;
        default:
            break;
    }
}

void ClothInstance::land_pins(uint32_t begin, uint32_t end, Vec3Soa& x) {
    // Pinned particles land exactly on their substep targets.
    const float fraction_end = static_cast<float>(cursor_.substep + 1) / static_cast<float>(substeps_);
    auto first = std::lower_bound(pinned_list_.begin(), pinned_list_.end(), begin);
    for (auto it = first; it != pinned_list_.end() && *it < end; ++it) {
        x.set(*it, pin_position(*it, fraction_end));
    }
}

void ClothInstance::run_collisions(uint32_t group) {
    // Particles against the world's colliders over this substep (colliders.h).
    const float from = static_cast<float>(cursor_.substep) / static_cast<float>(substeps_);
    const float to = static_cast<float>(cursor_.substep + 1) / static_cast<float>(substeps_);
    contact_.collide(h_, from, to, pinned_.data(), group_begin(group), group_end(group), x_, v_);
}

}  // namespace cloth
