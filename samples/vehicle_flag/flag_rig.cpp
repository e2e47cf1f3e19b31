#include "flag_rig.h"

#include <algorithm>
#include <cmath>

namespace vehicle_flag {

FlagRig::FlagRig(const FlagSettings& s, VehicleWorld& vehicle) : vehicle_(vehicle) {
    cloth_world_desc world_desc = cloth_default_world_desc();
    world_desc.worker_count = s.threads;
    if (!check(cloth_world_create(&world_desc, &world_), "cloth_world_create")) return;
    if (s.profile_tasks > 0 &&
        !check(cloth_world_set_profiling(world_, s.profile_tasks), "cloth_world_set_profiling"))
        return;
    if (!create_colliders()) return;

    // The flag in the chassis frame: its pole edge runs down the rear of the
    // pole from the top, one thickness clear of the capsule, and it streams
    // backwards (-z), hanging in a vertical plane.
    const VehicleLayout& layout = vehicle.layout();
    const float gap = layout.pole_radius + s.thickness;
    const btVector3 top_local(layout.pole_base[0], layout.pole_base[1] + layout.pole_height,
                              layout.pole_base[2] - gap);
    if (!create_cloth(s, vehicle.chassis_pose(), top_local)) return;

    // The pole-side column rides on the chassis body at these offsets.
    for (uint32_t r = 0; r < s.rows; ++r) {
        attached_.push_back(r * s.columns);
        attached_local_.push_back(top_local + btVector3(0, -s.height * r / (s.rows - 1), 0));
    }
    std::vector<float> offsets;
    for (const btVector3& p : attached_local_) offsets.insert(offsets.end(), {p.x(), p.y(), p.z()});
    if (!check(cloth_attach(cloth_, chassis_body_, attached_.data(), offsets.data(),
                            static_cast<uint32_t>(attached_.size())),
               "cloth_attach"))
        return;

    // The chassis carries the flag: physical inertia while driving (1), but a
    // jump of more than teleport_distance in one frame moves the flag with it.
    cloth_carrier_desc carrier = cloth_default_carrier_desc();
    carrier.teleport_distance = s.teleport_distance;
    carrier.teleport_mode = CLOTH_TELEPORT_MOVE;
    if (!check(cloth_set_carrier(cloth_, chassis_body_, &carrier), "cloth_set_carrier")) return;
}

FlagRig::~FlagRig() {
    mirror_.reset();  // its bodies and colliders go before the world
    if (world_.index1) cloth_world_destroy(world_);
}

bool FlagRig::check(cloth_result result, const char* call) {
    if (result == CLOTH_OK) return true;
    error_ = std::string(call) + ": " + cloth_result_name(result) + " (" + cloth_get_last_error() + ")";
    return false;
}

bool FlagRig::create_colliders() {
    // The chassis: a body mirrored from the btRigidBody, with a collider for
    // each child of its compound (the box and the pole capsule).
    mirror_ = std::make_unique<cloth_bullet::BodyMirror>(world_);
    if (mirror_->add(vehicle_.chassis_body(), 1u, &chassis_body_) != CLOTH_OK) {
        error_ = "mirroring the chassis: " + mirror_->last_error();
        return false;
    }
    collider_count_ = mirror_->colliders(vehicle_.chassis_body()).size();

    // The terrain never moves: a static collider at the terrain object's pose.
    const btCollisionObject* terrain = vehicle_.terrain_object();
    std::vector<cloth_bullet::ColliderSpec> specs;
    std::string message;
    if (!cloth_bullet::describe_shape(*terrain->getCollisionShape(), terrain->getWorldTransform(), &specs,
                                      &message)) {
        error_ = "terrain: " + message;
        return false;
    }
    for (const cloth_bullet::ColliderSpec& spec : specs) {
        cloth_collider_id collider{};
        if (!check(cloth_bullet::create_collider(world_, spec, cloth_body_id{}, 1u, &collider),
                   "terrain collider"))
            return false;
        ++collider_count_;
    }
    return true;
}

bool FlagRig::create_cloth(const FlagSettings& s, const btTransform& chassis_pose,
                           const btVector3& top_local) {
    const btVector3 top = chassis_pose * top_local;
    const btVector3 u = chassis_pose.getBasis() * btVector3(0, 0, -s.width);
    const btVector3 v = chassis_pose.getBasis() * btVector3(0, -s.height, 0);
    cloth_grid_desc grid = cloth_default_grid_desc();
    grid.columns = s.columns;
    grid.rows = s.rows;
    for (int k = 0; k < 3; ++k) {
        grid.origin[k] = top[k];
        grid.u[k] = u[k];
        grid.v[k] = v[k];
    }
    if (!check(cloth_fabric_create_grid(world_, &grid, &fabric_), "cloth_fabric_create_grid")) return false;

    cloth_desc desc = cloth_default_desc();
    desc.fabric = fabric_;
    desc.area_density = s.area_density;
    desc.structural.stiffness = s.stiffness;
    desc.shear.stiffness = 0.2f * s.stiffness;
    desc.bend.stiffness = 0.02f * s.stiffness;
    desc.structural.damping = s.damping;
    desc.shear.damping = 0.4f * s.damping;
    desc.bend.damping = 0.1f * s.damping;
    desc.solver = s.solver;
    if (!check(cloth_create(world_, &desc, &cloth_), "cloth_create")) return false;
    particle_count_ = s.columns * s.rows;

    cloth_collision_params collision = cloth_default_collision_params();
    collision.thickness = s.thickness;
    collision.friction = s.friction;
    if (!check(cloth_set_collision(cloth_, &collision), "cloth_set_collision")) return false;
    cloth_strain_limit limit = cloth_default_strain_limit();
    limit.max_strain = s.max_strain;  // 0: off, for the default solver too
    if (!check(cloth_set_strain_limit(cloth_, &limit), "cloth_set_strain_limit")) return false;

    uint32_t triangle_count = 0;
    cloth_fabric_get_triangle_count(fabric_, &triangle_count);
    triangles_.resize(3 * triangle_count);
    if (!check(
            cloth_fabric_read_triangles(fabric_, triangles_.data(), static_cast<uint32_t>(triangles_.size())),
            "cloth_fabric_read_triangles"))
        return false;
    positions_.resize(3 * particle_count_);
    normals_.resize(3 * particle_count_);
    return true;
}

const double* FlagRig::origin() const { return mirror_->origin(); }

bool FlagRig::follow_chassis() {
    constexpr double kStep = 32.0;
    const btVector3 p = vehicle_.chassis_pose().getOrigin();
    const double* origin = mirror_->origin();
    bool far = false;
    for (int k = 0; k < 3; ++k) far = far || std::abs(double{p[k]} - origin[k]) > kStep;
    if (!far) return true;
    btVector3 shift;
    for (int k = 0; k < 3; ++k) shift[k] = static_cast<float>(std::round(p[k] / kStep) * kStep - origin[k]);
    if (mirror_->shift_origin(shift) == CLOTH_OK) return true;
    error_ = "origin shift: " + mirror_->last_error();
    return false;
}

cloth_result FlagRig::teleport_chassis() {
    // First bring the origin to where the chassis lands, so the flag is
    // moved there in well-resolved coordinates.
    if (!follow_chassis()) return CLOTH_ERROR_INVALID_VALUE;
    const cloth_result result = mirror_->teleport(vehicle_.chassis_body());
    if (result != CLOTH_OK) error_ = "teleport: " + mirror_->last_error();
    return result;
}

cloth_result FlagRig::sync() {
    if (!follow_chassis()) return CLOTH_ERROR_INVALID_VALUE;
    const cloth_result result = mirror_->sync();
    if (result != CLOTH_OK) error_ = "sync: " + mirror_->last_error();
    return result;
}

double FlagRig::attachment_error(const btTransform& chassis_pose) {
    // In double: Bullet's own float product (chassis_pose * offset) rounds
    // to 3e-5 m 256 m out, more than the error measured here.
    const std::vector<float>& p = local_positions();
    const double* origin = mirror_->origin();
    double worst = 0;
    for (size_t i = 0; i < attached_.size(); ++i) {
        const size_t a = 3 * size_t{attached_[i]};
        double d2 = 0;
        for (int k = 0; k < 3; ++k) {
            const btVector3& row = chassis_pose.getBasis()[k];
            double target = chassis_pose.getOrigin()[k];
            for (int j = 0; j < 3; ++j) target += double{row[j]} * double{attached_local_[i][j]};
            const double d = double{p[a + k]} + origin[k] - target;
            d2 += d * d;
        }
        worst = std::max(worst, std::sqrt(d2));
    }
    return worst;
}

bool FlagRig::teleported() const {
    bool fired = false;
    cloth_get_teleported(cloth_, &fired);
    return fired;
}

const std::vector<float>& FlagRig::local_positions() {
    cloth_read_positions(cloth_, positions_.data(), static_cast<uint32_t>(positions_.size()));
    return positions_;
}

const std::vector<float>& FlagRig::positions() {
    local_positions();
    const double* origin = mirror_->origin();
    for (size_t i = 0; i < positions_.size(); ++i) {
        positions_[i] = static_cast<float>(double{positions_[i]} + origin[i % 3]);
    }
    return positions_;
}

const std::vector<float>& FlagRig::normals() {
    cloth_read_normals(cloth_, normals_.data(), static_cast<uint32_t>(normals_.size()));
    return normals_;
}

}  // namespace vehicle_flag
