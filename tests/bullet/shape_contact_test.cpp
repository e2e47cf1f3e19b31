// Each Bullet shape type maps to cloth colliders that give the same contact
// answer as Bullet's own query. For sampled points p around a shape placed
// at a non-trivial pose, Bullet's btCollisionWorld::contactPairTest between
// the shape and a small sphere (radius r) centred at p says whether they
// touch, how deep, and along which normal; the cloth side asks the colliders
// the adapter made (their shapes built as the C API builds them, queried
// with the core's query_shape at p taken into each collider's frame) for the
// nearest surface. Both must agree on touching (distance < r), and where
// they touch on the distance (1e-3 m) and the normal (within ~2.6 degrees).
//
// Where the nearest feature is not unique (the normal flips between two
// faces), Bullet's contact point must lie on the cloth surface instead.
//
// Bullet's collision margins are set near zero here (see cloth_bullet.h: the
// adapter maps nominal surfaces). Concave shapes (triangle mesh, height
// field) are sampled on their front side only: Bullet's triangles are
// two-sided, the cloth's one-sided (solid below).
#include <BulletCollision/CollisionShapes/btHeightfieldTerrainShape.h>
#include <BulletCollision/NarrowPhaseCollision/btRaycastCallback.h>
#include <cloth_bullet/cloth_bullet.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "collide/colliders.h"

namespace {

constexpr float kProbe = 0.05f;  // probe sphere radius, m

const cloth::HostMemory* heap() {
    static const cloth::HostMemory memory{};
    return &memory;
}

cloth::Status build(const cloth_bullet::ColliderSpec& spec, cloth::Shape& shape) {
    using cloth_bullet::ColliderKind;
    switch (spec.kind) {
        case ColliderKind::kSphere:
            return cloth::build_sphere(spec.radius, shape);
        case ColliderKind::kCapsule:
            return cloth::build_capsule(spec.radius, spec.half_height, shape);
        case ColliderKind::kBox:
            return cloth::build_box(
                cloth::Vec3(spec.half_extents.x(), spec.half_extents.y(), spec.half_extents.z()), shape);
        case ColliderKind::kPlane:
            return cloth::build_plane(
                cloth::Vec3(spec.plane_normal.x(), spec.plane_normal.y(), spec.plane_normal.z()),
                spec.plane_offset, shape);
        case ColliderKind::kConvexHull:
            return cloth::build_convex_hull(spec.points.data(), static_cast<uint32_t>(spec.points.size() / 3),
                                            shape);
        case ColliderKind::kTriangleMesh:
            return cloth::build_triangle_mesh(
                spec.points.data(), static_cast<uint32_t>(spec.points.size() / 3), spec.indices.data(),
                static_cast<uint32_t>(spec.indices.size() / 3), shape);
        case ColliderKind::kHeightfield:
            return cloth::build_heightfield(spec.columns, spec.rows, spec.spacing_x, spec.spacing_z,
                                            spec.heights.data(), shape);
    }
    return cloth::Status::error(CLOTH_ERROR_INVALID_VALUE, "unknown kind");
}

struct Answer {
    bool touching = false;
    float distance = 1e30f;  // of the probe's centre to the surface, signed
    btVector3 normal{0, 0, 0};
};

// The cloth colliders of one Bullet object, as the cloth library sees them.
class ClothSide {
  public:
    ClothSide(const btCollisionObject& object) : pose_(object.getWorldTransform()) {
        std::string error;
        EXPECT_TRUE(cloth_bullet::describe_shape(*object.getCollisionShape(), btTransform::getIdentity(),
                                                 &specs_, &error))
            << error;
        for (const auto& spec : specs_) {
            shapes_.push_back(std::make_unique<cloth::Shape>(heap()));
            const cloth::Status status = build(spec, *shapes_.back());
            EXPECT_TRUE(status.ok()) << status.message;
        }
    }
    size_t collider_count() const { return specs_.size(); }
    const cloth_bullet::ColliderSpec& spec(size_t i) const { return specs_[i]; }

    Answer query(const btVector3& p) const {
        Answer best;
        for (size_t i = 0; i < specs_.size(); ++i) {
            const btTransform to_local = (pose_ * specs_[i].local).inverse();
            const btVector3 q = to_local * p;
            const cloth::SurfaceQuery hit =
                cloth::query_shape(*shapes_[i], cloth::Vec3(q.x(), q.y(), q.z()), 4 * kProbe);
            if (hit.distance < best.distance) {
                best.distance = hit.distance;
                best.normal = (pose_ * specs_[i].local).getBasis() *
                              btVector3(hit.normal.x(), hit.normal.y(), hit.normal.z());
            }
        }
        best.touching = best.distance < kProbe;
        return best;
    }

