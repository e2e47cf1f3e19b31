// The analytic shapes (sphere, capsule, tapered capsule, box, plane), the shape dispatch,
// and the collision stage. Hulls are in collider_hull.cpp, triangle meshes
// and height fields in collider_mesh.cpp.
#include "collide/colliders.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "base/lanes.h"

namespace cloth {

namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

bool positive_finite(float value) { return std::isfinite(value) && value > 0; }

SurfaceQuery query_sphere(float radius, const Vec3& p) {
    const float length = p.norm();
    SurfaceQuery q;
    q.distance = length - radius;
    q.normal = length > 0 ? Vec3(p / length) : Vec3(Vec3::UnitY());
    return q;
}

SurfaceQuery query_capsule(float radius, float half_height, const Vec3& p) {
    const Vec3 axis_point(0.0f, std::clamp(p.y(), -half_height, half_height), 0.0f);
    SurfaceQuery q = query_sphere(radius, p - axis_point);
    if (p.x() == 0 && p.z() == 0 && std::abs(p.y()) <= half_height) q.normal = Vec3::UnitX();
    return q;
}

// The convex hull of two spheres on the y axis (a round cone): in the
// plane of the axis and p, with q = (distance from the axis, height above
// the bottom centre), the side is the line at distance r_b from the bottom
// centre along the unit normal (a, s), s = (r_b - r_t) / L the slope the
// radii fall by over the centres' distance L. Points whose foot on that
// line lies below the bottom centre's tangent point are nearest the bottom
// sphere, past the top's the top sphere, else the side: the exact signed
// distance (Quilez's round cone).
SurfaceQuery query_tapered_capsule(float bottom_radius, float top_radius, float half_height, const Vec3& p) {
    const float length = 2.0f * half_height;
    const float slope = (bottom_radius - top_radius) / length;
    const float across = std::sqrt(1.0f - slope * slope);
    const float radial = std::hypot(p.x(), p.z());
    const float up = p.y() + half_height;
    const float along = up * across - radial * slope;  // the foot's position along the side
    if (along < 0.0f) return query_sphere(bottom_radius, p - Vec3(0.0f, -half_height, 0.0f));
    if (along > across * length) return query_sphere(top_radius, p - Vec3(0.0f, half_height, 0.0f));
    const Vec3 out = radial > 0 ? Vec3(p.x() / radial, 0.0f, p.z() / radial) : Vec3(Vec3::UnitX());
    SurfaceQuery q;
    q.distance = radial * across + up * slope - bottom_radius;
    q.normal = across * out + slope * Vec3::UnitY();
    return q;
}

SurfaceQuery query_box(const Vec3& e, const Vec3& p) {
    const Vec3 a = p.cwiseAbs();
    const Vec3 excess = a - e;
    SurfaceQuery q;
    const Vec3 outside = excess.cwiseMax(0.0f);
    const float outside_length = outside.norm();
    if (outside_length > 0) {
        q.distance = outside_length;
        const Vec3 sign(p.x() < 0 ? -1.0f : 1.0f, p.y() < 0 ? -1.0f : 1.0f, p.z() < 0 ? -1.0f : 1.0f);
        q.normal = outside.cwiseProduct(sign) / outside_length;
        return q;
    }
    // Inside (or on the surface): the nearest face.
    int axis = 0;
    if (excess.y() > excess[axis]) axis = 1;
    if (excess.z() > excess[axis]) axis = 2;
    q.distance = excess[axis];
    q.normal = Vec3::Zero();
    q.normal[axis] = p[axis] < 0 ? -1.0f : 1.0f;
    return q;
}

Status not_finite(const char* what) {
    return Status::error(CLOTH_ERROR_NOT_FINITE, "%s is not finite", what);
}

}  // namespace

Status build_sphere(float radius, Shape& shape) {
    if (!std::isfinite(radius)) return not_finite("sphere radius");
    if (!positive_finite(radius))
        return Status::error(CLOTH_ERROR_INVALID_VALUE, "sphere radius must be > 0");
    shape.kind = ShapeKind::kSphere;
    shape.radius = radius;
    shape.bound_radius = radius;
    return {};
}

