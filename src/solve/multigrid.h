// Aggregation multigrid: the default's preconditioner for PCG
// (docs/method.md, "Multigrid-preconditioned CG").
//
// Block-Jacobi PCG moves tension one spring per iteration, so a stiff cloth
// needs on the order of sqrt(condition) iterations (docs/method.md, "Where
// one iteration stops holding"); a V-cycle over coarser copies of the
// cloth moves it across the whole cloth in one. The levels: particles are
// grouped into aggregates (2 x 2 blocks on a grid, greedy neighbourhoods on
// a mesh), each aggregate one node of the next level, down to at most
// kCoarsestSize nodes. The coarse operator is the Galerkin product P^T W P
// with P piecewise constant on aggregates: sums of the fine 3x3 blocks,
// formed each substep from the system the assembly stage produced
// (assemble). The cycle: one damped block-Jacobi sweep before and after the
// coarse correction on every level, a dense Cholesky solve on the coarsest.
// The same sweeps on both sides keep the preconditioner symmetric, as PCG
// needs. PCG so preconditioned brings a 64x64 or 128x128 cloth's residual
// to 1e-4 in 12-16 iterations, block-Jacobi PCG in 144-257.
//
// Written by hand: the levels follow the fabric's own grid, and every pass
// must run over the library's SoA buffers without allocating (the coarsest
// level's Cholesky too: 48 unknowns at most, factored in the host's
// memory). The passes that read the fine level split across workers: the
// fine passes by particle ranges like every PCG pass, and the first coarse
// level's operator and right-hand side by ranges of its nodes and pairs,
// each a gather in a fixed order. The cycle over the coarse levels, a
// quarter of the fine work and less, runs on one thread between two
// barriers (docs/measurements.md, "The first coarse level on every
// worker"). So results do not depend on the worker count.
#pragma once

#include "base/host_allocator.h"
#include "base/math.h"
#include "base/soa.h"
#include "base/staged.h"
#include "fabric/fabric.h"
#include "forces/grid_products.h"
#include "forces/spring_terms.h"
#include "solve/linear_system.h"

namespace cloth {

class Multigrid {
  public:
    static constexpr uint32_t kCoarsestSize = 16;    // nodes solved directly
    static constexpr float kSmootherWeight = 0.66f;  // damped block Jacobi

    explicit Multigrid(const HostMemory* memory);

    // The levels of `fabric` (once per cloth). No levels (empty()) when the
    // fabric is no larger than kCoarsestSize particles.
    void plan(const Fabric& fabric, const SpringTerms& springs);
    bool empty() const { return levels_.empty(); }

    // Per substep: the coarse operators of `system` (pinned particles are
    // left out, as they are of the system). Not kept across a frame's
    // substeps: the strain cable switches within a frame, and five
    // iterations with a stale operator gain energy at the stiff extreme of
    // the stability map (docs/measurements.md, "The coarse operators kept
    // across a frame's substeps").
    void assemble(const LinearSystem& system);  // on this thread
    // The same in two parts: the first level's pairs and nodes that `task`
    // owns (GroupTask::items), on any worker, then, on one thread after
    // every task's, the coarser levels and the coarsest factor.
    void assemble_top(const LinearSystem& system, const GroupTask& task);
    void assemble_coarse();

    // The fine passes of one preconditioner application z = M r, each over
    // particles [begin, end); a barrier separates them:
    //   smooth_from_zero  z = w W_ii^-1 r
    //   residual          t = r - W z
    //   restrict_residual  the first level's right-hand side: each node sums its particles' t
    //   (correct_coarse, one thread: cycle the coarse levels)
    //   prolong           z += P e
    //   smooth            out = z + w W_ii^-1 (r - W z)   (solver_pcg.cpp, with PCG's dot product)
    static void smooth_from_zero(const LinearSystem& system, const Vec3Soa& r, uint32_t begin, uint32_t end,
                                 Vec3Soa& z);
    static void residual(const LinearSystem& system, const Vec3Soa& r, const Vec3Soa& z, uint32_t begin,
                         uint32_t end, Vec3Soa& t);
    // The first level's nodes that `task` owns (GroupTask::items).
    void restrict_residual(const Vec3Soa& t, const GroupTask& task);
    void correct_coarse();
    void prolong(const float* pinned, uint32_t begin, uint32_t end, Vec3Soa& z) const;

    uint32_t level_count() const { return static_cast<uint32_t>(levels_.size()); }
    uint32_t level_size(uint32_t level) const { return levels_[level].size; }

  private:
    // One coarse level: its nodes, the coupled pairs (each once), and the
    // map of its nodes onto the next level's.
    struct Level {
        explicit Level(const HostMemory* memory);
        uint32_t size = 0;
        uint32_t columns = 0, rows = 0;  // a grid's shape, 0 on meshes
        HostVector<uint32_t> pair_first, pair_second;
        HostVector<Sym3> pair_block;  // W_IJ
        // Each node's pairs (both directions), for products by gathering:
        // entries row_start[I] .. row_start[I + 1] of row_column, row_pair.
        HostVector<uint32_t> row_start, row_column, row_pair;
        // A grid level (at least 3 columns) also holds its pairs the way
        // the grid springs hold theirs (grid_products.h): four families,
        // east, north, north-east and north-west, so products vectorize.
        HostVector<uint8_t> pair_family;
        HostVector<uint32_t> family_offset;
        std::vector<Sym3Soa, HostAllocator<Sym3Soa>> family_block;
        HostVector<const Sym3Soa*> family_block_pointer;
        uint32_t family_pad = 0;
        HostVector<Sym3> diagonal;         // W_II as assembled
        Sym3Soa diagonal_blocks, inverse;  // W_II and W_II^-1 as arrays, for the cycle's passes
        Vec3Soa rhs, x, product;           // the cycle's vectors
        HostVector<uint32_t> aggregate;    // node -> next level's node (not on the coarsest)
        HostVector<uint32_t> pair_target;  // pair -> next level's pair, or its pair count + node
    };

    void plan_families(Level& level);
    static void spread_blocks(Level& level, uint32_t pair_begin, uint32_t pair_end, uint32_t node_begin,
                              uint32_t node_end);
    void multiply(const Level& level, const Vec3Soa& x, Vec3Soa& y) const;
    void cycle(uint32_t level_index);
    void factor_coarsest();

    const HostMemory* memory_;
    HostVector<uint32_t> aggregate_;  // fine particle -> level 0 node
    HostVector<uint32_t>
        spring_target_;  // fine spring (for_each_block order) -> level 0 pair or pair count + node
    // The same as lists per target (pairs, then nodes), and each level 0
    // node's particles: what assemble_top gathers.
    HostVector<uint32_t> target_start_, target_spring_, child_start_, child_;
    HostVector<Sym3> inner_;  // per level 0 node: the sum of the springs inside it
    std::vector<Level, HostAllocator<Level>> levels_;
    // The coarsest level as a dense matrix (3 unknowns per node), row-major,
    // factored in place (lower triangle: its Cholesky factor), and a vector.
    HostVector<double> coarsest_, coarsest_vector_;
    bool coarsest_factored_ = false;
};

}  // namespace cloth
