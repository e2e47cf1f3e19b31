// A grid fabric's levels of detail (fabric_levels.h): each level's grid
// and the maps between it and the full fabric, built once with the fabric;
// and the restriction and prolongation that move a cloth's state across.
#include "fabric/fabric_levels.h"

#include <algorithm>

#include "fabric/fabric_builder.h"
#include "fabric/grid_coarsening.h"

namespace cloth {

FabricLevel::FabricLevel(const HostMemory* memory)
    : child_start(HostAllocator<uint32_t>(memory)),
      child(HostAllocator<uint32_t>(memory)),
      child_area_weight(HostAllocator<float>(memory)),
      node_of(HostAllocator<uint32_t>(memory)),
      from_node(HostAllocator<uint32_t>(memory)),
      from_weight(HostAllocator<float>(memory)) {}

namespace {

// The spring kinds (cloth_spring_kind bits) of a grid fabric's families.
uint32_t grid_spring_kinds(const Fabric& fabric) {
    uint32_t kinds = 0;
    for (const SpringFamily& family : fabric.grid_families) {
        kinds |= family.kind == kStructural ? CLOTH_SPRING_STRUCTURAL
                 : family.kind == kShear    ? CLOTH_SPRING_SHEAR
                                            : CLOTH_SPRING_BEND;
    }
    return kinds;
}

// Per node of a level whose nodes span `span` full columns (rows) each, of
// `extent` in all: the middle of its span, in full column (row) units.
double span_middle(uint32_t node, uint32_t span, uint32_t extent) {
    const uint32_t first = node * span, last = std::min(first + span, extent) - 1;
    return 0.5 * (double(first) + double(last));
}

// The cell of the level's grid (its first node along one axis) whose span
// holds full column (row) `index`, the border cells taking what lies
// beyond them, and where in the cell it lies (0 at that node, 1 at the next).
uint32_t cell_of(uint32_t index, uint32_t span, uint32_t extent, uint32_t nodes, double& at) {
    uint32_t cell = std::min(index / span, nodes - 1);
    if (double(index) < span_middle(cell, span, extent) && cell > 0) --cell;
    cell = std::min(cell, nodes - 2);
    const double from = span_middle(cell, span, extent), to = span_middle(cell + 1, span, extent);
    at = (double(index) - from) / (to - from);
    return cell;
}

// Barycentric weights of point p in triangle (a, b, c), all in one plane.
void barycentric(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& p, double weight[3]) {
    const Eigen::Vector3d e1 = (b - a).cast<double>(), e2 = (c - a).cast<double>(),
                          d = (p - a).cast<double>();
    const double d11 = e1.dot(e1), d12 = e1.dot(e2), d22 = e2.dot(e2);
    const double r1 = d.dot(e1), r2 = d.dot(e2);
    const double det = d11 * d22 - d12 * d12;
    weight[1] = (r1 * d22 - r2 * d12) / det;
    weight[2] = (r2 * d11 - r1 * d12) / det;
    weight[0] = 1.0 - weight[1] - weight[2];
}

Status build_level(const Fabric& full, uint32_t full_columns, uint32_t full_rows, uint32_t depth,
                   const HostVector<uint32_t>& node_of, uint32_t columns, uint32_t rows, FabricLevel& level) {
    const HostMemory* memory = full.memory;
    const uint32_t n = full.particle_count(), nodes = columns * rows;
    level.columns = columns;
    level.rows = rows;
    level.node_of = node_of;

    // Each node's particles, in index order, and their share of its area.
    level.child_start.assign(nodes + 1, 0);
    for (uint32_t i = 0; i < n; ++i) ++level.child_start[node_of[i] + 1];
    for (uint32_t node = 0; node < nodes; ++node) level.child_start[node + 1] += level.child_start[node];
    level.child.resize(n);
    HostVector<uint32_t> fill(level.child_start.begin(), level.child_start.end() - 1,
                              HostAllocator<uint32_t>(memory));
    for (uint32_t i = 0; i < n; ++i) level.child[fill[node_of[i]]++] = i;

    auto fabric = std::allocate_shared<Fabric>(HostAllocator<Fabric>(memory), memory);
    fabric->rest_positions.resize(nodes);
    HostVector<float> node_area{HostAllocator<float>(memory)};
    node_area.resize(nodes);
    level.child_area_weight.resize(n);
    for (uint32_t node = 0; node < nodes; ++node) {
        double area = 0;
        for (uint32_t k = level.child_start[node]; k < level.child_start[node + 1]; ++k)
            area += full.rest_area[level.child[k]];
        Eigen::Vector3d mean = Eigen::Vector3d::Zero();
        for (uint32_t k = level.child_start[node]; k < level.child_start[node + 1]; ++k) {
            const uint32_t i = level.child[k];
            const double share = full.rest_area[i] / area;
            level.child_area_weight[k] = static_cast<float>(share);
            mean += share * full.rest_positions[i].cast<double>();
        }
        fabric->rest_positions[node] = mean.cast<float>();
        node_area[node] = static_cast<float>(area);
    }
    Status status = build_grid_topology(columns, rows, grid_spring_kinds(full), *fabric);
    if (!status.ok()) return status;
    fabric->rest_area.swap(node_area);  // masses sum to the full fabric's
    fabric->identity = fabric_identity(*fabric);

    // Each particle from the level's triangle over its rest position: the
    // grid's two shapes per cell, (0, 1, columns + 1) and (0, columns + 1, columns).
    const uint32_t span = 1u << depth;
    level.from_node.resize(3 * size_t{n});
    level.from_weight.resize(3 * size_t{n});
    for (uint32_t r = 0; r < full_rows; ++r) {
        for (uint32_t c = 0; c < full_columns; ++c) {
            double u = 0, v = 0;
            const uint32_t cell_c = cell_of(c, span, full_columns, columns, u);
            const uint32_t cell_r = cell_of(r, span, full_rows, rows, v);
            const uint32_t first = cell_r * columns + cell_c;
            const uint32_t corner[3] = {first, u >= v ? first + 1 : first + columns + 1,
                                        u >= v ? first + columns + 1 : first + columns};
            const uint32_t i = r * full_columns + c;
            double weight[3];
            barycentric(fabric->rest_positions[corner[0]], fabric->rest_positions[corner[1]],
                        fabric->rest_positions[corner[2]], full.rest_positions[i], weight);
            for (int k = 0; k < 3; ++k) {
                level.from_node[3 * size_t{i} + k] = corner[k];
                level.from_weight[3 * size_t{i} + k] = static_cast<float>(weight[k]);
            }
        }
    }
    level.fabric = std::move(fabric);
    return {};
}

}  // namespace

Status build_fabric_levels(Fabric& fabric) {
    fabric.levels.clear();
    uint32_t full_columns = 0, full_rows = 0;
    if (!grid_shape(fabric, full_columns, full_rows)) return {};
    const HostMemory* memory = fabric.memory;
    HostVector<uint32_t> node_of{HostAllocator<uint32_t>(memory)}, aggregate{HostAllocator<uint32_t>(memory)};
    node_of.resize(fabric.particle_count());
    for (uint32_t i = 0; i < fabric.particle_count(); ++i) node_of[i] = i;
    uint32_t columns = full_columns, rows = full_rows;
    for (uint32_t depth = 1;
         depth <= kMaxFabricLevels && columns >= kLevelMinExtent && rows >= kLevelMinExtent; ++depth) {
        aggregate_grid(columns, rows, aggregate);
        for (uint32_t& node : node_of) node = aggregate[node];
        columns = coarse_grid_extent(columns);
        rows = coarse_grid_extent(rows);
        auto level = std::allocate_shared<FabricLevel>(HostAllocator<FabricLevel>(memory), memory);
        Status status = build_level(fabric, full_columns, full_rows, depth, node_of, columns, rows, *level);
        if (!status.ok()) return status;
        fabric.levels.push_back(std::move(level));
    }
    return {};
}

void restrict_positions(const FabricLevel& level, const Vec3Soa& full_x, Vec3Soa& node_x) {
    for (uint32_t node = 0; node < level.node_count(); ++node) {
        double x = 0, y = 0, z = 0;
        for (uint32_t k = level.child_start[node]; k < level.child_start[node + 1]; ++k) {
            const uint32_t i = level.child[k];
            const double w = level.child_area_weight[k];
            x += w * full_x.x[i];
            y += w * full_x.y[i];
            z += w * full_x.z[i];
        }
        node_x.set(node, Vec3(float(x), float(y), float(z)));
    }
}

void restrict_masses(const FabricLevel& level, const float* full_mass, float* node_mass) {
    for (uint32_t node = 0; node < level.node_count(); ++node) {
        double mass = 0;
        for (uint32_t k = level.child_start[node]; k < level.child_start[node + 1]; ++k)
            mass += full_mass[level.child[k]];
        node_mass[node] = static_cast<float>(mass);
    }
}

void restrict_velocities(const FabricLevel& level, const float* full_mass, const Vec3Soa& full_v,
                         Vec3Soa& node_v) {
    for (uint32_t node = 0; node < level.node_count(); ++node) {
        double mass = 0, x = 0, y = 0, z = 0;
        for (uint32_t k = level.child_start[node]; k < level.child_start[node + 1]; ++k) {
            const uint32_t i = level.child[k];
            const double m = full_mass[i];
            mass += m;
            x += m * full_v.x[i];
            y += m * full_v.y[i];
            z += m * full_v.z[i];
        }
        node_v.set(node, Vec3(float(x / mass), float(y / mass), float(z / mass)));
    }
}

void restrict_pins(const FabricLevel& level, const float* full_pinned, const Vec3Soa& full_target,
                   const Vec3Soa& full_x, float* node_pinned, Vec3Soa& node_target) {
    for (uint32_t node = 0; node < level.node_count(); ++node) {
        bool pinned = false;
        double x = 0, y = 0, z = 0;
        for (uint32_t k = level.child_start[node]; k < level.child_start[node + 1]; ++k) {
            const uint32_t i = level.child[k];
            const bool pin = full_pinned[i] != 0.0f;
            const Vec3 at = pin ? full_target.get(i) : full_x.get(i);
            const double w = level.child_area_weight[k];
            pinned = pinned || pin;
            x += w * at.x();
            y += w * at.y();
            z += w * at.z();
        }
        node_pinned[node] = pinned ? 1.0f : 0.0f;
        node_target.set(node, pinned ? Vec3(float(x), float(y), float(z)) : Vec3::Zero());
    }
}

void prolong(const FabricLevel& level, const Vec3Soa& node_values, Vec3Soa& full_values) {
    const uint32_t n = static_cast<uint32_t>(level.node_of.size());
    for (uint32_t i = 0; i < n; ++i) {
        const uint32_t* node = &level.from_node[3 * size_t{i}];
        const float* w = &level.from_weight[3 * size_t{i}];
        full_values.x[i] =
            w[0] * node_values.x[node[0]] + w[1] * node_values.x[node[1]] + w[2] * node_values.x[node[2]];
        full_values.y[i] =
            w[0] * node_values.y[node[0]] + w[1] * node_values.y[node[1]] + w[2] * node_values.y[node[2]];
        full_values.z[i] =
            w[0] * node_values.z[node[0]] + w[1] * node_values.z[node[1]] + w[2] * node_values.z[node[2]];
    }
}

}  // namespace cloth