Status build_capsule(float radius, float half_height, Shape& shape) {
    if (!std::isfinite(radius)) return not_finite("capsule radius");
    if (!std::isfinite(half_height)) return not_finite("capsule half_height");
    if (!positive_finite(radius))
        return Status::error(CLOTH_ERROR_INVALID_VALUE, "capsule radius must be > 0");
    if (half_height < 0) return Status::error(CLOTH_ERROR_INVALID_VALUE, "capsule half_height must be >= 0");
    shape.kind = ShapeKind::kCapsule;
    shape.radius = radius;
    shape.half_height = half_height;
    shape.bound_radius = radius + half_height;
    return {};
}

Status build_tapered_capsule(float bottom_radius, float top_radius, float half_height, Shape& shape) {
    if (!std::isfinite(bottom_radius) || !std::isfinite(top_radius))
        return not_finite("tapered capsule radius");
    if (!std::isfinite(half_height)) return not_finite("tapered capsule half_height");
    if (!positive_finite(bottom_radius) || !positive_finite(top_radius))
        return Status::error(CLOTH_ERROR_INVALID_VALUE, "tapered capsule radii must be > 0");
    // One sphere inside the other has no side: that is a sphere.
    if (!(std::abs(bottom_radius - top_radius) < 2.0f * half_height))
        return Status::error(CLOTH_ERROR_INVALID_VALUE,
                             "tapered capsule: the radii must differ by less than 2 * half_height "
                             "(else one sphere holds the other: use a sphere)");
    shape.kind = ShapeKind::kTaperedCapsule;
    shape.radius = bottom_radius;
    shape.top_radius = top_radius;
    shape.half_height = half_height;
    shape.bound_radius = half_height + std::max(bottom_radius, top_radius);
    return {};
}

Status build_box(const Vec3& half_extents, Shape& shape) {
    if (!half_extents.allFinite()) return not_finite("box half extents");
    for (int k = 0; k < 3; ++k) {
        if (!positive_finite(half_extents[k]))
            return Status::error(CLOTH_ERROR_INVALID_VALUE, "box half extents must be > 0");
    }
    shape.kind = ShapeKind::kBox;
    shape.half_extents = half_extents;
    shape.bound_radius = half_extents.norm();
    return {};
}

Status build_plane(const Vec3& normal, float offset, Shape& shape) {
    if (!normal.allFinite() || !std::isfinite(offset))
        return Status::error(CLOTH_ERROR_NOT_FINITE, "plane normal or offset is not finite");
    Vec3 unit = Vec3::Zero();
    float length = normal.norm();
    if (std::isfinite(length)) {
        if (!(length > 1e-12f)) return Status::error(CLOTH_ERROR_INVALID_VALUE, "plane normal is zero");
        unit = normal / length;
    } else {
        // A finite normal whose squared length overflows: scaled by its
        // largest component first.
        const float largest = normal.cwiseAbs().maxCoeff();
        const Vec3 scaled = normal / largest;
        unit = scaled / scaled.norm();
        length = scaled.norm() * largest;
    }
    shape.kind = ShapeKind::kPlane;
    shape.plane_normal = unit;
    shape.plane_offset = offset / length;
    shape.bound_radius = kInfinity;
    return {};
}

SurfaceQuery query_shape(const Shape& shape, const Vec3& p, float radius) {
    switch (shape.kind) {
        case ShapeKind::kSphere:
            return query_sphere(shape.radius, p);
        case ShapeKind::kCapsule:
            return query_capsule(shape.radius, shape.half_height, p);
        case ShapeKind::kTaperedCapsule:
            return query_tapered_capsule(shape.radius, shape.top_radius, shape.half_height, p);
        case ShapeKind::kBox:
            return query_box(shape.half_extents, p);
        case ShapeKind::kPlane:
            return {shape.plane_normal.dot(p) - shape.plane_offset, shape.plane_normal};
        case ShapeKind::kConvexHull:
            return query_hull(shape.hull, p, radius);
        case ShapeKind::kTriangleMesh:
            return query_mesh(shape.mesh, p, radius);
        case ShapeKind::kHeightfield:
            return query_heightfield(shape.heightfield, p, radius);
    }
    return {kInfinity, Vec3::UnitY()};
}

