// Fabric: the shared, immutable topology of a cloth (paper section II;
// Jolt's SoftBodySharedSettings, NvCloth's Fabric). Built once from a grid
// or a triangle mesh; any number of cloth instances reference it.
//
// Springs are stored as structure-of-arrays. Each particle also gets the
// list of its incident springs (CSR), in a fixed order, so every stage of
// the step can gather per particle instead of scattering per spring: the
// sums are then formed in the same order whatever thread runs them.
#pragma once

#include <cloth/cloth.h>

#include <cstdint>
#include <vector>

#include "host_allocator.h"
#include "math.h"
#include "status.h"

namespace cloth {

enum SpringKind : uint8_t { kStructural = 0, kShear = 1, kBend = 2, kSpringKindCount = 3 };

// A regular grid's springs grouped by direction: family f joins particle p
// to p + offset wherever mask[p] is 1 (columns at the edge have no
// neighbour on that side).
struct SpringFamily {
    explicit SpringFamily(const HostMemory* memory) : mask(HostAllocator<float>(memory)) {}

    uint32_t offset = 0;
    SpringKind kind = kStructural;
    float rest_length = 0;
    HostVector<float> mask;
};

struct Fabric {
    explicit Fabric(const HostMemory* memory);

    const HostMemory* memory;

    uint32_t particle_count() const { return static_cast<uint32_t>(rest_positions.size()); }
    uint32_t triangle_count() const { return static_cast<uint32_t>(triangles.size() / 3); }
    uint32_t spring_count() const { return static_cast<uint32_t>(spring_first.size()); }

    HostVector<Vec3> rest_positions;
    HostVector<float> rest_area;      // lumped: a third of each incident triangle's area
    HostVector<uint32_t> triangles;   // 3 indices per triangle

    HostVector<uint32_t> spring_first;  // particle i of spring s
    HostVector<uint32_t> spring_second; // particle j of spring s
    HostVector<float> spring_rest_length;
    HostVector<uint8_t> spring_kind;
    uint32_t springs_of_kind[kSpringKindCount] = {0, 0, 0};

    // Per particle p, entries incidence_offset[p] .. incidence_offset[p+1].
    HostVector<uint32_t> incidence_offset;
    HostVector<uint32_t> incidence_spring;
    HostVector<uint32_t> incidence_other;  // the particle at the other end
    HostVector<float> incidence_sign;      // +1 if p is the spring's first particle, else -1

    // Triangles incident to each particle, for normals and wind forces.
    HostVector<uint32_t> triangle_incidence_offset;
    HostVector<uint32_t> triangle_incidence;

    // The same incidence lists padded to a fixed width and stored slot-major
    // (entry k of particle p at k * particle_count + p), so that the gathers
    // run as vectorized loops over particles. Padding points at a dummy
    // spring (index spring_count) or triangle (index triangle_count) whose
    // per-instance data is kept zero; its sign is 0. The order within a
    // particle is the CSR order, so sums are formed identically.
    uint32_t padded_spring_width = 0;
    HostVector<uint32_t> padded_spring;
    HostVector<uint32_t> padded_other;
    HostVector<float> padded_sign;
    uint32_t padded_triangle_width = 0;
    HostVector<uint32_t> padded_triangle;

    // Grid fabrics only (empty otherwise): the same springs as families,
    // and the triangles as two shapes per cell. Shape k of the cell whose
    // first corner is particle p has corners p + grid_triangle_shapes[3k + i];
    // the cell exists where grid_cell_mask[p] is 1.
    std::vector<SpringFamily, HostAllocator<SpringFamily>> grid_families;
    HostVector<uint32_t> grid_triangle_shapes;
    HostVector<float> grid_cell_mask;
};

// Largest particle count a fabric may have.
constexpr uint32_t kMaxParticles = 1u << 24;

// Builders fill a freshly constructed `out`; on error, discard it.
// Build from a grid description.
Status build_grid_fabric(const cloth_grid_desc& desc, Fabric& out);
// Build from a triangle mesh (positions: 3 floats per vertex).
Status build_mesh_fabric(const float* positions, uint32_t vertex_count, const uint32_t* indices,
                         uint32_t triangle_count, uint32_t spring_kinds, Fabric& out);
// Load an OBJ file (triangulated) and build from it.
Status build_obj_fabric(const char* path, uint32_t spring_kinds, Fabric& out);

}  // namespace cloth
