#include "support/sheet_side.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

namespace cloth_test {

namespace {

using Vec = std::array<double, 3>;

Vec sub(const Vec& a, const Vec& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec add(const Vec& a, const Vec& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
Vec scale(const Vec& a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }
double dot(const Vec& a, const Vec& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec cross(const Vec& a, const Vec& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
Vec normalised(const Vec& a) {
    const double length = std::sqrt(dot(a, a));
    return length > 0.0 ? scale(a, 1.0 / length) : Vec{0, 0, 0};
}
Vec at(const std::vector<float>& xyz, uint32_t i) { return {xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]}; }

// Where on a triangle its nearest point to p lies.
enum class Feature { kFace, kEdgeAB, kEdgeBC, kEdgeCA, kVertexA, kVertexB, kVertexC };

// The nearest point of triangle abc to p and its feature (Ericson,
// Real-Time Collision Detection, 5.1.5, by Voronoi regions).
Vec closest_on_triangle(const Vec& p, const Vec& a, const Vec& b, const Vec& c, Feature* feature) {
    const Vec ab = sub(b, a), ac = sub(c, a), ap = sub(p, a);
    const double d1 = dot(ab, ap), d2 = dot(ac, ap);
    if (d1 <= 0 && d2 <= 0) return *feature = Feature::kVertexA, a;
    const Vec bp = sub(p, b);
    const double d3 = dot(ab, bp), d4 = dot(ac, bp);
    if (d3 >= 0 && d4 <= d3) return *feature = Feature::kVertexB, b;
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return *feature = Feature::kEdgeAB, add(a, scale(ab, d1 / (d1 - d3)));
    const Vec cp = sub(p, c);
    const double d5 = dot(ab, cp), d6 = dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) return *feature = Feature::kVertexC, c;
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return *feature = Feature::kEdgeCA, add(a, scale(ac, d2 / (d2 - d6)));
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
        return *feature = Feature::kEdgeBC, add(b, scale(sub(c, b), (d4 - d3) / ((d4 - d3) + (d5 - d6))));
    }
    const double denominator = 1.0 / (va + vb + vc);
    *feature = Feature::kFace;
    return add(a, add(scale(ab, vb * denominator), scale(ac, vc * denominator)));
}

uint64_t edge_key(uint32_t a, uint32_t b) {
    return (static_cast<uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
}

}  // namespace

std::vector<float> signed_distances_to_sheet(const std::vector<float>& points,
                                             const std::vector<float>& vertices,
                                             const std::vector<uint32_t>& triangles) {
    const size_t vertex_count = vertices.size() / 3, triangle_count = triangles.size() / 3;
    // The pseudo-normals: each triangle's, each edge's, each vertex's.
    std::vector<Vec> face(triangle_count), vertex(vertex_count, Vec{0, 0, 0});
    std::map<uint64_t, std::pair<Vec, int>> edge;  // the sum of its triangles' normals, and their count
    for (size_t t = 0; t < triangle_count; ++t) {
        const uint32_t* corner = &triangles[3 * t];
        face[t] = normalised(cross(sub(at(vertices, corner[1]), at(vertices, corner[0])),
                                   sub(at(vertices, corner[2]), at(vertices, corner[0]))));
        for (int k = 0; k < 3; ++k) {
            const uint32_t here = corner[k], next = corner[(k + 1) % 3], previous = corner[(k + 2) % 3];
            auto& e = edge.emplace(edge_key(here, next), std::make_pair(Vec{0, 0, 0}, 0)).first->second;
            e.first = add(e.first, face[t]);
            ++e.second;
            const Vec to_next = normalised(sub(at(vertices, next), at(vertices, here)));
            const Vec to_previous = normalised(sub(at(vertices, previous), at(vertices, here)));
            const double angle = std::acos(std::clamp(dot(to_next, to_previous), -1.0, 1.0));
            vertex[here] = add(vertex[here], scale(face[t], angle));
        }
    }
    // The border: the edges of one triangle, and their ends.
    std::vector<bool> border_vertex(vertex_count, false);
    for (auto& [key, normal] : edge) {
        normal.first = normalised(normal.first);
        if (normal.second == 1) {
            border_vertex[key >> 32] = true;
            border_vertex[key & 0xffffffffu] = true;
        }
    }
    for (Vec& normal : vertex) normal = normalised(normal);
    // Each triangle's bounds, to skip the triangles that cannot hold a
    // nearer point than one already found (every triangle is still tried).
    std::vector<Vec> low(triangle_count), high(triangle_count);
    for (size_t t = 0; t < triangle_count; ++t) {
        for (int d = 0; d < 3; ++d) {
            low[t][d] = high[t][d] = vertices[3 * triangles[3 * t] + d];
            for (int k = 1; k < 3; ++k) {
                low[t][d] = std::min<double>(low[t][d], vertices[3 * triangles[3 * t + k] + d]);
                high[t][d] = std::max<double>(high[t][d], vertices[3 * triangles[3 * t + k] + d]);
            }
        }
    }

    std::vector<float> out(points.size() / 3);
    for (size_t i = 0; i < out.size(); ++i) {
        const Vec p = at(points, static_cast<uint32_t>(i));
        // The nearest vertex bounds the nearest point's distance from above.
        double best = std::numeric_limits<double>::infinity();
        for (size_t v = 0; v < vertex_count; ++v) {
            const Vec d = sub(p, at(vertices, static_cast<uint32_t>(v)));
            best = std::min(best, dot(d, d));
        }
        best *= 1.0 + 1e-9;
        double signed_distance = 0;
        for (size_t t = 0; t < triangle_count; ++t) {
            double outside = 0;  // squared distance from p to the triangle's bounds
            for (int d = 0; d < 3; ++d) {
                const double gap = std::max({low[t][d] - p[d], 0.0, p[d] - high[t][d]});
                outside += gap * gap;
            }
            if (outside > best) continue;
            const uint32_t* corner = &triangles[3 * t];
            Feature feature;
            const Vec q = closest_on_triangle(p, at(vertices, corner[0]), at(vertices, corner[1]),
                                              at(vertices, corner[2]), &feature);
            const Vec offset = sub(p, q);
            const double squared = dot(offset, offset);
            if (squared > best) continue;  // the nearest vertex's triangle is within it
            // The pseudo-normal of the nearest point's feature, and whether
            // that feature is on the border.
            Vec normal = face[t];
            bool on_border = false;
            if (feature == Feature::kEdgeAB || feature == Feature::kEdgeBC || feature == Feature::kEdgeCA) {
                const int k = feature == Feature::kEdgeAB ? 0 : feature == Feature::kEdgeBC ? 1 : 2;
                const auto& e = edge[edge_key(corner[k], corner[(k + 1) % 3])];
                normal = e.first;
                on_border = e.second == 1;
            } else if (feature != Feature::kFace) {
                const uint32_t v = corner[feature == Feature::kVertexA   ? 0
                                          : feature == Feature::kVertexB ? 1
                                                                         : 2];
                normal = vertex[v];
                on_border = border_vertex[v];
            }
            best = squared;
            signed_distance = dot(offset, normal);
            // Nearest to the border and leaning out past it more than 45
            // degrees from the normal: beside the sheet, not across it.
            if (on_border && std::abs(signed_distance) < std::sqrt(0.5 * squared)) signed_distance = 0;
        }
        out[i] = static_cast<float>(signed_distance);
    }
    return out;
}

std::vector<float> sides_of_sheet(const std::vector<float>& signed_distances) {
    std::vector<float> sides(signed_distances.size());
    for (size_t i = 0; i < sides.size(); ++i) sides[i] = signed_distances[i] >= 0.0f ? 1.0f : -1.0f;
    return sides;
}

void follow_sides_round_the_border(const std::vector<float>& signed_distances, std::vector<float>& sides) {
    for (size_t i = 0; i < sides.size(); ++i) {
        if (signed_distances[i] == 0.0f) {
            sides[i] = 0.0f;
        } else if (sides[i] == 0.0f) {
            sides[i] = signed_distances[i] > 0.0f ? 1.0f : -1.0f;
        }
    }
}

Through count_through(const std::vector<float>& signed_distances, const std::vector<float>& start_side,
                      float depth) {
    Through through;
    for (size_t i = 0; i < signed_distances.size(); ++i) {
        const float beyond = -signed_distances[i] * start_side[i];  // > 0: on the other side
        through.deepest = std::max(through.deepest, beyond);
        through.count += beyond > depth;
    }
    return through;
}

}  // namespace cloth_test
