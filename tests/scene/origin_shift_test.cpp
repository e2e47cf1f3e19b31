// Origin rebasing (cloth_world_shift_origin), checked against the physical
// and contractual facts it exists for:
//   - attached particles on a body that drives 450 m from the origin stay
//     within 1e-5 m of their targets when the host rebases, and not without
//     (floats resolve 3e-5 m there: the failure the call removes);
//   - a shift moves every particle, pin target, body and static collider by
//     the same amount, so a rebased scene keeps simulating the same motion.
#include <cloth/cloth.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstring>
#include <vector>

namespace {

constexpr float kFrame = 1.0f / 60.0f;

struct Scene {
    cloth_world_id world{};
    cloth_fabric_id fabric{};
    cloth_id cloth{};
    uint32_t n = 0;

    // A columns x rows flag hanging down -y from (0, 2, 0), spanning +x.
    Scene(uint32_t columns, uint32_t rows) {
        const cloth_world_desc wd = cloth_default_world_desc();
        EXPECT_EQ(cloth_world_create(&wd, &world), CLOTH_OK);
        cloth_grid_desc g = cloth_default_grid_desc();
        g.columns = columns;
        g.rows = rows;
        g.origin[1] = 2.0f;
        g.u[0] = 1.0f;
        g.v[1] = -0.8f;
        EXPECT_EQ(cloth_fabric_create_grid(world, &g, &fabric), CLOTH_OK);
        cloth_desc cd = cloth_default_desc();
        cd.fabric = fabric;
        EXPECT_EQ(cloth_create(world, &cd, &cloth), CLOTH_OK) << cloth_get_last_error();
        n = columns * rows;
    }
    ~Scene() { cloth_world_destroy(world); }

