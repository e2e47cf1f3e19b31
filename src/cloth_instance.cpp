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

#include "aerodynamics.h"
#include "integrator_explicit.h"
#include "solvers.h"
#include "springs.h"

namespace cloth {

ClothInstance::ClothInstance(const HostMemory* memory, std::shared_ptr<const Fabric> fabric,
                             const Material& material, const SolverSettings& solver, const AeroParams& aero)
    : fabric_(std::move(fabric)),
      material_(material),
      solver_(solver),
      aero_(aero),
      x_(HostAllocator<Vec3>(memory)),
      v_(HostAllocator<Vec3>(memory)),
      mass_(HostAllocator<float>(memory)),
      pinned_(HostAllocator<uint8_t>(memory)),
      pin_target_(HostAllocator<Vec3>(memory)),
      pin_start_(HostAllocator<Vec3>(memory)),
      external_force_(HostAllocator<Vec3>(memory)),
      triangle_force_(HostAllocator<Vec3>(memory)),
      spring_force_(HostAllocator<Vec3>(memory)),
      spring_block_(HostAllocator<Sym3>(memory)),
      diagonal_(HostAllocator<Sym3>(memory)),
      diagonal_inverse_(HostAllocator<Sym3>(memory)),
      rhs_(HostAllocator<Vec3>(memory)),
      dv_(HostAllocator<Vec3>(memory)),
      dv_scratch_(HostAllocator<Vec3>(memory)),
      normals_(HostAllocator<Vec3>(memory)),
      backup_x_(HostAllocator<Vec3>(memory)),
      backup_v_(HostAllocator<Vec3>(memory)) {
    const Fabric& f = *fabric_;
    const uint32_t n = f.particle_count();
    x_.assign(f.rest_positions.begin(), f.rest_positions.end());
    v_.assign(n, Vec3::Zero());
    mass_.resize(n);
    pinned_.assign(n, 0);
    pin_target_.assign(n, Vec3::Zero());
    pin_start_.assign(n, Vec3::Zero());
    external_force_.resize(n);
    triangle_force_.resize(f.triangle_count());
    spring_force_.resize(f.spring_count());
    spring_block_.resize(f.spring_count());
    diagonal_.resize(n);
    diagonal_inverse_.resize(n);
    rhs_.resize(n);
    dv_.resize(n);
    dv_scratch_.resize(n);
    normals_.resize(n);
    backup_x_.resize(n);
    backup_v_.resize(n);
    set_material(material);
}

void ClothInstance::set_material(const Material& material) {
    material_ = material;
    const Fabric& f = *fabric_;
    for (uint32_t i = 0; i < f.particle_count(); ++i) {
        mass_[i] = material.particle_mass > 0 ? material.particle_mass : material.area_density * f.rest_area[i];
    }
}

void ClothInstance::pin(uint32_t particle) {
    pinned_[particle] = 1;
    pin_target_[particle] = x_[particle];
}

void ClothInstance::unpin(uint32_t particle) { pinned_[particle] = 0; }

void ClothInstance::set_position(uint32_t particle, const Vec3& x) {
    x_[particle] = x;
    v_[particle].setZero();
    pin_target_[particle] = x;
}

const HostVector<Vec3>& ClothInstance::normals() const {
    compute_vertex_normals(*fabric_, x_.data(), 0, particle_count(), normals_.data());
    return normals_;
}

bool ClothInstance::state_is_finite() const {
    for (uint32_t i = 0; i < particle_count(); ++i) {
        if (!is_finite(x_[i]) || !is_finite(v_[i])) return false;
    }
    return true;
}

Status ClothInstance::step(float dt, const Vec3& gravity) {
    const uint32_t n = particle_count();
    backup_x_ = x_;
    backup_v_ = v_;
    for (uint32_t i = 0; i < n; ++i) {
        if (pinned_[i]) pin_start_[i] = x_[i];
    }
    const uint32_t substeps = solver_.substeps;
    const float h = dt / static_cast<float>(substeps);
    bool converged = true;
    for (uint32_t k = 0; k < substeps; ++k) {
        substep(h, static_cast<float>(k + 1) / static_cast<float>(substeps), gravity);
        converged = converged && last_solve_.converged;
    }
    if (!state_is_finite()) {
        x_ = backup_x_;
        v_ = backup_v_;
        last_step_result_ = CLOTH_ERROR_NONFINITE_STATE;
        return Status::error(CLOTH_ERROR_NONFINITE_STATE,
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

void ClothInstance::substep(float h, float frame_fraction_end, const Vec3& gravity) {
    const Fabric& f = *fabric_;
    const uint32_t n = f.particle_count();

    // 0. Pinned particles move linearly towards their frame-end targets.
    for (uint32_t i = 0; i < n; ++i) {
        if (!pinned_[i]) continue;
        const Vec3 end = pin_start_[i] + (pin_target_[i] - pin_start_[i]) * frame_fraction_end;
        v_[i] = (end - x_[i]) / h;
    }

    // 1. External forces: air (only when the scene has air), gravity, linear drag.
    const bool has_air = aero_.air_density > 0 && (aero_.drag_coefficient > 0 || aero_.lift_coefficient > 0);
    if (has_air) {
        evaluate_triangle_air(f, aero_, x_.data(), v_.data(), 0, f.triangle_count(), triangle_force_.data());
        gather_triangle_forces(f, triangle_force_.data(), 0, n, external_force_.data());
    }
    for (uint32_t i = 0; i < n; ++i) {
        const Vec3 body = gravity * mass_[i] - v_[i] * (aero_.linear_drag * mass_[i]);
        external_force_[i] = has_air ? Vec3(external_force_[i] + body) : body;
    }

    SpringPass springs{&f, material_.springs, x_.data(), v_.data(), h, solver_.compression_safe_jacobian};
    if (solver_.kind == CLOTH_SOLVER_EXPLICIT) {
        evaluate_springs(springs, 0, f.spring_count(), spring_force_.data(), nullptr);
        integrate_explicit(f, spring_force_.data(), external_force_.data(), mass_.data(), pinned_.data(), h, 0, n,
                           v_.data(), x_.data());
        last_solve_ = SolveReport{};
    } else {
        // 2. Springs.  3. Particle assembly (dv_ = p on exit).
        evaluate_springs(springs, 0, f.spring_count(), spring_force_.data(), spring_block_.data());
        AssemblyPass assembly{&f,           spring_force_.data(), spring_block_.data(), external_force_.data(),
                              mass_.data(), pinned_.data(),       h,                    aero_.linear_drag};
        assemble_particles(assembly, 0, n, diagonal_.data(), diagonal_inverse_.data(), rhs_.data(), dv_.data());
        // 4. Solve.
        const LinearSystem system{&f,           n, spring_block_.data(), diagonal_.data(), diagonal_inverse_.data(),
                                  rhs_.data(), pinned_.data()};
        if (solver_.kind == CLOTH_SOLVER_CG) {
            last_solve_ = solve_cg(system, solver_.cg_tolerance, solver_.cg_max_iterations, dv_.data());
        } else {
            last_solve_ = solve_jacobi(system, solver_.iterations, dv_.data(), dv_scratch_.data());
        }
        // 5. Integrate the free particles.
        for (uint32_t i = 0; i < n; ++i) {
            if (pinned_[i]) continue;
            v_[i] += dv_[i];
            x_[i] += v_[i] * h;
        }
    }

    // Pinned particles land exactly on their substep targets.
    for (uint32_t i = 0; i < n; ++i) {
        if (pinned_[i]) x_[i] = pin_start_[i] + (pin_target_[i] - pin_start_[i]) * frame_fraction_end;
    }
}

}  // namespace cloth