namespace {

float distance_to_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
    const Vec3 ab = b - a;
    const float length2 = ab.squaredNorm();
    const float t = length2 > 0 ? std::clamp((p - a).dot(ab) / length2, 0.0f, 1.0f) : 0.0f;
    return (p - (a + ab * t)).norm();
}

constexpr int kMaxSweepSteps = 32;

// Slack on the culling tests below: float rounding in the per-particle
// tests they stand for is far smaller, and a particle culled within it is
// still more than the thickness from the shape.
constexpr float kCullMargin = 1e-4f;

// Whether a static height field is clear of every particle of the range:
// each particle's own query would stop at its early out (the highest
// sample within its query radius is more than that radius below it), so
// none can touch the field. Mirrors query_heightfield's cell range.
bool heightfield_clear(const MovingCollider& c, const RangeBounds& b, float thickness) {
    const HeightfieldShape& f = c.shape->heightfield;
    Vec3 lo = Vec3::Constant(kInfinity), hi = Vec3::Constant(-kInfinity);
    for (int corner = 0; corner < 8; ++corner) {
        const Vec3 p((corner & 1) ? b.hi.x() : b.lo.x(), (corner & 2) ? b.hi.y() : b.lo.y(),
                     (corner & 4) ? b.hi.z() : b.lo.z());
        const Vec3 local = c.end.apply_inverse(p);
        lo = lo.cwiseMin(local);
        hi = hi.cwiseMax(local);
    }
    const float radius = thickness + std::max(b.travel, c.shape->query_step) + kCullMargin;
    HeightfieldCells cells;
    // Beside the field nothing is within reach (the field is solid only
    // below its surface); positions that are not finite go to the full stage.
    if (!heightfield_cells(f, lo.x(), hi.x(), lo.z(), hi.z(), radius, cells))
        return lo.allFinite() && hi.allFinite();
    return lo.y() - highest_sample(f, cells) > radius + kCullMargin;
}

// Whether a sphere, capsule, tapered capsule or box (shapes whose query is the exact
// distance) is clear of the whole range, from two queries: at the centre
// c_s of the range's start box (radius r_s) in the collider's frame at the
// substep's start, and at the centre c_e of its end box (radius r_e) in
// the frame at its end. Every particle's start lies within r_s of c_s and
// its end within r_e of c_e (the frames are rigid). The distance is
// 1-Lipschitz, so each particle's start and end queries are at least
// d_s - r_s and d_e - r_e, and its path in the moving frame is at most
// r_s + r_e + |c_e - c_s| long. collide_particles leaves a particle alone
// when both queries are at least the thickness and the path is no longer
// than the two clearances together (neither the slide nor the sphere trace
// starts): that holds for every particle when it holds for these bounds.
// A long thin shape (the flag's pole) has a bounding sphere that covers
// most of what is near it; this test culls by the shape itself. Separate
// start and end boxes keep a range that moves with the collider small in
// its frame: one box over both would carry the world-frame move (25 cm a
// substep at 30 m/s) in its radius.
bool exact_distance_clear(const MovingCollider& collider, float thickness, const RangeBounds& b) {
    const Shape& shape = *collider.shape;
    if (shape.kind != ShapeKind::kSphere && shape.kind != ShapeKind::kCapsule &&
        shape.kind != ShapeKind::kTaperedCapsule && shape.kind != ShapeKind::kBox)
        return false;
    const float r_start = 0.5f * (b.start_hi - b.start_lo).norm();
    const float r_end = 0.5f * (b.end_hi - b.end_lo).norm();
    if (!std::isfinite(r_start) || !std::isfinite(r_end)) return false;
    const Vec3 at_start = collider.start.apply_inverse(0.5f * (b.start_lo + b.start_hi));
    const Vec3 at_end = collider.end.apply_inverse(0.5f * (b.end_lo + b.end_hi));
    const float clear_start = query_shape(shape, at_start, 0.0f).distance - r_start - thickness - kCullMargin;
    const float clear_end = query_shape(shape, at_end, 0.0f).distance - r_end - thickness - kCullMargin;
    return clear_start > 0 && clear_end > 0 &&
           r_start + r_end + (at_end - at_start).norm() < clear_start + clear_end;
}

}  // namespace