    std::vector<float> positions() const {
        std::vector<float> x(3 * n);
        EXPECT_EQ(cloth_read_positions(cloth, x.data(), 3 * n), CLOTH_OK);
        return x;
    }
};

cloth_body_id make_body(cloth_world_id world) {
    const cloth_body_desc d = cloth_default_body_desc();
    cloth_body_id body{};
    EXPECT_EQ(cloth_body_create(world, &d, &body), CLOTH_OK) << cloth_get_last_error();
    return body;
}

// Drive a body 450 m along z at 30 m/s, swaying, with the flag's top row
// attached; the host keeps its own double-precision origin and, if
// `rebase`, moves it in 32 m steps whenever the body is more than 32 m
// away. Returns the largest distance of an attached particle from its
// target, in the host's double-precision world frame.
double drive_far(bool rebase) {
    constexpr uint32_t kColumns = 8;
    Scene s(kColumns, 6);
    const cloth_body_id body = make_body(s.world);
    std::vector<uint32_t> top;
    std::vector<float> offsets;
    for (uint32_t c = 0; c < kColumns; ++c) {
        top.push_back(c);
        offsets.insert(offsets.end(), {float(c) / (kColumns - 1), 2.0f, 0.0f});
    }
    EXPECT_EQ(cloth_attach(s.cloth, body, top.data(), offsets.data(), kColumns), CLOTH_OK);

    Eigen::Vector3d origin = Eigen::Vector3d::Zero();
    double worst = 0;
    for (int frame = 1; frame <= 900; ++frame) {
        const double t = frame * kFrame;
        const Eigen::Vector3d p(1.5 * std::sin(2 * t), 0.0, 30.0 * t);
        const Eigen::Quaterniond q(Eigen::AngleAxisd(0.3 * std::sin(2 * t), Eigen::Vector3d::UnitY()));
        if (rebase && (p - origin).cwiseAbs().maxCoeff() > 32.0) {
            const Eigen::Vector3d next = (p / 32.0).array().round() * 32.0;
            const float shift[3] = {float(next.x() - origin.x()), float(next.y() - origin.y()),
                                    float(next.z() - origin.z())};
            EXPECT_EQ(cloth_world_shift_origin(s.world, shift), CLOTH_OK);
            origin = next;
        }
        const Eigen::Vector3d local = p - origin;
        const float position[3] = {float(local.x()), float(local.y()), float(local.z())};
        const Eigen::Quaternionf qf = q.cast<float>();
        const float rotation[4] = {qf.x(), qf.y(), qf.z(), qf.w()};
        EXPECT_EQ(cloth_body_set_pose(body, position, rotation), CLOTH_OK);
        EXPECT_EQ(cloth_step(s.world, kFrame), CLOTH_OK) << cloth_get_last_error();

        // The target as the host knows it: its pose (as given, float
        // rotation) times the offset, in double.
        const std::vector<float> x = s.positions();
        for (uint32_t c = 0; c < kColumns; ++c) {
            const Eigen::Vector3d offset(offsets[3 * c], offsets[3 * c + 1], offsets[3 * c + 2]);
            const Eigen::Vector3d target = qf.cast<double>().normalized() * offset + p;
            const Eigen::Vector3d particle = Eigen::Vector3d(x[3 * c], x[3 * c + 1], x[3 * c + 2]) + origin;
            worst = std::max(worst, (particle - target).norm());
        }
    }
    return worst;
}

TEST(OriginShift, AttachmentsFarFromTheStartStayWithin1e5mOfTheirTargetsOnlyWhenTheHostRebases) {
    const double rebased = drive_far(true);
    EXPECT_LT(rebased, 1e-5) << "attached particles left their targets on a rebased world";
    // The control: without rebasing, 450 m out, float spacing alone is 3e-5 m.
    const double fixed = drive_far(false);
    EXPECT_GT(fixed, 1e-5) << "the far drive no longer shows the float limit rebasing removes";
}

// A flag attached along its top row to a body that sways and creeps
// forward (+z), its bottom-left corner pinned to a target that moves faster,
// so it presses into a static sphere ahead of it. The world is shifted by
// `shift` after frame 20, and from then on every host input is given in
// the shifted frame. Returns the positions after `frames` frames and the
// body's pose.
const Eigen::Vector3d kSphereCenter(0.5, 1.5, 0.25);
constexpr double kSphereRadius = 0.2;

std::vector<float> drape(const Eigen::Vector3f& shift, int frames, const Eigen::Vector3d& sphere_center,
                         std::vector<float>* body_pose) {
    Scene s(10, 10);
    const cloth_body_id body = make_body(s.world);
    const uint32_t top[] = {1, 2, 3, 4, 5, 6, 7, 8, 9};
    EXPECT_EQ(cloth_attach(s.cloth, body, top, nullptr, 9), CLOTH_OK);
    const uint32_t corner = 90;  // bottom-left
    EXPECT_EQ(cloth_pin(s.cloth, &corner, 1), CLOTH_OK);
    cloth_collider_desc d = cloth_default_collider_desc();
    for (int k = 0; k < 3; ++k) d.local_position[k] = float(sphere_center[k]);
    cloth_collider_id sphere{};
    EXPECT_EQ(cloth_collider_create_sphere(s.world, &d, float(kSphereRadius), &sphere), CLOTH_OK);

    Eigen::Vector3f origin = Eigen::Vector3f::Zero();
    for (int frame = 1; frame <= frames; ++frame) {
        if (frame == 21) {
            const float v[3] = {shift.x(), shift.y(), shift.z()};
            EXPECT_EQ(cloth_world_shift_origin(s.world, v), CLOTH_OK);
            origin = shift;
        }
        const float t = frame * kFrame;
        const Eigen::Vector3f p = Eigen::Vector3f(0.05f * std::sin(3 * t), 0.0f, 0.15f * t) - origin;
        const float position[3] = {p.x(), p.y(), p.z()};
        const float rotation[4] = {0, 0, 0, 1};
        EXPECT_EQ(cloth_body_set_pose(body, position, rotation), CLOTH_OK);
        const Eigen::Vector3f pin = Eigen::Vector3f(0.0f, 1.2f, 0.3f * t) - origin;
        EXPECT_EQ(cloth_set_pin_targets(s.cloth, &corner, pin.data(), 1), CLOTH_OK);
        EXPECT_EQ(cloth_step(s.world, kFrame), CLOTH_OK) << cloth_get_last_error();
    }
    body_pose->resize(7);
    EXPECT_EQ(cloth_body_get_pose(body, body_pose->data(), body_pose->data() + 3), CLOTH_OK);
    return s.positions();
}

TEST(OriginShift, ARebasedSceneSimulatesTheSameMotionOffsetByTheShift) {
    // The sphere out of reach: no contact, whose on/off switch would turn
    // rounding differences into millimetres.
    const Eigen::Vector3d far_sphere(0.5, 1.5, 5.0);
    const Eigen::Vector3f shift(64.0f, -32.0f, 96.0f);
    std::vector<float> pose, shifted_pose;
    const std::vector<float> reference = drape(Eigen::Vector3f::Zero(), 90, far_sphere, &pose);
    const std::vector<float> rebased = drape(shift, 90, far_sphere, &shifted_pose);
    // Only rounding differs: positions 100 m out carry 8e-6 m float steps.
    double worst = 0;
    for (size_t i = 0; i < reference.size(); ++i) {
        worst = std::max(worst, std::abs(double(rebased[i]) + shift[i % 3] - reference[i]));
    }
    EXPECT_LT(worst, 5e-4) << "the rebased cloth took a different path";
    for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(shifted_pose[k] + shift[k], pose[k], 1e-5) << "body pose axis " << k;
    }
}

