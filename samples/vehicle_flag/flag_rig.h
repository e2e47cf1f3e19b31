// The cloth side of the sample: one flag (a grid fabric) on the pole of the
// vehicle's chassis, through the Bullet adapter (cloth_bullet):
//  - the chassis btRigidBody is mirrored into a cloth body each frame, with
//    colliders for its btCompoundShape children (the box and the pole capsule);
//  - the terrain's btHeightfieldTerrainShape becomes a static height-field
//    collider;
//  - the flag's pole-side column is attached to the chassis body
//    (cloth_attach) at fixed offsets behind the pole;
//  - the chassis body is the flag's carrier, so the course's teleport back to
//    the start moves the flag with the vehicle instead of stretching it;
//  - the cloth world's origin follows the vehicle in 32 m steps
//    (BodyMirror::shift_origin), so the flag is simulated near the origin
//    wherever the course takes it: floats there resolve far better than the
//    1e-5 m the attachment check asks for.
// Coupling is one-way: the flag never pushes the vehicle.
#pragma once

#include <cloth/cloth.h>
#include <cloth_bullet/cloth_bullet.h>

#include <memory>
#include <string>
#include <vector>

#include "vehicle_world.h"

namespace vehicle_flag {

struct FlagSettings {
    uint32_t columns = 48;  // particles along the flag
    uint32_t rows = 32;     // particles up the pole
    float width = 1.2f;     // m
    float height = 0.8f;    // m
    float area_density = 0.25f;
    float stiffness = 1000.0f;  // structural N/m; shear 0.2x, bend 0.02x
    float damping = 0.5f;       // structural N s/m (the library's default); shear 0.4x, bend 0.1x
    float thickness = 0.01f;    // m, kept from every collider
    float friction = 0.3f;
    float max_strain = 0.08f;  // strain limit after each substep (0: off): the default solver's own
    cloth_solver_settings solver = cloth_default_solver_settings();
    uint32_t threads = 1;            // workers of the cloth world (1: the calling thread only)
    uint32_t profile_tasks = 0;      // task records kept per frame (0: profiling off)
    float teleport_distance = 5.0f;  // m: a carrier move beyond this in one frame is a teleport
};

class FlagRig {
  public:
    FlagRig(const FlagSettings& settings, VehicleWorld& vehicle);
    ~FlagRig();
    FlagRig(const FlagRig&) = delete;
    FlagRig& operator=(const FlagRig&) = delete;

    bool ok() const { return error_.empty(); }
    const std::string& error() const { return error_; }

    // The host teleported the chassis (in Bullet): jump its cloth body there
    // without a sweep; the carrier moves the flag with it in the next step.
    cloth_result teleport_chassis();
    // After the Bullet step, before cloth_step: the chassis body's pose and
    // velocities, reached at the end of the next step.
    cloth_result sync();
    cloth_result set_wind(const float wind[3]) { return cloth_set_wind(cloth_, wind); }
    cloth_result step(float dt) { return cloth_step(world_, dt); }

    // After a step: largest distance of an attached particle from its target
    // (the chassis pose times its offset, in double), m.
    double attachment_error(const btTransform& chassis_pose);
    // Whether the carrier's teleport handling fired in the last step.
    bool teleported() const;

    cloth_world_id world() const { return world_; }
    // Where the cloth world's origin lies in Bullet's frame (it follows the chassis).
    const double* origin() const;
    cloth_id cloth() const { return cloth_; }
    cloth_body_id chassis_body() const { return chassis_body_; }
    size_t collider_count() const { return collider_count_; }
    uint32_t particle_count() const { return particle_count_; }
    const std::vector<uint32_t>& attached() const { return attached_; }
    const std::vector<float>& positions();  // in Bullet's frame; refreshed on each call
    const std::vector<float>& normals();
    const std::vector<uint32_t>& triangles() const { return triangles_; }

  private:
    bool check(cloth_result result, const char* call);
    bool create_cloth(const FlagSettings& s, const btTransform& chassis_pose, const btVector3& top_local);
    bool create_colliders();
    // Shift the cloth world's origin to the chassis (rounded to 32 m) once
    // the chassis is more than 32 m from it.
    bool follow_chassis();
    // The cloth's positions in the cloth world's frame (Bullet's minus the origin).
    const std::vector<float>& local_positions();

    VehicleWorld& vehicle_;
    std::string error_;
    cloth_world_id world_{};
    std::unique_ptr<cloth_bullet::BodyMirror> mirror_;  // chassis body and its colliders
    cloth_body_id chassis_body_{};
    size_t collider_count_ = 0;
    cloth_fabric_id fabric_{};
    cloth_id cloth_{};
    uint32_t particle_count_ = 0;
    std::vector<uint32_t> attached_;
    std::vector<btVector3> attached_local_;  // offsets in the chassis frame
    std::vector<float> positions_, normals_;
    std::vector<uint32_t> triangles_;
};

}  // namespace vehicle_flag