MovingCollider::MovingCollider(const Shape* shape, const Pose& start, const Pose& end, const Body* body)
    : shape(shape),
      start(start),
      end(end),
      body(body),
      bound_start(start.apply(shape->bound_center)),
      bound_end(end.apply(shape->bound_center)),
      bound_half_chord(0.5f * (bound_end - bound_start).norm()),
      is_static(start.position == end.position && start.rotation.coeffs() == end.rotation.coeffs()) {}

namespace {

// The minima and maxima of eight points at a time in lanes, then across
// the lanes: min and max are exact, so the same values as one at a time
// (a zero's sign may differ, which no bound test sees).
template <class T>
CLOTH_LANES_INLINE T lanes_min(T a, T b) {
    return b < a ? b : a;
}
template <class T>
CLOTH_LANES_INLINE T lanes_max(T a, T b) {
    return a < b ? b : a;
}

// A range's extent, one particle at a time (T = float) or per lane (T =
// eight floats): the start points' and end points' minima and maxima
// (x, y, z of the start, then of the end), the longest squared path, and
// whether a free particle was seen (1) or not (0).
template <class T>
struct Extent {
    T lo[6], hi[6], path, any;

    CLOTH_LANES_INLINE static Extent empty() {
        const float inf = std::numeric_limits<float>::infinity();
        Extent e;
        for (int k = 0; k < 6; ++k) {
            e.lo[k] = T{} + inf;
            e.hi[k] = T{} - inf;
        }
        e.path = e.any = T{};
        return e;
    }
};

// Raw __restrict parameters: GCC does not vectorize through restrict locals.
CLOTH_HOT_LOOP Extent<float> bounds_kernel(float h, const float* __restrict kinematic, uint32_t begin,
                                           uint32_t end, const float* __restrict px,
                                           const float* __restrict py, const float* __restrict pz,
                                           const float* __restrict vx, const float* __restrict vy,
                                           const float* __restrict vz) {
    using V = VectorLanes::type;
    Extent<float> one = Extent<float>::empty();
    Extent<V> eight = Extent<V>::empty();
    const float* x[3] = {px, py, pz};
    const float* v[3] = {vx, vy, vz};
    const auto accumulate = [&](auto lanes, uint32_t i, auto& e) CLOTH_LANES_INLINE_LAMBDA {
        using L = decltype(lanes);
        using T = typename L::type;
        const auto free = L::load(&kinematic[i]) == 0.0f;
        T path = T{};
        for (int a = 0; a < 3; ++a) {
            const T x_end = L::load(&x[a][i]);
            const T x_start = x_end - L::load(&v[a][i]) * h;
            e.lo[a] = free ? lanes_min(e.lo[a], x_start) : e.lo[a];
            e.lo[3 + a] = free ? lanes_min(e.lo[3 + a], x_end) : e.lo[3 + a];
            e.hi[a] = free ? lanes_max(e.hi[a], x_start) : e.hi[a];
            e.hi[3 + a] = free ? lanes_max(e.hi[3 + a], x_end) : e.hi[3 + a];
            const T d = x_end - x_start;
            path = path + d * d;
        }
        e.path = free ? lanes_max(e.path, path) : e.path;
        e.any = free ? T{} + 1.0f : e.any;
    };
    for_each_lane_group(begin, end, begin, end, [&](auto lanes, uint32_t i) CLOTH_LANES_INLINE_LAMBDA {
        if constexpr (decltype(lanes)::width == 1) {
            accumulate(lanes, i, one);
        } else {
            accumulate(lanes, i, eight);
        }
    });
    // Across the lanes in three halvings (ranges are chunks of
    // kCollisionChunk = 8 particles: one vector step, then this).
    const auto fold = [](V e, bool minimum) CLOTH_LANES_INLINE_LAMBDA {
        const auto pick = [minimum](V a, V b) CLOTH_LANES_INLINE_LAMBDA {
            return minimum ? lanes_min(a, b) : lanes_max(a, b);
        };
        e = pick(e, __builtin_shufflevector(e, e, 4, 5, 6, 7, 0, 1, 2, 3));
        e = pick(e, __builtin_shufflevector(e, e, 2, 3, 0, 1, 6, 7, 4, 5));
        e = pick(e, __builtin_shufflevector(e, e, 1, 0, 3, 2, 5, 4, 7, 6));
        return e[0];
    };
    for (int k = 0; k < 6; ++k) {
        one.lo[k] = lanes_min(one.lo[k], fold(eight.lo[k], true));
        one.hi[k] = lanes_max(one.hi[k], fold(eight.hi[k], false));
    }
    one.path = lanes_max(one.path, fold(eight.path, false));
    one.any = lanes_max(one.any, fold(eight.any, false));
    return one;
}

}  // namespace

