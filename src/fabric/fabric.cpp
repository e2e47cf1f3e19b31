// Fabrics: the constructor, the builders' shared tail (rest lengths, areas,
// incidence lists and their padded slots), the identity hash, and the grid
// builder. Triangle meshes are built in mesh_fabric.cpp.
#include "fabric/fabric.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "base/hash.h"
#include "fabric/fabric_builder.h"
#include "fabric/fabric_levels.h"

namespace cloth {

Fabric::Fabric(const HostMemory* memory)
    : memory(memory),
      rest_positions(HostAllocator<Vec3>(memory)),
      rest_area(HostAllocator<float>(memory)),
      triangles(HostAllocator<uint32_t>(memory)),
      spring_first(HostAllocator<uint32_t>(memory)),
      spring_second(HostAllocator<uint32_t>(memory)),
      spring_rest_length(HostAllocator<float>(memory)),
      spring_kind(HostAllocator<uint8_t>(memory)),
      incidence_offset(HostAllocator<uint32_t>(memory)),
      incidence_spring(HostAllocator<uint32_t>(memory)),
      triangle_incidence_offset(HostAllocator<uint32_t>(memory)),
      triangle_incidence(HostAllocator<uint32_t>(memory)),
      spring_slots(memory),
      triangle_slots(memory),
      limited_slots(memory),
      limited_slot_rest(HostAllocator<float>(memory)),
      limited_slot_structural_rest(HostAllocator<float>(memory)),
      grid_families(HostAllocator<SpringFamily>(memory)),
      grid_triangle_shapes(HostAllocator<uint32_t>(memory)),
      grid_cell_mask(HostAllocator<float>(memory)),
      particle_of_vertex(HostAllocator<uint32_t>(memory)),
      vertex_of_particle(HostAllocator<uint32_t>(memory)),
      levels(HostAllocator<std::shared_ptr<const FabricLevel>>(memory)) {}

namespace {

// |b - a| formed as the spring terms form a length (springs.h), so a spring
// at rest has a stretch of exactly zero.
float spring_length(const Vec3& a, const Vec3& b) {
    const float dx = b.x() - a.x(), dy = b.y() - a.y(), dz = b.z() - a.z();
    return std::sqrt(dx * dx + dy * dy + dz * dz);
}

// Build CSR lists: for each particle, the items (in increasing item order)
// that touch it. `ends(item, out)` writes the particles an item touches.
template <class Ends>
void build_incidence(uint32_t particle_count, uint32_t item_count, int ends_per_item, Ends ends,
                     HostVector<uint32_t>& offset, HostVector<uint32_t>& items) {
    offset.assign(particle_count + 1, 0);
    uint32_t touched[3];
    for (uint32_t item = 0; item < item_count; ++item) {
        ends(item, touched);
        for (int e = 0; e < ends_per_item; ++e) ++offset[touched[e] + 1];
    }
    for (uint32_t p = 0; p < particle_count; ++p) offset[p + 1] += offset[p];
    items.resize(offset[particle_count]);
    std::vector<uint32_t> cursor(offset.begin(), offset.end() - 1);
    for (uint32_t item = 0; item < item_count; ++item) {
        ends(item, touched);
        for (int e = 0; e < ends_per_item; ++e) items[cursor[touched[e]]++] = item;
    }
}

// Lays out CSR lists as padded slots (PaddedSlots) and calls
// put(slot, p, e) for every slot of particle p: e is its CSR entry, or
// UINT32_MAX for padding.
template <class Put>
void build_slots(const HostVector<uint32_t>& offset, bool with_other_and_sign, PaddedSlots& slots, Put put) {
    const uint32_t n = static_cast<uint32_t>(offset.size() - 1);
    const uint32_t chunks = (n + PaddedSlots::kChunk - 1) / PaddedSlots::kChunk;
    slots.begin.resize(chunks);
    slots.width.resize(chunks);
    size_t total = 0;
    for (uint32_t c = 0; c < chunks; ++c) {
        const uint32_t first = c * PaddedSlots::kChunk, last = std::min(n, first + PaddedSlots::kChunk);
        uint32_t width = 0;
        for (uint32_t p = first; p < last; ++p) width = std::max(width, offset[p + 1] - offset[p]);
        slots.begin[c] = total;
        slots.width[c] = width;
        total += static_cast<size_t>(width) * (last - first);
    }
    slots.item.resize(total);
    if (with_other_and_sign) {
        slots.other.resize(total);
        slots.sign.resize(total);
    }
    slots.for_each_slot(n, 0, n, [&](uint32_t lo, uint32_t hi, int64_t base, uint32_t k) {
        for (uint32_t p = lo; p < hi; ++p) {
            put(static_cast<size_t>(base + p), p, offset[p] + k < offset[p + 1] ? offset[p] + k : UINT32_MAX);
        }
    });
}

// Padded slots (build_slots) of the springs listed per particle by the CSR
// `offset` and spring_of(entry): item the spring, other the particle at its
// other end, sign +1 at its first particle and -1 at its second; padding
// the dummy spring (spring_count()), the particle itself, sign 0.
template <class SpringOf>
void build_spring_slots(Fabric& f, const HostVector<uint32_t>& offset, SpringOf spring_of,
                        PaddedSlots& slots) {
    build_slots(offset, true, slots, [&](size_t slot, uint32_t p, uint32_t e) {
        const uint32_t spring = e == UINT32_MAX ? f.spring_count() : spring_of(e);
        const bool first = e != UINT32_MAX && f.spring_first[spring] == p;
        slots.item[slot] = spring;
        slots.other[slot] = e == UINT32_MAX ? p : first ? f.spring_second[spring] : f.spring_first[spring];
        slots.sign[slot] = e == UINT32_MAX ? 0.0f : first ? 1.0f : -1.0f;
    });
}

}  // namespace

Status finish_fabric(const std::vector<SpringSpec>& springs, Fabric& f) {
    const uint32_t n = f.particle_count();
    const uint32_t t_count = f.triangle_count();

    f.rest_area.assign(n, 0.0f);
    for (uint32_t t = 0; t < t_count; ++t) {
        const uint32_t a = f.triangles[3 * t], b = f.triangles[3 * t + 1], c = f.triangles[3 * t + 2];
        const Vec3 e1 = f.rest_positions[b] - f.rest_positions[a];
        const Vec3 e2 = f.rest_positions[c] - f.rest_positions[a];
        const float area = 0.5f * e1.cross(e2).norm();
        const float longest = std::max({e1.squaredNorm(), e2.squaredNorm(), (e2 - e1).squaredNorm()});
        if (!(area > 1e-6f * longest)) {
            return Status::error(CLOTH_ERROR_DEGENERATE_GEOMETRY, "triangle %u (%u, %u, %u) has zero area", t,
                                 a, b, c);
        }
        for (uint32_t v : {a, b, c}) f.rest_area[v] += area / 3.0f;
    }
    for (uint32_t p = 0; p < n; ++p) {
        if (f.rest_area[p] == 0.0f) {
            return Status::error(CLOTH_ERROR_DEGENERATE_GEOMETRY,
                                 "vertex %u belongs to no triangle (it would have no mass)", p);
        }
    }

    const auto count = static_cast<uint32_t>(springs.size());
    f.spring_first.resize(count);
    f.spring_second.resize(count);
    f.spring_rest_length.resize(count);
    f.spring_kind.resize(count);
    for (uint32_t s = 0; s < count; ++s) {
        const SpringSpec& spec = springs[s];
        const float length = spring_length(f.rest_positions[spec.i], f.rest_positions[spec.j]);
        if (!(length > 0.0f)) {
            return Status::error(CLOTH_ERROR_DEGENERATE_GEOMETRY,
                                 "particles %u and %u coincide (zero-length spring)", spec.i, spec.j);
        }
        f.spring_first[s] = spec.i;
        f.spring_second[s] = spec.j;
        f.spring_rest_length[s] = length;
        f.spring_kind[s] = spec.kind;
        ++f.springs_of_kind[spec.kind];
    }

    build_incidence(
        n, count, 2,
        [&](uint32_t s, uint32_t* out) {
            out[0] = f.spring_first[s];
            out[1] = f.spring_second[s];
        },
        f.incidence_offset, f.incidence_spring);
    build_spring_slots(
        f, f.incidence_offset, [&](uint32_t e) { return f.incidence_spring[e]; }, f.spring_slots);
    // The strain limiter's lists: the same, structural and shear springs only.
    std::vector<uint32_t> limited;
    for (uint32_t s = 0; s < count; ++s)
        if (f.spring_kind[s] != kBend) limited.push_back(s);
    HostVector<uint32_t> limited_offset{HostAllocator<uint32_t>(f.memory)};
    HostVector<uint32_t> limited_incidence{HostAllocator<uint32_t>(f.memory)};
    build_incidence(
        n, static_cast<uint32_t>(limited.size()), 2,
        [&](uint32_t l, uint32_t* out) {
            out[0] = f.spring_first[limited[l]];
            out[1] = f.spring_second[limited[l]];
        },
        limited_offset, limited_incidence);
    build_spring_slots(
        f, limited_offset, [&](uint32_t e) { return limited[limited_incidence[e]]; }, f.limited_slots);
    f.limited_slot_rest.resize(f.limited_slots.item.size());
    f.limited_slot_structural_rest.resize(f.limited_slots.item.size());
    for (size_t slot = 0; slot < f.limited_slot_rest.size(); ++slot) {
        const uint32_t spring = f.limited_slots.item[slot];
        f.limited_slot_rest[slot] =
            spring < count ? f.spring_rest_length[spring] : std::numeric_limits<float>::infinity();
        f.limited_slot_structural_rest[slot] =
            spring < count && f.spring_kind[spring] == kStructural ? f.spring_rest_length[spring] : 0.0f;
    }
    build_incidence(
        n, t_count, 3,
        [&](uint32_t t, uint32_t* out) {
            for (int k = 0; k < 3; ++k) out[k] = f.triangles[3 * t + k];
        },
        f.triangle_incidence_offset, f.triangle_incidence);
    build_slots(f.triangle_incidence_offset, false, f.triangle_slots, [&](size_t slot, uint32_t, uint32_t e) {
        f.triangle_slots.item[slot] = e == UINT32_MAX ? t_count : f.triangle_incidence[e];
    });
    return {};
}

bool finite3(const float* v) { return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]); }

