// Which side of a cloth sheet a point is on, by brute force: the check of
// contact between two cloths that no particle ends a frame through the
// other cloth. Plain and slow on purpose (every triangle of the sheet is
// tried for every point), so that it shares nothing with the library's
// contact but the positions it reads.
#pragma once

#include <cstdint>
#include <vector>

namespace cloth_test {

// The signed distance of each point of `points` (xyz) to the sheet of
// `vertices` (xyz) and `triangles` (three vertex indices each, wound the
// same way across the sheet): with q the sheet's nearest point to p (over
// every triangle) and n(q) the sheet's unit angle-weighted pseudo-normal
// there (Baerentzen and Aanaes 2005: inside a triangle its normal, on an
// edge the sum of the normals of the triangles that share it, at a vertex
// the sum of the normals of the triangles around it each weighted by its
// angle there, normalised), s = (p - q) . n(q). Over the inside of the
// sheet |s| is the distance to it, positive on the side its triangles'
// normals (counter-clockwise winding) face, and the pseudo-normal keeps
// the sign right where the nearest point is on an edge or a vertex of a
// folded sheet. Where q is on the sheet's border (an edge of one
// triangle, or an end of one) s is the same unless the offset leans more
// than 45 degrees from the normal, out past the border: then the point is
// beside the sheet, on neither side, and s is 0 (a point level with a
// sagging sheet's rim, or a particle round its edge, is not through it).
std::vector<float> signed_distances_to_sheet(const std::vector<float>& points,
                                             const std::vector<float>& vertices,
                                             const std::vector<uint32_t>& triangles);

// The side of the sheet each point is on: +1 where its signed distance is
// >= 0, else -1 (taken at the start, before the sheets move).
std::vector<float> sides_of_sheet(const std::vector<float>& signed_distances);

// A point changes sides legitimately only round the sheet's border: where
// it is beside the sheet (signed distance 0) its side is forgotten (0), and
// the next side it is seen on becomes its side. Tunnelling through the
// inside of the sheet never passes beside it, so it is not forgiven.
void follow_sides_round_the_border(const std::vector<float>& signed_distances, std::vector<float>& sides);

// Points through the sheet: on the other side of it than `start_side`
// says they started on (0: no side, never through), by more than `depth`.
struct Through {
    uint32_t count = 0;  // points more than `depth` through
    float deepest = 0;   // m, the farthest a point is on the other side (0: none is)
};
Through count_through(const std::vector<float>& signed_distances, const std::vector<float>& start_side,
                      float depth);

}  // namespace cloth_test
