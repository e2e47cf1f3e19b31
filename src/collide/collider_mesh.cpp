// Triangle-mesh and height-field colliders.
//
// A mesh gets a uniform grid over its local bounds, built once at creation
// (CSR lists of the triangles overlapping each cell): meshes here are static
// in their own frame, so there is nothing to refit, and a grid query touches
// only the cells within the query radius. Written by hand because the core
// must not depend on Bullet's BVH and the structure is thirty lines.
// A height field needs no structure: its cells are its grid.
#include <algorithm>
#include <cmath>
#include <limits>

#include "collide/colliders.h"

namespace cloth {

Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 ab = b - a, ac = c - a, ap = p - a;
    const float d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0 && d2 <= 0) return a;
    const Vec3 bp = p - b;
    const float d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0 && d4 <= d3) return b;
    const float vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
    const Vec3 cp = p - c;
    const float d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0 && d5 <= d6) return c;
    const float vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
    const float va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    const float denominator = 1.0f / (va + vb + vc);
    return a + ab * (vb * denominator) + ac * (vc * denominator);
}

namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();
constexpr size_t kMaxGridCells = size_t{1} << 21;

// Keeps the closest triangle; among (nearly) equally close ones, the one
// the point is most clearly in front of or behind (edges and vertices
// shared by several triangles).
struct Nearest {
    float distance2 = kInfinity;
    float side = 0;  // dot(p - closest, triangle normal)
    Vec3 closest = Vec3::Zero();
    Vec3 face_normal = Vec3::UnitY();

    void offer(const Vec3& p, const Vec3& c, const Vec3& n) {
        const float d2 = (p - c).squaredNorm();
        const float side_here = (p - c).dot(n);
        if (d2 > distance2 * (1.0f + 1e-4f) + 1e-12f) return;
        const bool tie = d2 >= distance2 * (1.0f - 1e-4f) - 1e-12f;
        if (!tie || std::abs(side_here) > std::abs(side)) {
            distance2 = d2;
            side = side_here;
            closest = c;
            face_normal = n;
        }
    }

    // Signed answer: behind the closest face is inside.
    SurfaceQuery answer(const Vec3& p, float radius) const {
        if (!(distance2 <= radius * radius)) return {radius, Vec3::UnitY()};
        const float distance = std::sqrt(distance2);
        const float sign = side < 0 ? -1.0f : 1.0f;
        if (distance <= 1e-9f) return {0.0f, face_normal};
        return {sign * distance, (p - closest) * (sign / distance)};
    }
};

}  // namespace

