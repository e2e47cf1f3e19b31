// Collision shapes the cloth's particles stay out of, and the collision
// stage that keeps them out.
//
// Every shape answers one query in its local frame: the signed distance of
// a point (negative inside) and the outward normal at the closest surface
// point. Convex shapes are exact solids; triangle meshes are one-sided
// solids of shallow depth (behind a triangle only within the query radius);
// height fields are solid below. The collision stage (collide_particles) is
// a loop over a particle range, per collider: the particle's path over the
// substep is taken into the collider's moving frame (start pose at the
// substep start, end pose at its end), so a collider that crosses a particle
// within one substep is found by sphere tracing along that path rather than
// missed. Each particle is independent: any split of the range gives the
// same bits.
#pragma once

#include <algorithm>
#include <cstdint>
#include <limits>
#include <memory>

#include "base/host_allocator.h"
#include "base/math.h"
#include "base/soa.h"
#include "base/status.h"
#include "collide/bodies.h"

namespace cloth {

enum class ShapeKind : uint8_t {
    kSphere,
    kCapsule,
    kTaperedCapsule,
    kBox,
    kPlane,
    kConvexHull,
    kTriangleMesh,
    kHeightfield
};

// Closest-surface answer of a shape query.
struct SurfaceQuery {
    float distance = 0;           // signed, m; negative inside; a lower bound when >= the query radius
    Vec3 normal = Vec3::UnitY();  // outward unit normal at the closest surface point
};

// A convex polytope as outward triangles (from hull_build in collider_hull.cpp).
struct HullShape {
    explicit HullShape(const HostMemory* memory)
        : vertices(HostAllocator<Vec3>(memory)),
          triangles(HostAllocator<uint32_t>(memory)),
          normals(HostAllocator<Vec3>(memory)),
          offsets(HostAllocator<float>(memory)) {}
    HostVector<Vec3> vertices;
    HostVector<uint32_t> triangles;  // 3 per face, counter-clockwise seen from outside
    HostVector<Vec3> normals;        // per face, unit
    HostVector<float> offsets;       // per face: dot(normal, p) = offset on the face plane
};

// A triangle mesh with a uniform grid over its bounds (built once).
struct MeshShape {
    explicit MeshShape(const HostMemory* memory)
        : vertices(HostAllocator<Vec3>(memory)),
          triangles(HostAllocator<uint32_t>(memory)),
          normals(HostAllocator<Vec3>(memory)),
          cell_begin(HostAllocator<uint32_t>(memory)),
          cell_items(HostAllocator<uint32_t>(memory)) {}
    HostVector<Vec3> vertices;
    HostVector<uint32_t> triangles;  // 3 per triangle
    HostVector<Vec3> normals;        // per triangle, unit (front side)
    Vec3 grid_min = Vec3::Zero();
    float cell_size = 1;
    uint32_t cells[3] = {1, 1, 1};
    HostVector<uint32_t> cell_begin;  // CSR over cells (x fastest), size cells + 1
    HostVector<uint32_t> cell_items;  // triangle indices
};

struct HeightfieldShape {
    explicit HeightfieldShape(const HostMemory* memory) : heights(HostAllocator<float>(memory)) {}
    uint32_t columns = 2, rows = 2;
    float spacing_x = 1, spacing_z = 1;
    HostVector<float> heights;  // row-major
    float height(uint32_t c, uint32_t r) const { return heights[static_cast<size_t>(r) * columns + c]; }
};

// The immutable geometry of a collider, in its local frame.
struct Shape {
    explicit Shape(const HostMemory* memory) : hull(memory), mesh(memory), heightfield(memory) {}