  private:
    btTransform pose_;
    std::vector<cloth_bullet::ColliderSpec> specs_;
    std::vector<std::unique_ptr<cloth::Shape>> shapes_;
};

// Bullet's own answer for a sphere of radius kProbe at p.
class BulletSide {
  public:
    BulletSide()
        : dispatcher_(&configuration_), world_(&dispatcher_, &broadphase_, &configuration_), sphere_(kProbe) {
        probe_.setCollisionShape(&sphere_);
    }
    Answer query(btCollisionObject& object, const btVector3& p) {
        btTransform at = btTransform::getIdentity();
        at.setOrigin(p);
        probe_.setWorldTransform(at);
        struct Callback : btCollisionWorld::ContactResultCallback {
            const btCollisionObject* probe = nullptr;
            Answer answer;
            btScalar addSingleResult(btManifoldPoint& point, const btCollisionObjectWrapper* a, int, int,
                                     const btCollisionObjectWrapper*, int, int) override {
                const float distance = point.getDistance() + kProbe;
                if (distance < answer.distance) {
                    answer.distance = distance;
                    // m_normalWorldOnB points from B towards A.
                    answer.normal =
                        a->getCollisionObject() == probe ? point.m_normalWorldOnB : -point.m_normalWorldOnB;
                }
                return 0;
            }
        } callback;
        callback.probe = &probe_;
        world_.contactPairTest(&probe_, &object, callback);
        callback.answer.touching = callback.answer.distance < kProbe;
        return callback.answer;
    }

