#include "collide/cloth_pair_contact.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "collide/contact_response.h"
#include "collide/self_collision.h"
#include "forces/aerodynamics.h"

namespace cloth {

namespace {

// A projection pass that leaves every pair within this fraction of the
// thickness is the last (as self-collision's).
constexpr float kConvergence = 0.01f;

// No hashed particle to skip: the query point is of the other cloth.
constexpr uint32_t kNoParticle = std::numeric_limits<uint32_t>::max();

struct Bounds {
    Vec3 low = Vec3::Constant(std::numeric_limits<float>::infinity());
    Vec3 high = Vec3::Constant(-std::numeric_limits<float>::infinity());
};

// The particles now and `dt` later at their velocities (of a cloth that steps).
Bounds bounds_of(const ParticleView& cloth, float dt) {
    Bounds b;
    const Vec3Soa& x = *cloth.x;
    const Vec3Soa& v = *cloth.v;
    const float ahead = cloth.steps ? dt : 0.0f;
    for (size_t i = 0; i < x.size(); ++i) {
        const Vec3 p = x.get(i), q = p + v.get(i) * ahead;
        b.low = b.low.cwiseMin(p).cwiseMin(q);
        b.high = b.high.cwiseMax(p).cwiseMax(q);
    }
    return b;
}

// Marks the particles on the fabric's border (on an edge of one triangle)
// into `border`, from entry `first`.
void mark_border(const Fabric& fabric, HostVector<uint8_t>& border, uint32_t first) {
    std::vector<uint64_t> edges;
    edges.reserve(fabric.triangles.size());
    for (size_t t = 0; t + 2 < fabric.triangles.size(); t += 3) {
        for (int e = 0; e < 3; ++e) {
            const uint64_t p = fabric.triangles[t + e], q = fabric.triangles[t + (e + 1) % 3];
            edges.push_back(std::min(p, q) << 32 | std::max(p, q));
        }
    }
    std::sort(edges.begin(), edges.end());
    for (size_t k = 0; k < edges.size();) {
        size_t next = k + 1;
        while (next < edges.size() && edges[next] == edges[k]) ++next;
        if (next - k == 1) {
            border[first + static_cast<uint32_t>(edges[k] >> 32)] = 1;
            border[first + static_cast<uint32_t>(edges[k] & 0xFFFFFFFFu)] = 1;
        }
        k = next;
    }
}

}  // namespace

ClothPairContact::ClothPairContact(const HostMemory* memory, const Fabric& a, const Fabric& b,
                                   const ClothPairSettings& settings)
    : settings_(settings),
      count_a_(a.particle_count()),
      count_b_(b.particle_count()),
      radius_(settings.thickness + std::max(mean_rest_edge(a), mean_rest_edge(b))),
      search_(radius_),
      hash_a_(memory),
      hash_b_(memory),
      x_(memory),
      v_(memory),
      normal_(memory),
      next_x_(memory),
      start_(memory),
      inverse_mass_(HostAllocator<float>(memory)),
      contact_other_(HostAllocator<uint32_t>(memory)),
      contact_distance2_(HostAllocator<float>(memory)),
      contact_normal_(memory),
      contact_count_(HostAllocator<uint32_t>(memory)),
      touching_(HostAllocator<uint8_t>(memory)),
      overlapping_(HostAllocator<uint8_t>(memory)),
      border_(HostAllocator<uint8_t>(memory)),
      task_speed2_(HostAllocator<float>(memory)),
      task_bounds_(HostAllocator<Vec3>(memory)),
      near_(HostAllocator<uint8_t>(memory)) {
    const uint32_t n = count();
    hash_a_.reserve(count_a_);
    hash_b_.reserve(count_b_);
    for (Vec3Soa* v : {&x_, &v_, &normal_, &next_x_, &start_}) v->resize(n);
    inverse_mass_.resize(n);
    contact_other_.resize(size_t{n} * kMaxContacts);
    contact_distance2_.resize(size_t{n} * kMaxContacts);
    contact_normal_.resize(size_t{n} * kMaxContacts);
    contact_count_.assign(n, 0u);
    touching_.assign(n, 0);
    overlapping_.assign(n, 0);
    border_.assign(n, 0);
    task_speed2_.assign(2 * size_t{group_count_of(n)}, 0.0f);
    task_bounds_.assign(4 * size_t{group_count_of(n)}, Vec3::Zero());
    near_.assign(n, 0);
    mark_border(a, border_, 0);
    mark_border(b, border_, count_a_);
}

bool ClothPairContact::near(const ParticleView& a, const ParticleView& b, float dt) const {
    const Bounds ba = bounds_of(a, dt), bb = bounds_of(b, dt);
    const float r = radius_;
    return (ba.low.array() - r <= bb.high.array()).all() && (bb.low.array() - r <= ba.high.array()).all();
}

void ClothPairContact::begin(const ParticleView& a, const ParticleView& b, float h) {
    a_ = a;
    b_ = b;
    h_ = h;
    round_ = Round::kGather;
}

void ClothPairContact::run(const GroupTask& task) {
    switch (round_) {
        case Round::kGather:
            gather(task.group, task.begin, task.end);
            return;
        case Round::kKeys:
            mark_near(task.begin, task.end);
            if (task.begin < count_a_)
                hash_a_.compute_keys(x_, search_, task.begin, std::min(task.end, count_a_));
            if (task.end > count_a_)
                hash_b_.compute_keys(x_, search_, std::max(task.begin, count_a_) - count_a_,
                                     task.end - count_a_, count_a_);
            return;
        case Round::kSort:
            hash_a_.sort_into_buckets(x_);
            hash_b_.sort_into_buckets(x_, count_a_);
            return;
        case Round::kContacts:
            find_contacts(task.begin, task.end);
            return;
        case Round::kProject:
            project(task.begin, task.end);
            return;
        case Round::kScatter:
            scatter(task.begin, task.end);
            return;
        case Round::kDone:
            return;
    }
}

void ClothPairContact::finish_round() {
    switch (round_) {
        case Round::kGather: {
            // The search grows by how far the two cloths' fastest particles
            // move towards each other in the substep, up to twice the radius.
            float fastest[2] = {0.0f, 0.0f};
            for (size_t t = 0; t < task_speed2_.size(); ++t)
                fastest[t % 2] = std::max(fastest[t % 2], task_speed2_[t]);
            const float travel = (std::sqrt(fastest[0]) + std::sqrt(fastest[1])) * h_;
            search_ = radius_ + std::min(travel, radius_);
            // Each cloth's bounds, grown by the search: a particle outside
            // the other cloth's can meet none of its particles.
            for (int side = 0; side < 2; ++side) {
                Vec3 low = Vec3::Constant(std::numeric_limits<float>::infinity()), high = -low;
                for (size_t t = 0; t < task_bounds_.size(); t += 4) {
                    low = low.cwiseMin(task_bounds_[t + 2 * side]);
                    high = high.cwiseMax(task_bounds_[t + 2 * side + 1]);
                }
                reach_low_[side] = low - Vec3::Constant(search_);
                reach_high_[side] = high + Vec3::Constant(search_);
            }
            round_ = Round::kKeys;
            return;
        }
        case Round::kKeys:
            round_ = Round::kSort;
            return;
        case Round::kSort:
            found_ = true;
            round_ = Round::kContacts;
            return;
        case Round::kContacts:
            passes_ = 0;
            round_ = Round::kProject;
            return;
        case Round::kProject: {
            x_.swap_buffers(next_x_);
            ++passes_;
            uint8_t any = 0;
            for (uint8_t flag : overlapping_) any |= flag;
            if (any == 0 || passes_ >= settings_.passes) round_ = Round::kScatter;
            return;
        }
        case Round::kScatter:
            started_ = true;
            round_ = Round::kDone;
            return;
        case Round::kDone:
            return;
    }
}

void ClothPairContact::gather(uint32_t task, uint32_t begin, uint32_t end) {
    float fastest[2] = {0.0f, 0.0f};  // squared speeds, of a's and of b's particles
    Vec3 low[2], high[2];             // bounds, of a's and of b's particles
    for (int side = 0; side < 2; ++side) {
        low[side] = Vec3::Constant(std::numeric_limits<float>::infinity());
        high[side] = -low[side];
    }
    for (uint32_t i = begin; i < end; ++i) {
        const ParticleView& cloth = side_b(i) ? b_ : a_;
        const uint32_t p = side_b(i) ? i - count_a_ : i;
        const Vec3 xi = cloth.x->get(p);
        x_.set(i, xi);
        if (!started_) start_.set(i, xi);
        v_.set(i, cloth.v->get(p));
        const bool moves = cloth.steps && cloth.pinned[p] == 0.0f;
        inverse_mass_[i] = moves ? 1.0f / cloth.mass[p] : 0.0f;
        if (moves) fastest[side_b(i)] = std::max(fastest[side_b(i)], v_.get(i).squaredNorm());
        low[side_b(i)] = low[side_b(i)].cwiseMin(xi);
        high[side_b(i)] = high[side_b(i)].cwiseMax(xi);
    }
    task_speed2_[2 * size_t{task}] = fastest[0];
    task_speed2_[2 * size_t{task} + 1] = fastest[1];
    for (int side = 0; side < 2; ++side) {
        task_bounds_[4 * size_t{task} + 2 * side] = low[side];
        task_bounds_[4 * size_t{task} + 2 * side + 1] = high[side];
    }
}

void ClothPairContact::mark_near(uint32_t begin, uint32_t end) {
    for (uint32_t i = begin; i < end; ++i) {
        const int other = side_b(i) ? 0 : 1;
        const Vec3 xi = x_.get(i);
        const bool near = (xi.array() >= reach_low_[other].array()).all() &&
                          (xi.array() <= reach_high_[other].array()).all();
        near_[i] = near ? 1 : 0;
        // Only a particle near the other cloth is ever another's contact.
        if (near) {
            const ParticleView& cloth = side_b(i) ? b_ : a_;
            normal_.set(i, vertex_normal(*cloth.fabric, *cloth.x, side_b(i) ? i - count_a_ : i));
        }
    }
}

void ClothPairContact::find_contacts(uint32_t begin, uint32_t end) {
    const float radius2 = search_ * search_, theta = settings_.thickness;
    const float tangential2 = (radius_ - theta) * (radius_ - theta);
    for (uint32_t i = begin; i < end; ++i) {
        if (!near_[i]) {
            contact_count_[i] = 0;
            touching_[i] = 0;
            continue;
        }
        const size_t first = size_t{i} * kMaxContacts;
        uint32_t* other = &contact_other_[first];
        float* distance2 = &contact_distance2_[first];
        uint32_t count = 0;
        bool touching = false;
        const bool b = side_b(i);
        const Vec3 xi = x_.get(i), start_i = start_.get(i);
        // Only the other cloth's hash: its particles are entries from `first` on.
        const SpatialHash& other_hash = b ? hash_a_ : hash_b_;
        const uint32_t first_other = b ? 0 : count_a_;
        int32_t bx, by, bz;
        SpatialHash::query_block(xi, search_, bx, by, bz);
        other_hash.for_each_in_block(
            bx, by, bz, kNoParticle, [&](uint32_t local, float xj, float yj, float zj) {
                const uint32_t j = first_other + local;
                const Vec3 d = xi - Vec3(xj, yj, zj);
                const float d2 = d.squaredNorm();
                if (!(d2 < radius2)) return;
                // j's plane, turned towards the side i was on when the contact last looked.
                const Vec3 nj = normal_.get(j);
                const float side = (start_i - start_.get(j)).dot(nj);
                const Vec3 n = (side > 0.0f || (side == 0.0f && !b)) ? nj : Vec3(-nj);
                const float along = d.dot(n);
                // Over j's part of the surface, and not so far behind it that
                // it is another part of the cloth (the search reaches further
                // only to find the fast ones in front of it); behind a
                // particle on the other cloth's border (a hem) at most a
                // thickness: deeper, it went round the border, and pushing
                // it back through the hem's plane tears its own cloth.
                const float behind = border_[j] ? theta : radius_;
                if (!((d - n * along).squaredNorm() < tangential2) || !(along > -behind)) return;
                touching = touching || along < theta;
                uint32_t slot = count;
                if (count < kMaxContacts) {
                    ++count;
                } else {
                    // Full: the farthest contact (first of equals) makes room for a nearer one.
                    slot = 0;
                    for (uint32_t k = 1; k < kMaxContacts; ++k)
                        slot = distance2[k] > distance2[slot] ? k : slot;
                    if (!(d2 < distance2[slot])) return;
                }
                other[slot] = j;
                distance2[slot] = d2;
                contact_normal_.set(first + slot, n);
            });
        contact_count_[i] = count;
        touching_[i] = touching ? 1 : 0;
    }
}

void ClothPairContact::project(uint32_t begin, uint32_t end) {
    const float theta = settings_.thickness, tolerance = kConvergence * theta;
    for (uint32_t i = begin; i < end; ++i) {
        const Vec3 xi = x_.get(i);
        Vec3 push = Vec3::Zero();
        uint32_t pushes = 0;
        bool overlapping = false;
        const float wi = inverse_mass_[i];
        if (wi > 0) {
            for (uint32_t k = 0; k < contact_count_[i]; ++k) {
                const size_t slot = size_t{i} * kMaxContacts + k;
                const uint32_t j = contact_other_[slot];
                const Vec3 n = contact_normal_.get(slot);
                const float along = (xi - x_.get(j)).dot(n);
                if (!(along < theta)) continue;
                overlapping = overlapping || along < theta - tolerance;
                // Each end moves by its share of the depth (its inverse mass
                // over the pair's); pinned particles and a cloth that does
                // not step do not move.
                const float share = wi / (wi + inverse_mass_[j]);
                push += n * (share * (theta - along));
                ++pushes;
            }
        }
        next_x_.set(i, pushes ? Vec3(xi + push / static_cast<float>(pushes)) : xi);
        overlapping_[i] = overlapping ? 1 : 0;
    }
}

void ClothPairContact::scatter(uint32_t begin, uint32_t end) {
    for (uint32_t i = begin; i < end; ++i) {
        start_.set(i, x_.get(i));
        if (contact_count_[i] == 0 || inverse_mass_[i] == 0.0f) continue;
        const ParticleView& cloth = side_b(i) ? b_ : a_;
        cloth.x->set(side_b(i) ? i - count_a_ : i, x_.get(i));
    }
}

void ClothPairContact::respond_side(uint32_t side, const Vec3Soa& x, Vec3Soa& v, uint32_t begin,
                                    uint32_t end) const {
    // Contacts within the thickness plus the convergence tolerance count
    // as touching after the projection left them at the thickness.
    const float reach = settings_.thickness * (1.0f + kConvergence), friction = settings_.friction;
    const uint32_t first = first_of(side);
    for (uint32_t p = begin; p < end; ++p) {
        const uint32_t i = first + p;
        const float wi = inverse_mass_[i];
        if (contact_count_[i] == 0 || !(wi > 0)) continue;
        const Vec3 xi = x.get(p), vi = v.get(p);
        Vec3 change = Vec3::Zero();
        uint32_t changes = 0;
        for (uint32_t k = 0; k < contact_count_[i]; ++k) {
            const size_t slot = size_t{i} * kMaxContacts + k;
            const uint32_t j = contact_other_[slot];
            const Vec3 n = contact_normal_.get(slot);
            if (!((xi - x_.get(j)).dot(n) < reach)) continue;
            const Vec3 relative = vi - v_.get(j);
            const float approach = relative.dot(n);
            if (!(approach < 0)) continue;
            const float share = wi / (wi + inverse_mass_[j]);
            change += contact_velocity_change(relative, n, approach, share, friction);
            ++changes;
        }
        if (changes) v.set(p, Vec3(vi + change / static_cast<float>(changes)));
    }
}

uint32_t ClothPairContact::contacts() const {
    if (!found_) return 0;
    uint32_t touching = 0;
    for (uint8_t t : touching_) touching += t;
    return touching;
}

}  // namespace cloth
