// One simulated cloth: per-instance state over a shared Fabric (Jolt's
// SoftBodyMotionProperties, NvCloth's Cloth). Owns its material, solver
// settings and scratch buffers; advances itself by one frame in step().
#pragma once

#include <cloth/cloth.h>

#include <memory>

#include "fabric.h"
#include "host_allocator.h"
#include "math.h"
#include "settings.h"
#include "soa.h"
#include "status.h"

namespace cloth {

class SpringTerms;

class ClothInstance {
  public:
    ClothInstance(const HostMemory* memory, std::shared_ptr<const Fabric> fabric, const Material& material,
                  const SolverSettings& solver, const AeroParams& aero);

    const Fabric& fabric() const { return *fabric_; }
    uint32_t particle_count() const { return fabric_->particle_count(); }

    // Advance by one frame of `dt` seconds (settings().substeps substeps).
    // Returns CLOTH_ERROR_NONFINITE_STATE after restoring the state from
    // before the call if the result was not finite.
    Status step(float dt, const Vec3& gravity);

    void set_material(const Material& material);  // recomputes masses
    const Material& material() const { return material_; }
    SolverSettings& solver() { return solver_; }
    const SolverSettings& solver() const { return solver_; }
    AeroParams& aero() { return aero_; }
    const AeroParams& aero() const { return aero_; }

    // Pin (kinematic, at their current positions) or release particles.
    // Allocates nothing: the pinned list has room for every particle.
    void set_pinned(const uint32_t* particles, uint32_t count, bool pinned);
    void pin(uint32_t particle) { set_pinned(&particle, 1, true); }
    void unpin(uint32_t particle) { set_pinned(&particle, 1, false); }
    bool is_pinned(uint32_t particle) const { return pinned_[particle] != 0.0f; }
    void set_pin_target(uint32_t particle, const Vec3& target) { pin_target_.set(particle, target); }
    // Teleport a particle: new position, zero velocity (and pin target).
    void set_position(uint32_t particle, const Vec3& x);

    const Vec3Soa& positions() const { return x_; }
    const Vec3Soa& velocities() const { return v_; }
    const HostVector<float>& masses() const { return mass_; }
    // Unit area-weighted vertex normals of the current positions.
    const Vec3Soa& normals() const;

    const SolveReport& last_solve() const { return last_solve_; }
    cloth_result last_step_result() const { return last_step_result_; }

  private:
    void substep(float h, float frame_fraction_end, const Vec3& gravity);
    bool state_is_finite() const;
    // Where pinned particle i is at `frame_fraction` of the current frame.
    Vec3 pin_position(uint32_t i, float frame_fraction) const;

    std::shared_ptr<const Fabric> fabric_;
    Material material_;
    SolverSettings solver_;
    AeroParams aero_;

    // State.
    Vec3Soa x_, v_;
    HostVector<float> mass_;
    HostVector<float> pinned_;          // 1 pinned, 0 free (a factor in branch-free loops)
    HostVector<uint32_t> pinned_list_;  // the pinned particles, ascending
    Vec3Soa pin_target_;                // where a pinned particle is at the end of the next frame
    Vec3Soa pin_start_;                 // where it was at the start of this frame

    // Scratch, sized once at creation (no allocation per step).
    Vec3Soa external_force_;                // per particle
    Vec3Soa triangle_force_;                // per triangle, share of each corner
    std::shared_ptr<SpringTerms> springs_;  // per-spring f~ and A_s, in the layout that suits the fabric
    Sym3Soa diagonal_;                      // per particle: W_ii
    Sym3Soa diagonal_inverse_;              // per particle: W_ii^-1 (zero if pinned)
    Vec3Soa rhs_;                           // per particle: b_i = h f~_i
    Vec3Soa dv_, dv_scratch_;               // per particle
    mutable Vec3Soa normals_;               // per particle, filled by normals()
    Vec3Soa backup_x_, backup_v_;

    SolveReport last_solve_;
    cloth_result last_step_result_ = CLOTH_OK;
};

}  // namespace cloth
