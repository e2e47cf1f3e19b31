// The cloth side of the sample: one flag (a grid fabric) whose pole-side
// column follows the pole on the vehicle's chassis. The attached particles
// sit on the rear of the pole at fixed offsets in the chassis frame.
#pragma once

#include <cloth/cloth.h>

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
    cloth_solver_settings solver = cloth_default_solver_settings();
    uint32_t threads = 1;        // workers of the cloth world (1: the calling thread only)
    uint32_t profile_tasks = 0;  // task records kept per frame (0: profiling off)
};

class FlagRig {
  public:
    FlagRig(const FlagSettings& settings, const VehicleLayout& vehicle, const btTransform& chassis_pose);
    ~FlagRig();
    FlagRig(const FlagRig&) = delete;
    FlagRig& operator=(const FlagRig&) = delete;

    bool ok() const { return error_.empty(); }
    const std::string& error() const { return error_; }

    // Move the flag with the chassis by a pose jump (teleport): every particle
    // keeps its place in the chassis frame and comes to rest there.
    cloth_result teleport(const btTransform& from, const btTransform& to);
    // Before a step: where the attached particles must be at its end.
    cloth_result follow(const btTransform& chassis_pose);
    cloth_result set_wind(const float wind[3]) { return cloth_set_wind(cloth_, wind); }
    cloth_result step(float dt) { return cloth_step(world_, dt); }

    // After a step: largest distance of an attached particle from its target (m).
    float attachment_error(const btTransform& chassis_pose);

    cloth_world_id world() const { return world_; }
    cloth_fabric_id fabric() const { return fabric_; }
    cloth_id cloth() const { return cloth_; }
    uint32_t particle_count() const { return particle_count_; }
    const std::vector<uint32_t>& attached() const { return attached_; }
    const std::vector<float>& positions();  // refreshed on each call
    const std::vector<float>& normals();
    const std::vector<uint32_t>& triangles() const { return triangles_; }

  private:
    bool check(cloth_result result, const char* call);
    void attached_targets(const btTransform& chassis_pose, std::vector<float>* out) const;

    std::string error_;
    cloth_world_id world_{};
    cloth_fabric_id fabric_{};
    cloth_id cloth_{};
    uint32_t particle_count_ = 0;
    std::vector<uint32_t> attached_;
    std::vector<btVector3> attached_local_;  // offsets in the chassis frame
    std::vector<float> targets_, positions_, normals_;
    std::vector<uint32_t> triangles_;
};

}  // namespace vehicle_flag
