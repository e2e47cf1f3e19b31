// Self-collision: contacts, projection, response and the rounds that run
// them (self_collision.h); rest neighbours and regions are in
// self_collision_regions.cpp.
#include "collide/self_collision.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "collide/contact_response.h"

namespace cloth {

namespace {

constexpr float kConvergence = 0.02f;  // a pass is needed while an overlap exceeds 2% of theta_c

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
                change += contact_velocity_change(relative, normal, approach, share, friction);
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

void SelfCollision::begin(Vec3Soa& x, Vec3Soa& v, const float* mass, const float* pinned, bool respond) {
    respond_ = respond;
    x_ = &x;
    v_ = &v;
    mass_ = mass;
    pinned_ = pinned;
    round_ = Round::kHash;
}

void SelfCollision::run(const GroupTask& task) {
    const Vec3Soa& x = *x_;
    switch (round_) {
        case Round::kHash: {
            uint32_t region_begin, region_end;
            task.items(region_count(), region_begin, region_end);
            check_regions(x, region_begin, region_end);
            compute_keys(x, task.begin, task.end);
            break;
        }
        case Round::kSort:
            sort_into_buckets(x);
            break;
        case Round::kContacts:
            find_contacts(x, task.begin, task.end);
            compute_inverse_mass(mass_, pinned_, task.begin, task.end);
            break;
        case Round::kProject:
            project(x, task.begin, task.end);
            break;
        case Round::kRespond:
            respond_velocities(x, *v_, task.begin, task.end);
            break;
        case Round::kDone:
            break;
    }
}

void SelfCollision::finish_round() {
    switch (round_) {
        case Round::kHash:
            round_ = Round::kSort;
            break;
        case Round::kSort:
            round_ = Round::kContacts;
            break;
        case Round::kContacts:
            round_ = Round::kProject;
            break;
        case Round::kProject:
            // Another pass while overlaps remain, at most `passes` in all.
            apply_positions(*x_);
            ++last_passes_;
            if (!any_overlapping() || last_passes_ >= settings_.passes)
                round_ = respond_ ? Round::kRespond : Round::kDone;
            break;
        case Round::kRespond:
            apply_velocities(*v_);
            round_ = Round::kDone;
            break;
        case Round::kDone:
            break;
    }
}

void SelfCollision::run_serially(Vec3Soa& x, Vec3Soa& v, const float* mass, const float* pinned) {
    begin(x, v, mass, pinned);
    cloth::run_serially(*this, particle_count_);
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
