// Character cloth through the C API: linear blend skinning against a
// reference computed here, a max distance of 0 as a pin, the max-distance
// and backstop promises under a fast skeleton, the same bits for any
// worker count with the skin on, and snapshots of a skinned cloth.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "cloth/cloth.h"

namespace {

constexpr float kFrame = 1.0f / 60.0f;

// A column-major 4x4 matrix: rotation by `angle` about the unit `axis`,
// uniform `scale`, then translation `t`.
std::vector<float> joint_matrix(const double axis[3], double angle, double scale, const double t[3]) {
    const double c = std::cos(angle), s = std::sin(angle), k = 1.0 - c;
    const double x = axis[0], y = axis[1], z = axis[2];
    const double r[3][3] = {{c + x * x * k, x * y * k - z * s, x * z * k + y * s},
                            {y * x * k + z * s, c + y * y * k, y * z * k - x * s},
                            {z * x * k - y * s, z * y * k + x * s, c + z * z * k}};
    std::vector<float> m(16, 0.0f);
    for (int row = 0; row < 3; ++row) {
        for (int col = 0; col < 3; ++col) m[4 * col + row] = static_cast<float>(scale * r[row][col]);
        m[12 + row] = static_cast<float>(t[row]);
    }
    m[15] = 1.0f;
    return m;
}

// A side x side cloth hanging in the x-y plane (1 m), skinned to two
// joints: joint 0 holds the top rows, the weights move to joint 1 down the
// cloth.
struct SkinnedScene {
    static constexpr uint32_t kJoints = 2;
    uint32_t side = 16, count = 256;
    cloth_world_id world{};
    cloth_id cloth{};
    std::vector<uint32_t> joints;
    std::vector<float> weights;

    SkinnedScene(uint32_t side_, uint32_t workers) : side(side_), count(side_ * side_) {
        cloth_world_desc wd = cloth_default_world_desc();
        wd.worker_count = workers;
        EXPECT_EQ(cloth_world_create(&wd, &world), CLOTH_OK);
        cloth_grid_desc grid = cloth_default_grid_desc();
        grid.columns = grid.rows = side;
        cloth_fabric_id fabric{};
        EXPECT_EQ(cloth_fabric_create_grid(world, &grid, &fabric), CLOTH_OK);
        cloth_desc desc = cloth_default_desc();
        desc.fabric = fabric;
        EXPECT_EQ(cloth_create(world, &desc, &cloth), CLOTH_OK);
        for (uint32_t v = 0; v < count; ++v) {
            const float down = static_cast<float>(v / side) / static_cast<float>(side - 1);
            joints.push_back(0);
            joints.push_back(1);
            weights.push_back(1.0f - down);
            weights.push_back(down);
        }
        cloth_skin_desc skin = cloth_default_skin_desc();
        skin.particle_count = count;
        skin.joint_count = kJoints;
        skin.influences = 2;
        skin.joints = joints.data();
        skin.weights = weights.data();
        EXPECT_EQ(cloth_set_skin(cloth, &skin), CLOTH_OK);
    }
    ~SkinnedScene() { cloth_world_destroy(world); }

    // The clip at frame f: the body turns about y at 4 rad/s and runs along
    // x at 5 m/s; joint 1 (the lower cloth) swings about x besides.
    // `rigid`: joint 1 follows joint 0, so the skin moves as one body;
    // `turn`: the body's turn, rad/s.
    void pose(int f, bool rigid = false, double turn = 4.0) {
        const double t = f * static_cast<double>(kFrame);
        const double up[3] = {0, 1, 0}, side_axis[3] = {1, 0, 0};
        const double at[3] = {5.0 * t, 0.0, 0.0};
        std::vector<float> m = joint_matrix(up, turn * t, 1.0, at);
        const std::vector<float> m1 = rigid ? m : joint_matrix(side_axis, 0.8 * std::sin(6.0 * t), 1.0, at);
        m.insert(m.end(), m1.begin(), m1.end());
        ASSERT_EQ(cloth_set_joint_matrices(cloth, m.data(), kJoints, CLOTH_MATRIX_COLUMN_MAJOR_4X4),
                  CLOTH_OK);
    }
    std::vector<float> read(cloth_result (*f)(cloth_id, float*, uint32_t)) const {
        std::vector<float> out(3 * count);
        EXPECT_EQ(f(cloth, out.data(), 3 * count), CLOTH_OK);
        return out;
    }
};

float distance(const float* a, const float* b) {
    return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                     (a[2] - b[2]) * (a[2] - b[2]));
}