    ShapeKind kind = ShapeKind::kSphere;
    float radius = 0;                   // sphere, capsule; tapered capsule: at y = -half_height
    float top_radius = 0;               // tapered capsule: at y = +half_height
    float half_height = 0;              // capsule, tapered capsule (along local y)
    Vec3 half_extents = Vec3::Zero();   // box
    Vec3 plane_normal = Vec3::UnitY();  // plane (unit)
    float plane_offset = 0;             // plane: dot(n, p) <= offset is inside
    HullShape hull;
    MeshShape mesh;
    HeightfieldShape heightfield;
    // Local bounds: a sphere around the shape (unbounded shapes: infinite).
    Vec3 bound_center = Vec3::Zero();
    float bound_radius = 0;
    // Meshes and height fields only know distances up to a query radius;
    // this is the radius a sweep should use (about one grid cell).
    float query_step = 0;
};

// The signed distance of local point p to the shape (see SurfaceQuery).
// Distances beyond `radius` may be reported as any lower bound >= radius
// (meshes, height fields and hulls stop looking there).
SurfaceQuery query_shape(const Shape& shape, const Vec3& p, float radius);

// Shape builders: validate, fill `shape` (bounds included) and return OK, or
// return the error and leave `shape` unusable. Defined with their shapes.
Status build_sphere(float radius, Shape& shape);
Status build_capsule(float radius, float half_height, Shape& shape);
Status build_tapered_capsule(float bottom_radius, float top_radius, float half_height, Shape& shape);
Status build_box(const Vec3& half_extents, Shape& shape);
Status build_plane(const Vec3& normal, float offset, Shape& shape);
Status build_convex_hull(const float* points_xyz, uint32_t point_count, Shape& shape);
Status build_triangle_mesh(const float* vertices_xyz, uint32_t vertex_count, const uint32_t* indices,
                           uint32_t triangle_count, Shape& shape);
Status build_heightfield(uint32_t columns, uint32_t rows, float spacing_x, float spacing_z,
                         const float* heights, Shape& shape);

// Per-shape queries (collider_shapes.cpp, collider_hull.cpp, collider_mesh.cpp).
SurfaceQuery query_hull(const HullShape& hull, const Vec3& p, float radius);
SurfaceQuery query_mesh(const MeshShape& mesh, const Vec3& p, float radius);
SurfaceQuery query_heightfield(const HeightfieldShape& field, const Vec3& p, float radius);

// The cells of a height field within `radius` of the local xz rectangle
// [x_lo, x_hi] x [z_lo, z_hi], clamped to the field (false: none), and the
// highest sample at their corners: every triangle of those cells lies
// below it (collider_mesh.cpp; the query and the collision stage's culling
// both use them, so they agree bit for bit).
struct HeightfieldCells {
    uint32_t c0 = 0, c1 = 0, r0 = 0, r1 = 0;
};
bool heightfield_cells(const HeightfieldShape& field, float x_lo, float x_hi, float z_lo, float z_hi,
                       float radius, HeightfieldCells& out);
float highest_sample(const HeightfieldShape& field, const HeightfieldCells& cells);

// Closest point to p on triangle abc (Ericson, Real-Time Collision Detection 5.1.5).
Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

// A collider placed in a world: shape, local pose, the body it rides on.
struct Collider {
    std::shared_ptr<const Shape> shape;
    Pose local;                  // relative to the body (or the world)
    uint32_t body = UINT32_MAX;  // body slot, or UINT32_MAX: static
    uint32_t group_bits = 1;
};

// A collider as the collision stage sees it over one substep, with what
// every range and particle test of the substep needs from its pose taken
// once (per collider and pass, not per chunk and particle).
struct MovingCollider {
    MovingCollider() = default;
    MovingCollider(const Shape* shape, const Pose& start, const Pose& end, const Body* body = nullptr);

    const Shape* shape = nullptr;
    Pose start, end;             // world poses at the substep's start and end
    const Body* body = nullptr;  // for the surface velocity (friction); null if static
    // The shape's bounding sphere's centre at the start and end, and half
    // the chord between them: the centre's path under slerp is an arc, and
    // half its chord bounds how far the arc strays from the chord.
    Vec3 bound_start = Vec3::Zero(), bound_end = Vec3::Zero();
    float bound_half_chord = 0;
    bool is_static = true;  // the same pose at start and end
};

struct CollisionParams {
    float thickness = 0.01f;
    float friction = 0.3f;
    uint32_t collider_mask = 0xFFFFFFFFu;
};

// The bounds of the free particles of [begin, end) over a substep of
// length h (start and end positions, x - h v and x) and their longest path,
// as collide_particles forms them: one pass, shared by every collider.
struct RangeBounds {
    // Every start and end point (lo, hi), the start points alone and the
    // end points alone: a range carried along with a moving collider (a
    // flag beside its pole) sweeps a long box in the world, but its start
    // and end boxes, each taken into the collider's frame at its own time,
    // lie close together.
    Vec3 lo = Vec3::Constant(std::numeric_limits<float>::infinity());
    Vec3 hi = Vec3::Constant(-std::numeric_limits<float>::infinity());
    Vec3 start_lo = lo, start_hi = hi, end_lo = lo, end_hi = hi;
    float travel = 0;
    bool any = false;  // a free particle in the range

    // The bounds of this range and `other` together (the same bits as
    // range_bounds over both: minima, maxima and the longest path).
    void merge(const RangeBounds& other) {
        lo = lo.cwiseMin(other.lo);
        hi = hi.cwiseMax(other.hi);
        start_lo = start_lo.cwiseMin(other.start_lo);
        start_hi = start_hi.cwiseMax(other.start_hi);
        end_lo = end_lo.cwiseMin(other.end_lo);
        end_hi = end_hi.cwiseMax(other.end_hi);
        travel = std::max(travel, other.travel);
        any = any || other.any;
    }
};

// The collision stage culls by the bounds of chunks of this many particles
// inside a particle group (ClothContact::collide).
constexpr uint32_t kCollisionChunk = 8;
RangeBounds range_bounds(float h, const float* kinematic, uint32_t begin, uint32_t end, const Vec3Soa& x,
                         const Vec3Soa& v);

// Whether no particle of the range can touch the collider over the
// substep, decided from the range's bounds alone: a static height field
// whose highest sample under the range is far enough below it, a bounded
// shape whose swept bound is far enough away, or a sphere, capsule or box
// (tapered or not) whose distance from the range's box (two shape queries) leaves every
// particle's path clear of it. Exact:
// where it says yes, collide_particles would change nothing (tests check
// the two paths give the same bits).
bool range_is_clear(const MovingCollider& collider, const CollisionParams& params, const RangeBounds& bounds);

// Push particles [begin, end) out of one moving collider. x and v are the
// positions and velocities after integration of a substep of length h (so
// a particle's substep start is x - h v); kinematic particles (kinematic[i]
// != 0) are skipped. Returns the number of particles that were in contact.
uint32_t collide_particles(const MovingCollider& collider, const CollisionParams& params, float h,
                           const float* kinematic, uint32_t begin, uint32_t end, Vec3Soa& x, Vec3Soa& v);

}  // namespace cloth
