// Where a cloth's per-spring forces and Jacobian blocks live, and the three
// loops that produce and read them (docs/method.md, "Every stage a
// parallel loop", stages 1-3):
//
//   evaluate        per spring: f~ contribution and A_s      (paper Code 4)
//   gather          per particle: sum of +-f~ and of A_s     (paper Code 1)
//   neighbour_sums  per particle: sum of A_s x_other         (paper Code 2/3)
//
// Two layouts behind one interface:
//   IndexedSprings  any mesh: springs as index pairs; particles gather
//                   through padded incidence slots (fabric.h).
//   GridSprings     regular grids: every spring of a family joins particle
//                   p to p + offset, so no loop needs an index array and
//                   every load is contiguous. Same physics; a mesh's
//                   frame costs about 1.6 times a grid's
//                   (docs/measurements.md, "The mesh's products and
//                   spring kernels").
//
// Every sum over a particle's springs runs in a fixed order that does not
// depend on how the particle range is split, so results are bit-identical
// for any split (the basis of thread-count independence).
#pragma once

#include <functional>
#include <memory>

#include "base/soa.h"
#include "fabric/fabric.h"
#include "forces/material.h"
#include "forces/springs.h"

namespace cloth {

class SpringTerms {
  public:
    virtual ~SpringTerms() = default;

    // New stiffness and damping per kind.
    virtual void set_material(const Material& material) = 0;

    // Stage 1 works on items [0, item_count()): springs or grid particles.
    virtual uint32_t item_count() const = 0;
    // Stage 1 for items [begin, end). h = 0 gives plain forces (explicit).
    virtual void evaluate(const Vec3Soa& x, const Vec3Soa& v, float h, SpringModel model, uint32_t begin,
                          uint32_t end) = 0;
    // Stage 2 for particles [begin, end): force_i += sum of the incident
    // spring forces (signed); diagonal_i += sum of their A_s unless null.
    virtual void gather(uint32_t begin, uint32_t end, Vec3Soa& force, Sym3Soa* diagonal) const = 0;
    // q_i = sum over incident springs of A_s x_other, particles [begin, end),
    // with the blocks of the last evaluate once a gather with a diagonal
    // (the assembly stage) has run over those particles: the index-pair
    // layout copies each block next to its particle there.
    virtual void neighbour_sums(const Vec3Soa& x, uint32_t begin, uint32_t end, Vec3Soa& q) const = 0;
    // Every spring's (i, j, A_s) once, in a fixed order.
    virtual void for_each_block(const std::function<void(uint32_t, uint32_t, const Sym3&)>& visit) const = 0;
    // For targets t in [begin, end): out[t] = the sum, in list order, of
    // A_s over springs spring[start[t]] .. spring[start[t + 1] - 1] (s: the
    // spring's place in for_each_block's order) whose two particles are
    // free. A gather, so targets split across workers (multigrid's coarse
    // operators).
    virtual void sum_blocks(const float* pinned, const uint32_t* start, const uint32_t* spring,
                            uint32_t begin, uint32_t end, Sym3* out) const = 0;
};

// The layout that suits the fabric (grid families when it has them).
std::shared_ptr<SpringTerms> make_spring_terms(const HostMemory* memory, std::shared_ptr<const Fabric> fabric,
                                               const Material& material);
// The general layout, for any fabric (tests compare it with the grid one).
std::shared_ptr<SpringTerms> make_indexed_springs(const HostMemory* memory,
                                                  std::shared_ptr<const Fabric> fabric,
                                                  const Material& material);

}  // namespace cloth