// Skinned positions are sum_k w_k M_k (b, 1) of the rest position b, and
// normals the unit sum_k w_k R_k n_b: to a micrometre of a double-precision
// reference, with three joints, three influences and a scaled joint, in
// either matrix layout.
TEST(Skin, LinearBlendSkinningMatchesAReferenceWithinAMicrometre) {
    for (cloth_matrix_layout layout : {CLOTH_MATRIX_COLUMN_MAJOR_4X4, CLOTH_MATRIX_ROW_MAJOR_3X4}) {
        cloth_world_desc wd = cloth_default_world_desc();
        cloth_world_id world{};
        ASSERT_EQ(cloth_world_create(&wd, &world), CLOTH_OK);
        cloth_grid_desc grid = cloth_default_grid_desc();
        grid.columns = grid.rows = 8;
        cloth_fabric_id fabric{};
        ASSERT_EQ(cloth_fabric_create_grid(world, &grid, &fabric), CLOTH_OK);
        cloth_desc desc = cloth_default_desc();
        desc.fabric = fabric;
        cloth_id cloth{};
        ASSERT_EQ(cloth_create(world, &desc, &cloth), CLOTH_OK);
        const uint32_t n = 64;
        std::vector<float> rest(3 * n), rest_normals(3 * n);
        ASSERT_EQ(cloth_read_positions(cloth, rest.data(), 3 * n), CLOTH_OK);
        ASSERT_EQ(cloth_read_normals(cloth, rest_normals.data(), 3 * n), CLOTH_OK);
        std::vector<uint32_t> joints;
        std::vector<float> weights;
        for (uint32_t v = 0; v < n; ++v) {
            const float a = 0.2f + 0.6f * static_cast<float>(v % 8) / 7.0f;
            const float b = 0.5f * (1.0f - a) * static_cast<float>(v / 8) / 7.0f;
            joints.insert(joints.end(), {v % 3, (v + 1) % 3, (v + 2) % 3});
            weights.insert(weights.end(), {a, b, 1.0f - a - b});
        }
        cloth_skin_desc skin = cloth_default_skin_desc();
        skin.particle_count = n;
        skin.joint_count = 3;
        skin.influences = 3;
        skin.joints = joints.data();
        skin.weights = weights.data();
        ASSERT_EQ(cloth_set_skin(cloth, &skin), CLOTH_OK);
        const double axes[3][3] = {{0, 1, 0}, {0.6, 0, 0.8}, {0, 0, 1}};
        const double angles[3] = {0.7, -1.9, 2.5}, scales[3] = {1.0, 1.0, 1.5};
        const double moves[3][3] = {{1, 2, 3}, {-0.5, 0.25, 4}, {0.1, -3, 0.2}};
        std::vector<std::vector<float>> m;
        std::vector<float> given;
        for (int j = 0; j < 3; ++j) {
            m.push_back(joint_matrix(axes[j], angles[j], scales[j], moves[j]));
            for (int r = 0; r < 3 && layout == CLOTH_MATRIX_ROW_MAJOR_3X4; ++r) {
                for (int c = 0; c < 4; ++c) given.push_back(m[j][4 * c + r]);
            }
            if (layout == CLOTH_MATRIX_COLUMN_MAJOR_4X4) given.insert(given.end(), m[j].begin(), m[j].end());
        }
        ASSERT_EQ(cloth_set_joint_matrices(cloth, given.data(), 3, layout), CLOTH_OK);
        ASSERT_EQ(cloth_step(world, kFrame), CLOTH_OK);
        std::vector<float> x(3 * n), normals(3 * n);
        ASSERT_EQ(cloth_read_skinned_positions(cloth, x.data(), normals.data(), 3 * n), CLOTH_OK);
        for (uint32_t v = 0; v < n; ++v) {
            double p[3] = {0, 0, 0}, q[3] = {0, 0, 0};
            for (int k = 0; k < 3; ++k) {
                const std::vector<float>& mj = m[joints[3 * v + k]];
                const double w = weights[3 * v + k];
                for (int r = 0; r < 3; ++r) {
                    double pr = mj[12 + r], qr = 0;
                    for (int c = 0; c < 3; ++c) {
                        pr += double(mj[4 * c + r]) * rest[3 * v + c];
                        qr += double(mj[4 * c + r]) * rest_normals[3 * v + c];
                    }
                    p[r] += w * pr;
                    q[r] += w * qr;
                }
            }
            const double length = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
            for (int r = 0; r < 3; ++r) {
                EXPECT_NEAR(x[3 * v + r], p[r], 1e-6) << "vertex " << v << ", layout " << layout;
                EXPECT_NEAR(normals[3 * v + r], q[r] / length, 1e-5)
                    << "vertex " << v << ", layout " << layout;
            }
        }
        cloth_world_destroy(world);
    }
}

