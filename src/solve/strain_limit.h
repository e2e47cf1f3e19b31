// Strain limiting (Provot 1995, "Deformation constraints in a mass-spring
// model to describe rigid cloth behavior") as Jacobi passes: every particle
// gathers the corrections of its own springs past the limit from the
// previous pass's positions, so the passes split across workers with the
// same bits for any split (Provot's spring-by-spring order would not).
// Structural springs are held both ways (cloth buckles rather than
// shortens, and a pass that pulls a stretched spring in pushes its ends
// into their other neighbours); shear springs, which shorten whenever the
// cloth shears, only against stretch (docs/method.md, "The strain
// limiter").
//
// Grid fabrics take the corrections family by family (GridStrainTerms),
// every loop contiguous; meshes run over the fabric's padded slots of
// structural and shear springs (Fabric::limited_slots) with gathers.
#pragma once

#include "base/soa.h"
#include "base/staged.h"
#include "fabric/fabric.h"
#include "forces/material.h"
#include "solve/solver_settings.h"
#include "solve/tethers.h"

namespace cloth {

struct StrainLimitPass {
    const Fabric* fabric;
    const float* mass;
    const float* pinned;  // 1 pinned (does not move), 0 free
    float max_strain;     // allowed (L - l0) / l0
    // Scratch of one byte per particle, or null. With it a pass tests its
    // springs by squared length, eight particles at a time, and computes
    // the exact corrections only for runs that may be over the limit (6 %
    // of the vehicle flag's); the same bits either way.
    uint8_t* maybe_over = nullptr;
    // Scratch of one float per particle (required): each particle's pull
    // in a pass (see strain_limit_corrections).
    float* pull = nullptr;
    // Structural springs held against compression too (past 1 - max_strain),
    // not only against stretch (ClothInstance::holds_compression says when).
    bool hold_compression = true;
};

// What a corrections or terms pass found over its springs: how many are
// longer than the limit (what the pass corrects) and how many longer than
// the limit plus kStrainPromiseSlack (what more passes are for).
struct StretchCount {
    uint32_t over_limit = 0, over_promise = 0;
};
constexpr float kStrainPromiseSlack = 0.01f;
// A frame's strain limiter runs at most this many times the passes asked
// for (cloth_strain_limit.iterations), and only while springs are past
// the promise.
constexpr uint32_t kStrainLimitMorePasses = 4;
// The least share of a correction either free end of a spring takes (a
// mass ratio past 9:1 counts as 9:1): by inverse mass alone a light
// particle between heavy ones takes nearly all of both springs'
// corrections and cannot meet both (docs/measurements.md, "The least share
// of a correction"). A grid of one density stays within it.
constexpr float kLeastShare = 0.1f;

// correction_i = 1/2 sum over springs s = (i, j) past the limit of
// w_i (L - (1 + max_strain) l0) (x_j - x_i) / L, or for structural springs
// compressed past it w_i (L - (1 - max_strain) l0) (x_j - x_i) / L, with w_i = m_i^-1 /
// (m_i^-1 + m_j^-1) (pinned: m^-1 = 0) kept within [kLeastShare,
// 1 - kLeastShare] when both are free, divided by the particle's pull
// P_i = 1/2 sum of those w_i where P_i > 1. Particles [begin, end); reads x;
// `correction` holds the result; returns what the pass found.
//
// The division keeps the passes from diverging: a particle with every
// spring far past the limit moves by about P_i times its neighbours' mean
// pull, and past P_i = 1 the passes amplify an alternating pattern
// (docs/measurements.md, "Corrections divided by each particle's pull").
// Where P_i <= 1 (four springs of equal masses make 1) it changes no bit.
StretchCount strain_limit_corrections(const StrainLimitPass& pass, const Vec3Soa& x, uint32_t begin,
                                      uint32_t end, Vec3Soa& correction);

// Long-range limits on grids: along rows and columns, each particle and
// the one kStrainReach places on are kept within (1 + limit) times their
// straight rest distance, as one more family of the passes with its
// corrections weighted by kStrainReachWeight. They carry tension four
// springs per pass, across the seam between two pins' regions where no
// tether runs; a heavier weight overshoots a cloth dragged far in one step
// (docs/measurements.md, "Long-range strain limits on grids").
constexpr uint32_t kStrainReach = 4;
constexpr float kStrainReachWeight = 0.25f;

// The grid layout's per-spring terms: for each structural and shear family
// (fabric.grid_families), then each long-range one, by first particle p
// after `lead` zero entries, the spring's correction
// t = 1/2 (L - (1 + max_strain) l0) (x_q - x_p) / L times the family's
// weight (zero unless over-stretched) and the first end's share
// w_p / (w_p + w_q). Sized once per cloth (resize); entries past
// n - offset stay zero.
struct GridStrainTerms {
    explicit GridStrainTerms(const HostMemory* memory);
    void resize(const Fabric& fabric);
    bool empty() const { return families.empty(); }
    // The long-range families (rows, then columns; none past a grid's size).
    std::vector<SpringFamily, HostAllocator<SpringFamily>> reach;
    HostVector<const SpringFamily*> families;  // the fabric's structural and shear ones, then `reach`
    HostVector<float> weight;                  // per family: 1, or kStrainReachWeight
    HostVector<uint8_t> compresses;            // per family: 1 where compression is limited (structural)
    uint32_t lead = 0, stride = 0;
    HostVector<float> x, y, z, share;  // family k's entry for p at k * stride + lead + p
    HostVector<float> pull;            // and the term's weight in its ends' pull (0 within the limits)
};

// Grid fabrics: the terms of springs whose first particle is in [begin, end),
// and with `shares` their first ends' shares (which follow from the masses
// and pins alone: a substep's first pass writes them, its others keep them)...
StretchCount strain_limit_grid_terms(const StrainLimitPass& pass, const Vec3Soa& x, uint32_t begin,
                                     uint32_t end, bool shares, GridStrainTerms& terms);
// ... then correction_i = sum over families of share * t at i minus
// (1 - share) * t at i - offset, divided by the pull as above (the
// families' weights count in it), zero for pinned particles, [begin, end).
void strain_limit_grid_corrections(const StrainLimitPass& pass, const GridStrainTerms& terms, uint32_t begin,
                                   uint32_t end, Vec3Soa& correction);

// Chebyshev acceleration of the passes (Wang 2015, "A Chebyshev
// semi-iterative approach for accelerating projective and position-based
// dynamics"): pass k + 1 moves each particle past its corrected position
// along the last two passes' move,
//     x_k+1 = omega_k+1 (x_k + c_k - x_k-1) + x_k-1,
// omega_1 = 1, omega_2 = 2 / (2 - rho^2), omega_k+1 = 4 / (4 - rho^2 omega_k),
// which carries tension further in the same passes (docs/measurements.md,
// "Chebyshev-accelerated strain-limit passes", for rho). The last pass is
// plain (see finish_round). Not for the explicit integrator: its substeps
// are so short that the moves over h, which become speed, shake the cloth.
constexpr float kStrainLimitChebyshevRho = 0.9f;
// The weight of the pass after pass `pass` (counted from 0), from that
// pass's weight `omega` (the first pass's is 1).
float strain_limit_next_omega(uint32_t pass, float omega);

// x += correction (omega = 1), or the accelerated move above with
// `previous` holding x_k-1; either way `previous` gets x_k and v the
// position change over h (the velocity follows it, as in Provot).
// Particles [begin, end).
void strain_limit_apply(const Vec3Soa& correction, float h, float omega, uint32_t begin, uint32_t end,
                        Vec3Soa& x, Vec3Soa& v, Vec3Soa& previous);

// The passes as a staged algorithm (base/staged.h): with tethers, first a
// round clamping every particle to its tether (tethers.h); then passes of
// a round of corrections and a round applying them. With `counts` (two
// per particle group) the number of passes follows what they find: at
// least `iterations`, more while a spring is longer than the limit plus
// kStrainPromiseSlack, up to `max_iterations` (with tethers only), and
// none after a pass that finds nothing to correct. Without, exactly
// `iterations`. A frame runs the colliders after the last round
// (step/cloth_stages.cpp).
class StrainLimiter final : public StagedAlgorithm {
  public:
    // x, v, the scratch `correction` and `previous` (one entry per
    // particle each) and, for a grid fabric, its `grid` terms (sized for
    // it) outlive it; a null or empty `grid` takes the general path. Null
    // or empty `tethers`: no tether round. `accelerate`: Chebyshev passes
    // (above), else plain ones.
    void begin(const StrainLimitPass& pass, uint32_t iterations, float h, Vec3Soa& x, Vec3Soa& v,
               Vec3Soa& correction, Vec3Soa& previous, bool accelerate, GridStrainTerms* grid = nullptr,
               const Tethers* tethers = nullptr, StretchCount* counts = nullptr, uint32_t max_iterations = 0);
    // The limit its passes hold: the one asked for, or `demand` where
    // that is more (Tethers::strain_pins_demand). Before its first round.
    void hold_at_least(float demand);
    // Passes run so far (the last frame's, after it).
    uint32_t passes() const { return iterations_; }
    // The last pass asked for found a spring longer than the limit plus
    // kStrainPromiseSlack (with `counts`): the passes asked for did not
    // hold it. False until that pass.
    bool past_promise() const { return past_promise_; }
    // The first pass found a spring longer than the limit (with `counts`):
    // the limiter held the cloth. False until that pass.
    bool held() const { return held_; }
    // The last pass found a spring longer than the limit plus the slack
    // and no more passes were allowed (with `counts`): the passes stopped
    // at their cap, not where the cloth was held.
    bool capped() const { return capped_; }
    // Particles [begin, end) moved between two passes by something else
    // (`from` -> `to`, a self-collision projection): the next accelerated
    // pass carries the move over as it is, not as part of its momentum.
    void moved_between_passes(const Vec3Soa& from, const Vec3Soa& to, uint32_t begin, uint32_t end);
    // The current round applies corrections.
    bool applying() const { return !tether_round() && (round_ - first_pass_round_) % 2 == 1; }

