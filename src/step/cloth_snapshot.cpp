// Snapshots of a cloth's dynamic state, for replays and rollback
// networking: positions, velocities, pins and their targets, the solver
// settings a budget policy may have changed, air, the sleep state and a
// skinned cloth's skin state, so that restoring and stepping again gives
// the same bits as the first time.
// Topology, material and scratch buffers are not saved (the snapshot is
// restored into a cloth of the same fabric).
//
// Layout (native endianness, floats IEEE 754):
//   SnapshotHeader, then x, y, z of positions, of velocities and of pin
//   targets (n floats each), then the pinned flags (n floats, 0 or 1);
//   for a skinned cloth then a SkinSection and the skin's state
//   (Skin::save_state). The header's flags say whether the strain limiter
//   of the last frame's last substep ended past its promise (the
//   default's next substep depends on it), whether the host holds the
//   cloth asleep, and whether the skin's state follows.
// The header's checksum is XXH3 of every byte before it and every byte
// after it, so a restore checks it before it reads anything else: a
// snapshot is either exactly what was saved or refused as corrupt.
//
// Format versions: 1 had no library version, size, fabric identity or
// checksum (libraries up to 1.4); 2 is this one. A library reads its own
// format only (cloth.h, "Snapshots").
#include <cloth/cloth.h>

#include <cmath>
#include <cstddef>
#include <cstring>

#include "base/hash.h"
#include "step/cloth_instance.h"

