// What self-collision precomputes from the fabric and checks each substep
// per region: rest neighbours (never repelled) and collision-free regions
// (Volino's criterion; self_collision.h says why it holds).
#include <algorithm>
#include <cmath>
#include <vector>

#include "collide/self_collision.h"

namespace cloth {

namespace {

constexpr uint32_t kTile = 8;        // grid regions: kTile x kTile particles
constexpr uint32_t kPatchSize = 64;  // mesh regions: at most this many particles

// Particle adjacency along triangle edges (CSR, sorted, no duplicates).
void triangle_edge_adjacency(const Fabric& fabric, std::vector<uint32_t>& offset,
                             std::vector<uint32_t>& neighbour) {
    const uint32_t n = fabric.particle_count();
    std::vector<std::vector<uint32_t>> lists(n);
    for (uint32_t t = 0; t < fabric.triangle_count(); ++t) {
        for (uint32_t e = 0; e < 3; ++e) {
            const uint32_t a = fabric.triangles[3 * t + e], b = fabric.triangles[3 * t + (e + 1) % 3];
            lists[a].push_back(b);
            lists[b].push_back(a);
        }
    }
    offset.assign(n + 1, 0);
    neighbour.clear();
    for (uint32_t i = 0; i < n; ++i) {
        std::sort(lists[i].begin(), lists[i].end());
        lists[i].erase(std::unique(lists[i].begin(), lists[i].end()), lists[i].end());
        neighbour.insert(neighbour.end(), lists[i].begin(), lists[i].end());
        offset[i + 1] = static_cast<uint32_t>(neighbour.size());
    }
}

float orientation(float ax, float ay, float bx, float by, float cx, float cy) {
    return (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
}

int sign_beyond(float value, float epsilon) { return value > epsilon ? 1 : (value < -epsilon ? -1 : 0); }

}  // namespace

void SelfCollision::build_rest_neighbours(const Fabric& fabric) {
    const uint32_t n = particle_count_;
    std::vector<uint32_t> adjacency_offset, adjacency;
    triangle_edge_adjacency(fabric, adjacency_offset, adjacency);
    // Spring endpoints, per particle.
    std::vector<std::vector<uint32_t>> springs(n);
    for (uint32_t s = 0; s < fabric.spring_count(); ++s) {
        springs[fabric.spring_first[s]].push_back(fabric.spring_second[s]);
        springs[fabric.spring_second[s]].push_back(fabric.spring_first[s]);
    }
    rest_neighbour_offset_.assign(n + 1, 0);
    rest_neighbour_.clear();
    std::vector<uint32_t> stamp(n, UINT32_MAX), frontier, next, found;
    for (uint32_t i = 0; i < n; ++i) {
        // Breadth-first over triangle edges, `rings_` rings deep.
        found.assign(springs[i].begin(), springs[i].end());
        frontier.assign(1, i);
        stamp[i] = i;
        for (uint32_t ring = 0; ring < rings_ && !frontier.empty(); ++ring) {
            next.clear();
            for (uint32_t p : frontier) {
                for (uint32_t k = adjacency_offset[p]; k < adjacency_offset[p + 1]; ++k) {
                    const uint32_t q = adjacency[k];
                    if (stamp[q] == i) continue;
                    stamp[q] = i;
                    next.push_back(q);
                    found.push_back(q);
                }
            }
            frontier.swap(next);
        }
        std::sort(found.begin(), found.end());
        found.erase(std::unique(found.begin(), found.end()), found.end());
        found.erase(std::remove(found.begin(), found.end(), i), found.end());
        rest_neighbour_.insert(rest_neighbour_.end(), found.begin(), found.end());
        rest_neighbour_offset_[i + 1] = static_cast<uint32_t>(rest_neighbour_.size());
    }
}

void SelfCollision::build_regions(const Fabric& fabric) {
    const uint32_t n = particle_count_;
    region_of_.assign(n, UINT32_MAX);
    uint32_t regions = 0;
    if (!fabric.grid_triangle_shapes.empty()) {
        // A grid: kTile x kTile tiles (shape 0 is {0, 1, columns + 1}).
        const uint32_t columns = fabric.grid_triangle_shapes[2] - 1, rows = n / columns;
        const uint32_t tiles_across = (columns + kTile - 1) / kTile;
        for (uint32_t r = 0; r < rows; ++r) {
            for (uint32_t c = 0; c < columns; ++c)
                region_of_[r * columns + c] = (r / kTile) * tiles_across + c / kTile;
        }
        regions = tiles_across * ((rows + kTile - 1) / kTile);
    } else {
        // A mesh: greedy breadth-first patches of up to kPatchSize particles,
        // seeded at the lowest unassigned index.
        std::vector<uint32_t> adjacency_offset, adjacency, queue;
        triangle_edge_adjacency(fabric, adjacency_offset, adjacency);
        for (uint32_t seed = 0; seed < n; ++seed) {
            if (region_of_[seed] != UINT32_MAX) continue;
            queue.assign(1, seed);
            region_of_[seed] = regions;
            uint32_t size = 1;
            for (size_t head = 0; head < queue.size() && size < kPatchSize; ++head) {
                const uint32_t p = queue[head];
                for (uint32_t k = adjacency_offset[p]; k < adjacency_offset[p + 1] && size < kPatchSize;
                     ++k) {
                    const uint32_t q = adjacency[k];
                    if (region_of_[q] != UINT32_MAX) continue;
                    region_of_[q] = regions;
                    queue.push_back(q);
                    ++size;
                }
            }
            ++regions;
        }
    }

    // Triangles whose three corners share a region belong to it; its
    // outline is the edges used by exactly one of its triangles.
    std::vector<std::vector<uint32_t>> triangles(regions);
    for (uint32_t t = 0; t < fabric.triangle_count(); ++t) {
        const uint32_t* c = &fabric.triangles[3 * t];
        const uint32_t r = region_of_[c[0]];
        if (region_of_[c[1]] == r && region_of_[c[2]] == r) triangles[r].insert(triangles[r].end(), c, c + 3);
    }
    region_triangle_offset_.assign(regions + 1, 0);
    region_outline_offset_.assign(regions + 1, 0);
    region_usable_.assign(regions, 0);
    region_valid_.assign(regions, 0);
    std::vector<uint32_t> covered(n, UINT32_MAX), particles_in(regions, 0);
    for (uint32_t i = 0; i < n; ++i) ++particles_in[region_of_[i]];
    std::vector<std::pair<uint32_t, uint32_t>> edges;
    for (uint32_t r = 0; r < regions; ++r) {
        const std::vector<uint32_t>& tri = triangles[r];
        region_triangle_.insert(region_triangle_.end(), tri.begin(), tri.end());
        region_triangle_offset_[r + 1] = static_cast<uint32_t>(region_triangle_.size());
        edges.clear();
        uint32_t covered_count = 0;
        for (size_t k = 0; k < tri.size(); ++k) {
            if (covered[tri[k]] != r) {
                covered[tri[k]] = r;
                ++covered_count;
            }
            const uint32_t a = tri[k], b = tri[k % 3 == 2 ? k - 2 : k + 1];
            edges.emplace_back(std::min(a, b), std::max(a, b));
        }
        std::sort(edges.begin(), edges.end());
        for (size_t k = 0; k < edges.size();) {
            size_t same = k;
            while (same < edges.size() && edges[same] == edges[k]) ++same;
            if (same - k == 1)
                region_outline_.insert(region_outline_.end(), {edges[k].first, edges[k].second});
            k = same;
        }
        region_outline_offset_[r + 1] = static_cast<uint32_t>(region_outline_.size());
        // A particle on no region triangle is not held by the criterion.
        region_usable_[r] = !tri.empty() && covered_count == particles_in[r];
    }
}

bool SelfCollision::is_rest_neighbour(uint32_t i, uint32_t j) const {
    const uint32_t* first = rest_neighbour_.data() + rest_neighbour_offset_[i];
    const uint32_t* last = rest_neighbour_.data() + rest_neighbour_offset_[i + 1];
    return std::binary_search(first, last, j);
}

bool SelfCollision::region_is_collision_free(const Vec3Soa& x, uint32_t r) {
    if (!region_usable_[r]) return false;
    const uint32_t* tri = region_triangle_.data();
    // (a) Normal cone: every triangle normal within acos(kConeCos) of the mean.
    Vec3 mean = Vec3::Zero();
    for (uint32_t k = region_triangle_offset_[r]; k < region_triangle_offset_[r + 1]; k += 3) {
        const Vec3 a = x.get(tri[k]);
        mean += (x.get(tri[k + 1]) - a).cross(x.get(tri[k + 2]) - a);
    }
    const float mean_length = mean.norm();
    if (!(mean_length > 0)) return false;
    const Vec3 axis = mean / mean_length;
    for (uint32_t k = region_triangle_offset_[r]; k < region_triangle_offset_[r + 1]; k += 3) {
        const Vec3 a = x.get(tri[k]);
        const Vec3 normal = (x.get(tri[k + 1]) - a).cross(x.get(tri[k + 2]) - a);
        if (!(normal.dot(axis) > kConeCos * normal.norm())) return false;
    }
    // (b) The outline projected on the plane normal to the axis does not
    // cross itself (edges sharing a corner are neighbours on the outline).
    const Vec3 helper = std::fabs(axis.x()) < 0.6f ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
    const Vec3 e1 = axis.cross(helper).normalized(), e2 = axis.cross(e1);
    // Each region projects its outline endpoints into its own slice of the
    // scratch arrays (so regions may run in parallel), then tests the edge
    // pairs, rejecting most by their 2D bounding boxes.
    const uint32_t* outline = region_outline_.data();
    const uint32_t first = region_outline_offset_[r], last = region_outline_offset_[r + 1];
    float* u = outline_u_.data();
    float* v = outline_v_.data();
    for (uint32_t k = first; k < last; ++k) {
        const Vec3 p = x.get(outline[k]);
        u[k] = p.dot(e1);
        v[k] = p.dot(e2);
    }
    for (uint32_t a = first; a < last; a += 2) {
        const float ax = u[a], ay = v[a], bx = u[a + 1], by = v[a + 1];
        const float min_x = std::min(ax, bx), max_x = std::max(ax, bx);
        const float min_y = std::min(ay, by), max_y = std::max(ay, by);
        for (uint32_t b = a + 2; b < last; b += 2) {
            const float cx = u[b], cy = v[b], dx = u[b + 1], dy = v[b + 1];
            if (std::max(cx, dx) < min_x || std::min(cx, dx) > max_x || std::max(cy, dy) < min_y ||
                std::min(cy, dy) > max_y) {
                continue;
            }
            if (outline[b] == outline[a] || outline[b] == outline[a + 1] || outline[b + 1] == outline[a] ||
                outline[b + 1] == outline[a + 1]) {
                continue;
            }
            const int s1 = sign_beyond(orientation(ax, ay, bx, by, cx, cy), outline_epsilon_);
            const int s2 = sign_beyond(orientation(ax, ay, bx, by, dx, dy), outline_epsilon_);
            const int s3 = sign_beyond(orientation(cx, cy, dx, dy, ax, ay), outline_epsilon_);
            const int s4 = sign_beyond(orientation(cx, cy, dx, dy, bx, by), outline_epsilon_);
            if (s1 * s2 < 0 && s3 * s4 < 0) return false;
        }
    }
    return true;
}

void SelfCollision::check_regions(const Vec3Soa& x, uint32_t region_begin, uint32_t region_end) {
    for (uint32_t r = region_begin; r < region_end; ++r) {
        region_valid_[r] = settings_.use_regions && region_is_collision_free(x, r) ? 1 : 0;
    }
}

}  // namespace cloth
