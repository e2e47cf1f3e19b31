// Levels of detail of a grid fabric: coarser copies of the cloth that a
// far cloth steps instead of the full one (scene/cloth_levels.h), at a
// quarter, a sixteenth, ... of the particles and of the cost.
//
// Level k > 0 is the multigrid's level k - 1 (fabric/grid_coarsening.h:
// 2 x 2 blocks of the level above, each one node) built as a Fabric of its
// own: a grid of those nodes with the full fabric's spring kinds, rest
// lengths between the nodes' rest positions, triangles, and lumped areas
// that are the sums of its particles' (so masses sum to the same total).
// Level 0 is the fabric itself; mesh fabrics have no other level.
//
// The transfer between the full fabric and a level, both ways direct (no
// chain through the levels between):
// - restriction sums over each node's particles, the multigrid's P^T:
//   positions weighted by rest area (a node's rest position is the same
//   mean of its particles', so an affine motion of the cloth restricts to
//   the same motion of the nodes), velocities weighted by mass (momentum
//   and total mass kept), masses summed;
// - prolongation is not the multigrid's P, which is constant over a block
//   and would put a block's four particles on one point: each particle is
//   interpolated linearly in the level's triangle that holds its rest
//   position (extrapolated at the border), with barycentric weights from
//   the rest positions. Any affine map of the rest shape (a flat sheet
//   moved, turned or stretched) restricts and prolongs back exactly, and
//   the interpolated mesh is continuous.
#pragma once

#include <cstdint>
#include <memory>

#include "base/host_allocator.h"
#include "base/soa.h"
#include "base/status.h"
#include "fabric/fabric.h"

namespace cloth {

struct FabricLevel {
    explicit FabricLevel(const HostMemory* memory);

    std::shared_ptr<const Fabric> fabric;  // the level's own grid
    uint32_t columns = 0, rows = 0;

    // From the full fabric's particles: each node's particles (index order,
    // entries child_start[I] .. child_start[I + 1] of child) with each one's
    // share of the node's rest area; and per particle the three nodes it is
    // interpolated from and their weights.
    HostVector<uint32_t> child_start, child;
    HostVector<float> child_area_weight;
    HostVector<uint32_t> node_of;  // particle -> its node
    HostVector<uint32_t> from_node;
    HostVector<float> from_weight;  // 3 per particle, summing to 1

    uint32_t node_count() const { return static_cast<uint32_t>(child_start.size() - 1); }
};

// Coarse levels are made while a level has at least this many columns and
// rows (so the coarsest has 3), and at most kMaxFabricLevels of them.
constexpr uint32_t kLevelMinExtent = 5;
constexpr uint32_t kMaxFabricLevels = 3;

// Builds fabric.levels for a grid fabric (after its builder); a mesh
// fabric, or a grid too small to coarsen, gets none.
Status build_fabric_levels(Fabric& fabric);

// The transfers (serial, in a fixed order; `full_*` over the full
// fabric's particles, `node_*` over the level's nodes).
// Positions: area-weighted means.
void restrict_positions(const FabricLevel& level, const Vec3Soa& full_x, Vec3Soa& node_x);
// Masses: sums. Velocities: mass-weighted means (momentum kept).
void restrict_masses(const FabricLevel& level, const float* full_mass, float* node_mass);
void restrict_velocities(const FabricLevel& level, const float* full_mass, const Vec3Soa& full_v,
                         Vec3Soa& node_v);
// Pins: a node is pinned (1) if any of its particles is; its target is the
// area-weighted mean of its particles' targets, a free particle's target
// being its position (so the node sits where the block's rest shape puts
// it). full_pinned per particle 0 or 1.
void restrict_pins(const FabricLevel& level, const float* full_pinned, const Vec3Soa& full_target,
                   const Vec3Soa& full_x, float* node_pinned, Vec3Soa& node_target);
// Interpolation from the nodes to every particle.
void prolong(const FabricLevel& level, const Vec3Soa& node_values, Vec3Soa& full_values);

}  // namespace cloth
