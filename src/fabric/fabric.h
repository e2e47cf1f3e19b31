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

#include <algorithm>
#include <cstdint>
#include <memory>
#include <vector>

#include "base/host_allocator.h"
#include "base/math.h"
#include "base/staged.h"
#include "base/status.h"

namespace cloth {

enum SpringKind : uint8_t { kStructural = 0, kShear = 1, kBend = 2, kSpringKindCount = 3 };

// A regular grid's springs grouped by direction: family f joins particle p
// to p + offset wherever mask[p] is 1 (columns at the edge have no
// neighbour on that side), with rest length rest_length[p]: the distance
// between the two float rest positions, which differs from spring to
// spring in the last bits (one length per family would leave springs a
// few micrometres off rest, a stiffness no one asked for).
struct SpringFamily {
    explicit SpringFamily(const HostMemory* memory)
        : mask(HostAllocator<float>(memory)), rest_length(HostAllocator<float>(memory)) {}

    uint32_t offset = 0;
    SpringKind kind = kStructural;
    HostVector<float> mask;
    HostVector<float> rest_length;  // per first particle; 0 where mask is 0
};

// Incidence lists laid out for vectorized gathers. Particles are taken in
// chunks of kChunk; within a chunk every list is padded to the chunk's
// widest one and stored slot-major, so slot k of consecutive particles is
// contiguous. Entry k of particle p in chunk c is at
// begin[c] + k * (particles in chunk c) + (p - c * kChunk). Padding points at
// a dummy item (index = item count) whose per-instance data stays zero, with
// sign 0. Within a particle the order is the CSR order, so sums are formed
// identically however a particle range is split. Padding per chunk keeps a
// single high-valence vertex (a fan, a pole) from padding the whole mesh.
struct PaddedSlots {
    static constexpr uint32_t kChunk = kGroupSize;  // a chunk is a particle group

    explicit PaddedSlots(const HostMemory* memory)
        : begin(HostAllocator<size_t>(memory)),
          width(HostAllocator<uint32_t>(memory)),
          item(HostAllocator<uint32_t>(memory)),
          other(HostAllocator<uint32_t>(memory)),
          sign(HostAllocator<float>(memory)) {}

    HostVector<size_t> begin;    // per chunk
    HostVector<uint32_t> width;  // per chunk
    HostVector<uint32_t> item;
    HostVector<uint32_t> other;  // optional, same layout as item
    HostVector<float> sign;      // optional, same layout as item

    // Calls visit(lo, hi, base, k) for every slot k of every chunk piece of
    // [first, last), chunk by chunk and k = 0, 1, ... within a chunk: slot k
    // of particle p in [lo, hi) is at index base + p.
    template <class Visit>
    void for_each_slot(uint32_t particle_count, uint32_t first, uint32_t last, Visit visit) const {
        for (uint32_t lo = first; lo < last;) {
            const uint32_t c = lo / kChunk;
            const uint32_t chunk_first = c * kChunk;
            const uint32_t chunk_size = std::min(kChunk, particle_count - chunk_first);
            const uint32_t hi = std::min(last, chunk_first + chunk_size);
            for (uint32_t k = 0; k < width[c]; ++k) {
                visit(lo, hi,
                      static_cast<int64_t>(begin[c] + static_cast<size_t>(k) * chunk_size) - chunk_first, k);
            }
            lo = hi;
        }
    }
};

struct FabricLevel;  // fabric/fabric_levels.h

struct Fabric {
    explicit Fabric(const HostMemory* memory);

    const HostMemory* memory;

    uint32_t particle_count() const { return static_cast<uint32_t>(rest_positions.size()); }
    uint32_t triangle_count() const { return static_cast<uint32_t>(triangles.size() / 3); }
    uint32_t spring_count() const { return static_cast<uint32_t>(spring_first.size()); }

    HostVector<Vec3> rest_positions;
    HostVector<float> rest_area;     // lumped: a third of each incident triangle's area
    HostVector<uint32_t> triangles;  // 3 indices per triangle

    HostVector<uint32_t> spring_first;   // particle i of spring s
    HostVector<uint32_t> spring_second;  // particle j of spring s
    HostVector<float> spring_rest_length;
    HostVector<uint8_t> spring_kind;
    uint32_t springs_of_kind[kSpringKindCount] = {0, 0, 0};

