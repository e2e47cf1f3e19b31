// The sample's Bullet world: the terrain as a btHeightfieldTerrainShape and a
// four-wheeled btRaycastVehicle whose chassis is a btCompoundShape (a box,
// shifted up so the centre of mass sits low, and the flag pole as a
// btCapsuleShape). Axes: y up;
// the vehicle drives along its local +z (Bullet's raycast vehicle coordinate
// system 0, 1, 2: x across, y up, z forward).
#pragma once

#include <BulletCollision/CollisionShapes/btHeightfieldTerrainShape.h>
#include <btBulletDynamicsCommon.h>

#include <memory>
#include <vector>

#include "terrain.h"

class btHeightfieldTerrainShape;

namespace vehicle_flag {

// Geometry of the vehicle in the chassis body frame (metres).
struct VehicleLayout {
    float mass = 800.0f;                             // kg
    float box_half_extents[3] = {0.9f, 0.4f, 2.1f};  // chassis box...
    float box_center[3] = {0.0f, 0.9f, 0.0f};        // ...centred here in the body frame
    float wheel_radius = 0.4f;
    float wheel_half_width = 0.15f;
    float suspension_rest = 0.5f;
    float wheel_connection_y = 0.8f;
    float pole_base[3] = {0.0f, 1.3f, -1.5f};  // on the roof, near the rear
    float pole_height = 2.0f;                  // base to top
    float pole_radius = 0.035f;
};

class VehicleWorld {
  public:
    VehicleWorld(const Terrain& terrain, const VehicleLayout& layout = {});
    ~VehicleWorld();
    VehicleWorld(const VehicleWorld&) = delete;
    VehicleWorld& operator=(const VehicleWorld&) = delete;

    // Controls for the next step: engine force per driven (rear) wheel (N),
    // brake per wheel (Bullet's per-step impulse limit), front steering (rad).
    void set_controls(float engine, float brake, float steering);
    // One fixed Bullet step of dt seconds.
    void step(float dt);
    // Put the chassis at `pose` at rest (the sample's teleport back to the start).
    void teleport(const btTransform& pose);

    const VehicleLayout& layout() const { return layout_; }
    const btTransform& start_pose() const { return start_pose_; }
    btTransform chassis_pose() const;
    btVector3 chassis_velocity() const;
    btVector3 chassis_angular_velocity() const;
    float forward_speed() const;  // m/s along the chassis' forward axis
    int wheels_in_contact() const;
    int wheel_count() const;
    btTransform wheel_pose(int wheel) const;

    btDiscreteDynamicsWorld* dynamics_world() { return world_.get(); }
    btRigidBody* chassis_body() { return chassis_.get(); }
    btCollisionObject* terrain_object() { return terrain_body_.get(); }
    btCompoundShape* chassis_shape() { return chassis_shape_.get(); }

  private:
    VehicleLayout layout_;
    btTransform start_pose_;
    std::unique_ptr<btDefaultCollisionConfiguration> configuration_;
    std::unique_ptr<btCollisionDispatcher> dispatcher_;
    std::unique_ptr<btBroadphaseInterface> broadphase_;
    std::unique_ptr<btSequentialImpulseConstraintSolver> solver_;
    std::unique_ptr<btDiscreteDynamicsWorld> world_;
    std::unique_ptr<btHeightfieldTerrainShape> terrain_shape_;
    std::unique_ptr<btRigidBody> terrain_body_;
    std::unique_ptr<btBoxShape> box_shape_;
    std::unique_ptr<btCapsuleShape> pole_shape_;
    std::unique_ptr<btCompoundShape> chassis_shape_;
    std::unique_ptr<btDefaultMotionState> chassis_motion_;
    std::unique_ptr<btRigidBody> chassis_;
    std::unique_ptr<btDefaultVehicleRaycaster> raycaster_;
    std::unique_ptr<btRaycastVehicle> vehicle_;
};

}  // namespace vehicle_flag