bool within_range3(const float* v) {
    return std::abs(v[0]) <= CLOTH_MAX_COORDINATE && std::abs(v[1]) <= CLOTH_MAX_COORDINATE &&
           std::abs(v[2]) <= CLOTH_MAX_COORDINATE;
}

float mean_structural_rest_length(const Fabric& fabric) {
    double sum = 0;
    for (uint32_t s = 0; s < fabric.spring_count(); ++s) {
        if (fabric.spring_kind[s] == kStructural) sum += fabric.spring_rest_length[s];
    }
    const uint32_t count = fabric.springs_of_kind[kStructural];
    return count > 0 ? static_cast<float>(sum / count) : 0.0f;
}

uint64_t fabric_identity(const Fabric& f) {
    const uint32_t counts[] = {f.particle_count(),
                               f.triangle_count(),
                               f.spring_count(),
                               f.springs_of_kind[0],
                               f.springs_of_kind[1],
                               f.springs_of_kind[2],
                               static_cast<uint32_t>(f.grid_families.size())};
    uint64_t h = hash_bytes(counts, sizeof counts);
    auto add = [&h](const auto& values) {
        h = hash_bytes(values.data(), values.size() * sizeof(values[0]), h);
    };
    for (const Vec3& p : f.rest_positions) h = hash_bytes(p.data(), 3 * sizeof(float), h);
    add(f.rest_area);
    add(f.triangles);
    add(f.spring_first);
    add(f.spring_second);
    add(f.spring_rest_length);
    add(f.spring_kind);
    add(f.particle_of_vertex);
    for (const SpringFamily& family : f.grid_families) {
        const uint32_t shape[] = {family.offset, static_cast<uint32_t>(family.kind)};
        h = hash_bytes(shape, sizeof shape, h);
        add(family.mask);
        add(family.rest_length);
    }
    return h;
}