    // Per particle p, entries incidence_offset[p] .. incidence_offset[p+1].
    HostVector<uint32_t> incidence_offset;
    HostVector<uint32_t> incidence_spring;

    // Triangles incident to each particle, for normals and wind forces.
    HostVector<uint32_t> triangle_incidence_offset;
    HostVector<uint32_t> triangle_incidence;

    // The same incidence lists in padded slots (see PaddedSlots), so that
    // the gathers run as vectorized loops over particles.
    PaddedSlots spring_slots;    // item: spring; other: particle at its other end; sign: +-1
    PaddedSlots triangle_slots;  // item: triangle
    // The strain limiter's: the same for structural and shear springs only
    // (in the same order), and per slot its spring's rest length (infinity
    // for padding, which is never over the limit).
    PaddedSlots limited_slots;  // item, other and sign as in spring_slots
    HostVector<float> limited_slot_rest;
    // The rest length where the slot's spring is structural (the limiter
    // bounds its compression too), else 0.
    HostVector<float> limited_slot_structural_rest;

    // Grid fabrics only (empty otherwise): the same springs as families,
    // and the triangles as two shapes per cell. Shape k of the cell whose
    // first corner is particle p has corners p + grid_triangle_shapes[3k + i];
    // the cell exists where grid_cell_mask[p] is 1. The two shapes are a fan
    // around the cell's first corner, (0, o1, o2) and (0, o2, o3), so the
    // air pass evaluates both from shared loads (aerodynamics.cpp).
    std::vector<SpringFamily, HostAllocator<SpringFamily>> grid_families;
    HostVector<uint32_t> grid_triangle_shapes;
    HostVector<float> grid_cell_mask;

    // Mesh fabrics store their particles in a spatial order (so that each
    // group of kChunk consecutive particles is a compact patch, paper Fig.
    // 1-2); the C API speaks the host's vertex indices and maps them here.
    // Both maps are empty when the two orders agree (grids).
    HostVector<uint32_t> particle_of_vertex;
    HostVector<uint32_t> vertex_of_particle;
    uint32_t particle(uint32_t vertex) const {
        return particle_of_vertex.empty() ? vertex : particle_of_vertex[vertex];
    }
    uint32_t vertex(uint32_t particle) const {
        return vertex_of_particle.empty() ? particle : vertex_of_particle[particle];
    }

    // A grid fabric's coarser levels of detail, level 1 first (fabric_levels.h;
    // the fabric itself is level 0): empty on meshes and small grids.
    std::vector<std::shared_ptr<const FabricLevel>, HostAllocator<std::shared_ptr<const FabricLevel>>> levels;

    // A hash of the counts and the rest data above (fabric_identity), set
    // when the world takes the fabric: equal for fabrics built from the same
    // description, so a snapshot names the fabric it belongs to.
    uint64_t identity = 0;
};

// The identity of a built fabric: XXH3 of its particle, triangle and spring
// counts, rest positions and areas, triangles, springs with their rest
// lengths and kinds, grid families and vertex order.
uint64_t fabric_identity(const Fabric& fabric);

// The mean rest length of the fabric's structural springs (m; 0 without any).
float mean_structural_rest_length(const Fabric& fabric);

// Largest particle count a fabric may have, and triangle count a mesh
// fabric may have (cloth.h).
constexpr uint32_t kMaxParticles = CLOTH_MAX_PARTICLES;
constexpr uint32_t kMaxTriangles = CLOTH_MAX_TRIANGLES;
static_assert(kMaxParticles == 1u << 24 && kMaxTriangles == 2 * kMaxParticles,
              "a grid at the particle limit has fewer triangles than the triangle limit");

// Builders fill a freshly constructed `out`; on error, discard it.
// Build from a grid description.
Status build_grid_fabric(const cloth_grid_desc& desc, Fabric& out);
// Build from a triangle mesh (positions: 3 floats per vertex); particles are
// stored in Morton order of the rest positions (see particle_of_vertex).
Status build_mesh_fabric(const float* positions, uint32_t vertex_count, const uint32_t* indices,
                         uint32_t triangle_count, uint32_t spring_kinds, Fabric& out);
// Load an OBJ file (triangulated) and build from it.
Status build_obj_fabric(const char* path, uint32_t spring_kinds, Fabric& out);

}  // namespace cloth
