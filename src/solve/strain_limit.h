// Strain limiting (Provot 1995, "Deformation constraints in a mass-spring
// model to describe rigid cloth behavior"), rearranged into per-particle
// passes: Provot corrects one spring at a time (Gauss-Seidel, order
// dependent); here every particle gathers the corrections of its own
// over-stretched structural and shear springs from the positions of the
// previous pass (Jacobi), so the passes split across workers and give the
// same bits for any split.
#pragma once

#include "base/soa.h"
#include "base/staged.h"
#include "fabric/fabric.h"
#include "forces/material.h"
#include "solve/solver_settings.h"

namespace cloth {

struct StrainLimitPass {
    const Fabric* fabric;
    const float* mass;
    const float* pinned;  // 1 pinned (does not move), 0 free
    float max_strain;     // allowed (L - l0) / l0
};

// correction_i = 1/2 sum over over-stretched springs s = (i, j) of
// w_i (L - (1 + max_strain) l0) (x_j - x_i) / L, with w_i = m_i^-1 /
// (m_i^-1 + m_j^-1) (pinned: m^-1 = 0). Particles [begin, end); reads x.
// Returns nothing; `correction` holds the result.
void strain_limit_corrections(const StrainLimitPass& pass, const Vec3Soa& x, uint32_t begin, uint32_t end,
                              Vec3Soa& correction);

// x += correction, v += correction / h (the velocity follows the position
// change, as in Provot), particles [begin, end).
void strain_limit_apply(const Vec3Soa& correction, float h, uint32_t begin, uint32_t end, Vec3Soa& x,
                        Vec3Soa& v);

// The passes as a staged algorithm (base/staged.h): `iterations` times a
// round of corrections, then a round applying them. A frame runs the
// colliders after each applying round (step/frame_plan.cpp).
class StrainLimiter final : public StagedAlgorithm {
  public:
    // x, v and the scratch `correction` (one entry per particle) outlive it.
    void begin(const StrainLimitPass& pass, uint32_t iterations, float h, Vec3Soa& x, Vec3Soa& v,
               Vec3Soa& correction);
    // The current round moves particles (it applies corrections).
    bool applying() const { return round_ % 2 == 1; }

    bool done() const override { return round_ >= 2 * iterations_; }
    bool last_round() const override { return round_ + 1 == 2 * iterations_; }
    void run(const GroupTask& task) override;
    void finish_round() override { ++round_; }

  private:
    StrainLimitPass pass_{};
    uint32_t iterations_ = 0, round_ = 0;
    float h_ = 0;
    Vec3Soa* x_ = nullptr;
    Vec3Soa* v_ = nullptr;
    Vec3Soa* correction_ = nullptr;
};

// The same rounds on this thread, over all particles.
void limit_strain(const StrainLimitPass& pass, const StrainLimit& limit, float h, Vec3Soa& x, Vec3Soa& v,
                  Vec3Soa& scratch);

}  // namespace cloth