Status build_grid_fabric(const cloth_grid_desc& desc, Fabric& f) {
    const uint32_t cols = desc.columns, rows = desc.rows;
    if (cols < 2 || rows < 2) {
        return Status::error(CLOTH_ERROR_INVALID_COUNT,
                             "grid needs at least 2 columns and 2 rows (got %u x %u)", cols, rows);
    }
    if (static_cast<uint64_t>(cols) * rows > kMaxParticles) {
        return Status::error(CLOTH_ERROR_INVALID_COUNT, "grid of %u x %u exceeds %u particles", cols, rows,
                             kMaxParticles);
    }
    if (!finite3(desc.origin) || !finite3(desc.u) || !finite3(desc.v)) {
        return Status::error(CLOTH_ERROR_NOT_FINITE, "grid origin, u or v is not finite");
    }
    if (!within_range3(desc.origin) || !within_range3(desc.u) || !within_range3(desc.v)) {
        return Status::error(CLOTH_ERROR_INVALID_VALUE,
                             "grid origin, u or v has a coordinate beyond CLOTH_MAX_COORDINATE (%g m)",
                             double(CLOTH_MAX_COORDINATE));
    }
    if (desc.spring_kinds & ~static_cast<uint32_t>(CLOTH_SPRING_ALL)) {
        return Status::error(CLOTH_ERROR_INVALID_VALUE, "unknown spring kind bits 0x%x", desc.spring_kinds);
    }
    const Vec3 origin(desc.origin[0], desc.origin[1], desc.origin[2]);
    const Vec3 u(desc.u[0], desc.u[1], desc.u[2]);
    const Vec3 v(desc.v[0], desc.v[1], desc.v[2]);
    if (!(u.cross(v).norm() > 1e-6f * u.norm() * v.norm())) {
        return Status::error(CLOTH_ERROR_DEGENERATE_GEOMETRY, "grid edges u and v are zero or parallel");
    }

    auto index = [cols](uint32_t c, uint32_t r) { return r * cols + c; };
    f.rest_positions.resize(static_cast<size_t>(cols) * rows);
    for (uint32_t r = 0; r < rows; ++r) {
        for (uint32_t c = 0; c < cols; ++c) {
            f.rest_positions[index(c, r)] = origin +
                                            u * (static_cast<float>(c) / static_cast<float>(cols - 1)) +
                                            v * (static_cast<float>(r) / static_cast<float>(rows - 1));
        }
    }
    Status status = build_grid_topology(cols, rows, desc.spring_kinds, f);
    if (!status.ok()) return status;
    return build_fabric_levels(f);
}

