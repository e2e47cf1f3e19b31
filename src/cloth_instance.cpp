// One frame of one cloth, as a fixed sequence of stages (algorithm.md 4):
//
//   per substep h = dt / substeps:
//     0. per particle: kinematic velocities of pinned particles
//     1. per triangle: air forces;  per particle: gather + gravity + drag
//     2. per spring:   force, J, A_s (paper Code 4)
//     3. per particle: W_ii, W_ii^-1, b_i, p_i (paper Code 1)
//     4. solver:       dv (Jacobi: per-particle gathers; CG: reference)
//     5. per particle: v += dv, x += h v
//
// Every stage is a loop over a range of particles, springs or triangles
// that reads the previous stage's output only, with a barrier between
// stages; all sums are gathers in the fabric's fixed order. That makes the
// step parallel without atomics and bit-identical for any split of ranges.
#include "cloth_instance.h"

#include <algorithm>
#include <cmath>

#include "aerodynamics.h"
#include "integrator_explicit.h"
#include "lanes.h"
#include "solvers.h"
#include "spring_terms.h"
#include "springs.h"

namespace cloth {

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
      normals_(memory),
      backup_x_(memory),
      backup_v_(memory) {
    const Fabric& f = *fabric_;
    const uint32_t n = f.particle_count();
    for (Vec3Soa* a : {&x_, &v_, &pin_target_, &pin_start_, &external_force_, &rhs_, &dv_, &dv_scratch_,
                       &normals_, &backup_x_, &backup_v_}) {
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
    set_material(material);
}

void ClothInstance::set_material(const Material& material) {
    material_ = material;
    const Fabric& f = *fabric_;
    for (uint32_t i = 0; i < f.particle_count(); ++i) {
        mass_[i] =
            material.particle_mass > 0 ? material.particle_mass : material.area_density * f.rest_area[i];
    }
    springs_->set_material(material);
}

void ClothInstance::set_pinned(const uint32_t* particles, uint32_t count, bool pinned) {
    for (uint32_t k = 0; k < count; ++k) {
        const uint32_t i = particles[k];
        if (pinned) pin_target_.set(i, x_.get(i));
        pinned_[i] = pinned ? 1.0f : 0.0f;
    }
    pinned_list_.clear();  // keeps its capacity of one entry per particle
    for (uint32_t i = 0; i < particle_count(); ++i) {
        if (pinned_[i] != 0.0f) pinned_list_.push_back(i);
    }
}

void ClothInstance::set_position(uint32_t particle, const Vec3& x) {
    x_.set(particle, x);
    v_.set(particle, Vec3::Zero());
    pin_target_.set(particle, x);
}

const Vec3Soa& ClothInstance::normals() const {
    compute_vertex_normals(*fabric_, x_, 0, particle_count(), normals_);
    return normals_;
}

CLOTH_HOT_LOOP bool ClothInstance::state_is_finite() const {
    // x * 0 is 0 for finite x and NaN otherwise; NaN survives any sum.
    const uint32_t n = particle_count();
    float sum[VectorLanes::width] = {};
    for_each_lane_group(0, n, 0, n, [&](auto lanes, uint32_t i) {
        using L = decltype(lanes);
        typename L::type acc = L::load(sum);
        for (const Vec3Soa* a : {&x_, &v_}) {
            acc += L::load(&a->x[i]) * 0.0f + L::load(&a->y[i]) * 0.0f + L::load(&a->z[i]) * 0.0f;
        }
        L::store(sum, acc);
    });
    float total = 0;
    for (float s : sum) total += s;
    return std::isfinite(total);
}

Status ClothInstance::step(float dt, const Vec3& gravity) {
    backup_x_ = x_;
    backup_v_ = v_;
    for (uint32_t i : pinned_list_) pin_start_.set(i, x_.get(i));
    const uint32_t substeps = solver_.substeps;
    const float h = dt / static_cast<float>(substeps);
    bool converged = true;
    try {
        for (uint32_t k = 0; k < substeps; ++k) {
            substep(h, static_cast<float>(k + 1) / static_cast<float>(substeps), gravity);
            converged = converged && last_solve_.converged;
        }
    } catch (const std::bad_alloc&) {
        // Only the CG reference solver allocates during a step.
        x_ = backup_x_;
        v_ = backup_v_;
        last_step_result_ = CLOTH_ERROR_OUT_OF_MEMORY;
        return Status::error(
            CLOTH_ERROR_OUT_OF_MEMORY,
            "the solver could not allocate; the cloth was restored to its state before the step");
    }
    if (!state_is_finite()) {
        x_ = backup_x_;
        v_ = backup_v_;
        last_step_result_ = CLOTH_ERROR_NONFINITE_STATE;
        return Status::error(
            CLOTH_ERROR_NONFINITE_STATE,
            "the step produced a non-finite state; the cloth was restored to its state before "
            "the step (lower dt, raise substeps or iterations, or use a sturdier solver)");
    }
    last_step_result_ = converged ? CLOTH_OK : CLOTH_ERROR_SOLVER_FAILED;
    if (!converged) {
        return Status::error(CLOTH_ERROR_SOLVER_FAILED,
                             "conjugate gradient stopped at its iteration limit (residual %g)",
                             static_cast<double>(last_solve_.residual));
    }
    return {};
}

Vec3 ClothInstance::pin_position(uint32_t i, float frame_fraction) const {
    return pin_start_.get(i) + (pin_target_.get(i) - pin_start_.get(i)) * frame_fraction;
}

CLOTH_HOT_LOOP void ClothInstance::substep(float h, float frame_fraction_end, const Vec3& gravity) {
    const Fabric& f = *fabric_;
    const uint32_t n = f.particle_count();

    // 0. Pinned particles move linearly towards their frame-end targets.
    for (uint32_t i : pinned_list_) v_.set(i, (pin_position(i, frame_fraction_end) - x_.get(i)) / h);

    // 1. External forces: air (only when the scene has air), gravity, linear drag.
    const bool has_air = aero_.air_density > 0 && (aero_.drag_coefficient > 0 || aero_.lift_coefficient > 0);
    if (has_air) {
        evaluate_air(f, aero_, x_, v_, 0, air_item_count(f), triangle_force_);
        gather_air(f, triangle_force_, 0, n, external_force_);
    } else {
        external_force_.fill(Vec3::Zero());
    }
    const float linear_drag = aero_.linear_drag;
    for_each_lane_group(0, n, 0, n, [&](auto lanes, uint32_t i) {
        using L = decltype(lanes);
        const typename L::type m = L::load(&mass_[i]), drag = m * linear_drag;
        L::store(&external_force_.x[i],
                 L::load(&external_force_.x[i]) + m * gravity.x() - L::load(&v_.x[i]) * drag);
        L::store(&external_force_.y[i],
                 L::load(&external_force_.y[i]) + m * gravity.y() - L::load(&v_.y[i]) * drag);
        L::store(&external_force_.z[i],
                 L::load(&external_force_.z[i]) + m * gravity.z() - L::load(&v_.z[i]) * drag);
    });

    const JacobianClamp clamp = JacobianClamp::make(solver_.compression_safe_jacobian);
    if (solver_.kind == CLOTH_SOLVER_EXPLICIT) {
        // Plain spring forces (h = 0 drops the implicit terms), then Euler.
        springs_->evaluate(x_, v_, 0.0f, clamp, 0, springs_->item_count());
        springs_->gather(0, n, external_force_, nullptr);
        integrate_explicit(external_force_, mass_.data(), pinned_.data(), h, 0, n, v_, x_);
        last_solve_ = SolveReport{};
    } else {
        // 2. Springs.  3. Particle assembly (dv_ = p on exit).
        springs_->evaluate(x_, v_, h, clamp, 0, springs_->item_count());
        const AssemblyPass assembly{springs_.get(),   &external_force_, mass_.data(), pinned_.data(), h,
                                    aero_.linear_drag};
        assemble_particles(assembly, 0, n, diagonal_, diagonal_inverse_, rhs_, dv_);
        // 4. Solve.
        const LinearSystem system{springs_.get(), n, &diagonal_, &diagonal_inverse_, &rhs_, pinned_.data()};
        if (solver_.kind == CLOTH_SOLVER_CG) {
            last_solve_ = solve_cg(system, solver_.cg_tolerance, solver_.cg_max_iterations, dv_);
        } else {
            last_solve_ = solve_jacobi(system, solver_.iterations, dv_, dv_scratch_);
        }
        // 5. Integrate (dv is zero on pinned particles; they are placed below).
        for_each_lane_group(0, n, 0, n, [&](auto lanes, uint32_t i) {
            using L = decltype(lanes);
            const typename L::type vx = L::load(&v_.x[i]) + L::load(&dv_.x[i]);
            const typename L::type vy = L::load(&v_.y[i]) + L::load(&dv_.y[i]);
            const typename L::type vz = L::load(&v_.z[i]) + L::load(&dv_.z[i]);
            store_vec3<L>(v_, i, vx, vy, vz);
            store_vec3<L>(x_, i, L::load(&x_.x[i]) + vx * h, L::load(&x_.y[i]) + vy * h,
                          L::load(&x_.z[i]) + vz * h);
        });
    }

    // Pinned particles land exactly on their substep targets.
    for (uint32_t i : pinned_list_) x_.set(i, pin_position(i, frame_fraction_end));
}

}  // namespace cloth