namespace cloth {
namespace {

constexpr uint32_t kSnapshotMagic = 0x4E534C43;  // "CLSN"
constexpr uint32_t kSnapshotFormat = 2;

struct SnapshotHeader {
    uint32_t magic;
    uint32_t format;
    uint32_t size_of_header;
    uint32_t library_major, library_minor, library_patch;  // the library that wrote it
    uint64_t total_size;                                   // header and arrays, in bytes
    uint64_t fabric_identity;                              // Fabric::identity
    uint32_t particle_count;
    uint32_t solver_kind;
    uint32_t iterations;
    uint32_t substeps;
    uint32_t sleeping;
    uint32_t rest_frames;
    float wind[3];
    float air_density, drag_coefficient, lift_coefficient, linear_drag;
    uint32_t flags;     // kStrainedFlag or zero (zero in 1.5.0); keeps the checksum 8-byte aligned
    uint64_t checksum;  // XXH3 of every other byte of the snapshot
};

// The last frame's last substep ended with its strain limiter past its
// promise (the default's next substep runs backward Euler: solver_default.h).
constexpr uint32_t kStrainedFlag = 1;
// The host holds the sleeping cloth asleep (ClothInstance::hold_asleep).
constexpr uint32_t kHeldAsleepFlag = 2;
// A SkinSection and the skin's state follow the arrays (since 1.12.1).
constexpr uint32_t kSkinFlag = 4;
// The last frame left the cloth quiet (ClothInstance::starts_quiet; since 1.12.2).
constexpr uint32_t kQuietFlag = 8;
constexpr uint32_t kKnownFlags = kStrainedFlag | kHeldAsleepFlag | kSkinFlag | kQuietFlag;

struct SkinSection {
    uint32_t source;       // 1: joint matrices, 2: the host's skinned positions
    uint32_t joint_count;  // of the skin (joint matrices only)
    uint32_t primed;       // 1 once a frame has been skinned
    uint32_t reserved;     // 0
};
constexpr uint32_t kSkinFromJoints = 1, kSkinFromHost = 2;

constexpr size_t kChecksumAt = offsetof(SnapshotHeader, checksum);
constexpr size_t kAfterChecksum = kChecksumAt + sizeof(uint64_t);
static_assert(kAfterChecksum == sizeof(SnapshotHeader), "the checksum ends the header");

constexpr size_t kArrays = 10;  // x, v, pin target (3 each) and pinned

uint64_t checksum_of(const unsigned char* bytes, size_t size) {
    const uint64_t head = hash_bytes(bytes, kChecksumAt);
    return hash_bytes(bytes + kAfterChecksum, size - kAfterChecksum, head);
}

Status corrupt(const char* why) {
    return Status::error(CLOTH_ERROR_CORRUPT_SNAPSHOT, "the snapshot is corrupt: %s; nothing was restored",
                         why);
}

}  // namespace

// The skin's state goes into snapshots once the cloth has a skin.
bool ClothInstance::snapshot_has_skin() const { return skin_.active() && skin_.sized_for(particle_count()); }

size_t ClothInstance::snapshot_size() const {
    const size_t arrays = sizeof(SnapshotHeader) + kArrays * sizeof(float) * particle_count();
    if (!snapshot_has_skin()) return arrays;
    return arrays + sizeof(SkinSection) + sizeof(float) * skin_.state_floats(particle_count());
}

void ClothInstance::save_snapshot(void* out) const {
    SnapshotHeader h{};
    h.magic = kSnapshotMagic;
    h.format = kSnapshotFormat;
    h.size_of_header = sizeof h;
    h.library_major = CLOTH_VERSION_MAJOR;
    h.library_minor = CLOTH_VERSION_MINOR;
    h.library_patch = CLOTH_VERSION_PATCH;
    h.total_size = snapshot_size();
    h.fabric_identity = fabric().identity;
    h.particle_count = particle_count();
    h.solver_kind = static_cast<uint32_t>(solver_.kind);
    h.iterations = solver_.iterations;
    h.substeps = solver_.substeps;
    h.sleeping = sleep_.sleeping ? 1 : 0;
    h.rest_frames = sleep_.rest_frames;
    h.flags = (last_.strained ? kStrainedFlag : 0) | (sleep_.held ? kHeldAsleepFlag : 0) |
              (snapshot_has_skin() ? kSkinFlag : 0) | (last_.quiet ? kQuietFlag : 0);
    for (int c = 0; c < 3; ++c) h.wind[c] = aero_.wind[c];
    h.air_density = aero_.air_density;
    h.drag_coefficient = aero_.drag_coefficient;
    h.lift_coefficient = aero_.lift_coefficient;
    h.linear_drag = aero_.linear_drag;
    auto* const start = static_cast<unsigned char*>(out);
    unsigned char* bytes = start;
    std::memcpy(bytes, &h, sizeof h);
    bytes += sizeof h;
    const size_t row = sizeof(float) * particle_count();
    for (const HostVector<float>* a : {&x_.x, &x_.y, &x_.z, &v_.x, &v_.y, &v_.z, &pins_.target.x,
                                       &pins_.target.y, &pins_.target.z, &pins_.pinned}) {
        std::memcpy(bytes, a->data(), row);
        bytes += row;
    }
    if (snapshot_has_skin()) {
        const bool joints = skin_.source() == Skin::Source::kJoints;
        const SkinSection section{joints ? kSkinFromJoints : kSkinFromHost, joints ? skin_.joint_count() : 0,
                                  skin_.primed() ? 1u : 0u, 0};
        std::memcpy(bytes, &section, sizeof section);
        bytes += sizeof section;
        skin_.save_state(bytes);
    }
    const uint64_t checksum = checksum_of(start, snapshot_size());
    std::memcpy(start + kChecksumAt, &checksum, sizeof checksum);
}

Status ClothInstance::restore_snapshot(const void* in, size_t size) {
    const uint32_t n = particle_count();
    const auto* const bytes = static_cast<const unsigned char*>(in);
    // The buffer may be unaligned: every field is read through memcpy.
    if (size < sizeof(SnapshotHeader)) return corrupt("it is shorter than a snapshot header");
    SnapshotHeader h;
    std::memcpy(&h, bytes, sizeof h);
    if (h.magic != kSnapshotMagic) return corrupt("it does not start as a cloth snapshot");
    if (h.format != kSnapshotFormat) {
        return Status::error(CLOTH_ERROR_CORRUPT_SNAPSHOT,
                             "the snapshot has format %u; this library (%d.%d.%d) reads format %u only; "
                             "nothing was restored",
                             h.format, CLOTH_VERSION_MAJOR, CLOTH_VERSION_MINOR, CLOTH_VERSION_PATCH,
                             kSnapshotFormat);
    }
    if (h.size_of_header != sizeof h) return corrupt("its header size is wrong");
    if (h.total_size != size) {
        return Status::error(CLOTH_ERROR_CORRUPT_SNAPSHOT,
                             "the snapshot was saved as %llu bytes, but %zu were given; nothing was restored",
                             static_cast<unsigned long long>(h.total_size), size);
    }
    if (h.checksum != checksum_of(bytes, size)) return corrupt("its checksum does not match its bytes");

    // Intact: it is what some cloth saved. Is it this cloth's kind?
    if (h.particle_count != n) {
        return Status::error(CLOTH_ERROR_INVALID_COUNT,
                             "snapshot of %u particles (%zu bytes) does not fit this cloth of %u particles",
                             h.particle_count, size, n);
    }
    const size_t arrays_end = sizeof h + kArrays * sizeof(float) * n;
    SkinSection skin{};
    const bool has_skin = (h.flags & kSkinFlag) != 0;
    uint64_t expected = arrays_end;
    if (has_skin) {
        if (size < arrays_end + sizeof skin) return corrupt("its skin section is cut short");
        std::memcpy(&skin, bytes + arrays_end, sizeof skin);
        if ((skin.source != kSkinFromJoints && skin.source != kSkinFromHost) || skin.primed > 1 ||
            skin.reserved != 0 || (skin.source == kSkinFromHost && skin.joint_count != 0))
            return corrupt("its skin section is out of range");
        const uint64_t given = skin.source == kSkinFromJoints
                                   ? uint64_t{skin.joint_count} * Skin::kMatrixFloats
                                   : 6 * uint64_t{n};
        expected += sizeof skin + sizeof(float) * (6 * uint64_t{n} + given);
    }
    if (expected != size) return corrupt("its size does not match its particle count");
    if (h.fabric_identity != fabric().identity) {
        return Status::error(CLOTH_ERROR_INVALID_VALUE,
                             "the snapshot is of another fabric (same particle count, other topology or "
                             "rest shape)");
    }
    if (!has_skin && snapshot_has_skin()) {
        return Status::error(
            CLOTH_ERROR_INVALID_VALUE,
            "the snapshot is of a cloth without a skin (or from a library before 1.12.1, "
            "whose snapshots hold no skin), and this cloth has one: it could not step as the "
            "snapshot's cloth did");
    }
    if (has_skin) {
        const bool joints = skin.source == kSkinFromJoints;
        const Skin::Source source = joints ? Skin::Source::kJoints : Skin::Source::kHost;
        if (!snapshot_has_skin() || skin_.source() != source ||
            (joints && skin_.joint_count() != skin.joint_count)) {
            return Status::error(
                CLOTH_ERROR_INVALID_VALUE,
                "the snapshot is of a cloth whose skin follows %s; restore it into a cloth "
                "with the same skin (cloth_set_skin, and joint matrices or skinned positions "
                "as the first had)",
                joints ? "joint matrices" : "skinned positions the host gives");
        }
    }
    // What a library of this format writes; checked again, so that a bug
    // elsewhere cannot restore a state no step could have made.
    if (h.solver_kind > CLOTH_SOLVER_CHEBYSHEV || h.iterations < 1 || h.iterations > CLOTH_MAX_ITERATIONS ||
        h.substeps < 1 || h.substeps > CLOTH_MAX_SUBSTEPS) {
        return corrupt("its solver settings are out of range");
    }
    if ((h.flags & ~kKnownFlags) != 0 || ((h.flags & kHeldAsleepFlag) && !h.sleeping)) {
        return corrupt("it has flags no library of this format writes");
    }
    const float air[7] = {h.wind[0],          h.wind[1],          h.wind[2],    h.air_density,
                          h.drag_coefficient, h.lift_coefficient, h.linear_drag};
    for (float a : air) {
        if (!std::isfinite(a)) return corrupt("its air parameters are not finite");
    }
    const unsigned char* values = bytes + sizeof h;
    for (size_t k = 0; k < kArrays * n; ++k) {
        float value;
        std::memcpy(&value, values + k * sizeof(float), sizeof value);
        if (!std::isfinite(value)) return corrupt("it holds a value that is not finite");
        if (k >= 9 * static_cast<size_t>(n) && value != 0.0f && value != 1.0f)
            return corrupt("it holds a pinned flag that is neither 0 nor 1");
    }
    const unsigned char* skin_state = has_skin ? bytes + arrays_end + sizeof skin : nullptr;
    for (const unsigned char* at = skin_state; has_skin && at < bytes + size; at += sizeof(float)) {
        float value;
        std::memcpy(&value, at, sizeof value);
        if (!std::isfinite(value)) return corrupt("its skin holds a value that is not finite");
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
    const size_t row = sizeof(float) * n;
    for (HostVector<float>* a : {&x_.x, &x_.y, &x_.z, &v_.x, &v_.y, &v_.z, &pins_.target.x, &pins_.target.y,
                                 &pins_.target.z, &pins_.pinned}) {
        std::memcpy(a->data(), values, row);
        values += row;
    }
    if (has_skin) skin_.restore_state(skin.primed != 0, skin_state);
    strain_.tethers_follow_pins = false;
    pins_.list.clear();
    for (uint32_t i = 0; i < n; ++i) {
        if (pins_.pinned[i] != 0.0f) pins_.list.push_back(i);
    }
    sleep_.sleeping = h.sleeping != 0;
    sleep_.held = (h.flags & kHeldAsleepFlag) != 0;
    contact_.forget_sleep();
    if (sleep_.held) contact_.fall_asleep();  // a carrier is caught up with from where it is now
    sleep_.rest_frames = h.rest_frames;
    last_.strained = (h.flags & kStrainedFlag) != 0;
    last_.quiet = (h.flags & kQuietFlag) != 0;
    return {};
}

}  // namespace cloth