RangeBounds range_bounds(float h, const float* kinematic, uint32_t begin, uint32_t end, const Vec3Soa& x,
                         const Vec3Soa& v) {
    const Extent<float> e = bounds_kernel(h, kinematic, begin, end, x.x.data(), x.y.data(), x.z.data(),
                                          v.x.data(), v.y.data(), v.z.data());
    RangeBounds b;
    b.start_lo = Vec3(e.lo[0], e.lo[1], e.lo[2]);
    b.end_lo = Vec3(e.lo[3], e.lo[4], e.lo[5]);
    b.start_hi = Vec3(e.hi[0], e.hi[1], e.hi[2]);
    b.end_hi = Vec3(e.hi[3], e.hi[4], e.hi[5]);
    b.any = e.any > 0;
    // The same minima and maxima as over every point at once.
    b.lo = b.start_lo.cwiseMin(b.end_lo);
    b.hi = b.start_hi.cwiseMax(b.end_hi);
    // sqrt is monotonic and correctly rounded: this is the largest of the
    // particles' own path lengths, bit for bit.
    b.travel = std::sqrt(e.path);
    return b;
}

bool range_is_clear(const MovingCollider& collider, const CollisionParams& params, const RangeBounds& b) {
    if (!b.any) return true;
    const Shape& shape = *collider.shape;
    if (shape.kind == ShapeKind::kHeightfield && collider.is_static)
        return heightfield_clear(collider, b, params.thickness);
    if (!std::isfinite(shape.bound_radius)) return false;
    // Bounded shapes: every particle's own early out in collide_particles
    // (its end point farther from the bound centre's chord than the reach
    // plus its path) holds for the whole box when the box is that far from
    // the chord's bounds.
    const Vec3& center_start = collider.bound_start;
    const Vec3& center_end = collider.bound_end;
    const float reach = shape.bound_radius + params.thickness + collider.bound_half_chord;
    const Vec3 chord_lo = center_start.cwiseMin(center_end), chord_hi = center_start.cwiseMax(center_end);
    const Vec3 gap = (chord_lo - b.hi).cwiseMax(b.lo - chord_hi).cwiseMax(0.0f);
    if (gap.norm() - b.travel > reach + kCullMargin) return true;
    return exact_distance_clear(collider, params.thickness, b);
}