  private:
    btDefaultCollisionConfiguration configuration_;
    btCollisionDispatcher dispatcher_;
    btDbvtBroadphase broadphase_;
    btCollisionWorld world_;
    btSphereShape sphere_;
    btCollisionObject probe_;
};

btTransform some_pose() {
    btTransform pose;
    pose.setOrigin(btVector3(0.4f, -0.3f, 1.2f));
    pose.setRotation(btQuaternion(btVector3(0.3f, 1.0f, -0.2f).normalized(), 0.8f));
    return pose;
}

// How deep world point p lies in a convex shape at `pose`, measured along
// the outward world direction n (support function minus p's projection).
float support_depth(const btConvexShape& shape, const btTransform& pose, const btVector3& p,
                    const btVector3& n) {
    const btVector3 local_n = pose.getBasis().transpose() * n;
    const btVector3 local_p = pose.inverse() * p;
    return shape.localGetSupportingVertexWithoutMargin(local_n).dot(local_n) - local_n.dot(local_p);
}

// Compares the two answers at `count` points drawn by `sample`; returns how
// many touched (so a test can insist the samples hit the shape).
template <typename Sample>
int compare(btCollisionShape& shape, int count, Sample sample, const char* what) {
    btCollisionObject object;
    object.setCollisionShape(&shape);
    object.setWorldTransform(some_pose());
    const ClothSide cloth_side(object);
    BulletSide bullet_side;
    const btConvexShape* convex = shape.isConvex() ? static_cast<const btConvexShape*>(&shape) : nullptr;
    std::mt19937 random(11);
    int touching = 0, mismatches = 0;
    for (int i = 0; i < count && mismatches < 5; ++i) {
        const btVector3 p = object.getWorldTransform() * sample(random);
        const Answer ours = cloth_side.query(p);
        // Too close to the touching threshold for either float answer to decide.
        if (std::fabs(ours.distance - kProbe) < 2e-3f) continue;
        const Answer bullet = bullet_side.query(object, p);
        bool same = ours.touching == bullet.touching;
        if (same && ours.touching) {
            same = std::fabs(ours.distance - bullet.distance) < 1e-3f;
            // Where the nearest feature is a tie (inside a box or hull near
            // its medial surface, on a terrain edge) either normal is right:
            // then Bullet's contact point, p moved by its depth along its
            // normal, must lie on our surface.
            if (same && ours.normal.dot(bullet.normal) <= 0.999f) {
                const btVector3 on_surface = p - bullet.distance * bullet.normal;
                same = std::fabs(cloth_side.query(on_surface).distance) < 1e-3f;
            }
            // With the probe's centre inside a convex shape Bullet answers by
            // EPA, which is approximate (mm of depth, degrees of normal on a
            // random hull). There ours must be the exact way out by Bullet's
            // own support function: as deep along our normal as we say, and
            // no shallower along Bullet's.
            if (!same && convex != nullptr && ours.distance < 0 && bullet.distance < 0) {
                const float along_ours = support_depth(*convex, object.getWorldTransform(), p, ours.normal);
                const float along_bullet =
                    support_depth(*convex, object.getWorldTransform(), p, bullet.normal);
                same = std::fabs(along_ours + ours.distance) < 1e-4f && along_bullet > -ours.distance - 1e-4f;
            }
        }
        if (!same) {
            ++mismatches;
            ADD_FAILURE() << what << " at (" << p.x() << ", " << p.y() << ", " << p.z() << "): cloth "
                          << (ours.touching ? "touches" : "misses") << " d=" << ours.distance << " n=("
                          << ours.normal.x() << ", " << ours.normal.y() << ", " << ours.normal.z()
                          << "), Bullet " << (bullet.touching ? "touches" : "misses")
                          << " d=" << bullet.distance << " n=(" << bullet.normal.x() << ", "
                          << bullet.normal.y() << ", " << bullet.normal.z() << ")";
        }
        touching += ours.touching;
    }
    return touching;
}

// Uniform points in a box around the origin of the shape's frame. One draw
// per statement, z first: the order in which a call's arguments are
// evaluated is unspecified (GCC goes right to left, clang left to right), and
// the samples must not depend on the compiler.
auto in_box(float hx, float hy, float hz) {
    return [=](std::mt19937& random) {
        std::uniform_real_distribution<float> x(-hx, hx), y(-hy, hy), z(-hz, hz);
        const float pz = z(random);
        const float py = y(random);
        const float px = x(random);
        return btVector3(px, py, pz);
    };
}

// The height of the highest front surface of a concave shape below local
// (x, z), from Bullet's own ray cast (samples sit exactly above Bullet's
// triangles, not above the function they were made from).
template <typename ConcaveShape>
float surface_below(ConcaveShape& shape, float x, float z) {
    struct Nearest : btTriangleRaycastCallback {
        Nearest(const btVector3& from, const btVector3& to) : btTriangleRaycastCallback(from, to) {}
        btScalar reportHit(const btVector3&, btScalar fraction, int, int) override {
            m_hitFraction = std::min(m_hitFraction, fraction);
            return m_hitFraction;
        }
    };
    const btVector3 from(x, 2.0f, z), to(x, -2.0f, z);
    Nearest hit(from, to);
    shape.performRaycast(&hit, from, to);
    return 2.0f - 4.0f * hit.m_hitFraction;
}

TEST(BulletShapes, SphereMatchesBullet) {
    btSphereShape sphere(0.4f);
    EXPECT_GT(compare(sphere, 2000, in_box(0.5f, 0.5f, 0.5f), "sphere"), 200);
}

TEST(BulletShapes, CapsulesOfEveryAxisMatchBullet) {
    btCapsuleShape along_y(0.25f, 0.8f);
    btCapsuleShapeX along_x(0.25f, 0.8f);
    btCapsuleShapeZ along_z(0.25f, 0.8f);
    EXPECT_GT(compare(along_y, 2000, in_box(0.35f, 0.8f, 0.35f), "capsule y"), 200);
    EXPECT_GT(compare(along_x, 2000, in_box(0.8f, 0.35f, 0.35f), "capsule x"), 200);
    EXPECT_GT(compare(along_z, 2000, in_box(0.35f, 0.35f, 0.8f), "capsule z"), 200);
}

TEST(BulletShapes, BoxMatchesBullet) {
    btBoxShape box(btVector3(0.5f, 0.3f, 0.8f));
    box.setMargin(1e-4f);
    EXPECT_GT(compare(box, 3000, in_box(0.6f, 0.4f, 0.9f), "box"), 300);
}

TEST(BulletShapes, ConvexHullMatchesBullet) {
    btConvexHullShape hull;
    std::mt19937 random(3);
    std::normal_distribution<float> n(0.0f, 1.0f);
    for (int i = 0; i < 40; ++i) {
        const float z = n(random);  // one draw per statement, z first (see in_box)
        const float y = n(random);
        const float x = n(random);
        const btVector3 d = btVector3(x, y, z).normalized();
        hull.addPoint(btVector3(0.6f * d.x(), 0.4f * d.y(), 0.5f * d.z()), false);
    }
    hull.recalcLocalAabb();
    hull.setMargin(0.0f);
    EXPECT_GT(compare(hull, 3000, in_box(0.7f, 0.5f, 0.6f), "convex hull"), 300);
}

TEST(BulletShapes, StaticPlaneMatchesBullet) {
    btStaticPlaneShape plane(btVector3(0.2f, 1.0f, -0.1f).normalized(), 0.15f);
    EXPECT_GT(compare(plane, 2000, in_box(1.0f, 0.4f, 1.0f), "plane"), 200);
}

TEST(BulletShapes, EveryChildOfACompoundMatchesBullet) {
    btBoxShape box(btVector3(0.6f, 0.2f, 0.4f));
    box.setMargin(1e-4f);
    btSphereShape sphere(0.25f);
    btCapsuleShape capsule(0.1f, 0.6f);
    btCompoundShape compound;
    btTransform child = btTransform::getIdentity();
    compound.addChildShape(child, &box);
    child.setOrigin(btVector3(0.5f, 0.4f, 0.0f));
    compound.addChildShape(child, &sphere);
    child.setOrigin(btVector3(-0.4f, 0.5f, 0.1f));
    child.setRotation(btQuaternion(btVector3(0, 0, 1), 0.5f));
    compound.addChildShape(child, &capsule);
    EXPECT_GT(compare(compound, 4000, in_box(0.8f, 0.9f, 0.5f), "compound"), 400);
}

// A bumpy grid of triangles wound counter-clockwise seen from +y (its front).
TEST(BulletShapes, BvhTriangleMeshMatchesBulletOnItsFrontSide) {
    btTriangleMesh mesh;
    const int n = 8;
    const float cell = 0.25f;
    auto vertex = [&](int i, int j) {
        const float x = (i - n / 2) * cell, z = (j - n / 2) * cell;
        return btVector3(x, 0.1f * std::sin(3.0f * x) * std::cos(2.0f * z), z);
    };
    for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
            mesh.addTriangle(vertex(i, j), vertex(i, j + 1), vertex(i + 1, j));
            mesh.addTriangle(vertex(i + 1, j), vertex(i, j + 1), vertex(i + 1, j + 1));
        }
    }
    btBvhTriangleMeshShape shape(&mesh, true);
    shape.setMargin(0.0f);
    const float half = 0.5f * n * cell - 0.3f;  // away from the mesh's rim
    auto above = [&](std::mt19937& random) {
        std::uniform_real_distribution<float> x(-half, half), z(-half, half), up(0.0f, 0.12f);
        const float px = x(random), pz = z(random);
        return btVector3(px, surface_below(shape, px, pz) + up(random), pz);
    };
    EXPECT_GT(compare(shape, 2000, above, "triangle mesh"), 200);
}

