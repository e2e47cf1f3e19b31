#include "solve/skin.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "forces/aerodynamics.h"

namespace cloth {

namespace {

Vec3 lerp(const Vec3Soa& from, const Vec3Soa& to, uint32_t i, float fraction) {
    const Vec3 a = from.get(i);
    return a + (to.get(i) - a) * fraction;
}

Vec3 unit_or(const Vec3& v, const Vec3& fallback) {
    const float length = v.norm();
    return length > 1e-20f ? Vec3(v / length) : fallback;
}

}  // namespace

Skin::Skin(const HostMemory* memory)
    : joints_(HostAllocator<uint32_t>(memory)),
      weights_(HostAllocator<float>(memory)),
      matrices_(HostAllocator<float>(memory)),
      bind_x_(memory),
      bind_n_(memory),
      host_x_(memory),
      host_n_(memory),
      from_x_(memory),
      from_n_(memory),
      to_x_(memory),
      to_n_(memory),
      held_x_(memory),
      held_n_(memory),
      max_distance_(HostAllocator<float>(memory)),
      backstop_distance_(HostAllocator<float>(memory)),
      backstop_radius_(HostAllocator<float>(memory)) {}

// Every allocating setter sizes its buffers aside and swaps them in last,
// so that an allocator returning NULL leaves the skin as it was.
void Skin::size_for(uint32_t n) {
    if (from_x_.size() == n) return;
    Skin sized(max_distance_.get_allocator().memory());
    for (Vec3Soa* a :
         {&sized.from_x_, &sized.from_n_, &sized.to_x_, &sized.to_n_, &sized.held_x_, &sized.held_n_})
        a->resize(n);
    sized.max_distance_.assign(n, kNoMaxDistance);
    sized.backstop_distance_.assign(n, 0.0f);
    sized.backstop_radius_.assign(n, 0.0f);
    from_x_.swap_buffers(sized.from_x_);
    from_n_.swap_buffers(sized.from_n_);
    to_x_.swap_buffers(sized.to_x_);
    to_n_.swap_buffers(sized.to_n_);
    held_x_.swap_buffers(sized.held_x_);
    held_n_.swap_buffers(sized.held_n_);
    max_distance_.swap(sized.max_distance_);
    backstop_distance_.swap(sized.backstop_distance_);
    backstop_radius_.swap(sized.backstop_radius_);
    constrained_count_ = 0;
}

void Skin::bind(const Fabric& fabric, uint32_t joint_count, uint32_t influences, const uint32_t* joints,
                const float* weights) {
    const uint32_t n = fabric.particle_count();
    Skin bound(max_distance_.get_allocator().memory());
    bound.joints_.assign(size_t{n} * kMaxInfluences, 0u);
    bound.weights_.assign(size_t{n} * kMaxInfluences, 0.0f);
    for (uint32_t i = 0; i < n; ++i) {
        for (uint32_t k = 0; k < influences; ++k) {
            bound.joints_[size_t{i} * kMaxInfluences + k] = joints[size_t{i} * influences + k];
            bound.weights_[size_t{i} * kMaxInfluences + k] =
                weights ? weights[size_t{i} * influences + k] : 1.0f;
        }
    }
    bound.bind_x_.resize(n);
    for (uint32_t i = 0; i < n; ++i) bound.bind_x_.set(i, fabric.rest_positions[i]);
    bound.bind_n_.resize(n);
    compute_vertex_normals(fabric, bound.bind_x_, 0, n, bound.bind_n_);
    bound.matrices_.assign(size_t{joint_count} * kMatrixFloats, 0.0f);
    for (uint32_t j = 0; j < joint_count; ++j) {
        float* m = bound.matrices_.data() + size_t{j} * kMatrixFloats;
        m[0] = m[5] = m[10] = 1.0f;
    }
    size_for(n);  // the last allocation
    joints_.swap(bound.joints_);
    weights_.swap(bound.weights_);
    bind_x_.swap_buffers(bound.bind_x_);
    bind_n_.swap_buffers(bound.bind_n_);
    matrices_.swap(bound.matrices_);
    joint_count_ = joint_count;
    influences_ = influences;
    source_ = Source::kJoints;
    primed_ = false;
}

void Skin::set_joint_matrices(const float* matrices, bool column_major_4x4) {
    const uint32_t stride = column_major_4x4 ? 16 : kMatrixFloats;
    for (uint32_t j = 0; j < joint_count_; ++j) {
        const float* in = matrices + size_t{j} * stride;
        float* out = matrices_.data() + size_t{j} * kMatrixFloats;
        for (int r = 0; r < 3; ++r) {
            for (int col = 0; col < 4; ++col)
                out[4 * r + col] = column_major_4x4 ? in[4 * col + r] : in[4 * r + col];
        }
    }
    if (source_ != Source::kJoints) primed_ = false;  // the host's skin is not where the joints start
    source_ = Source::kJoints;
}

void Skin::set_skinned(const Fabric& fabric, const float* positions, const float* normals) {
    const uint32_t n = fabric.particle_count();
    if (host_x_.size() != n) {
        const HostMemory* memory = max_distance_.get_allocator().memory();
        Vec3Soa x(memory), normal(memory);
        x.resize(n);
        normal.resize(n);
        size_for(n);  // the last allocation
        host_x_.swap_buffers(x);
        host_n_.swap_buffers(normal);
    }
    for (uint32_t v = 0; v < n; ++v) {
        const float *p = positions + 3 * size_t{v}, *d = normals + 3 * size_t{v};
        host_x_.set(fabric.particle(v), Vec3(p[0], p[1], p[2]));
        host_n_.set(fabric.particle(v), Vec3(d[0], d[1], d[2]).normalized());
    }
    if (source_ != Source::kHost) primed_ = false;
    source_ = Source::kHost;
}

void Skin::count_constrained(uint32_t particle, bool before) {
    const bool now = constrained(particle);
    if (now != before) constrained_count_ = now ? constrained_count_ + 1 : constrained_count_ - 1;
}

bool Skin::constrained(uint32_t particle) const {
    const float d = max_distance_[particle];
    return (d > 0.0f && d < kNoMaxDistance) || backstop_radius_[particle] > 0.0f;
}

void Skin::set_max_distance(uint32_t particle, float distance) {
    const bool before = constrained(particle);
    max_distance_[particle] = distance;
    count_constrained(particle, before);
}

void Skin::set_backstop(uint32_t particle, float distance, float radius) {
    const bool before = constrained(particle);
    backstop_distance_[particle] = distance;
    backstop_radius_[particle] = radius;
    count_constrained(particle, before);
}

void Skin::begin_frame(bool jump) {
    from_x_.swap_buffers(to_x_);
    from_n_.swap_buffers(to_n_);
    jump_ = jump;
}

void Skin::skin(uint32_t begin, uint32_t end) {
    for (uint32_t i = begin; i < end; ++i) {
        Vec3 x, n;
        if (source_ == Source::kHost) {
            x = host_x_.get(i);
            n = host_n_.get(i);
        } else {
            // Linear blend skinning: sum of w_k M_k (b, 1) and w_k R_k n_b.
            const Vec3 b = bind_x_.get(i), bn = bind_n_.get(i);
            x = Vec3::Zero();
            n = Vec3::Zero();
            for (uint32_t k = 0; k < influences_; ++k) {
                const float w = weights_[size_t{i} * kMaxInfluences + k];
                const float* m =
                    matrices_.data() + size_t{joints_[size_t{i} * kMaxInfluences + k]} * kMatrixFloats;
                x += w * Vec3(m[0] * b.x() + m[1] * b.y() + m[2] * b.z() + m[3],
                              m[4] * b.x() + m[5] * b.y() + m[6] * b.z() + m[7],
                              m[8] * b.x() + m[9] * b.y() + m[10] * b.z() + m[11]);
                n += w * Vec3(m[0] * bn.x() + m[1] * bn.y() + m[2] * bn.z(),
                              m[4] * bn.x() + m[5] * bn.y() + m[6] * bn.z(),
                              m[8] * bn.x() + m[9] * bn.y() + m[10] * bn.z());
            }
            n = unit_or(n, bn);
        }
        to_x_.set(i, x);
        to_n_.set(i, n);
        if (!primed_ || jump_) {  // the first skinned frame, or a jump, starts where it ends
            from_x_.set(i, x);
            from_n_.set(i, n);
        }
    }
}

Vec3 Skin::position(uint32_t i, float fraction) const { return lerp(from_x_, to_x_, i, fraction); }

Vec3 Skin::normal(uint32_t i, float fraction) const {
    return unit_or(lerp(from_n_, to_n_, i, fraction), to_n_.get(i));
}

void Skin::prepare(uint32_t begin, uint32_t end, float fraction) {
    for (uint32_t i = begin; i < end; ++i) {
        if (!constrained(i)) continue;
        held_x_.set(i, position(i, fraction));
        if (backstop_radius_[i] > 0.0f) held_n_.set(i, normal(i, fraction));
    }
}

void Skin::constrain(uint32_t begin, uint32_t end, float fraction, float h, const float* pinned, Vec3Soa& x,
                     Vec3Soa& v, bool prepared) const {
    const float inverse_h = 1.0f / h;
    for (uint32_t i = begin; i < end; ++i) {
        if (pinned[i] != 0.0f || !constrained(i)) continue;
        const Vec3 s = prepared ? held_x_.get(i) : position(i, fraction), before = x.get(i);
        Vec3 p = before;
        // The backstop, then the max distance, then back out of the backstop
        // towards the skinned position if the max distance pulled the
        // particle in: both hold wherever the skinned position is outside
        // the backstop (radius <= distance); elsewhere the max distance does.
        const float radius = backstop_radius_[i];
        const Vec3 n = radius <= 0.0f ? Vec3::Zero() : prepared ? held_n_.get(i) : normal(i, fraction);
        if (radius > 0.0f) {
            const Vec3 centre = s - n * backstop_distance_[i];
            const Vec3 out = p - centre;
            const float distance = out.norm();
            if (distance < radius) p = centre + unit_or(out, n) * radius;
        }
        const float reach = max_distance_[i];
        const Vec3 away = p - s;
        const float distance = away.norm();
        if (distance > reach) {
            p = s + away * (reach / distance);
            if (radius > 0.0f) p = back_out_towards(p, s, n, i);
        }
        if (p == before) continue;
        x.set(i, p);
        v.set(i, v.get(i) + (p - before) * inverse_h);
    }
}

Vec3 Skin::back_out_towards(const Vec3& p, const Vec3& s, const Vec3& n, uint32_t i) const {
    // The point of the segment p -> s nearest p outside the backstop sphere:
    // the segment stays within the max distance (both ends are), and s is
    // outside the sphere unless its radius passes its distance.
    const float radius = backstop_radius_[i];
    const Vec3 centre = s - n * backstop_distance_[i];
    const Vec3 e = p - centre, f = s - p;
    const float inside = e.squaredNorm() - radius * radius;
    if (inside >= 0.0f || (s - centre).squaredNorm() < radius * radius) return p;
    const float a = f.squaredNorm(), b = e.dot(f);
    if (a <= 0.0f) return p;
    const float t = std::min((-b + std::sqrt(std::max(b * b - a * inside, 0.0f))) / a, 1.0f);
    return p + f * t;
}

void Skin::shift_origin(const Vec3& shift) {
    for (Vec3Soa* a : {&from_x_, &to_x_, &host_x_}) {
        for (size_t i = 0; i < a->size(); ++i) a->set(i, a->get(i) - shift);
    }
    for (uint32_t j = 0; j < joint_count_; ++j) {
        float* m = matrices_.data() + size_t{j} * kMatrixFloats;
        m[3] -= shift.x();
        m[7] -= shift.y();
        m[11] -= shift.z();
    }
}

// Layout: the last frame's end, positions then normals (x, y, z arrays of
// n floats each), then the joint matrices (kMatrixFloats per joint) or the
// host's positions and normals (the same six arrays).
size_t Skin::state_floats(uint32_t n) const {
    const size_t given = source_ == Source::kJoints ? size_t{joint_count_} * kMatrixFloats : 6 * size_t{n};
    return 6 * size_t{n} + given;
}

namespace {

// The state's arrays in their order, as copy(data, count); Soa is
// Vec3Soa or const Vec3Soa.
template <class Soa, class Copy>
void each_state_array(Soa& end_x, Soa& end_n, Soa& host_x, Soa& host_n, bool joints, Copy copy) {
    for (Soa* a : {&end_x, &end_n, &host_x, &host_n}) {
        if (joints && (a == &host_x || a == &host_n)) return;
        for (auto* c : {&a->x, &a->y, &a->z}) copy(c->data(), c->size());
    }
}

}  // namespace

void Skin::save_state(unsigned char* out) const {
    const bool joints = source_ == Source::kJoints;
    const auto put = [&](const float* a, size_t count) {
        std::memcpy(out, a, sizeof(float) * count);
        out += sizeof(float) * count;
    };
    each_state_array(to_x_, to_n_, host_x_, host_n_, joints, put);
    if (joints) put(matrices_.data(), matrices_.size());
}

void Skin::restore_state(bool primed, const unsigned char* in) {
    const bool joints = source_ == Source::kJoints;
    const auto take = [&](float* a, size_t count) {
        std::memcpy(a, in, sizeof(float) * count);
        in += sizeof(float) * count;
    };
    each_state_array(to_x_, to_n_, host_x_, host_n_, joints, take);
    if (joints) take(matrices_.data(), matrices_.size());
    primed_ = primed;
    jump_ = false;
}

}  // namespace cloth