// A particle with a max distance of 0 is a pin whose target is its skinned
// position: the same cloth with those particles pinned by cloth_pin and
// given the skinned positions as targets ends every frame bit-identical.
TEST(Skin, AMaxDistanceOfZeroIsAPinBitForBit) {
    SkinnedScene skinned(12, 1), pinned(12, 1);
    const uint32_t side = 12;
    std::vector<float> reach(side * side, INFINITY);
    std::vector<uint32_t> top;
    for (uint32_t c = 0; c < side; ++c) {
        reach[c] = 0.0f;
        top.push_back(c);
    }
    ASSERT_EQ(cloth_set_max_distances(skinned.cloth, reach.data(), side * side), CLOTH_OK);
    ASSERT_EQ(cloth_pin(pinned.cloth, top.data(), side), CLOTH_OK);
    bool pin = false;
    ASSERT_EQ(cloth_is_pinned(skinned.cloth, 3, &pin), CLOTH_OK);
    EXPECT_TRUE(pin) << "a max distance of 0 pins";
    const float elsewhere[3] = {0, 0, 0};
    EXPECT_EQ(cloth_set_pin_targets(skinned.cloth, top.data(), elsewhere, 1), CLOTH_ERROR_INVALID_VALUE)
        << "the skin sets its pins' targets";
    for (int f = 0; f < 60; ++f) {
        skinned.pose(f);
        ASSERT_EQ(cloth_step(skinned.world, kFrame), CLOTH_OK);
        std::vector<float> s(3 * side * side), targets;
        ASSERT_EQ(cloth_read_skinned_positions(skinned.cloth, s.data(), nullptr, 3 * side * side), CLOTH_OK);
        targets.assign(s.begin(), s.begin() + 3 * side);
        ASSERT_EQ(cloth_set_pin_targets(pinned.cloth, top.data(), targets.data(), side), CLOTH_OK);
        ASSERT_EQ(cloth_step(pinned.world, kFrame), CLOTH_OK);
        const std::vector<float> a = skinned.read(cloth_read_positions),
                                 b = pinned.read(cloth_read_positions);
        ASSERT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)), 0) << "frame " << f;
        for (uint32_t c = 0; c < side; ++c) ASSERT_LT(distance(&a[3 * c], &s[3 * c]), 1e-5f) << "pin " << c;
    }
}

