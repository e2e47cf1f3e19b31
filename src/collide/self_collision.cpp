// Self-collision: see self_collision.h for the stages and the region criterion.
#include "collide/self_collision.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace cloth {

namespace {

constexpr uint32_t kTile = 8;          // grid regions: kTile x kTile particles
constexpr uint32_t kPatchSize = 64;    // mesh regions: at most this many particles
constexpr float kConvergence = 0.02f;  // a pass is needed while an overlap exceeds 2% of theta_c

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

float mean_rest_edge(const Fabric& fabric) {
    double sum = 0;
    for (uint32_t t = 0; t < fabric.triangle_count(); ++t) {
        for (uint32_t e = 0; e < 3; ++e) {
            const Vec3& a = fabric.rest_positions[fabric.triangles[3 * t + e]];
            const Vec3& b = fabric.rest_positions[fabric.triangles[3 * t + (e + 1) % 3]];
            sum += static_cast<double>((a - b).norm());
        }
    }
    return fabric.triangle_count() ? static_cast<float>(sum / (3.0 * fabric.triangle_count())) : 0.0f;
}

float max_self_collision_thickness(const Fabric& fabric) {
    // kMaxRings rings reach at least about (rings + 1) / sqrt(2) mean edges
    // on a grid triangulated along one diagonal; keep theta_c within 2 edges.
    return 2.0f * mean_rest_edge(fabric);
}

SelfCollision::SelfCollision(const HostMemory* memory, const Fabric& fabric,
                             const SelfCollisionSettings& settings)
    : settings_(settings),
      particle_count_(fabric.particle_count()),
      rest_(HostAllocator<Vec3>(memory)),
      rest_neighbour_offset_(HostAllocator<uint32_t>(memory)),
      rest_neighbour_(HostAllocator<uint32_t>(memory)),
      region_of_(HostAllocator<uint32_t>(memory)),
      region_triangle_offset_(HostAllocator<uint32_t>(memory)),
      region_triangle_(HostAllocator<uint32_t>(memory)),
      region_outline_offset_(HostAllocator<uint32_t>(memory)),
      region_outline_(HostAllocator<uint32_t>(memory)),
      region_usable_(HostAllocator<uint8_t>(memory)),
      region_valid_(HostAllocator<uint8_t>(memory)),
      outline_u_(HostAllocator<float>(memory)),
      outline_v_(HostAllocator<float>(memory)),
      hash_(memory),
      contact_count_(HostAllocator<uint32_t>(memory)),
      contact_other_(HostAllocator<uint32_t>(memory)),
      contact_distance2_(HostAllocator<float>(memory)),
      touching_(HostAllocator<uint32_t>(memory)),
      overflowed_(HostAllocator<uint8_t>(memory)),
      overlapping_(HostAllocator<uint8_t>(memory)),
      inverse_mass_(HostAllocator<float>(memory)),
      next_x_(memory),
      next_v_(memory) {
    const uint32_t n = particle_count_;
    rest_.assign(fabric.rest_positions.begin(), fabric.rest_positions.end());
    const float edge = mean_rest_edge(fabric);
    rings_ = edge > 0 ? static_cast<uint32_t>(std::ceil(2.0f * settings.thickness / edge)) : kMaxRings;
    rings_ = std::min(std::max(rings_, 2u), kMaxRings);
    outline_epsilon_ = 1e-4f * edge * edge;
    build_rest_neighbours(fabric);
    build_regions(fabric);
    outline_u_.assign(region_outline_.size(), 0.0f);
    outline_v_.assign(region_outline_.size(), 0.0f);
    hash_.reserve(n);
    contact_count_.assign(n, 0);
    contact_other_.assign(static_cast<size_t>(n) * kMaxContacts, 0);
    contact_distance2_.assign(static_cast<size_t>(n) * kMaxContacts, 0.0f);
    touching_.assign(n, 0);
    overflowed_.assign(n, 0);
    overlapping_.assign(n, 0);
    inverse_mass_.assign(n, 0.0f);
    next_x_.resize(n);
    next_v_.resize(n);
}

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

void SelfCollision::compute_keys(const Vec3Soa& x, uint32_t begin, uint32_t end) {
    hash_.compute_keys(x, settings_.thickness * kSearchMargin, begin, end);  // the search radius
}

void SelfCollision::find_contacts(const Vec3Soa& x, uint32_t begin, uint32_t end) {
    const float radius = settings_.thickness * kSearchMargin;
    const float radius2 = radius * radius, thickness2 = settings_.thickness * settings_.thickness;
    // Plain pointers, so the stores into the contact slots cannot make the
    // compiler reload them per candidate.
    const uint32_t* region = region_of_.data();
    const uint8_t* region_valid = region_valid_.data();
    const bool use_regions = settings_.use_regions;
    const uint32_t* neighbours = rest_neighbour_.data();
    const uint32_t* neighbour_offset = rest_neighbour_offset_.data();
    for (uint32_t i = begin; i < end; ++i) {
        uint32_t* other = &contact_other_[static_cast<size_t>(i) * kMaxContacts];
        float* distance2 = &contact_distance2_[static_cast<size_t>(i) * kMaxContacts];
        uint32_t count = 0, touching = 0;
        bool overflow = false;
        const float xi = x.x[i], yi = x.y[i], zi = x.z[i];
        const uint32_t region_i = region[i];
        const bool region_i_free = use_regions && region_valid[region_i] != 0;
        const uint32_t* neighbours_first = neighbours + neighbour_offset[i];
        const uint32_t* neighbours_last = neighbours + neighbour_offset[i + 1];
        hash_.for_each_near(i, [&](uint32_t j, float xj, float yj, float zj) {
            const float dx = xi - xj, dy = yi - yj, dz = zi - zj;
            const float d2 = dx * dx + dy * dy + dz * dz;
            if (!(d2 < radius2)) return;
            if (region_i_free && region[j] == region_i) return;  // one collision-free region
            if (std::binary_search(neighbours_first, neighbours_last, j)) return;  // rest neighbours
            if (d2 < thickness2) ++touching;
            if (count < kMaxContacts) {
                other[count] = j;
                distance2[count++] = d2;
                return;
            }
            // Full: the farthest contact (first of equals) makes room for a nearer one.
            overflow = true;
            uint32_t far = 0;
            for (uint32_t k = 1; k < kMaxContacts; ++k) far = distance2[k] > distance2[far] ? k : far;
            if (d2 < distance2[far]) {
                other[far] = j;
                distance2[far] = d2;
            }
        });
        contact_count_[i] = count;
        touching_[i] = touching;
        overflowed_[i] = overflow ? 1 : 0;
    }
}

void SelfCollision::compute_inverse_mass(const float* mass, const float* pinned, uint32_t begin,
                                         uint32_t end) {
    for (uint32_t i = begin; i < end; ++i) inverse_mass_[i] = pinned[i] != 0.0f ? 0.0f : 1.0f / mass[i];
}

Vec3 SelfCollision::contact_normal(uint32_t i, uint32_t j, const Vec3& d, float length) const {
    if (length > 1e-12f) return d / length;
    const Vec3 rest = rest_[i] - rest_[j];
    const float rest_length = rest.norm();
    if (rest_length > 0) return rest / rest_length;
    return Vec3(0.0f, i < j ? 1.0f : -1.0f, 0.0f);
}

void SelfCollision::project(const Vec3Soa& x, uint32_t begin, uint32_t end) {
    const float theta = settings_.thickness, tolerance = kConvergence * theta;
    for (uint32_t i = begin; i < end; ++i) {
        const Vec3 xi = x.get(i);
        Vec3 push = Vec3::Zero();
        uint32_t pushes = 0;
        bool overlapping = false;
        const float wi = inverse_mass_[i];
        if (wi > 0) {
            for (uint32_t k = 0; k < contact_count_[i]; ++k) {
                const uint32_t j = contact(i, k);
                const Vec3 d = xi - x.get(j);
                const float length = d.norm();
                if (!(length < theta)) continue;
                overlapping = overlapping || length < theta - tolerance;
                // Each end moves by its share of the overlap (its inverse
                // mass over the pair's); pinned particles do not move.
                const float share = wi / (wi + inverse_mass_[j]);
                push += contact_normal(i, j, d, length) * (share * (theta - length));
                ++pushes;
            }
        }
        next_x_.set(i, pushes ? Vec3(xi + push / static_cast<float>(pushes)) : xi);
        overlapping_[i] = overlapping ? 1 : 0;
    }
}

void SelfCollision::apply_positions(Vec3Soa& x) {
    x.x.swap(next_x_.x);
    x.y.swap(next_x_.y);
    x.z.swap(next_x_.z);
    ++last_passes_;
}

bool SelfCollision::any_overlapping() const {
    uint32_t any = 0;
    for (uint8_t flag : overlapping_) any |= flag;
    return any != 0;
}

void SelfCollision::respond_velocities(const Vec3Soa& x, const Vec3Soa& v, uint32_t begin, uint32_t end) {
    // Contacts within theta_c plus the convergence tolerance count as
    // touching after the projection left them at theta_c.
    const float reach = settings_.thickness * (1.0f + kConvergence), friction = settings_.friction;
    for (uint32_t i = begin; i < end; ++i) {
        const Vec3 xi = x.get(i), vi = v.get(i);
        Vec3 change = Vec3::Zero();
        uint32_t changes = 0;
        const float wi = inverse_mass_[i];
        if (wi > 0) {
            for (uint32_t k = 0; k < contact_count_[i]; ++k) {
                const uint32_t j = contact(i, k);
                const Vec3 d = xi - x.get(j);
                const float length = d.norm();
                if (!(length < reach)) continue;
                const Vec3 normal = contact_normal(i, j, d, length);
                // Paper eq. 13 with v_c the pair's velocity weighted by mass:
                // i keeps its share of the relative velocity's approaching part.
                const Vec3 relative = vi - v.get(j);
                const float approach = relative.dot(normal);
                if (!(approach < 0)) continue;
                const float share = wi / (wi + inverse_mass_[j]);
                Vec3 dv = normal * (-share * approach);
                if (friction > 0) {
                    const Vec3 tangential = relative - normal * approach;
                    const float speed = tangential.norm();
                    if (speed > 0) dv -= tangential * (share * std::min(1.0f, -friction * approach / speed));
                }
                change += dv;
                ++changes;
            }
        }
        next_v_.set(i, changes ? Vec3(vi + change / static_cast<float>(changes)) : vi);
    }
}

void SelfCollision::apply_velocities(Vec3Soa& v) {
    v.x.swap(next_v_.x);
    v.y.swap(next_v_.y);
    v.z.swap(next_v_.z);
}

void SelfCollision::run(Vec3Soa& x, Vec3Soa& v, const float* mass, const float* pinned) {
    const uint32_t n = particle_count_;
    check_regions(x, 0, region_count());
    compute_keys(x, 0, n);
    sort_into_buckets(x);
    find_contacts(x, 0, n);
    compute_inverse_mass(mass, pinned, 0, n);
    for (uint32_t pass = 0; pass < settings_.passes; ++pass) {
        project(x, 0, n);
        apply_positions(x);
        if (!any_overlapping()) break;
    }
    respond_velocities(x, v, 0, n);
    apply_velocities(v);
}

SelfCollisionStats SelfCollision::stats() const {
    SelfCollisionStats s;
    uint32_t touching = 0;
    for (uint32_t i = 0; i < particle_count_; ++i) {
        touching += touching_[i];
        s.overflowed_particles += overflowed_[i];
    }
    s.contacts = touching / 2;
    s.regions = region_count();
    for (uint32_t r = 0; r < region_count(); ++r) s.valid_regions += region_valid_[r];
    s.passes = last_passes_;
    return s;
}

}  // namespace cloth
