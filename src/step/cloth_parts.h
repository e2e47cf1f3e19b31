// The parts of a cloth's state that belong together, each owned by one
// family of stages (ClothInstance holds one of each): the pins, the
// linearized system's buffers, the strain limiter's terms and scratch, and
// sleep. Everything here is sized once, at the cloth's creation (no
// allocation per step).
#pragma once

#include <cstdint>

#include "base/host_allocator.h"
#include "base/math.h"
#include "base/soa.h"
#include "solve/multigrid.h"
#include "solve/solvers.h"
#include "solve/strain_limit.h"
#include "solve/tethers.h"

namespace cloth {

// Pinned (kinematic) particles, and which of them the skin drives: a max
// distance of 0 is stored here only, as a pin whose target is the
// skinned position (the skin keeps no distance for it).
struct PinSet {
    explicit PinSet(const HostMemory* memory)
        : pinned(HostAllocator<float>(memory)),
          list(HostAllocator<uint32_t>(memory)),
          target(memory),
          by_skin(HostAllocator<uint8_t>(memory)) {}
    HostVector<float> pinned;     // per particle: 1 pinned, 0 free (a factor in branch-free loops)
    HostVector<uint32_t> list;    // the pinned particles, ascending (room for every particle)
    Vec3Soa target;               // where a pinned particle is at the end of the next frame
    HostVector<uint8_t> by_skin;  // per particle: 1 where the host gave a max distance of 0
};

// The linearized backward Euler system of a substep and its solve
// (docs/method.md): forces, the block diagonal, the right-hand side, the
// solution and the solvers' vectors.
struct SystemBuffers {
    explicit SystemBuffers(const HostMemory* memory)
        : external_force(memory),
          triangle_force(memory),
          diagonal(memory),
          diagonal_inverse(memory),
          rhs(memory),
          dv(memory),
          dv_scratch(memory),
          work(memory),
          multigrid(memory),
          normals(memory) {}
    Vec3Soa external_force;    // per particle
    Vec3Soa triangle_force;    // per triangle, share of each corner
    Sym3Soa diagonal;          // per particle: W_ii
    Sym3Soa diagonal_inverse;  // per particle: W_ii^-1 (zero if pinned)
    Vec3Soa rhs;               // per particle: b_i = h f~_i
    Vec3Soa dv, dv_scratch;    // per particle
    SolverWorkspace work;      // PCG / Chebyshev vectors and block partials, strain-limit scratch
    Multigrid multigrid;       // PCG's preconditioner when the settings ask for it
    Vec3Soa normals;           // per particle, filled by ClothInstance::normals
};

// The strain limiter's terms and scratch (strain_limit.h, tethers.h).
struct StrainLimitParts {
    explicit StrainLimitParts(const HostMemory* memory)
        : grid_terms(memory),
          tethers(memory),
          counts(HostAllocator<StretchCount>(memory)),
          maybe_over(HostAllocator<uint8_t>(memory)),
          pull(HostAllocator<float>(memory)) {}
    GridStrainTerms grid_terms;        // per-family terms (grid fabrics)
    Tethers tethers;                   // long-range attachments
    HostVector<StretchCount> counts;   // one per group
    HostVector<uint8_t> maybe_over;    // one per particle (StrainLimitPass)
    HostVector<float> pull;            // pull weights, one per particle
    bool tethers_follow_pins = false;  // the tethers are planned for the current pin set
};

// When a cloth at rest goes to sleep (ClothInstance::set_sleep).
struct SleepSettings {
    bool enabled = true;
    float max_speed = 1e-3f;  // m/s: every particle slower than this...
    uint32_t frames = 60;     // ...for this many consecutive frames
};

struct SleepState {
    SleepSettings settings;
    bool sleeping = false;
    bool held = false;         // put to sleep by the host (ClothInstance::hold_asleep)
    uint32_t rest_frames = 0;  // consecutive frames below settings.max_speed
};

}  // namespace cloth