TEST(OriginShift, StaticCollidersMoveWithTheWorld) {
    // The flag reaches the sphere after the shift: it must press on the
    // sphere where the shifted world has it, and not pass into it.
    const Eigen::Vector3f shift(64.0f, -32.0f, 96.0f);
    std::vector<float> pose;
    const std::vector<float> x = drape(shift, 90, kSphereCenter, &pose);
    const Eigen::Vector3d center = kSphereCenter - shift.cast<double>();
    int touching = 0;
    double deepest = 1e9;
    for (size_t i = 0; i < x.size(); i += 3) {
        const double gap = (Eigen::Vector3d(x[i], x[i + 1], x[i + 2]) - center).norm() - kSphereRadius;
        deepest = std::min(deepest, gap);
        if (gap < 0.02) ++touching;
    }
    EXPECT_GT(touching, 3) << "the flag should press on the sphere";
    EXPECT_GT(deepest, 0.009) << "a particle went into the sphere (thickness 0.01 m)";
}

TEST(OriginShift, AShiftThatWouldOverflowAPositionIsRefusedAndMovesNothing) {
    // A fuzzer finding: a finite shift can still take a far position to
    // infinity, which no later step could undo. A shift, like every
    // coordinate a call takes, is now bounded by CLOTH_MAX_COORDINATE.
    Scene s(4, 4);
    const cloth_body_id body = make_body(s.world);
    const uint32_t far = 5;
    const float out_there[3] = {-CLOTH_MAX_COORDINATE, 0.0f, 0.0f};
    ASSERT_EQ(cloth_set_positions(s.cloth, &far, out_there, 1), CLOTH_OK);
    const std::vector<float> before = s.positions();
    const float shift[3] = {3e38f, 1.0f, 0.0f};
    EXPECT_EQ(cloth_world_shift_origin(s.world, shift), CLOTH_ERROR_INVALID_VALUE);
    const std::vector<float> after = s.positions();
    EXPECT_EQ(std::memcmp(before.data(), after.data(), before.size() * sizeof(float)), 0)
        << "a refused shift moved particles";
    float position[3], rotation[4];
    ASSERT_EQ(cloth_body_get_pose(body, position, rotation), CLOTH_OK);
    EXPECT_EQ(position[1], 0.0f) << "a refused shift moved a body";
}

}  // namespace
