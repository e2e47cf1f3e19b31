// cloth_bullet: the optional Bullet adapter of the cloth library (C++).
//
// It mirrors Bullet collision objects into cloth bodies and colliders:
//  - describe_shape() turns a Bullet shape into collider descriptions in the
//    object's frame (btSphereShape, btCapsuleShape (any up axis), btBoxShape,
//    btConvexHullShape, btStaticPlaneShape, every child of a btCompoundShape,
//    btBvhTriangleMeshShape and btHeightfieldTerrainShape);
//  - create_collider() makes one cloth collider from a description;
//  - BodyMirror keeps a cloth body per mirrored btCollisionObject and copies
//    its pose and velocities into it each frame (sync(), after the Bullet
//    step and before cloth_step).
//
// Coupling is one-way: Bullet bodies move the cloth (attachments, colliders),
// the cloth never pushes them back.
//
// What is not reproduced exactly:
//  - Bullet's collision margins where they lie outside the shape's nominal
//    surface: btConvexHullShape (0.04 m by default) and the rounding of
//    btBoxShape edges and corners by its margin. The colliders are the bare
//    hull and the sharp box (btBoxShape's faces are exact: its margin is
//    inside its half extents). Set hull margins to 0 for an exact match.
//  - Triangle meshes are one-sided in the cloth library (front: the
//    counter-clockwise normal); Bullet's are two-sided. Wind them facing the
//    side the cloth comes from.
//  - Height fields with flipped quad edges, diamond or zigzag subdivision,
//    or an up axis other than y, become triangle meshes (same triangles).
//
// Bullet types stay out of the cloth C API (include/cloth/cloth.h); this
// header is the only place they meet it. The C entry points are in
// cloth_bullet_c.h.
#pragma once

#include <btBulletCollisionCommon.h>
#include <cloth/cloth.h>

#include <string>
#include <unordered_map>
#include <vector>

namespace cloth_bullet {

enum class ColliderKind { kSphere, kCapsule, kBox, kPlane, kConvexHull, kTriangleMesh, kHeightfield };

const char* collider_kind_name(ColliderKind kind);

// One cloth collider, described in the frame of the Bullet collision object
// (`local` places the collider's own frame in it). Only the fields of its
// kind are used.
struct ColliderSpec {
    ColliderKind kind = ColliderKind::kSphere;
    btTransform local = btTransform::getIdentity();
    float radius = 0.0f;              // sphere, capsule
    float half_height = 0.0f;         // capsule: half the segment, along the local y axis
    btVector3 half_extents{0, 0, 0};  // box
    btVector3 plane_normal{0, 1, 0};  // plane: solid where dot(normal, p) <= offset
    float plane_offset = 0.0f;
    std::vector<float> points;                 // hull points / mesh vertices, xyz
    std::vector<uint32_t> indices;             // mesh triangles
    uint32_t columns = 0, rows = 0;            // height field samples along x and z
    float spacing_x = 0.0f, spacing_z = 0.0f;  // height field sample spacing
    std::vector<float> heights;                // height field, row-major (x fastest)
};

// Colliders for `shape`, placed at `local` in the collision object's frame
// (identity for an object's own shape). Appends to *out. Returns false with
// a message in *error for a shape it does not map (the message names it);
// *out is then unchanged.
bool describe_shape(const btCollisionShape& shape, const btTransform& local, std::vector<ColliderSpec>* out,
                    std::string* error);

// Create the collider of `spec` in `world`, fixed to `body` (null: static,
// then spec.local is its pose in the cloth world's frame: after origin
// shifts, the Bullet pose minus BodyMirror::origin()). Returns the cloth
// API's result.
cloth_result create_collider(cloth_world_id world, const ColliderSpec& spec, cloth_body_id body,
                             uint32_t group_bits, cloth_collider_id* out_collider);

// Pose conversions (position xyz, rotation quaternion xyzw).
void to_pose(const btTransform& transform, float position[3], float rotation[4]);

// Mirrors Bullet collision objects into cloth bodies with colliders. The
// mirror owns the bodies and colliders it creates (destroyed with it, unless
// the world went first) and only reads the Bullet objects, which must
// outlive it or be removed first. Not thread-safe (like a cloth world).
class BodyMirror {
  public:
    explicit BodyMirror(cloth_world_id world) : world_(world) {}
    ~BodyMirror();
    BodyMirror(const BodyMirror&) = delete;
    BodyMirror& operator=(const BodyMirror&) = delete;

    // Create a cloth body at the object's pose and colliders for its shape
    // (with these group bits). On failure nothing is created.
    cloth_result add(const btCollisionObject* object, uint32_t group_bits, cloth_body_id* out_body);
    // Destroy the object's body and colliders.
    cloth_result remove(const btCollisionObject* object);
    // The object jumped (a host teleport): move its body there now, without
    // a sweep (cloth_body_teleport). The next sync() continues from there.
    cloth_result teleport(const btCollisionObject* object);
    // Copy every mirrored object's pose and velocities into its body: the
    // bodies reach those poses at the end of the next cloth_step.
    cloth_result sync();

    // Origin rebasing for scenes that travel far (cloth_world_shift_origin):
    // the cloth world's frame is Bullet's moved to origin(), so a cloth
    // position plus origin() is its Bullet position. shift_origin() moves
    // the cloth world's origin by `shift` (in whole multiples of 32 m every
    // position it brings nearer moves exactly) and adds it to origin(),
    // which the mirror keeps in double and subtracts from every pose it
    // copies. Between steps only.
    cloth_result shift_origin(const btVector3& shift);
    const double* origin() const { return origin_; }

    // The object's body (null if not mirrored).
    cloth_body_id body(const btCollisionObject* object) const;
    // The colliders made for the object (empty if not mirrored).
    const std::vector<cloth_collider_id>& colliders(const btCollisionObject* object) const;
    // The last failure's message ("" if none).
    const std::string& last_error() const { return error_; }

  private:
    struct Entry {
        cloth_body_id body{};
        std::vector<cloth_collider_id> colliders;
    };
    cloth_result fail(cloth_result result, const std::string& message);

    cloth_world_id world_;
    std::unordered_map<const btCollisionObject*, Entry> entries_;
    std::vector<const btCollisionObject*> order_;  // insertion order: sync in a fixed order
    double origin_[3] = {0, 0, 0};                 // Bullet position of the cloth world's origin
    std::string error_;
    // The object's pose in the cloth world's frame.
    void cloth_pose(const btCollisionObject& object, float position[3], float rotation[4]) const;
};

}  // namespace cloth_bullet