Status build_triangle_mesh(const float* xyz, uint32_t vertex_count, const uint32_t* indices,
                           uint32_t triangle_count, Shape& shape) {
    if (vertex_count < 3 || vertex_count > (1u << 24))
        return Status::error(CLOTH_ERROR_INVALID_COUNT, "vertex_count %u is not in 3..2^24", vertex_count);
    if (triangle_count < 1 || triangle_count > (1u << 24))
        return Status::error(CLOTH_ERROR_INVALID_COUNT, "triangle_count %u is not in 1..2^24",
                             triangle_count);
    MeshShape& mesh = shape.mesh;
    mesh.vertices.resize(vertex_count);
    Vec3 lo = Vec3::Constant(kInfinity), hi = -lo;
    for (uint32_t i = 0; i < vertex_count; ++i) {
        mesh.vertices[i] = Vec3(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
        lo = lo.cwiseMin(mesh.vertices[i]);
        hi = hi.cwiseMax(mesh.vertices[i]);
    }
    // Finite vertices can still span more than a float (+-1e38 apart): the
    // grid below divides that span.
    if (!(hi - lo).allFinite())
        return Status::error(CLOTH_ERROR_INVALID_VALUE, "the vertices span more than the float range");
    mesh.triangles.assign(indices, indices + 3 * static_cast<size_t>(triangle_count));
    mesh.normals.resize(triangle_count);
    double edge_sum = 0;
    for (uint32_t t = 0; t < triangle_count; ++t) {
        const uint32_t* tri = &mesh.triangles[3 * static_cast<size_t>(t)];
        for (int k = 0; k < 3; ++k) {
            if (tri[k] >= vertex_count) {
                return Status::error(CLOTH_ERROR_INDEX_OUT_OF_RANGE,
                                     "indices[%u] = %u, but there are %u vertices", 3 * t + k, tri[k],
                                     vertex_count);
            }
        }
        const Vec3& a = mesh.vertices[tri[0]];
        const Vec3& b = mesh.vertices[tri[1]];
        const Vec3& c = mesh.vertices[tri[2]];
        const Vec3 n = (b - a).cross(c - a);
        const float length = n.norm();
        const float scale = std::max({(b - a).norm(), (c - a).norm(), (c - b).norm()});
        if (!(length > 1e-7f * scale * scale)) {
            return Status::error(CLOTH_ERROR_DEGENERATE_GEOMETRY, "triangle %u has (nearly) zero area", t);
        }
        mesh.normals[t] = n / length;
        edge_sum += scale;
    }

    // Grid: cells about the size of a triangle, at most kMaxGridCells.
    const Vec3 extent = hi - lo;
    float cell = std::max(static_cast<float>(edge_sum / triangle_count), 1e-3f * extent.maxCoeff());
    auto cell_count = [&](float size) {
        size_t total = 1;
        for (int k = 0; k < 3; ++k) total *= static_cast<size_t>(extent[k] / size) + 1;
        return total;
    };
    while (cell_count(cell) > kMaxGridCells) cell *= 1.5f;
    mesh.cell_size = cell;
    mesh.grid_min = lo;
    for (int k = 0; k < 3; ++k) mesh.cells[k] = static_cast<uint32_t>(extent[k] / cell) + 1;
    const size_t cells = cell_count(cell);
    auto cell_range = [&](uint32_t t, uint32_t* first, uint32_t* last) {
        const uint32_t* tri = &mesh.triangles[3 * static_cast<size_t>(t)];
        Vec3 tlo = mesh.vertices[tri[0]], thi = tlo;
        for (int k = 1; k < 3; ++k) {
            tlo = tlo.cwiseMin(mesh.vertices[tri[k]]);
            thi = thi.cwiseMax(mesh.vertices[tri[k]]);
        }
        for (int k = 0; k < 3; ++k) {
            first[k] = std::min(mesh.cells[k] - 1, static_cast<uint32_t>((tlo[k] - lo[k]) / cell));
            last[k] = std::min(mesh.cells[k] - 1, static_cast<uint32_t>((thi[k] - lo[k]) / cell));
        }
    };
    auto for_cells = [&](uint32_t t, auto visit) {
        uint32_t first[3], last[3];
        cell_range(t, first, last);
        for (uint32_t z = first[2]; z <= last[2]; ++z)
            for (uint32_t y = first[1]; y <= last[1]; ++y)
                for (uint32_t x = first[0]; x <= last[0]; ++x)
                    visit((static_cast<size_t>(z) * mesh.cells[1] + y) * mesh.cells[0] + x);
    };
    mesh.cell_begin.assign(cells + 1, 0);
    for (uint32_t t = 0; t < triangle_count; ++t) for_cells(t, [&](size_t c) { ++mesh.cell_begin[c + 1]; });
    for (size_t c = 0; c < cells; ++c) mesh.cell_begin[c + 1] += mesh.cell_begin[c];
    mesh.cell_items.resize(mesh.cell_begin[cells]);
    HostVector<uint32_t> fill(mesh.cell_begin.begin(), mesh.cell_begin.end() - 1,
                              mesh.cell_begin.get_allocator());
    for (uint32_t t = 0; t < triangle_count; ++t)
        for_cells(t, [&](size_t c) { mesh.cell_items[fill[c]++] = t; });

    shape.kind = ShapeKind::kTriangleMesh;
    shape.bound_center = (lo + hi) * 0.5f;
    shape.bound_radius = 0.5f * extent.norm();
    shape.query_step = cell;
    return {};
}

SurfaceQuery query_mesh(const MeshShape& mesh, const Vec3& p, float radius) {
    uint32_t first[3], last[3];
    for (int k = 0; k < 3; ++k) {
        const float lo = (p[k] - radius - mesh.grid_min[k]) / mesh.cell_size;
        const float hi = (p[k] + radius - mesh.grid_min[k]) / mesh.cell_size;
        if (!(hi >= 0) || !(lo < static_cast<float>(mesh.cells[k]))) return {radius, Vec3::UnitY()};
        first[k] = static_cast<uint32_t>(std::max(lo, 0.0f));
        last[k] = std::min(mesh.cells[k] - 1, static_cast<uint32_t>(hi));
    }
    Nearest nearest;
    for (uint32_t z = first[2]; z <= last[2]; ++z) {
        for (uint32_t y = first[1]; y <= last[1]; ++y) {
            for (uint32_t x = first[0]; x <= last[0]; ++x) {
                const size_t cell = (static_cast<size_t>(z) * mesh.cells[1] + y) * mesh.cells[0] + x;
                for (uint32_t k = mesh.cell_begin[cell]; k < mesh.cell_begin[cell + 1]; ++k) {
                    const uint32_t t = mesh.cell_items[k];
                    const uint32_t* tri = &mesh.triangles[3 * static_cast<size_t>(t)];
                    nearest.offer(p,
                                  closest_point_on_triangle(p, mesh.vertices[tri[0]], mesh.vertices[tri[1]],
                                                            mesh.vertices[tri[2]]),
                                  mesh.normals[t]);
                }
            }
        }
    }
    return nearest.answer(p, radius);
}

Status build_heightfield(uint32_t columns, uint32_t rows, float spacing_x, float spacing_z,
                         const float* heights, Shape& shape) {
    HeightfieldShape& field = shape.heightfield;
    field.columns = columns;
    field.rows = rows;
    field.spacing_x = spacing_x;
    field.spacing_z = spacing_z;
    field.heights.assign(heights, heights + static_cast<size_t>(columns) * rows);
    float lo = kInfinity, hi = -kInfinity;
    for (float h : field.heights) lo = std::min(lo, h), hi = std::max(hi, h);
    const Vec3 min_corner(0, lo, 0), max_corner(spacing_x * (columns - 1), hi, spacing_z * (rows - 1));
    shape.kind = ShapeKind::kHeightfield;
    shape.bound_center = (min_corner + max_corner) * 0.5f;
    shape.bound_radius = 0.5f * (max_corner - min_corner).norm();
    shape.query_step = std::min(spacing_x, spacing_z);
    return {};
}

namespace {

// The two triangles of cell (c, r), counter-clockwise seen from above.
void cell_triangles(const HeightfieldShape& f, uint32_t c, uint32_t r, Vec3 (&tri)[2][3]) {
    auto vertex = [&](uint32_t cc, uint32_t rr) {
        return Vec3(static_cast<float>(cc) * f.spacing_x, f.height(cc, rr),
                    static_cast<float>(rr) * f.spacing_z);
    };
    const Vec3 v00 = vertex(c, r), v10 = vertex(c + 1, r), v01 = vertex(c, r + 1), v11 = vertex(c + 1, r + 1);
    tri[0][0] = v00, tri[0][1] = v01, tri[0][2] = v10;
    tri[1][0] = v10, tri[1][1] = v01, tri[1][2] = v11;
}

// Surface height at (x, z) inside the field.
float surface_height(const HeightfieldShape& f, float x, float z) {
    const float u = x / f.spacing_x, w = z / f.spacing_z;
    const uint32_t c = std::min(f.columns - 2, static_cast<uint32_t>(u));
    const uint32_t r = std::min(f.rows - 2, static_cast<uint32_t>(w));
    const float fu = u - static_cast<float>(c), fw = w - static_cast<float>(r);
    if (fu + fw <= 1.0f) {
        const float h00 = f.height(c, r);
        return h00 + fu * (f.height(c + 1, r) - h00) + fw * (f.height(c, r + 1) - h00);
    }
    const float h11 = f.height(c + 1, r + 1);
    return h11 + (1.0f - fu) * (f.height(c, r + 1) - h11) + (1.0f - fw) * (f.height(c + 1, r) - h11);
}

}  // namespace

bool heightfield_cells(const HeightfieldShape& f, float x_lo, float x_hi, float z_lo, float z_hi,
                       float radius, HeightfieldCells& out) {
    const float c_lo = (x_lo - radius) / f.spacing_x, c_hi = (x_hi + radius) / f.spacing_x;
    const float r_lo = (z_lo - radius) / f.spacing_z, r_hi = (z_hi + radius) / f.spacing_z;
    if (!(c_hi >= 0 && r_hi >= 0 && c_lo < static_cast<float>(f.columns - 1) &&
          r_lo < static_cast<float>(f.rows - 1))) {
        return false;
    }
    // Clamped to the field in float before the cast: a particle that moves
    // far in one substep asks with a radius past any uint32_t.
    out.c0 = static_cast<uint32_t>(std::max(c_lo, 0.0f));
    out.c1 = static_cast<uint32_t>(std::min(c_hi, static_cast<float>(f.columns - 2)));
    out.r0 = static_cast<uint32_t>(std::max(r_lo, 0.0f));
    out.r1 = static_cast<uint32_t>(std::min(r_hi, static_cast<float>(f.rows - 2)));
    return true;
}

float highest_sample(const HeightfieldShape& f, const HeightfieldCells& cells) {
    float highest = -kInfinity;
    for (uint32_t r = cells.r0; r <= cells.r1 + 1; ++r) {
        for (uint32_t c = cells.c0; c <= cells.c1 + 1; ++c) highest = std::max(highest, f.height(c, r));
    }
    return highest;
}

SurfaceQuery query_heightfield(const HeightfieldShape& f, const Vec3& p, float radius) {
    const float width = f.spacing_x * static_cast<float>(f.columns - 1);
    const float depth = f.spacing_z * static_cast<float>(f.rows - 1);
    const bool over = p.x() >= 0 && p.x() <= width && p.z() >= 0 && p.z() <= depth;
    const float below = over ? p.y() - surface_height(f, p.x(), p.z()) : kInfinity;

    Nearest nearest;
    HeightfieldCells cells;
    if (heightfield_cells(f, p.x(), p.x(), p.z(), p.z(), radius, cells)) {
        // Early out for the usual case, a particle well above the ground:
        // every triangle of these cells lies below their highest sample, so
        // a point more than `radius` above it is clear of all of them (the
        // same answer as testing each triangle, for a fraction of the cost).
        if (p.y() - highest_sample(f, cells) > radius) return {radius, Vec3::UnitY()};
        for (uint32_t r = cells.r0; r <= cells.r1; ++r) {
            for (uint32_t c = cells.c0; c <= cells.c1; ++c) {
                Vec3 tri[2][3];
                cell_triangles(f, c, r, tri);
                for (auto& t : tri) {
                    const Vec3 n = (t[1] - t[0]).cross(t[2] - t[0]).normalized();
                    nearest.offer(p, closest_point_on_triangle(p, t[0], t[1], t[2]), n);
                }
            }
        }
    }
    if (below < 0) {
        // Solid below the surface: inside whatever side the closest face shows.
        if (!(nearest.distance2 <= radius * radius)) return {below, Vec3::UnitY()};  // deep: straight up
        const float distance = std::sqrt(nearest.distance2);
        if (distance <= 1e-9f) return {0.0f, nearest.face_normal};
        return {-distance, (nearest.closest - p) / distance};
    }
    if (!(nearest.distance2 <= radius * radius)) return {radius, Vec3::UnitY()};
    const float distance = std::sqrt(nearest.distance2);
    if (distance <= 1e-9f) return {0.0f, nearest.face_normal};
    return {distance, (p - nearest.closest) / distance};
}

}  // namespace cloth
