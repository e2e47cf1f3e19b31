// Triangle-mesh fabrics: springs from the triangles' edges (an edge is a
// structural spring, an edge shared by two triangles adds a bend spring
// across it), particles stored in the
// Morton order of their rest positions so a particle group is a compact
// patch; Fabric::particle maps the host's vertex indices.
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "fabric/fabric.h"
#include "fabric/fabric_builder.h"

namespace cloth {

namespace {

// Builds a mesh fabric with the particles in the given vertex order.
Status build_mesh_in_given_order(const float* positions, uint32_t vertex_count, const uint32_t* indices,
                                 uint32_t triangle_count, uint32_t spring_kinds, Fabric& f) {
    if (!positions || !indices)
        return Status::error(CLOTH_ERROR_NULL_POINTER, "mesh positions or indices is NULL");
    if (vertex_count < 3 || vertex_count > kMaxParticles) {
        return Status::error(CLOTH_ERROR_INVALID_COUNT, "mesh vertex_count %u is not in 3..%u", vertex_count,
                             kMaxParticles);
    }
    if (triangle_count == 0 || triangle_count > kMaxTriangles) {
        return Status::error(CLOTH_ERROR_INVALID_COUNT, "mesh triangle_count %u is not in 1..%u",
                             triangle_count, kMaxTriangles);
    }
    if (spring_kinds & ~static_cast<uint32_t>(CLOTH_SPRING_ALL)) {
        return Status::error(CLOTH_ERROR_INVALID_VALUE, "unknown spring kind bits 0x%x", spring_kinds);
    }
    for (uint32_t p = 0; p < vertex_count; ++p) {
        if (!finite3(positions + 3 * p))
            return Status::error(CLOTH_ERROR_NOT_FINITE, "vertex %u is not finite", p);
    }
    for (uint32_t p = 0; p < vertex_count; ++p) {
        if (!within_range3(positions + 3 * p)) {
            return Status::error(CLOTH_ERROR_INVALID_VALUE,
                                 "vertex %u has a coordinate beyond CLOTH_MAX_COORDINATE (%g m)", p,
                                 double(CLOTH_MAX_COORDINATE));
        }
    }
    for (uint32_t t = 0; t < triangle_count; ++t) {
        const uint32_t* tri = indices + 3 * t;
        for (int k = 0; k < 3; ++k) {
            if (tri[k] >= vertex_count) {
                return Status::error(CLOTH_ERROR_INDEX_OUT_OF_RANGE, "triangle %u uses vertex %u of %u", t,
                                     tri[k], vertex_count);
            }
        }
        if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) {
            return Status::error(CLOTH_ERROR_DEGENERATE_GEOMETRY, "triangle %u repeats a vertex (%u, %u, %u)",
                                 t, tri[0], tri[1], tri[2]);
        }
    }

    f.rest_positions.resize(vertex_count);
    for (uint32_t p = 0; p < vertex_count; ++p) {
        f.rest_positions[p] = Vec3(positions[3 * p], positions[3 * p + 1], positions[3 * p + 2]);
    }
    f.triangles.assign(indices, indices + 3 * static_cast<size_t>(triangle_count));

    // Every edge with the vertex opposite it, sorted so that the two
    // triangles sharing an edge sit next to each other (fixed order).
    struct EdgeUse {
        uint32_t lo, hi, opposite;
        bool operator<(const EdgeUse& o) const {
            return lo != o.lo ? lo < o.lo : hi != o.hi ? hi < o.hi : opposite < o.opposite;
        }
    };
    std::vector<EdgeUse> uses;
    uses.reserve(3 * static_cast<size_t>(triangle_count));
    for (uint32_t t = 0; t < triangle_count; ++t) {
        const uint32_t* tri = indices + 3 * t;
        for (int k = 0; k < 3; ++k) {
            const uint32_t a = tri[k], b = tri[(k + 1) % 3], o = tri[(k + 2) % 3];
            uses.push_back({std::min(a, b), std::max(a, b), o});
        }
    }
    std::sort(uses.begin(), uses.end());