// Under a skeleton that runs at 5 m/s and turns at 4 rad/s, every free
// particle ends every step within its max distance of its skinned position
// and outside its backstop sphere; the constraints are at work (particles
// end on their spheres).
TEST(Skin, MaxDistanceAndBackstopHoldAfterEveryStepUnderAFastSkeleton) {
    SkinnedScene scene(16, 2);
    const uint32_t n = scene.count;
    std::vector<float> reach(n), back_distance(n, 0.05f), back_radius(n, 0.04f);
    for (uint32_t v = 0; v < n; ++v)
        reach[v] = 0.1f * static_cast<float>(v / 16) / 15.0f;  // 0 on the top row
    ASSERT_EQ(cloth_set_max_distances(scene.cloth, reach.data(), n), CLOTH_OK);
    ASSERT_EQ(cloth_set_backstops(scene.cloth, back_distance.data(), back_radius.data(), n), CLOTH_OK);
    uint32_t on_max_distance = 0, on_backstop = 0;
    for (int f = 0; f < 120; ++f) {
        scene.pose(f);
        ASSERT_EQ(cloth_step(scene.world, kFrame), CLOTH_OK) << "frame " << f;
        const std::vector<float> x = scene.read(cloth_read_positions);
        std::vector<float> s(3 * n), normal(3 * n);
        ASSERT_EQ(cloth_read_skinned_positions(scene.cloth, s.data(), normal.data(), 3 * n), CLOTH_OK);
        for (uint32_t v = 16; v < n; ++v) {
            const float d = distance(&x[3 * v], &s[3 * v]);
            EXPECT_LE(d, reach[v] + 1e-5f) << "frame " << f << ", vertex " << v;
            const float centre[3] = {s[3 * v] - 0.05f * normal[3 * v],
                                     s[3 * v + 1] - 0.05f * normal[3 * v + 1],
                                     s[3 * v + 2] - 0.05f * normal[3 * v + 2]};
            const float out = distance(&x[3 * v], centre);
            EXPECT_GE(out, 0.04f - 1e-5f) << "frame " << f << ", vertex " << v;
            on_max_distance += d > reach[v] - 1e-4f;
            on_backstop += out < 0.04f + 1e-4f;
        }
    }
    EXPECT_GT(on_max_distance, 100u);
    EXPECT_GT(on_backstop, 10u);
}

// A cape's constraints (max distance growing to 0.5 m at the hem, a
// backstop sphere of 0.29 m 0.3 m behind the skinned position) on a 32x32
// cloth whose skin turns at 8 rad/s as one body: the skin's constraints
// run after each of the strain limiter's passes, so the limiter works
// where they hold the particles. Run only after its last pass they undid
// it: neighbours ended on different parts of their backstop spheres and
// the springs between them stretched 12-fold. The passes still do not
// reach the limit here (0.28, 0.16 with four times the passes:
// docs/character_cloth.md); the bound checks the order.
TEST(Skin, ItsConstraintsBetweenTheStrainLimitersPassesKeepAFastTurnFromStretchingTheCloth) {
    SkinnedScene scene(32, 2);
    const uint32_t n = scene.count;
    std::vector<float> reach(n), back_distance(n, 0.3f), back_radius(n, 0.29f);
    for (uint32_t v = 0; v < n; ++v) reach[v] = 0.5f * static_cast<float>(v / 32) / 31.0f;
    ASSERT_EQ(cloth_set_max_distances(scene.cloth, reach.data(), n), CLOTH_OK);
    ASSERT_EQ(cloth_set_backstops(scene.cloth, back_distance.data(), back_radius.data(), n), CLOTH_OK);
    float worst = 0;
    for (int f = 0; f < 240; ++f) {
        scene.pose(f, true, 8.0);
        ASSERT_EQ(cloth_step(scene.world, kFrame), CLOTH_OK) << "frame " << f;
        cloth_stats stats{};
        stats.struct_size = sizeof stats;
        ASSERT_EQ(cloth_get_stats(scene.cloth, &stats), CLOTH_OK);
        worst = std::max(worst, stats.max_strain);
    }
    EXPECT_LT(worst, 0.5f);
}

