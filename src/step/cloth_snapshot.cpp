// Snapshots of a cloth's dynamic state, for replays and rollback
// networking: positions, velocities, pins and their targets, the solver
// settings a budget policy may have changed, air, and the sleep state, so
// that restoring and stepping again gives the same bits as the first time.
// Topology, material and scratch buffers are not saved (the snapshot is
// restored into a cloth of the same fabric).
//
// Layout (native endianness, floats IEEE 754):
//   SnapshotHeader, then x, y, z of positions, of velocities and of pin
//   targets (n floats each), then the pinned flags (n floats, 0 or 1).
#include <cmath>
#include <cstring>

#include "step/cloth_instance.h"

namespace cloth {
namespace {

constexpr uint32_t kSnapshotMagic = 0x4E534C43;  // "CLSN"
constexpr uint32_t kSnapshotVersion = 1;

struct SnapshotHeader {
    uint32_t magic;
    uint32_t version;
    uint32_t size_of_header;
    uint32_t particle_count;
    uint32_t solver_kind;
    uint32_t iterations;
    uint32_t substeps;
    uint32_t sleeping;
    uint32_t rest_frames;
    float wind[3];
    float air_density, drag_coefficient, lift_coefficient, linear_drag;
};

constexpr size_t kArrays = 10;  // x, v, pin target (3 each) and pinned

}  // namespace

size_t ClothInstance::snapshot_size() const {
    return sizeof(SnapshotHeader) + kArrays * sizeof(float) * particle_count();
}

void ClothInstance::save_snapshot(void* out) const {
    SnapshotHeader h{};
    h.magic = kSnapshotMagic;
    h.version = kSnapshotVersion;
    h.size_of_header = sizeof h;
    h.particle_count = particle_count();
    h.solver_kind = static_cast<uint32_t>(solver_.kind);
    h.iterations = solver_.iterations;
    h.substeps = solver_.substeps;
    h.sleeping = sleeping_ ? 1 : 0;
    h.rest_frames = rest_frames_;
    for (int c = 0; c < 3; ++c) h.wind[c] = aero_.wind[c];
    h.air_density = aero_.air_density;
    h.drag_coefficient = aero_.drag_coefficient;
    h.lift_coefficient = aero_.lift_coefficient;
    h.linear_drag = aero_.linear_drag;
    auto* bytes = static_cast<unsigned char*>(out);
    std::memcpy(bytes, &h, sizeof h);
    bytes += sizeof h;
    const size_t row = sizeof(float) * particle_count();
    for (const HostVector<float>* a : {&x_.x, &x_.y, &x_.z, &v_.x, &v_.y, &v_.z, &pin_target_.x,
                                       &pin_target_.y, &pin_target_.z, &pinned_}) {
        std::memcpy(bytes, a->data(), row);
        bytes += row;
    }
}

Status ClothInstance::restore_snapshot(const void* in, size_t size) {
    const uint32_t n = particle_count();
    if (size < sizeof(SnapshotHeader)) {
        return Status::error(CLOTH_ERROR_INVALID_VALUE, "snapshot of %zu bytes is shorter than its header",
                             size);
    }
    SnapshotHeader h;
    std::memcpy(&h, in, sizeof h);
    if (h.magic != kSnapshotMagic || h.size_of_header != sizeof h) {
        return Status::error(CLOTH_ERROR_INVALID_VALUE, "buffer is not a cloth snapshot");
    }
    if (h.version != kSnapshotVersion) {
        return Status::error(CLOTH_ERROR_INVALID_VALUE, "snapshot version %u, expected %u", h.version,
                             kSnapshotVersion);
    }
    if (h.particle_count != n || size != snapshot_size()) {
        return Status::error(CLOTH_ERROR_INVALID_COUNT,
                             "snapshot of %u particles (%zu bytes) does not fit this cloth of %u particles",
                             h.particle_count, size, n);
    }
    if (h.solver_kind > CLOTH_SOLVER_CHEBYSHEV || h.iterations < 1 || h.iterations > 256 || h.substeps < 1 ||
        h.substeps > 64) {
        return Status::error(CLOTH_ERROR_INVALID_VALUE, "snapshot solver settings are out of range");
    }
    const float* values = reinterpret_cast<const float*>(static_cast<const unsigned char*>(in) + sizeof h);
    float air[7] = {h.wind[0],          h.wind[1],          h.wind[2],    h.air_density,
                    h.drag_coefficient, h.lift_coefficient, h.linear_drag};
    for (float a : air) {
        if (!std::isfinite(a))
            return Status::error(CLOTH_ERROR_NOT_FINITE, "snapshot air parameters are not finite");
    }
    // The buffer may be unaligned: read through memcpy.
    for (size_t k = 0; k < kArrays * n; ++k) {
        float value;
        std::memcpy(&value, values + k, sizeof value);
        if (!std::isfinite(value)) {
            return Status::error(CLOTH_ERROR_NOT_FINITE, "snapshot value %zu is not finite", k);
        }
        if (k >= 9 * static_cast<size_t>(n) && value != 0.0f && value != 1.0f) {
            return Status::error(CLOTH_ERROR_INVALID_VALUE, "snapshot pinned flag %zu is neither 0 nor 1",
                                 k - 9 * static_cast<size_t>(n));
        }
    }

    // Valid: apply.
    solver_.kind = static_cast<cloth_solver_kind>(h.solver_kind);
    solver_.iterations = h.iterations;
    solver_.substeps = h.substeps;
    aero_.wind = Vec3(h.wind[0], h.wind[1], h.wind[2]);
    aero_.air_density = h.air_density;
    aero_.drag_coefficient = h.drag_coefficient;
    aero_.lift_coefficient = h.lift_coefficient;
    aero_.linear_drag = h.linear_drag;
    const auto* bytes = reinterpret_cast<const unsigned char*>(values);
    const size_t row = sizeof(float) * n;
    for (HostVector<float>* a : {&x_.x, &x_.y, &x_.z, &v_.x, &v_.y, &v_.z, &pin_target_.x, &pin_target_.y,
                                 &pin_target_.z, &pinned_}) {
        std::memcpy(a->data(), bytes, row);
        bytes += row;
    }
    pinned_list_.clear();
    for (uint32_t i = 0; i < n; ++i) {
        if (pinned_[i] != 0.0f) pinned_list_.push_back(i);
    }
    sleeping_ = h.sleeping != 0;
    rest_frames_ = h.rest_frames;
    return {};
}

}  // namespace cloth