TEST(BulletShapes, HeightfieldMatchesBulletAboveItsSurface) {
    const int columns = 9, rows = 7;
    std::vector<float> heights(columns * rows);
    std::mt19937 random(5);
    std::uniform_real_distribution<float> h(-0.2f, 0.3f);
    for (float& value : heights) value = h(random);
    btHeightfieldTerrainShape shape(columns, rows, heights.data(), -0.2f, 0.3f, 1, false);
    shape.setLocalScaling(btVector3(0.3f, 1.5f, 0.4f));
    shape.setMargin(0.0f);
    auto above = [&](std::mt19937& r) {
        std::uniform_real_distribution<float> x(-0.3f * (columns - 1) / 2 + 0.2f,
                                                0.3f * (columns - 1) / 2 - 0.2f);
        std::uniform_real_distribution<float> z(-0.4f * (rows - 1) / 2 + 0.2f, 0.4f * (rows - 1) / 2 - 0.2f);
        std::uniform_real_distribution<float> up(0.0f, 0.12f);
        const float px = x(r), pz = z(r);
        return btVector3(px, surface_below(shape, px, pz) + up(r), pz);
    };
    EXPECT_GT(compare(shape, 2000, above, "height field"), 200);
}

TEST(BulletShapes, UnsupportedShapeIsRefusedByName) {
    btCylinderShape cylinder(btVector3(0.2f, 0.5f, 0.2f));
    std::vector<cloth_bullet::ColliderSpec> specs;
    std::string error;
    EXPECT_FALSE(cloth_bullet::describe_shape(cylinder, btTransform::getIdentity(), &specs, &error));
    EXPECT_TRUE(specs.empty());
    EXPECT_NE(error.find("CylinderY"), std::string::npos) << error;
}

}  // namespace
