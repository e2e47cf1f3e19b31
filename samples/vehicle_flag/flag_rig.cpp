#include "flag_rig.h"

namespace vehicle_flag {

FlagRig::FlagRig(const FlagSettings& s, const VehicleLayout& vehicle, const btTransform& chassis_pose) {
    cloth_world_desc world_desc = cloth_default_world_desc();
    world_desc.worker_count = s.threads;
    if (!check(cloth_world_create(&world_desc, &world_), "cloth_world_create")) return;
    if (s.profile_tasks > 0 &&
        !check(cloth_world_set_profiling(world_, s.profile_tasks), "cloth_world_set_profiling"))
        return;

    // The flag in the chassis frame: its pole edge runs down the rear of the
    // pole from the top, and it streams backwards (-z), hanging in a vertical plane.
    const float gap = vehicle.pole_radius + 0.01f;
    const btVector3 top_local(vehicle.pole_base[0], vehicle.pole_base[1] + vehicle.pole_height,
                              vehicle.pole_base[2] - gap);
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
    if (!check(cloth_fabric_create_grid(world_, &grid, &fabric_), "cloth_fabric_create_grid")) return;

    cloth_desc desc = cloth_default_desc();
    desc.fabric = fabric_;
    desc.area_density = s.area_density;
    desc.structural.stiffness = s.stiffness;
    desc.shear.stiffness = 0.2f * s.stiffness;
    desc.bend.stiffness = 0.02f * s.stiffness;
    desc.solver = s.solver;
    if (!check(cloth_create(world_, &desc, &cloth_), "cloth_create")) return;
    particle_count_ = s.columns * s.rows;

    for (uint32_t r = 0; r < s.rows; ++r) {
        attached_.push_back(r * s.columns);
        attached_local_.push_back(top_local + btVector3(0, -s.height * r / (s.rows - 1), 0));
    }
    if (!check(cloth_pin(cloth_, attached_.data(), static_cast<uint32_t>(attached_.size())), "cloth_pin"))
        return;

    uint32_t triangle_count = 0;
    cloth_fabric_get_triangle_count(fabric_, &triangle_count);
    triangles_.resize(3 * triangle_count);
    if (!check(
            cloth_fabric_read_triangles(fabric_, triangles_.data(), static_cast<uint32_t>(triangles_.size())),
            "cloth_fabric_read_triangles"))
        return;
    positions_.resize(3 * particle_count_);
    normals_.resize(3 * particle_count_);
}

FlagRig::~FlagRig() {
    if (world_.index1) cloth_world_destroy(world_);
}

bool FlagRig::check(cloth_result result, const char* call) {
    if (result == CLOTH_OK) return true;
    error_ = std::string(call) + ": " + cloth_result_name(result) + " (" + cloth_get_last_error() + ")";
    return false;
}

void FlagRig::attached_targets(const btTransform& chassis_pose, std::vector<float>* out) const {
    out->resize(3 * attached_local_.size());
    for (size_t i = 0; i < attached_local_.size(); ++i) {
        const btVector3 p = chassis_pose * attached_local_[i];
        for (int k = 0; k < 3; ++k) (*out)[3 * i + k] = p[k];
    }
}

cloth_result FlagRig::teleport(const btTransform& from, const btTransform& to) {
    const btTransform delta = to * from.inverse();
    const std::vector<float>& current = positions();
    std::vector<uint32_t> all(particle_count_);
    std::vector<float> moved(3 * particle_count_);
    for (uint32_t i = 0; i < particle_count_; ++i) {
        all[i] = i;
        const btVector3 p = delta * btVector3(current[3 * i], current[3 * i + 1], current[3 * i + 2]);
        for (int k = 0; k < 3; ++k) moved[3 * i + k] = p[k];
    }
    return cloth_set_positions(cloth_, all.data(), moved.data(), particle_count_);
}

cloth_result FlagRig::follow(const btTransform& chassis_pose) {
    attached_targets(chassis_pose, &targets_);
    return cloth_set_pin_targets(cloth_, attached_.data(), targets_.data(),
                                 static_cast<uint32_t>(attached_.size()));
}

float FlagRig::attachment_error(const btTransform& chassis_pose) {
    attached_targets(chassis_pose, &targets_);
    const std::vector<float>& p = positions();
    float worst = 0.0f;
    for (size_t i = 0; i < attached_.size(); ++i) {
        const size_t a = 3 * size_t{attached_[i]};
        const btVector3 d(p[a] - targets_[3 * i], p[a + 1] - targets_[3 * i + 1],
                          p[a + 2] - targets_[3 * i + 2]);
        worst = std::max(worst, d.length());
    }
    return worst;
}

const std::vector<float>& FlagRig::positions() {
    cloth_read_positions(cloth_, positions_.data(), static_cast<uint32_t>(positions_.size()));
    return positions_;
}

const std::vector<float>& FlagRig::normals() {
    cloth_read_normals(cloth_, normals_.data(), static_cast<uint32_t>(normals_.size()));
    return normals_;
}

}  // namespace vehicle_flag