    std::vector<SpringSpec> springs;
    for (size_t begin = 0; begin < uses.size();) {
        size_t end = begin + 1;
        while (end < uses.size() && uses[end].lo == uses[begin].lo && uses[end].hi == uses[begin].hi) ++end;
        if (spring_kinds & CLOTH_SPRING_STRUCTURAL)
            springs.push_back({uses[begin].lo, uses[begin].hi, kStructural});
        // An edge shared by exactly two triangles: bend spring across it.
        if ((spring_kinds & CLOTH_SPRING_BEND) && end - begin == 2 &&
            uses[begin].opposite != uses[begin + 1].opposite) {
            springs.push_back({uses[begin].opposite, uses[begin + 1].opposite, kBend});
        }
        begin = end;
    }
    return finish_fabric(springs, f);
}

// Spreads the low 10 bits of v so that two zero bits follow each bit.
uint32_t spread_bits(uint32_t v) {
    v &= 0x3FFu;
    v = (v | (v << 16)) & 0x030000FFu;
    v = (v | (v << 8)) & 0x0300F00Fu;
    v = (v | (v << 4)) & 0x030C30C3u;
    v = (v | (v << 2)) & 0x09249249u;
    return v;
}

// Vertices sorted by the Morton (Z-order) code of their rest positions in
// the mesh's bounding box, ties by index: consecutive runs are compact
// patches of the surface, whatever order the mesh came in.
std::vector<uint32_t> spatial_order(const float* positions, uint32_t vertex_count) {
    Vec3 lo(positions[0], positions[1], positions[2]), hi = lo;
    for (uint32_t v = 0; v < vertex_count; ++v) {
        const Vec3 p(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]);
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
    }
    const float extent = std::max((hi - lo).maxCoeff(), 1e-30f);
    std::vector<std::pair<uint32_t, uint32_t>> keyed(vertex_count);
    for (uint32_t v = 0; v < vertex_count; ++v) {
        uint32_t code = 0;
        for (int axis = 0; axis < 3; ++axis) {
            const float t = (positions[3 * v + axis] - lo[axis]) / extent;  // 0..1
            code |= spread_bits(static_cast<uint32_t>(std::min(t, 1.0f) * 1023.0f)) << axis;
        }
        keyed[v] = {code, v};
    }
    std::sort(keyed.begin(), keyed.end());
    std::vector<uint32_t> order(vertex_count);
    for (uint32_t k = 0; k < vertex_count; ++k) order[k] = keyed[k].second;
    return order;
}

}  // namespace

Status build_mesh_fabric(const float* positions, uint32_t vertex_count, const uint32_t* indices,
                         uint32_t triangle_count, uint32_t spring_kinds, Fabric& f) {
    // Validate in the host's order, so that messages name its vertices and
    // triangles; then build again in the spatial order.
    {
        Fabric check(f.memory);
        Status s =
            build_mesh_in_given_order(positions, vertex_count, indices, triangle_count, spring_kinds, check);
        if (!s.ok()) return s;
    }
    const std::vector<uint32_t> order = spatial_order(positions, vertex_count);
    f.particle_of_vertex.resize(vertex_count);
    f.vertex_of_particle.assign(order.begin(), order.end());
    for (uint32_t k = 0; k < vertex_count; ++k) f.particle_of_vertex[order[k]] = k;
    std::vector<float> sorted_positions(3 * static_cast<size_t>(vertex_count));
    for (uint32_t k = 0; k < vertex_count; ++k) {
        for (int axis = 0; axis < 3; ++axis) sorted_positions[3 * k + axis] = positions[3 * order[k] + axis];
    }
    std::vector<uint32_t> sorted_indices(3 * static_cast<size_t>(triangle_count));
    for (size_t i = 0; i < sorted_indices.size(); ++i) sorted_indices[i] = f.particle_of_vertex[indices[i]];
    return build_mesh_in_given_order(sorted_positions.data(), vertex_count, sorted_indices.data(),
                                     triangle_count, spring_kinds, f);
}

}  // namespace cloth
