// The standard scenes, built through the public C API, shared by the demo,
// the tests and the benchmarks so they all measure the same thing.
//
// All scenes use a 1 m x 1 m cloth of `resolution` x `resolution`
// particles and `total_mass` kg (area density = total_mass / 1 m^2), the
// same stiffness for every spring kind, pinned at the two top corners
// (flag: the whole left column).
#pragma once

#include <cloth/cloth.h>

#include <cstdint>
#include <string>
#include <vector>

namespace cloth_samples {

enum class SceneKind {
    kHanging,       // vertical, released from rest
    kFallingFlat,   // horizontal, falls and swings down about its pinned edge
    kFlagInWind,    // vertical, left column pinned, wind along the flag (+x) with a cross breeze
    kDrapedSphere,  // horizontal, unpinned, falls onto a fixed sphere (contact applied by Scene::step)
};

const char* scene_name(SceneKind kind);

struct SceneConfig {
    SceneKind kind = SceneKind::kHanging;
    uint32_t resolution = 32;
    float total_mass = 1.0f;    // kg
    float stiffness = 1000.0f;  // N/m, every spring kind
    float damping = 0.0f;       // N s/m, every spring kind
    float wind_speed = 10.0f;   // m/s, flag only
    // No air at all (no wind, drag, lift or linear drag): springs and
    // gravity only, as an outside reference implementation runs them.
    bool still_air = false;
    cloth_solver_settings solver = cloth_default_solver_settings();
    uint32_t spring_kinds = CLOTH_SPRING_ALL;
    // The world (workers, host job system, ...).
    cloth_world_desc world = cloth_default_world_desc();
    // Cloths of the same fabric in the world, 1.5 m apart along z.
    uint32_t copies = 1;
    float strain_limit = 0;  // > 0: cloth_set_strain_limit with this max strain
    // > 0: every particle starts off the cloth's plane by a fixed
    // pseudo-random amount within +-out_of_plane m, so that the cloth is
    // not exactly flat (an exactly flat cloth hanging in still air never
    // leaves its plane).
    float out_of_plane = 0.0f;
    // The same particles and triangles as a mesh fabric (cloth_fabric_create_mesh:
    // index-pair springs, structural and bend, no shear) instead of a grid.
    bool mesh = false;
};

// Owns a world with one fabric and its cloths; destroys them on scope exit.
class Scene {
  public:
    explicit Scene(const SceneConfig& config);
    ~Scene();
    Scene(const Scene&) = delete;
    Scene& operator=(const Scene&) = delete;

    bool ok() const { return error_.empty(); }
    const std::string& error() const { return error_; }

    cloth_world_id world() const { return world_; }
    cloth_fabric_id fabric() const { return fabric_; }
    cloth_id cloth() const { return cloths_.empty() ? cloth_id{} : cloths_[0]; }
    const std::vector<cloth_id>& cloths() const { return cloths_; }
    uint32_t particle_count() const { return particle_count_; }

    // One frame; in kDrapedSphere, particles that entered the sphere are put
    // back on its surface at rest (sticky contact, through the public API).
    cloth_result step(float dt);
    cloth_stats stats() const;
    std::vector<float> positions() const;  // of the first cloth

    static constexpr float kSphereCenter[3] = {0.5f, 1.0f, 0.5f};
    static constexpr float kSphereRadius = 0.3f;

  private:
    SceneKind kind_ = SceneKind::kHanging;
    std::vector<float> scratch_, moved_;
    std::vector<uint32_t> inside_;
    cloth_world_id world_{};
    cloth_fabric_id fabric_{};
    std::vector<cloth_id> cloths_;
    uint32_t particle_count_ = 0;
    std::string error_;
};

}  // namespace cloth_samples