// A character teleported 20 m: its root body is the cloth's carrier, so
// the jump is a carrier teleport, and the skin jumps with it rather than
// dragging the particles pinned to it across 20 m within the frame's
// substeps. From the jump's frame on the jumped cloth keeps its max
// distances, stretches and moves no more than its twin that did not jump,
// and a second later hangs as the twin does, 20 m away.
TEST(Skin, ACarrierTeleportJumpsTheSkinAndTheClothWithIt) {
    SkinnedScene jumped(16, 1), twin(16, 1);
    const uint32_t n = jumped.count;
    std::vector<float> reach(n);
    for (uint32_t v = 0; v < n; ++v) reach[v] = 0.3f * static_cast<float>(v / 16) / 15.0f;  // top row 0
    cloth_body_id body[2]{};
    SkinnedScene* scenes[2] = {&jumped, &twin};
    for (int k = 0; k < 2; ++k) {
        ASSERT_EQ(cloth_set_max_distances(scenes[k]->cloth, reach.data(), n), CLOTH_OK);
        cloth_body_desc bd = cloth_default_body_desc();
        ASSERT_EQ(cloth_body_create(scenes[k]->world, &bd, &body[k]), CLOTH_OK);
        cloth_carrier_desc carrier = cloth_default_carrier_desc();
        carrier.teleport_distance = 1.0f;
        ASSERT_EQ(cloth_set_carrier(scenes[k]->cloth, body[k], &carrier), CLOTH_OK);
    }
    const float jump = 20.0f;
    auto frame = [&](int f, int k, float shift) {
        std::vector<float> m(32);
        scenes[k]->pose(f);  // then the same matrices moved by `shift` along z
        const double t = f * static_cast<double>(kFrame);
        const double up[3] = {0, 1, 0}, side_axis[3] = {1, 0, 0};
        const double at[3] = {5.0 * t, 0.0, shift};
        std::vector<float> m0 = joint_matrix(up, 4.0 * t, 1.0, at);
        const std::vector<float> m1 = joint_matrix(side_axis, 0.8 * std::sin(6.0 * t), 1.0, at);
        m0.insert(m0.end(), m1.begin(), m1.end());
        ASSERT_EQ(cloth_set_joint_matrices(scenes[k]->cloth, m0.data(), 2, CLOTH_MATRIX_COLUMN_MAJOR_4X4),
                  CLOTH_OK);
        const float position[3] = {static_cast<float>(at[0]), 0.0f, static_cast<float>(at[2])};
        const float rotation[4] = {0.0f, static_cast<float>(std::sin(2.0 * t)), 0.0f,
                                   static_cast<float>(std::cos(2.0 * t))};
        ASSERT_EQ(cloth_body_set_pose(body[k], position, rotation), CLOTH_OK);
        ASSERT_EQ(cloth_step(scenes[k]->world, kFrame), CLOTH_OK);
    };
    auto stats = [](cloth_id cloth) {
        cloth_stats s{};
        s.struct_size = sizeof s;
        EXPECT_EQ(cloth_get_stats(cloth, &s), CLOTH_OK);
        return s;
    };
    for (int f = 0; f < 60; ++f) {
        frame(f, 0, 0.0f);
        frame(f, 1, 0.0f);
    }
    for (int f = 60; f < 120; ++f) {
        frame(f, 0, jump);
        frame(f, 1, 0.0f);
        const cloth_stats a = stats(jumped.cloth), b = stats(twin.cloth);
        // This fast skeleton stretches the skin itself to about 0.75 (its
        // constraints win over the strain limit), and in single frames one
        // cloth of the pair runs up to 0.21 past the other (over jumps of 3
        // to 30 m): the jumped cloth stretches as its twin does, within that.
        EXPECT_LE(a.max_strain, b.max_strain + 0.25f) << "frame " << f;
        EXPECT_LT(a.max_speed, 2.0f * b.max_speed + 1.0f) << "frame " << f;
        const std::vector<float> x = jumped.read(cloth_read_positions);
        std::vector<float> s(3 * n), normal(3 * n);
        ASSERT_EQ(cloth_read_skinned_positions(jumped.cloth, s.data(), normal.data(), 3 * n), CLOTH_OK);
        for (uint32_t v = 0; v < n; ++v)
            ASSERT_LE(distance(&x[3 * v], &s[3 * v]), reach[v] + 1e-4f) << "frame " << f << ", vertex " << v;
        if (f == 60) {
            bool teleported = false;
            ASSERT_EQ(cloth_get_teleported(jumped.cloth, &teleported), CLOTH_OK);
            EXPECT_TRUE(teleported) << "the carrier saw the jump";
        }
    }
    const std::vector<float> a = jumped.read(cloth_read_positions), b = twin.read(cloth_read_positions);
    float farthest = 0.0f;
    for (uint32_t v = 0; v < n; ++v) {
        const float moved[3] = {b[3 * v], b[3 * v + 1], b[3 * v + 2] + jump};
        farthest = std::max(farthest, distance(&a[3 * v], moved));
    }
    // The cloths differ by the rounding of positions 20 m apart, which
    // this fast skeleton grows: over jumps of 3 to 30 m the farthest
    // particle ends 0.08-0.19 m from the twin's.
    EXPECT_LT(farthest, 0.25f) << "a second after the jump the cloth hangs as its twin does";
}

