// The stages of a substep, each the body of one task (one particle group)
// unless it says otherwise; frame_plan.cpp says in which order they run.
// Each body starts by checking that it runs as its planned stage.
#include <algorithm>
#include <cmath>
#include <new>

#include "base/lanes.h"
#include "collide/self_collision.h"
#include "forces/aerodynamics.h"
#include "forces/spring_terms.h"
#include "solve/integrate.h"
#include "solve/solver_default.h"
#include "step/cloth_instance.h"

namespace cloth {

LinearSystem ClothInstance::system() const {
    return LinearSystem{springs_.get(), particle_count(),   &system_.diagonal, &system_.diagonal_inverse,
                        &system_.rhs,   pins_.pinned.data()};
}

AssemblyPass ClothInstance::assembly() const {
    return AssemblyPass{springs_.get(), &system_.external_force, mass_.data(), pins_.pinned.data(),
                        frame_.h,       aero_.linear_drag,       frame_.theta};
}

SpringModel ClothInstance::spring_model() const {
    SpringModel model = SpringModel::make(frame_.decision.solver.compression_safe_jacobian);
    // The strain cable (springs.h) with a strain limit and an implicit
    // solver; the explicit integrator, whose step a spring 100 times
    // stiffer would blow up, relies on the projection passes alone.
    if (frame_.decision.solver.strain_limit.max_strain > 0 &&
        frame_.decision.solver.kind != CLOTH_SOLVER_EXPLICIT) {
        // The passes hold the limit, or what the pins demand where that is
        // more (Tethers::strain_pins_demand). The default's cable takes a
        // held cloth's load just inside that, where the passes leave it at
        // rest (solver_default.h).
        const bool inside = solver_.kind == CLOTH_SOLVER_DEFAULT;
        const float limit = frame_.decision.solver.strain_limit.max_strain,
                    demand = frame_.strain_pins_demand;
        float cable = std::max(limit, demand);
        if (inside)
            cable =
                demand > limit ? demand - limit * (1.0f - kStrainCableInside) : limit * kStrainCableInside;
        model.cable_stretch = 1.0f + cable;
        model.cable_factor = kStrainCableStiffness;
        model.cable_approach = inside ? limit * kStrainCableApproach : 0.0f;
    }
    return model;
}

bool ClothInstance::has_air() const {
    return aero_.air_density > 0 && (aero_.drag_coefficient > 0 || aero_.lift_coefficient > 0);
}

Vec3 ClothInstance::pin_position(uint32_t i, float frame_fraction) const {
    if (contact_.is_attached(i)) return contact_.attached_position(i, frame_fraction);
    return frame_.pin_start.get(i) + (pins_.target.get(i) - frame_.pin_start.get(i)) * frame_fraction;
}

void ClothInstance::land_pins(uint32_t begin, uint32_t end, Vec3Soa& x) {
    // Pinned particles land exactly on their substep targets.
    const float fraction_end = substep_end_fraction();
    auto first = std::lower_bound(pins_.list.begin(), pins_.list.end(), begin);
    for (auto it = first; it != pins_.list.end() && *it < end; ++it) {
        x.set(*it, pin_position(*it, fraction_end));
    }
}

// ---------------------------------------------------------------- stages, in plan order

void ClothInstance::move_pins() {
    // Pinned particles move linearly towards their frame-end targets.
    const float fraction_end = substep_end_fraction();
    for (uint32_t i : pins_.list) v_.set(i, (pin_position(i, fraction_end) - x_.get(i)) / frame_.h);
    frame_.strain_pins_demand = limits_strain() ? strain_.tethers.strain_pins_demand(x_, v_, frame_.h) : 0.0f;
}

void ClothInstance::skin_particles(const GroupTask& task) {
    expect_stage(Stage::kSkinning);
    skin_.skin(task.begin, task.end);
    if (!skin_.sized_for(particle_count())) return;
    // Across a jump the particles pinned to the skin start the frame on it.
    const bool jump = skin_.jumping();
    for (uint32_t i = task.begin; i < task.end; ++i) {
        if (!is_pinned(i) || !skin_pins(i)) continue;
        const Vec3 target = skin_.position(i, 1.0f);
        pins_.target.set(i, target);
        if (jump) {
            x_.set(i, target);
            frame_.pin_start.set(i, target);
        }
    }
}

void ClothInstance::finish_skinning() { skin_.finish_skinning(); }

void ClothInstance::apply_air(const GroupTask& task) {
    expect_stage(Stage::kAir);
    uint32_t begin, end;
    task.items(air_item_count(*fabric_), begin, end);
    evaluate_air(*fabric_, aero_, x_, v_, begin, end, system_.triangle_force);
}

CLOTH_HOT_LOOP void ClothInstance::evaluate_forces(const GroupTask& task) {
    expect_stage(Stage::kForces);
    const uint32_t begin = task.begin, end = task.end;
    // External forces: air (only when the scene has air), gravity, linear drag.
    if (has_air()) {
        gather_air(*fabric_, system_.triangle_force, begin, end, system_.external_force);
    } else {
        for (HostVector<float>* a :
             {&system_.external_force.x, &system_.external_force.y, &system_.external_force.z}) {
            std::fill(a->begin() + begin, a->begin() + end, 0.0f);
        }
    }
    const float linear_drag = aero_.linear_drag;
    const Vec3 gravity = frame_.gravity;
    for_each_lane_group(begin, end, begin, end, [&](auto lanes, uint32_t i) {
        using L = decltype(lanes);
        const typename L::type m = L::load(&mass_[i]), drag = m * linear_drag;
        L::store(&system_.external_force.x[i],
                 L::load(&system_.external_force.x[i]) + m * gravity.x() - L::load(&v_.x[i]) * drag);
        L::store(&system_.external_force.y[i],
                 L::load(&system_.external_force.y[i]) + m * gravity.y() - L::load(&v_.y[i]) * drag);
        L::store(&system_.external_force.z[i],
                 L::load(&system_.external_force.z[i]) + m * gravity.z() - L::load(&v_.z[i]) * drag);
    });
    // Springs: each spring (grid: each first particle) belongs to one group.
    uint32_t spring_begin, spring_end;
    task.items(springs_->item_count(), spring_begin, spring_end);
    // h = 0: plain forces; the theta step takes them at theta h (integrate.h).
    const float h = frame_.decision.solver.kind == CLOTH_SOLVER_EXPLICIT ? 0.0f : frame_.theta * frame_.h;
    springs_->evaluate(x_, v_, h, spring_model(), spring_begin, spring_end);
}

void ClothInstance::integrate_explicitly(const GroupTask& task) {
    expect_stage(Stage::kExplicit);
    // Plain spring forces (evaluated with h = 0), then symplectic Euler.
    springs_->gather(task.begin, task.end, system_.external_force, nullptr);
    integrate_explicit(system_.external_force, mass_.data(), pins_.pinned.data(), frame_.h, task.begin,
                       task.end, v_, x_);
    land_pins(task.begin, task.end, x_);
}

void ClothInstance::report_explicit_solve() { last_solve_ = SolveReport{}; }

void ClothInstance::assemble_system(const GroupTask& task) {
    expect_stage(Stage::kAssemble);
    // system_.dv = p on exit: the solvers' first iterate.
    assemble_particles(assembly(), task.begin, task.end, system_.diagonal, system_.diagonal_inverse,
                       system_.rhs, system_.dv);
}

void ClothInstance::solve_by_cg(const GroupTask&) {
    expect_stage(Stage::kSerialSolve);
    try {
        last_solve_ = solve_cg(system(), frame_.decision.solver.cg_tolerance,
                               frame_.decision.solver.cg_max_iterations, system_.dv);
    } catch (const std::bad_alloc&) {
        frame_.out_of_memory = true;  // end_frame restores the cloth
    }
}

void ClothInstance::record_cg_result() { frame_.converged = frame_.converged && last_solve_.converged; }

void ClothInstance::iterate_solver(const GroupTask& task) {
    expect_stage(frame_.decision.solver.kind == CLOTH_SOLVER_JACOBI ? Stage::kJacobiSweep
                                                                    : Stage::kIterativeSolve);
    frame_.iterative.run(task);
}

void ClothInstance::record_iterative_result() {
    if (!frame_.iterative.done()) return;
    last_solve_ = frame_.iterative.report();
    frame_.solution = &frame_.iterative.solution();
}

void ClothInstance::integrate_implicitly(const GroupTask& task) {
    expect_stage(Stage::kIntegrate);
    // dv is zero on pinned particles; they are placed below. Writes to x_, v_
    // or, on the frame's first integration, to the spare buffers.
    Vec3Soa& x_out = integration_x();
    integrate_implicit(x_, v_, *frame_.solution, frame_.h, frame_.theta, task.begin, task.end, x_out,
                       integration_v());
    land_pins(task.begin, task.end, x_out);
}

void ClothInstance::adopt_first_integration() {
    if (frame_.backup != FrameBackup::kFirstIntegration) return;
    // The new state is in the backups, the frame-start state in x_, v_: swap.
    x_.swap_buffers(frame_.backup_x);
    v_.swap_buffers(frame_.backup_v);
    frame_.backup = FrameBackup::kSwapped;
}

void ClothInstance::constrain_to_skin(const GroupTask& task) {
    expect_stage(Stage::kSkinConstraints);
    hold_to_skin(task, limits_strain());  // the limiter's first round prepared the skin
}

void ClothInstance::hold_to_skin(const GroupTask& task, bool prepared) {
    skin_.constrain(task.begin, task.end, substep_end_fraction(), frame_.h, pins_.pinned.data(), x_, v_,
                    prepared);
}

float ClothInstance::substep_end_fraction() const {
    return static_cast<float>(frame_.substep + 1) / static_cast<float>(frame_.decision.solver.substeps);
}

void ClothInstance::collide_stage(const GroupTask& task) {
    expect_stage(Stage::kCollisions);
    collide(task, ClothContact::Pass::kEvery, &frame_.group_contacts[task.group]);
}

void ClothInstance::note_contacts() {
    frame_.touching = std::any_of(frame_.group_contacts.begin(), frame_.group_contacts.end(),
                                  [](uint32_t n) { return n > 0; });
}

void ClothInstance::collide(const GroupTask& task, ClothContact::Pass pass, uint32_t* contacts) {
    // Particles against the world's colliders over this substep (colliders.h).
    const float from =
        static_cast<float>(frame_.substep) / static_cast<float>(frame_.decision.solver.substeps);
    const float to = substep_end_fraction();
    const uint32_t found =
        contact_.collide(frame_.h, from, to, pins_.pinned.data(), task.begin, task.end, x_, v_, pass);
    if (contacts) *contacts = found;
}

void ClothInstance::limit_strain(const GroupTask& task) {
    expect_stage(Stage::kStrainLimit);
    switch (frame_.limit_rounds.round()) {  // limit_rounds.h: what runs between the passes, and why
        case LimitRounds::Round::kColliders:
            collide(task, frame_.collider_pass);
            return;
        case LimitRounds::Round::kProject:
        case LimitRounds::Round::kRespond:
            self_between_passes(frame_.limit_rounds.round(), frame_.strain_limiter, task);
            return;
        case LimitRounds::Round::kPass:
            break;
    }
    // The skin's constraints run several times in the substep: its
    // skinned positions and normals are worked out once, in the first round.
    const bool skin = skin_.active() && skin_.constrains();
    if (skin && frame_.round == 0) skin_.prepare(task.begin, task.end, substep_end_fraction());
    // The skin's constraints follow every pass's application, as
    // in Jolt's and NvCloth's iterations, so the next pass limits the
    // springs where the skin holds their ends: run only after the last
    // pass, they undid it and left the cape stretched 25-fold in a
    // fast turn (docs/measurements.md, "The skin's constraints between
    // the strain limiter's passes"). They touch only this group's
    // particles, so they share the pass's task.
    const bool applying = frame_.strain_limiter.applying();
    frame_.strain_limiter.run(task);
    if (applying && skin) hold_to_skin(task, true);
}

void ClothInstance::self_between_passes(LimitRounds::Round round, StrainLimiter& limiter,
                                        const GroupTask& task) {
    if (round == LimitRounds::Round::kProject) {
        self_collision_->project(x_, task.begin, task.end);
        limiter.moved_between_passes(x_, self_collision_->next_positions(), task.begin, task.end);
    } else {
        self_collision_->respond_velocities(x_, v_, task.begin, task.end);
    }
}

void ClothInstance::run_pair_contact(const GroupTask& task) { planned_pair().run(task); }

void ClothInstance::respond_to_pairs(const GroupTask& task) {
    expect_stage(Stage::kClothContactRespond);
    for (uint32_t k = 0; k < frame_.pair_count; ++k) {
        const PairRounds::Side& side = *frame_.pairs[k];
        side.pair().contact().respond_side(side.side(), x_, v_, task.begin, task.end);
    }
}

void ClothInstance::note_strain() {
    if (!frame_.strain_limiter.done()) return;
    frame_.strained = frame_.strain_limiter.past_promise();
    frame_.limit_held |= frame_.strain_limiter.held();
    frame_.strain_passes += frame_.strain_limiter.passes();
    frame_.strain_capped |= frame_.strain_limiter.capped();
}

void ClothInstance::resolve_self_contacts(const GroupTask& task) {
    expect_stage(Stage::kSelfCollision);
    self_collision_->run(task);
}

// ---------------------------------------------------------------- finite check

namespace {

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

void ClothInstance::check_finite(uint32_t group) {
    // The state the last round wrote, which becomes x_, v_ after the barrier:
    // self-collision's response velocities or projected positions, or the
    // first integration's output.
    const Stage stage = planned().stage;
    const bool integrated = stage == Stage::kIntegrate;
    const LimitRounds::Round between =
        stage == Stage::kStrainLimit ? frame_.limit_rounds.round() : LimitRounds::Round::kPass;
    const bool responded = stage == Stage::kSelfCollision || between == LimitRounds::Round::kRespond;
    const Vec3Soa& x = integrated                                ? integration_x()
                       : between == LimitRounds::Round::kProject ? self_collision_->next_positions()
                                                                 : x_;
    const Vec3Soa& v = responded ? self_collision_->next_velocities() : integrated ? integration_v() : v_;
    const GroupTask task = group_task(group);
    float speed_squared = 0;
    frame_.group_finite[group] = range_is_finite(x, v, task.begin, task.end, speed_squared) ? 1 : 0;
    frame_.group_speed_squared[group] = speed_squared;
}

bool ClothInstance::state_is_finite() const {
    for (uint8_t finite : frame_.group_finite) {
        if (!finite) return false;
    }
    return true;
}

}  // namespace cloth
