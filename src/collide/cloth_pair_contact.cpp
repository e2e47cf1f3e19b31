#include "collide/cloth_pair_contact.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "collide/contact_response.h"
#include "collide/self_collision.h"
#include "forces/aerodynamics.h"
#include "step/cloth_instance.h"

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

Bounds bounds_of(const Vec3Soa& x) {
    Bounds b;
    for (size_t i = 0; i < x.size(); ++i) {
        const Vec3 p = x.get(i);
        b.low = b.low.cwiseMin(p);
        b.high = b.high.cwiseMax(p);
    }
    return b;
}

}  // namespace

ClothPairContact::ClothPairContact(const HostMemory* memory, const Fabric& a, const Fabric& b,
                                   const ClothPairSettings& settings)
    : settings_(settings),
      count_a_(a.particle_count()),
      count_b_(b.particle_count()),
      radius_(settings.thickness + std::max(mean_rest_edge(a), mean_rest_edge(b))),
      hash_a_(memory),
      hash_b_(memory),
      x_(memory),
      v_(memory),
      normal_(memory),
      next_x_(memory),
      next_v_(memory),
      start_(memory),
      inverse_mass_(HostAllocator<float>(memory)),
      contact_other_(HostAllocator<uint32_t>(memory)),
      contact_distance2_(HostAllocator<float>(memory)),
      contact_normal_(memory),
      contact_count_(HostAllocator<uint32_t>(memory)),
      touching_(HostAllocator<uint8_t>(memory)),
      overlapping_(HostAllocator<uint8_t>(memory)) {
    const uint32_t n = count();
    hash_a_.reserve(count_a_);
    hash_b_.reserve(count_b_);
    for (Vec3Soa* v : {&x_, &v_, &normal_, &next_x_, &next_v_, &start_}) v->resize(n);
    inverse_mass_.resize(n);
    contact_other_.resize(size_t{n} * kMaxContacts);
    contact_distance2_.resize(size_t{n} * kMaxContacts);
    contact_normal_.resize(size_t{n} * kMaxContacts);
    contact_count_.assign(n, 0u);
    touching_.assign(n, 0);
    overlapping_.assign(n, 0);
}

bool ClothPairContact::near(const ClothInstance& a, const ClothInstance& b) const {
    const Bounds ba = bounds_of(a.positions()), bb = bounds_of(b.positions());
    const float r = radius_;
    return (ba.low.array() - r <= bb.high.array()).all() && (bb.low.array() - r <= ba.high.array()).all();
}

void ClothPairContact::gather(const ClothInstance& a, const ClothInstance& b, uint32_t begin, uint32_t end) {
    for (uint32_t i = begin; i < end; ++i) {
        const ClothInstance& cloth = side_b(i) ? b : a;
        const uint32_t p = side_b(i) ? i - count_a_ : i;
        x_.set(i, cloth.positions().get(p));
        if (!started_) start_.set(i, x_.get(i));
        v_.set(i, cloth.velocities().get(p));
        normal_.set(i, vertex_normal(cloth.fabric(), cloth.positions(), p));
        inverse_mass_[i] = cloth.is_pinned(p) ? 0.0f : 1.0f / cloth.masses()[p];
    }
    if (begin < count_a_) hash_a_.compute_keys(x_, radius_, begin, std::min(end, count_a_));
    if (end > count_a_)
        hash_b_.compute_keys(x_, radius_, std::max(begin, count_a_) - count_a_, end - count_a_, count_a_);
}

void ClothPairContact::find_contacts(uint32_t begin, uint32_t end) {
    const float radius2 = radius_ * radius_, theta = settings_.thickness;
    const float tangential2 = (radius_ - theta) * (radius_ - theta);
    for (uint32_t i = begin; i < end; ++i) {
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
        SpatialHash::query_block(xi, radius_, bx, by, bz);
        other_hash.for_each_in_block(
            bx, by, bz, kNoParticle, [&](uint32_t local, float xj, float yj, float zj) {
                const uint32_t j = first_other + local;
                const Vec3 d = xi - Vec3(xj, yj, zj);
                const float d2 = d.squaredNorm();
                if (!(d2 < radius2)) return;
                // j's plane, turned towards the side i started the frame on.
                const Vec3 nj = normal_.get(j);
                const float side = (start_i - start_.get(j)).dot(nj);
                const Vec3 n = (side > 0.0f || (side == 0.0f && !b)) ? nj : Vec3(-nj);
                const float along = d.dot(n);
                // Over j's part of the surface, and not so far behind it that
                // it is another part of the cloth.
                if (!((d - n * along).squaredNorm() < tangential2) || !(along > -radius_)) return;
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
                // Each end moves by its share of the depth (its inverse
                // mass over the pair's); pinned particles do not move.
                const float share = wi / (wi + inverse_mass_[j]);
                push += n * (share * (theta - along));
                ++pushes;
            }
        }
        next_x_.set(i, pushes ? Vec3(xi + push / static_cast<float>(pushes)) : xi);
        overlapping_[i] = overlapping ? 1 : 0;
    }
}

bool ClothPairContact::apply_positions() {
    x_.swap_buffers(next_x_);
    ++passes_;
    uint8_t any = 0;
    for (uint8_t flag : overlapping_) any |= flag;
    return any != 0 && passes_ < settings_.passes;
}

void ClothPairContact::respond(uint32_t begin, uint32_t end) {
    // Contacts within the thickness plus the convergence tolerance count
    // as touching after the projection left them at the thickness.
    const float reach = settings_.thickness * (1.0f + kConvergence), friction = settings_.friction;
    for (uint32_t i = begin; i < end; ++i) {
        const Vec3 xi = x_.get(i), vi = v_.get(i);
        Vec3 change = Vec3::Zero();
        uint32_t changes = 0;
        const float wi = inverse_mass_[i];
        if (wi > 0) {
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
        }
        next_v_.set(i, changes ? Vec3(vi + change / static_cast<float>(changes)) : vi);
    }
}

void ClothPairContact::scatter(ClothInstance& a, ClothInstance& b, uint32_t begin, uint32_t end) {
    for (uint32_t i = begin; i < end; ++i) {
        start_.set(i, x_.get(i));
        if (contact_count_[i] == 0 || inverse_mass_[i] == 0.0f) continue;
        ClothInstance& cloth = side_b(i) ? b : a;
        cloth.set_particle_state(side_b(i) ? i - count_a_ : i, x_.get(i), v_.get(i));
    }
}

uint32_t ClothPairContact::contacts() const {
    if (!found_) return 0;
    uint32_t touching = 0;
    for (uint8_t t : touching_) touching += t;
    return touching;
}

}  // namespace cloth