// The skin's stages are per particle: a skinned cloth with max distances
// and backstops ends bit-identical on 1, 2 and 4 workers.
TEST(Determinism, ASkinnedClothIsBitIdenticalForAnyWorkerCount) {
    std::vector<float> first;
    for (uint32_t workers : {1u, 2u, 4u}) {
        SkinnedScene scene(24, workers);
        const uint32_t n = scene.count;
        std::vector<float> reach(n), back_distance(n, 0.05f), back_radius(n, 0.04f);
        for (uint32_t v = 0; v < n; ++v) reach[v] = 0.1f * static_cast<float>(v / 24) / 23.0f;
        ASSERT_EQ(cloth_set_max_distances(scene.cloth, reach.data(), n), CLOTH_OK);
        ASSERT_EQ(cloth_set_backstops(scene.cloth, back_distance.data(), back_radius.data(), n), CLOTH_OK);
        for (int f = 0; f < 40; ++f) {
            scene.pose(f);
            ASSERT_EQ(cloth_step(scene.world, kFrame), CLOTH_OK);
        }
        const std::vector<float> x = scene.read(cloth_read_positions);
        if (first.empty()) {
            first = x;
            EXPECT_GT(std::fabs(x[3 * (n - 1)]), 0.5f) << "the cloth moved with its skeleton";
        } else {
            EXPECT_EQ(std::memcmp(first.data(), x.data(), x.size() * sizeof(float)), 0)
                << workers << " workers";
        }
    }
}

// The skin's constraints of the determinism test above, on every particle
// below the top row.
void constrain(const SkinnedScene& scene) {
    const uint32_t n = scene.count;
    std::vector<float> reach(n), back_distance(n, 0.05f), back_radius(n, 0.04f);
    for (uint32_t v = 0; v < n; ++v)
        reach[v] = 0.1f * static_cast<float>(v / scene.side) / (scene.side - 1.0f);
    ASSERT_EQ(cloth_set_max_distances(scene.cloth, reach.data(), n), CLOTH_OK);
    ASSERT_EQ(cloth_set_backstops(scene.cloth, back_distance.data(), back_radius.data(), n), CLOTH_OK);
}