Status build_grid_topology(uint32_t cols, uint32_t rows, uint32_t spring_kinds, Fabric& f) {
    auto index = [cols](uint32_t c, uint32_t r) { return r * cols + c; };
    // Two triangles per cell, split along the same diagonal everywhere:
    // every interior particle then touches six triangles and gets the same
    // lumped mass, and the triangles of cell p are two fixed shapes at p.
    const uint32_t shapes[2][3] = {{0, 1, cols + 1}, {0, cols + 1, cols}};
    f.grid_triangle_shapes.assign(&shapes[0][0], &shapes[0][0] + 6);
    f.grid_cell_mask.assign(static_cast<size_t>(cols) * rows, 0.0f);
    f.triangles.reserve(static_cast<size_t>(cols - 1) * (rows - 1) * 6);
    for (uint32_t r = 0; r + 1 < rows; ++r) {
        for (uint32_t c = 0; c + 1 < cols; ++c) {
            const uint32_t p = index(c, r);
            f.grid_cell_mask[p] = 1.0f;
            for (const auto& shape : shapes) {
                for (uint32_t corner : shape) f.triangles.push_back(p + corner);
            }
        }
    }

    // Spring families: (column step, row step, kind).
    struct Direction {
        int dc, dr;
        SpringKind kind;
        uint32_t bit;
    };
    const Direction directions[] = {{1, 0, kStructural, CLOTH_SPRING_STRUCTURAL},
                                    {0, 1, kStructural, CLOTH_SPRING_STRUCTURAL},
                                    {1, 1, kShear, CLOTH_SPRING_SHEAR},
                                    {-1, 1, kShear, CLOTH_SPRING_SHEAR},
                                    {2, 0, kBend, CLOTH_SPRING_BEND},
                                    {0, 2, kBend, CLOTH_SPRING_BEND}};
    for (const Direction& d : directions) {
        if (!(spring_kinds & d.bit)) continue;
        SpringFamily& family = f.grid_families.emplace_back(f.memory);
        family.offset = static_cast<uint32_t>(d.dr * static_cast<int>(cols) + d.dc);
        family.kind = d.kind;
        family.mask.assign(static_cast<size_t>(cols) * rows, 0.0f);
        family.rest_length.assign(static_cast<size_t>(cols) * rows, 0.0f);
        for (uint32_t r = 0; r + d.dr < rows; ++r) {
            for (uint32_t c = 0; c < cols; ++c) {
                const int to = static_cast<int>(c) + d.dc;
                if (to < 0 || to >= static_cast<int>(cols)) continue;
                const uint32_t p = index(c, r);
                family.mask[p] = 1.0f;
                family.rest_length[p] =
                    spring_length(f.rest_positions[p], f.rest_positions[p + family.offset]);
            }
        }
    }

    std::vector<SpringSpec> springs;
    const uint32_t kinds = spring_kinds;
    for (uint32_t r = 0; r < rows; ++r) {
        for (uint32_t c = 0; c < cols; ++c) {
            const uint32_t p = index(c, r);
            if (kinds & CLOTH_SPRING_STRUCTURAL) {
                if (c + 1 < cols) springs.push_back({p, index(c + 1, r), kStructural});
                if (r + 1 < rows) springs.push_back({p, index(c, r + 1), kStructural});
            }
            if ((kinds & CLOTH_SPRING_SHEAR) && c + 1 < cols && r + 1 < rows) {
                springs.push_back({p, index(c + 1, r + 1), kShear});
                springs.push_back({index(c + 1, r), index(c, r + 1), kShear});
            }
            if (kinds & CLOTH_SPRING_BEND) {
                if (c + 2 < cols) springs.push_back({p, index(c + 2, r), kBend});
                if (r + 2 < rows) springs.push_back({p, index(c, r + 2), kBend});
            }
        }
    }
    return finish_fabric(springs, f);
}

}  // namespace cloth
