#include "wardrobe.h"

#include <algorithm>
#include <cmath>

#include "body.h"

namespace character_cloth {

namespace {

constexpr float kPi = 3.14159265f;
constexpr uint32_t kCapeColumns = 25, kCapeRows = 60;    // 1,500 particles
constexpr uint32_t kSkirtAround = 40, kSkirtRings = 25;  // 1,000 particles

// The garment's cloth of `mass` kg from its fabric and rest positions,
// with its skin, max distances, backstops and carrier.
bool dress(cloth_world_id world, cloth_body_id root, cloth_fabric_id fabric, const std::vector<float>& rest,
           uint32_t influences, const std::vector<uint32_t>& joints, const std::vector<float>& weights,
           float mass, Garment* g, std::string* error) {
    auto fail = [&](const char* what) {
        *error = g->name + ": " + what + ": " + cloth_get_last_error();
        return false;
    };
    uint32_t triangles = 0;
    if (cloth_fabric_get_triangle_count(fabric, &triangles) != CLOTH_OK) return fail("triangle count");
    g->triangles.resize(3 * triangles);
    if (cloth_fabric_read_triangles(fabric, g->triangles.data(), 3 * triangles) != CLOTH_OK)
        return fail("triangles");
    g->rest = rest;
    cloth_desc desc = cloth_default_desc();
    desc.fabric = fabric;
    desc.initial_positions = rest.data();
    desc.particle_mass = g->particle_mass = mass / static_cast<float>(g->count);
    desc.structural.stiffness += g->stiffness_offset;
    if (cloth_create(world, &desc, &g->cloth) != CLOTH_OK) return fail("cloth_create");
    cloth_skin_desc skin = cloth_default_skin_desc();
    skin.particle_count = g->count;
    skin.joint_count = kJointCount;
    skin.influences = influences;
    skin.joints = joints.data();
    skin.weights = weights.data();
    if (cloth_set_skin(g->cloth, &skin) != CLOTH_OK) return fail("cloth_set_skin");
    if (cloth_set_max_distances(g->cloth, g->max_distance.data(), g->count) != CLOTH_OK)
        return fail("cloth_set_max_distances");
    if (cloth_set_backstops(g->cloth, g->back_distance.data(), g->back_radius.data(), g->count) != CLOTH_OK)
        return fail("cloth_set_backstops");
    cloth_collision_params collision = cloth_default_collision_params();
    collision.collider_mask = g->collider_mask;
    if (cloth_set_collision(g->cloth, &collision) != CLOTH_OK) return fail("cloth_set_collision");
    cloth_carrier_desc carrier = cloth_default_carrier_desc();
    carrier.teleport_distance = 2.0f;  // a frame's root move beyond 2 m is a teleport
    if (cloth_set_carrier(g->cloth, root, &carrier) != CLOTH_OK) return fail("cloth_set_carrier");
    // The strain check's pairs: neighbours along the triangles' edges.
    for (size_t t = 0; t < g->triangles.size(); t += 3) {
        for (int e = 0; e < 3; ++e) {
            const uint32_t a = g->triangles[t + e], b = g->triangles[t + (e + 1) % 3];
            if (a > b) continue;
            const float dx = rest[3 * a] - rest[3 * b], dy = rest[3 * a + 1] - rest[3 * b + 1],
                        dz = rest[3 * a + 2] - rest[3 * b + 2];
            g->structural.emplace_back(a, b);
            g->rest_length.push_back(std::sqrt(dx * dx + dy * dy + dz * dz));
        }
    }
    return true;
}

// Whether the triangles' winding normals point along `outward` on average.
bool faces(const std::vector<float>& x, const std::vector<uint32_t>& tri, const Eigen::Vector3f& centre) {
    float along = 0.0f;
    for (size_t t = 0; t < tri.size(); t += 3) {
        const Eigen::Vector3f a(&x[3 * tri[t]]), b(&x[3 * tri[t + 1]]), c(&x[3 * tri[t + 2]]);
        along += (b - a).cross(c - a).dot((a + b + c) / 3.0f - centre);
    }
    return along > 0.0f;
}

}  // namespace

std::vector<float> skinning_matrices(const Pose& pose) {
    static const Pose bind = Clip::bind_pose();
    std::vector<float> out;
    out.reserve(16 * kJointCount);
    for (uint32_t j = 0; j < kJointCount; ++j) {
        const Eigen::Matrix4f m = (pose.world[j] * bind.world[j].inverse()).matrix();
        out.insert(out.end(), m.data(), m.data() + 16);  // Eigen is column-major
    }
    return out;
}

bool make_cape(cloth_world_id world, cloth_body_id root, Garment* cape, std::string* error) {
    cape->name = "cape";
    cape->collider_mask = kTrunkAndLegs;
    cape->count = kCapeColumns * kCapeRows;
    // 0.24 m wide across the shoulder blades (clear of the arms' swing), 1 m long, a hand behind the
    // back and flaring out towards the hem. Its triangles' normals must
    // point away from the back (the backstop lies behind them): the grid
    // runs from the character's left to right seen from behind.
    cloth_grid_desc grid = cloth_default_grid_desc();
    grid.columns = kCapeColumns;
    grid.rows = kCapeRows;
    const float origin[3] = {-0.12f, 1.47f, -0.21f}, u[3] = {0.24f, 0.0f, 0.0f}, v[3] = {0.0f, -1.0f, -0.28f};
    std::copy(origin, origin + 3, grid.origin);
    std::copy(u, u + 3, grid.u);
    std::copy(v, v + 3, grid.v);
    cloth_fabric_id fabric{};
    if (cloth_fabric_create_grid(world, &grid, &fabric) != CLOTH_OK) {
        *error = std::string("cape fabric: ") + cloth_get_last_error();
        return false;
    }
    std::vector<float> rest(3 * cape->count);
    std::vector<uint32_t> joints(2 * cape->count);
    std::vector<float> weights(2 * cape->count);
    cape->max_distance.resize(cape->count);
    cape->back_distance.assign(cape->count, 0.0f);
    cape->back_radius.assign(cape->count, 0.0f);
    for (uint32_t r = 0; r < kCapeRows; ++r) {
        const float down = float(r) / float(kCapeRows - 1);
        for (uint32_t c = 0; c < kCapeColumns; ++c) {
            const uint32_t i = r * kCapeColumns + c;
            const float across = float(c) / float(kCapeColumns - 1);
            for (int k = 0; k < 3; ++k) rest[3 * i + k] = origin[k] + across * u[k] + down * v[k];
            // The shoulders hold the top row; the hem follows the hips more.
            joints[2 * i] = kChest;
            joints[2 * i + 1] = kPelvis;
            weights[2 * i] = 1.0f - 0.6f * down;
            weights[2 * i + 1] = 0.6f * down;
            if (r == 0) cape->top.push_back(i);
            if (r + 1 == kCapeRows) cape->hem.push_back(i);
            cape->max_distance[i] = r == 0 ? 0.0f : 0.02f + 0.5f * std::pow(down, 1.5f);
            if (r > 0) {
                cape->back_distance[i] = 0.3f;  // 1 cm of the way to the back allowed
                cape->back_radius[i] = 0.29f;
            }
        }
    }
    return dress(world, root, fabric, rest, 2, joints, weights, 0.8f, cape, error) &&
           (faces(rest, cape->triangles, Eigen::Vector3f(0.0f, 1.0f, 0.0f)) ||
            (*error = "cape: its normals face the back", false));
}

bool make_skirt(cloth_world_id world, cloth_body_id root, Garment* skirt, std::string* error) {
    skirt->name = "skirt";
    skirt->collider_mask = kTrunkAndLegs | kArms;
    skirt->count = kSkirtAround * kSkirtRings;
    // A cone from the waist (radius 0.2 m at 1 m) to the hem (0.4 m at
    // 0.62 m, above the knees), its seam welded: the ring's last vertex
    // joins its first.
    std::vector<float> rest(3 * skirt->count);
    std::vector<uint32_t> indices;
    std::vector<uint32_t> joints(3 * skirt->count);
    std::vector<float> weights(3 * skirt->count);
    skirt->max_distance.resize(skirt->count);
    skirt->back_distance.assign(skirt->count, 0.0f);
    skirt->back_radius.assign(skirt->count, 0.0f);
    for (uint32_t r = 0; r < kSkirtRings; ++r) {
        const float down = float(r) / float(kSkirtRings - 1);
        const float radius = 0.2f + 0.2f * down, y = 1.0f - 0.38f * down;
        for (uint32_t a = 0; a < kSkirtAround; ++a) {
            const uint32_t i = r * kSkirtAround + a;
            const float angle = 2.0f * kPi * float(a) / float(kSkirtAround);
            rest[3 * i] = radius * std::sin(angle);
            rest[3 * i + 1] = y;
            rest[3 * i + 2] = radius * std::cos(angle);
            // The waist holds the top ring; lower down the thighs take a
            // little, each the more the nearer its side (continuous across
            // the front and back, where both take half): the legs push the
            // skirt through their colliders, the skin only leans it.
            const float left = 0.5f * (1.0f + std::sin(angle));
            joints[3 * i] = kPelvis;
            joints[3 * i + 1] = kLeftThigh;
            joints[3 * i + 2] = kRightThigh;
            weights[3 * i] = 1.0f - 0.3f * down;
            weights[3 * i + 1] = 0.3f * down * left;
            weights[3 * i + 2] = 0.3f * down * (1.0f - left);
            skirt->max_distance[i] = r == 0 ? 0.0f : 0.05f + 0.45f * down;
            if (r > 0) {
                skirt->back_distance[i] = 0.12f;  // 2 cm inwards allowed
                skirt->back_radius[i] = 0.1f;
            }
            if (r + 1 < kSkirtRings) {
                const uint32_t i1 = r * kSkirtAround + (a + 1) % kSkirtAround;
                const uint32_t j0 = i + kSkirtAround, j1 = i1 + kSkirtAround;
                indices.insert(indices.end(), {i, i1, j0, i1, j1, j0});
            }
        }
    }
    if (!faces(rest, indices, Eigen::Vector3f(0.0f, 0.7f, 0.0f))) {
        for (size_t t = 0; t < indices.size(); t += 3) std::swap(indices[t + 1], indices[t + 2]);
    }
    cloth_mesh_desc mesh = cloth_default_mesh_desc();
    mesh.positions = rest.data();
    mesh.vertex_count = skirt->count;
    mesh.indices = indices.data();
    mesh.triangle_count = static_cast<uint32_t>(indices.size() / 3);
    cloth_fabric_id fabric{};
    if (cloth_fabric_create_mesh(world, &mesh, &fabric) != CLOTH_OK) {
        *error = std::string("skirt fabric: ") + cloth_get_last_error();
        return false;
    }
    return dress(world, root, fabric, rest, 3, joints, weights, 0.6f, skirt, error);
}

}  // namespace character_cloth