// The host's own skin at frame f: the rest grid (1 m, in the x-y plane,
// top row at y = 0) carried along x at 5 m/s and swung in z, normals +z.
void host_skin(SkinnedScene& scene, int f) {
    const float t = static_cast<float>(f) * kFrame;
    std::vector<float> x(3 * scene.count), normals(3 * scene.count, 0.0f);
    for (uint32_t v = 0; v < scene.count; ++v) {
        const float col = static_cast<float>(v % scene.side) / (scene.side - 1.0f);
        const float down = static_cast<float>(v / scene.side) / (scene.side - 1.0f);
        x[3 * v] = col + 5.0f * t;
        x[3 * v + 1] = -down;
        x[3 * v + 2] = 0.3f * down * std::sin(6.0f * t);
        normals[3 * v + 2] = 1.0f;
    }
    ASSERT_EQ(cloth_set_skinned_positions(scene.cloth, x.data(), normals.data(), scene.count), CLOTH_OK);
}

// A snapshot of a skinned cloth holds where its skin ended the last frame
// (the next frame moves the skin from there) and what the host gave it
// last: a cloth restored from it steps as the original did, bit for bit,
// whichever skin it followed before (here, another clip).
TEST(SkinSnapshot, ARestoredSkinnedClothStepsAsTheOriginalDid) {
    for (bool from_host : {false, true}) {
        SCOPED_TRACE(from_host ? "the host's skinned positions" : "joint matrices");
        const auto drive = [&](SkinnedScene& scene, int f) {
            if (from_host) {
                host_skin(scene, f);
            } else {
                scene.pose(f);
            }
        };
        SkinnedScene original(16, 1), restored(16, 1);
        constrain(original);
        constrain(restored);
        for (int f = 0; f < 30; ++f) {
            drive(original, f);
            ASSERT_EQ(cloth_step(original.world, kFrame), CLOTH_OK);
        }
        for (int f = 0; f < 7; ++f) {  // another past: a still skeleton for 7 frames
            drive(restored, 0);
            ASSERT_EQ(cloth_step(restored.world, kFrame), CLOTH_OK);
        }
        size_t size = 0;
        ASSERT_EQ(cloth_get_snapshot_size(original.cloth, &size), CLOTH_OK);
        std::vector<unsigned char> snapshot(size);
        ASSERT_EQ(cloth_save_snapshot(original.cloth, snapshot.data(), size), CLOTH_OK);
        ASSERT_EQ(cloth_restore_snapshot(restored.cloth, snapshot.data(), size), CLOTH_OK);
        for (int f = 30; f < 60; ++f) {
            for (SkinnedScene* scene : {&original, &restored}) {
                drive(*scene, f);
                ASSERT_EQ(cloth_step(scene->world, kFrame), CLOTH_OK);
            }
        }
        const std::vector<float> a = original.read(cloth_read_positions),
                                 b = restored.read(cloth_read_positions);
        EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)), 0);
        const std::vector<float> sa = original.read([](cloth_id c, float* out, uint32_t capacity) {
            return cloth_read_skinned_positions(c, out, nullptr, capacity);
        });
        const std::vector<float> sb = restored.read([](cloth_id c, float* out, uint32_t capacity) {
            return cloth_read_skinned_positions(c, out, nullptr, capacity);
        });
        EXPECT_EQ(std::memcmp(sa.data(), sb.data(), sa.size() * sizeof(float)), 0);
    }
}