uint32_t collide_particles(const MovingCollider& collider, const CollisionParams& params, float h,
                           const float* kinematic, uint32_t begin, uint32_t end, Vec3Soa& x, Vec3Soa& v) {
    const Shape& shape = *collider.shape;
    const float thickness = params.thickness;
    const bool bounded = std::isfinite(shape.bound_radius);
    const Vec3& center_start = collider.bound_start;
    const Vec3& center_end = collider.bound_end;
    const float reach = shape.bound_radius + thickness + collider.bound_half_chord;
    // Sphere tracing stops this close to the thickness surface.
    const float tolerance = 1e-5f + 1e-3f * thickness;
    uint32_t contacts = 0;

    for (uint32_t i = begin; i < end; ++i) {
        if (kinematic[i] != 0.0f) continue;
        const Vec3 x_end = x.get(i);
        const Vec3 velocity = v.get(i);
        const Vec3 x_start = x_end - velocity * h;
        const float travel = (x_end - x_start).norm();
        if (bounded && distance_to_segment(x_end, center_start, center_end) - travel > reach) continue;

        // The path in the collider's moving frame.
        const Vec3 local_start = collider.start.apply_inverse(x_start);
        const Vec3 local_end = collider.end.apply_inverse(x_end);
        const Vec3 path = local_end - local_start;
        const float length = path.norm();
        const float radius = thickness + std::max(length, shape.query_step);

        bool hit = false;
        Vec3 contact = local_end;
        Vec3 normal = Vec3::UnitY();
        // From a contact point on the thickness surface: the particle ends
        // where its path ends, but not below the contact plane (so a
        // collider that moves past in one substep carries it), and outside
        // the thickness. The motion along the plane is kept: a particle that
        // touches the surface slides on it instead of being held where it
        // touched (friction acts on the velocity below).
        auto slide = [&](const Vec3& on_surface, const Vec3& plane_normal) {
            const float below = (local_end - on_surface).dot(plane_normal);
            Vec3 p = local_end;
            normal = plane_normal;
            if (below < 0) {
                p -= plane_normal * below;
                hit = true;
            }
            const SurfaceQuery q = query_shape(shape, p, radius);
            if (q.distance < thickness) {
                p += q.normal * (thickness - q.distance);
                hit = true;
                normal = q.normal;
            }
            contact = p;
        };
        const SurfaceQuery at_start = query_shape(shape, local_start, radius);
        const SurfaceQuery at_end = query_shape(shape, local_end, radius);
        if (at_start.distance < thickness) {
            // In contact at the start: slide from the start point.
            slide(local_start + at_start.normal * (thickness - at_start.distance), at_start.normal);
        } else if (length > 0 && (at_end.distance < thickness ||
                                  length > (at_start.distance - thickness) + (at_end.distance - thickness))) {
            // Started clear: sphere-trace along the path to the first point
            // within the thickness.
            float t = 0;
            SurfaceQuery q = at_start;
            Vec3 p = local_start;
            for (int step = 0; step < kMaxSweepSteps; ++step) {
                const float gap = q.distance - thickness;
                if (gap <= tolerance) {
                    // Reached the surface: slide on from there.
                    slide(p + q.normal * (thickness - q.distance), q.normal);
                    hit = true;
                    break;
                }
                t += gap / length;
                if (t >= 1.0f) break;
                p = local_start + path * t;
                q = query_shape(shape, p, radius);
            }
            if (!hit && at_end.distance < thickness) {
                hit = true;
                contact = local_end + at_end.normal * (thickness - at_end.distance);
                normal = at_end.normal;
            }
        }
        if (!hit) continue;

        ++contacts;
        const Vec3 x_new = collider.end.apply(contact);
        const Vec3 n = collider.end.rotation * normal;
        const Vec3 surface_velocity = collider.body ? collider.body->point_velocity(x_new) : Vec3::Zero();
        Vec3 relative = velocity - surface_velocity;
        const float approach = relative.dot(n);
        if (approach < 0) {
            // Remove the approaching normal velocity; Coulomb friction takes
            // up to friction * |removed| off the tangential velocity.
            const Vec3 tangential = relative - n * approach;
            const float tangential_speed = tangential.norm();
            const float scale = tangential_speed > 0
                                    ? std::max(0.0f, 1.0f - params.friction * -approach / tangential_speed)
                                    : 0.0f;
            relative = tangential * scale;
        }
        x.set(i, x_new);
        v.set(i, surface_velocity + relative);
    }
    return contacts;
}

}  // namespace cloth
