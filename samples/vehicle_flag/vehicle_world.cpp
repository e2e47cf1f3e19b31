#include "vehicle_world.h"

#include <cmath>

namespace vehicle_flag {

VehicleWorld::VehicleWorld(const Terrain& terrain, const VehicleLayout& layout) : layout_(layout) {
    configuration_ = std::make_unique<btDefaultCollisionConfiguration>();
    dispatcher_ = std::make_unique<btCollisionDispatcher>(configuration_.get());
    broadphase_ = std::make_unique<btDbvtBroadphase>();
    solver_ = std::make_unique<btSequentialImpulseConstraintSolver>();
    world_ = std::make_unique<btDiscreteDynamicsWorld>(dispatcher_.get(), broadphase_.get(), solver_.get(),
                                                       configuration_.get());
    world_->setGravity(btVector3(0, -9.81f, 0));

    // Terrain: Bullet centres a heightfield on its local origin, so the body
    // sits at the middle of the grid and of the height range.
    const TerrainLayout& t = terrain.layout();
    terrain_shape_ = std::make_unique<btHeightfieldTerrainShape>(t.columns, t.rows, terrain.heights().data(),
                                                                 terrain.min_height(), terrain.max_height(),
                                                                 /*upAxis=*/1, /*flipQuadEdges=*/false);
    terrain_shape_->setLocalScaling(btVector3(t.cell, 1.0f, t.cell));
    btTransform terrain_pose;
    terrain_pose.setIdentity();
    terrain_pose.setOrigin(btVector3(t.min_x + 0.5f * (t.columns - 1) * t.cell,
                                     0.5f * (terrain.min_height() + terrain.max_height()),
                                     t.min_z + 0.5f * (t.rows - 1) * t.cell));
    btRigidBody::btRigidBodyConstructionInfo terrain_info(0.0f, nullptr, terrain_shape_.get());
    terrain_info.m_startWorldTransform = terrain_pose;
    terrain_info.m_friction = 1.0f;
    terrain_body_ = std::make_unique<btRigidBody>(terrain_info);
    world_->addRigidBody(terrain_body_.get());

    // Chassis: a box and the pole capsule in one compound; wheels are rays.
    chassis_shape_ = std::make_unique<btCompoundShape>();
    box_shape_ = std::make_unique<btBoxShape>(
        btVector3(layout_.box_half_extents[0], layout_.box_half_extents[1], layout_.box_half_extents[2]));
    btTransform child;
    child.setIdentity();
    child.setOrigin(btVector3(layout_.box_center[0], layout_.box_center[1], layout_.box_center[2]));
    chassis_shape_->addChildShape(child, box_shape_.get());
    // btCapsuleShape is along y: `height` is the cylinder part between the caps.
    pole_shape_ = std::make_unique<btCapsuleShape>(layout_.pole_radius, layout_.pole_height);
    child.setOrigin(btVector3(layout_.pole_base[0], layout_.pole_base[1] + 0.5f * layout_.pole_height,
                              layout_.pole_base[2]));
    chassis_shape_->addChildShape(child, pole_shape_.get());

    start_pose_.setIdentity();
    start_pose_.setOrigin(btVector3(0.0f, terrain.height_at(0.0f, 0.0f) + 0.6f, 0.0f));
    btVector3 inertia(0, 0, 0);
    box_shape_->calculateLocalInertia(layout_.mass, inertia);  // the pole's share is negligible
    chassis_motion_ = std::make_unique<btDefaultMotionState>(start_pose_);
    btRigidBody::btRigidBodyConstructionInfo chassis_info(layout_.mass, chassis_motion_.get(),
                                                          chassis_shape_.get(), inertia);
    chassis_ = std::make_unique<btRigidBody>(chassis_info);
    chassis_->setActivationState(DISABLE_DEACTIVATION);
    world_->addRigidBody(chassis_.get());

    btRaycastVehicle::btVehicleTuning tuning;
    tuning.m_suspensionStiffness = 35.0f;
    tuning.m_suspensionCompression = 3.5f;
    tuning.m_suspensionDamping = 4.5f;
    tuning.m_frictionSlip = 2.0f;
    tuning.m_maxSuspensionTravelCm = 40.0f;
    tuning.m_maxSuspensionForce = 20000.0f;
    raycaster_ = std::make_unique<btDefaultVehicleRaycaster>(world_.get());
    vehicle_ = std::make_unique<btRaycastVehicle>(tuning, chassis_.get(), raycaster_.get());
    vehicle_->setCoordinateSystem(0, 1, 2);
    world_->addVehicle(vehicle_.get());

    const btVector3 down(0, -1, 0), axle(-1, 0, 0);
    const float x = layout_.box_half_extents[0] - layout_.wheel_half_width;
    const float z = layout_.box_half_extents[2] - 1.2f * layout_.wheel_radius;
    const float corners[4][2] = {{x, z}, {-x, z}, {x, -z}, {-x, -z}};  // front two first
    for (int w = 0; w < 4; ++w) {
        btWheelInfo& wheel = vehicle_->addWheel(
            btVector3(corners[w][0], layout_.wheel_connection_y, corners[w][1]), down, axle,
            layout_.suspension_rest, layout_.wheel_radius, tuning, /*isFrontWheel=*/w < 2);
        wheel.m_rollInfluence = 0.05f;
    }
    vehicle_->resetSuspension();
}

VehicleWorld::~VehicleWorld() {
    world_->removeVehicle(vehicle_.get());
    world_->removeRigidBody(chassis_.get());
    world_->removeRigidBody(terrain_body_.get());
}

void VehicleWorld::set_controls(float engine, float brake, float steering) {
    for (int w = 0; w < 4; ++w) {
        vehicle_->applyEngineForce(w >= 2 ? engine : 0.0f, w);
        vehicle_->setBrake(brake, w);
        vehicle_->setSteeringValue(w < 2 ? steering : 0.0f, w);
    }
}

void VehicleWorld::step(float dt) { world_->stepSimulation(dt, 1, dt); }

void VehicleWorld::teleport(const btTransform& pose) {
    chassis_->setWorldTransform(pose);
    chassis_->setInterpolationWorldTransform(pose);
    chassis_motion_->setWorldTransform(pose);
    chassis_->setLinearVelocity(btVector3(0, 0, 0));
    chassis_->setAngularVelocity(btVector3(0, 0, 0));
    chassis_->setInterpolationLinearVelocity(btVector3(0, 0, 0));
    chassis_->setInterpolationAngularVelocity(btVector3(0, 0, 0));
    chassis_->clearForces();
    world_->getBroadphase()->getOverlappingPairCache()->cleanProxyFromPairs(chassis_->getBroadphaseHandle(),
                                                                            dispatcher_.get());
    world_->updateSingleAabb(chassis_.get());
    vehicle_->resetSuspension();
}

btTransform VehicleWorld::chassis_pose() const { return chassis_->getWorldTransform(); }
btVector3 VehicleWorld::chassis_velocity() const { return chassis_->getLinearVelocity(); }
btVector3 VehicleWorld::chassis_angular_velocity() const { return chassis_->getAngularVelocity(); }

float VehicleWorld::forward_speed() const {
    const btVector3 forward = chassis_->getWorldTransform().getBasis().getColumn(2);
    return chassis_->getLinearVelocity().dot(forward);
}

int VehicleWorld::wheels_in_contact() const {
    int count = 0;
    for (int w = 0; w < vehicle_->getNumWheels(); ++w)
        count += vehicle_->getWheelInfo(w).m_raycastInfo.m_isInContact;
    return count;
}

int VehicleWorld::wheel_count() const { return vehicle_->getNumWheels(); }

// From the current chassis pose (Bullet's own wheel transforms date from the
// start of the last step, and refreshing them clears the contact flags).
btTransform VehicleWorld::wheel_pose(int wheel) const {
    const btWheelInfo& info = vehicle_->getWheelInfo(wheel);
    btTransform local;
    local.setIdentity();
    local.setOrigin(info.m_chassisConnectionPointCS +
                    info.m_wheelDirectionCS * info.m_raycastInfo.m_suspensionLength);
    local.setRotation(btQuaternion(btVector3(0, 1, 0), info.m_steering));
    return chassis_->getWorldTransform() * local;
}

}  // namespace vehicle_flag