// A snapshot and the cloth it is restored into agree on the skin: a cloth
// without a skin, with another joint count, or following the host's
// positions instead of joints refuses a skinned cloth's snapshot, and a
// skinned cloth an unskinned one's, with CLOTH_ERROR_INVALID_VALUE,
// unchanged.
TEST(SkinSnapshot, AClothAndASnapshotThatDisagreeOnTheSkinAreRefusedUnchanged) {
    SkinnedScene original(16, 1);
    for (int f = 0; f < 10; ++f) {
        original.pose(f);
        ASSERT_EQ(cloth_step(original.world, kFrame), CLOTH_OK);
    }
    size_t size = 0;
    ASSERT_EQ(cloth_get_snapshot_size(original.cloth, &size), CLOTH_OK);
    std::vector<unsigned char> snapshot(size);
    ASSERT_EQ(cloth_save_snapshot(original.cloth, snapshot.data(), size), CLOTH_OK);

    SkinnedScene other_joints(16, 1), host(16, 1), bare(16, 1);
    std::vector<uint32_t> joints(3 * 256);
    std::vector<float> weights(3 * 256, 1.0f / 3.0f);
    for (size_t i = 0; i < joints.size(); ++i) joints[i] = static_cast<uint32_t>(i % 3);
    cloth_skin_desc skin = cloth_default_skin_desc();
    skin.particle_count = 256;
    skin.joint_count = 3;
    skin.influences = 3;
    skin.joints = joints.data();
    skin.weights = weights.data();
    ASSERT_EQ(cloth_set_skin(other_joints.cloth, &skin), CLOTH_OK);
    host_skin(host, 0);
    cloth_destroy(bare.cloth);
    cloth_grid_desc grid = cloth_default_grid_desc();
    grid.columns = grid.rows = 16;
    cloth_fabric_id fabric{};
    ASSERT_EQ(cloth_fabric_create_grid(bare.world, &grid, &fabric), CLOTH_OK);
    cloth_desc desc = cloth_default_desc();
    desc.fabric = fabric;
    ASSERT_EQ(cloth_create(bare.world, &desc, &bare.cloth), CLOTH_OK);
    for (SkinnedScene* scene : {&other_joints, &host, &bare}) {
        ASSERT_EQ(cloth_step(scene->world, kFrame), CLOTH_OK);
        const std::vector<float> before = scene->read(cloth_read_positions);
        EXPECT_EQ(cloth_restore_snapshot(scene->cloth, snapshot.data(), size), CLOTH_ERROR_INVALID_VALUE);
        const std::vector<float> after = scene->read(cloth_read_positions);
        EXPECT_EQ(std::memcmp(before.data(), after.data(), before.size() * sizeof(float)), 0);
    }
    // And the other way: an unskinned cloth's snapshot into the skinned one.
    size_t bare_size = 0;
    ASSERT_EQ(cloth_get_snapshot_size(bare.cloth, &bare_size), CLOTH_OK);
    EXPECT_LT(bare_size, size) << "an unskinned cloth's snapshot holds no skin";
    std::vector<unsigned char> bare_snapshot(bare_size);
    ASSERT_EQ(cloth_save_snapshot(bare.cloth, bare_snapshot.data(), bare_size), CLOTH_OK);
    SkinnedScene twin(16, 1);
    ASSERT_EQ(cloth_destroy(twin.cloth), CLOTH_OK);
    ASSERT_EQ(cloth_fabric_create_grid(twin.world, &grid, &fabric), CLOTH_OK);
    desc.fabric = fabric;
    ASSERT_EQ(cloth_create(twin.world, &desc, &twin.cloth), CLOTH_OK);
    ASSERT_EQ(cloth_restore_snapshot(twin.cloth, bare_snapshot.data(), bare_size), CLOTH_OK)
        << "an unskinned cloth takes an unskinned cloth's snapshot";
    const std::vector<float> before = original.read(cloth_read_positions);
    EXPECT_EQ(cloth_restore_snapshot(original.cloth, bare_snapshot.data(), bare_size),
              CLOTH_ERROR_INVALID_VALUE);
    const std::vector<float> after = original.read(cloth_read_positions);
    EXPECT_EQ(std::memcmp(before.data(), after.data(), before.size() * sizeof(float)), 0);
}

}  // namespace