    bool done() const override { return round_ >= round_count(); }
    bool last_round() const override { return round_ + 1 == round_count(); }
    void run(const GroupTask& task) override;
    void finish_round() override;

  private:
    bool tether_round() const { return round_ < first_pass_round_; }
    uint32_t round_count() const { return first_pass_round_ + 2 * iterations_; }

    StrainLimitPass pass_{};
    float asked_strain_ = 0;
    const Tethers* tethers_ = nullptr;
    uint32_t iterations_ = 0, max_iterations_ = 0, asked_ = 0, round_ = 0, first_pass_round_ = 0;
    bool past_promise_ = false;
    bool held_ = false;
    bool capped_ = false;
    StretchCount* counts_ = nullptr;  // per group, written by the corrections or terms round
    float h_ = 0;
    Vec3Soa* x_ = nullptr;
    Vec3Soa* v_ = nullptr;
    Vec3Soa* correction_ = nullptr;
    Vec3Soa* previous_ = nullptr;  // the positions before the last pass
    float omega_ = 1.0f;           // the current pass's (Chebyshev)...
    float schedule_omega_ = 1.0f;  // ...and the schedule's, which the last pass does not follow
    bool accelerate_ = false;
    GridStrainTerms* grid_ = nullptr;
};

// The same rounds on this thread, over all particles (accelerated passes,
// no tethers, no pass counts), with two scratch vectors of one entry per
// particle.
void limit_strain(const StrainLimitPass& pass, const StrainLimit& limit, float h, Vec3Soa& x, Vec3Soa& v,
                  Vec3Soa& correction, Vec3Soa& previous);

}  // namespace cloth
