// Carrier controls: how a cloth travels with the body that carries it
// (a vehicle, a character). Once per step, before the substeps, the
// carrier's motion over the frame (from its start and target poses) is
// compared with its motion over the previous frame; the difference is the
// velocity change a particle fixed to the carrier would get. Free particles
// receive it scaled by (1 - inertia), split into
//   linear:      change of the origin's velocity,
//   angular:     change of the tangential (omega x r) velocity, plus the
//                rotation of the particle's velocity relative to the carrier
//                (Coriolis),
//   centrifugal: change of the centripetal part of the rotation.
// With every inertia 0 the cloth moves exactly as if rigidly fixed to the
// carrier; with 1 it feels the carrier only through its attachments and
// colliders (physical). Then relative speeds are clamped, and a pose jump
// over the thresholds (or a body teleport) moves the cloth rigidly with the
// carrier, or resets it to its reference shape at the new pose.
#pragma once

#include <cloth/cloth.h>

#include <cstdint>

#include "base/host_allocator.h"
#include "base/soa.h"
#include "collide/bodies.h"

namespace cloth {

struct CarrierParams {
    float linear_inertia = 1;
    float angular_inertia = 1;
    float centrifugal_inertia = 1;
    float max_relative_speed = 0;  // 0: no limit
    float teleport_distance = 0;   // 0: off
    float teleport_rotation = 0;   // 0: off
    cloth_teleport_mode teleport_mode = CLOTH_TELEPORT_MOVE;
};

class Carrier {
  public:
    explicit Carrier(const HostMemory* memory) : reference_(memory) {}

    bool active() const { return body_ != UINT32_MAX; }
    uint32_t body() const { return body_; }
    const CarrierParams& params() const { return params_; }
    bool teleported() const { return teleported_; }

    // Start carrying: `x` relative to `body.start` becomes the reference
    // shape; the previous frame's motion is taken from the body's velocities.
    void set(uint32_t body_slot, const Body& body, const CarrierParams& params, const Vec3Soa& x);
    void clear();

    // Once per step of `dt` seconds, before the substeps. Free particles
    // (pinned[i] == 0) feel the inertia terms; on a teleport, free and
    // attached particles (attached_body non-null and [i] != UINT32_MAX) move
    // with the carrier, host-pinned ones stay. `jumped_from` is non-null if
    // the host teleported the body (cloth_body_teleport): the pose it left.
    void begin_step(const Body& body, const Pose* jumped_from, float dt, const float* pinned,
                    const HostVector<uint32_t>* attached_body, Vec3Soa& x, Vec3Soa& v);

  private:
    uint32_t body_ = UINT32_MAX;
    CarrierParams params_;
    Vec3 previous_linear_ = Vec3::Zero();   // m/s of the origin over the previous frame
    Vec3 previous_angular_ = Vec3::Zero();  // rad/s over the previous frame
    Vec3Soa reference_;                     // particle positions in the carrier frame
    bool teleported_ = false;
};

}  // namespace cloth
