// The collision stage: a moving collider's bounds, the culling of particle
// ranges against it, and the sweep of each particle's path through it
// (collide_particles). The shapes' queries are in collider_shapes.cpp,
// collider_hull.cpp and collider_mesh.cpp.
#include "collide/colliders.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "base/lanes.h"

namespace cloth {

namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

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
