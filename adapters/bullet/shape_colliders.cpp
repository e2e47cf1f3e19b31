// Bullet shapes to cloth collider descriptions, and descriptions to cloth
// colliders through the public C API.
#include <BulletCollision/CollisionShapes/btHeightfieldTerrainShape.h>
#include <cloth_bullet/cloth_bullet.h>

#include <cmath>

namespace cloth_bullet {
namespace {

// btHeightfieldTerrainShape keeps its grid size and triangulation flags
// protected and has no getters for them. A pointer to a member named through
// a derived class is a pointer to the base's member (well-defined C++), which
// reads them without copying or changing the shape.
struct HeightfieldFields : btHeightfieldTerrainShape {
    static constexpr int btHeightfieldTerrainShape::*kWidth = &HeightfieldFields::m_heightStickWidth;
    static constexpr int btHeightfieldTerrainShape::*kLength = &HeightfieldFields::m_heightStickLength;
    static constexpr bool btHeightfieldTerrainShape::*kFlip = &HeightfieldFields::m_flipQuadEdges;
    static constexpr bool btHeightfieldTerrainShape::*kDiamond = &HeightfieldFields::m_useDiamondSubdivision;
    static constexpr bool btHeightfieldTerrainShape::*kZigzag = &HeightfieldFields::m_useZigzagSubdivision;
};

// Every triangle of a concave shape, as a mesh (vertices not shared).
struct TriangleCollector : btTriangleCallback {
    ColliderSpec* spec;
    explicit TriangleCollector(ColliderSpec* s) : spec(s) {}
    void processTriangle(btVector3* triangle, int, int) override {
        const btVector3 n = (triangle[1] - triangle[0]).cross(triangle[2] - triangle[0]);
        if (!(n.length2() > 1e-20f)) return;  // the cloth library rejects degenerate triangles
        for (int k = 0; k < 3; ++k) {
            spec->indices.push_back(static_cast<uint32_t>(spec->points.size() / 3));
            spec->points.insert(spec->points.end(), {triangle[k].x(), triangle[k].y(), triangle[k].z()});
        }
    }
};

ColliderSpec all_triangles(const btConcaveShape& shape, const btTransform& local) {
    ColliderSpec spec;
    spec.kind = ColliderKind::kTriangleMesh;
    spec.local = local;
    btVector3 lo, hi;
    shape.getAabb(btTransform::getIdentity(), lo, hi);
    const btVector3 pad(1, 1, 1);
    TriangleCollector collector(&spec);
    shape.processAllTriangles(&collector, lo - pad, hi + pad);
    return spec;
}

float read_scalar(const unsigned char* base, PHY_ScalarType type) {
    return type == PHY_DOUBLE ? static_cast<float>(*reinterpret_cast<const double*>(base))
                              : *reinterpret_cast<const float*>(base);
}

uint32_t read_index(const unsigned char* base, PHY_ScalarType type, int k) {
    switch (type) {
        case PHY_SHORT:
            return reinterpret_cast<const unsigned short*>(base)[k];
        case PHY_UCHAR:
            return base[k];
        default:
            return static_cast<uint32_t>(reinterpret_cast<const int*>(base)[k]);
    }
}

// A btBvhTriangleMeshShape's mesh with its shared vertices, every subpart, scaled.
bool triangle_mesh(const btBvhTriangleMeshShape& shape, const btTransform& local, ColliderSpec* spec,
                   std::string* error) {
    const btStridingMeshInterface* mesh = shape.getMeshInterface();
    const btVector3 scale = mesh->getScaling();
    spec->kind = ColliderKind::kTriangleMesh;
    spec->local = local;
    for (int part = 0; part < mesh->getNumSubParts(); ++part) {
        const unsigned char *vertices = nullptr, *indices = nullptr;
        int vertex_count = 0, vertex_stride = 0, index_stride = 0, face_count = 0;
        PHY_ScalarType vertex_type, index_type;
        mesh->getLockedReadOnlyVertexIndexBase(&vertices, vertex_count, vertex_type, vertex_stride, &indices,
                                               index_stride, face_count, index_type, part);
        if ((vertex_type != PHY_FLOAT && vertex_type != PHY_DOUBLE) ||
            (index_type != PHY_INTEGER && index_type != PHY_SHORT && index_type != PHY_UCHAR)) {
            mesh->unLockReadOnlyVertexBase(part);
            *error = "btBvhTriangleMeshShape: unsupported vertex or index type";
            return false;
        }
        const uint32_t base = static_cast<uint32_t>(spec->points.size() / 3);
        const size_t scalar = vertex_type == PHY_DOUBLE ? sizeof(double) : sizeof(float);
        for (int v = 0; v < vertex_count; ++v) {
            const unsigned char* p = vertices + static_cast<size_t>(v) * vertex_stride;
            for (int k = 0; k < 3; ++k)
                spec->points.push_back(read_scalar(p + k * scalar, vertex_type) * scale[k]);
        }
        for (int f = 0; f < face_count; ++f) {
            const unsigned char* tri = indices + static_cast<size_t>(f) * index_stride;
            uint32_t corner[3];
            for (int k = 0; k < 3; ++k) corner[k] = base + read_index(tri, index_type, k);
            const float* a = &spec->points[3 * size_t{corner[0]}];
            const float* b = &spec->points[3 * size_t{corner[1]}];
            const float* c = &spec->points[3 * size_t{corner[2]}];
            const btVector3 n = (btVector3(b[0], b[1], b[2]) - btVector3(a[0], a[1], a[2]))
                                    .cross(btVector3(c[0], c[1], c[2]) - btVector3(a[0], a[1], a[2]));
            if (!(n.length2() > 1e-20f)) continue;  // degenerate: rejected by the cloth library
            spec->indices.insert(spec->indices.end(), corner, corner + 3);
        }
        mesh->unLockReadOnlyVertexBase(part);
    }
    return true;
}

ColliderSpec heightfield(const btHeightfieldTerrainShape& shape, const btTransform& local) {
    const bool plain = shape.getUpAxis() == 1 && !(shape.*HeightfieldFields::kFlip) &&
                       !(shape.*HeightfieldFields::kDiamond) && !(shape.*HeightfieldFields::kZigzag);
    if (!plain) return all_triangles(shape, local);
    ColliderSpec spec;
    spec.kind = ColliderKind::kHeightfield;
    spec.columns = static_cast<uint32_t>(shape.*HeightfieldFields::kWidth);
    spec.rows = static_cast<uint32_t>(shape.*HeightfieldFields::kLength);
    // getVertex gives each sample in the shape's frame (scaled, centred on
    // the bounds as Bullet places it); the cloth height field starts at its
    // first sample, so that sample's x and z become the collider's offset.
    btVector3 first, next_x, next_z, vertex;
    shape.getVertex(0, 0, first);
    shape.getVertex(1, 0, next_x);
    shape.getVertex(0, 1, next_z);
    spec.spacing_x = next_x.x() - first.x();
    spec.spacing_z = next_z.z() - first.z();
    spec.heights.resize(size_t{spec.columns} * spec.rows);
    for (uint32_t r = 0; r < spec.rows; ++r) {
        for (uint32_t c = 0; c < spec.columns; ++c) {
            shape.getVertex(static_cast<int>(c), static_cast<int>(r), vertex);
            spec.heights[size_t{r} * spec.columns + c] = vertex.y();
        }
    }
    btTransform offset = btTransform::getIdentity();
    offset.setOrigin(btVector3(first.x(), 0, first.z()));
    spec.local = local * offset;
    return spec;
}

}  // namespace

const char* collider_kind_name(ColliderKind kind) {
    switch (kind) {
        case ColliderKind::kSphere:
            return "sphere";
        case ColliderKind::kCapsule:
            return "capsule";
        case ColliderKind::kBox:
            return "box";
        case ColliderKind::kPlane:
            return "plane";
        case ColliderKind::kConvexHull:
            return "convex hull";
        case ColliderKind::kTriangleMesh:
            return "triangle mesh";
        case ColliderKind::kHeightfield:
            return "height field";
    }
    return "?";
}

void to_pose(const btTransform& transform, float position[3], float rotation[4]) {
    const btVector3& origin = transform.getOrigin();
    const btQuaternion q = transform.getRotation();
    for (int k = 0; k < 3; ++k) position[k] = origin[k];
    rotation[0] = q.x();
    rotation[1] = q.y();
    rotation[2] = q.z();
    rotation[3] = q.w();
}

bool describe_shape(const btCollisionShape& shape, const btTransform& local, std::vector<ColliderSpec>* out,
                    std::string* error) {
    ColliderSpec spec;
    spec.local = local;
    switch (shape.getShapeType()) {
        case SPHERE_SHAPE_PROXYTYPE:
            spec.kind = ColliderKind::kSphere;
            spec.radius = static_cast<const btSphereShape&>(shape).getRadius();
            break;
        case CAPSULE_SHAPE_PROXYTYPE: {
            const auto& capsule = static_cast<const btCapsuleShape&>(shape);
            spec.kind = ColliderKind::kCapsule;
            spec.radius = capsule.getRadius();
            spec.half_height = capsule.getHalfHeight();
            // The cloth capsule runs along local y; turn y onto Bullet's up axis.
            btTransform turn = btTransform::getIdentity();
            if (capsule.getUpAxis() == 0) turn.setRotation(btQuaternion(btVector3(0, 0, 1), -SIMD_HALF_PI));
            if (capsule.getUpAxis() == 2) turn.setRotation(btQuaternion(btVector3(1, 0, 0), SIMD_HALF_PI));
            spec.local = local * turn;
            break;
        }
        case BOX_SHAPE_PROXYTYPE:
            spec.kind = ColliderKind::kBox;
            spec.half_extents = static_cast<const btBoxShape&>(shape).getHalfExtentsWithMargin();
            break;
        case STATIC_PLANE_PROXYTYPE: {
            const auto& plane = static_cast<const btStaticPlaneShape&>(shape);
            spec.kind = ColliderKind::kPlane;
            spec.plane_normal = plane.getPlaneNormal();
            spec.plane_offset = plane.getPlaneConstant();
            break;
        }
        case CONVEX_HULL_SHAPE_PROXYTYPE: {
            const auto& hull = static_cast<const btConvexHullShape&>(shape);
            spec.kind = ColliderKind::kConvexHull;
            for (int i = 0; i < hull.getNumPoints(); ++i) {
                const btVector3 p = hull.getScaledPoint(i);
                spec.points.insert(spec.points.end(), {p.x(), p.y(), p.z()});
            }
            break;
        }
        case COMPOUND_SHAPE_PROXYTYPE: {
            const auto& compound = static_cast<const btCompoundShape&>(shape);
            std::vector<ColliderSpec> children;
            for (int i = 0; i < compound.getNumChildShapes(); ++i) {
                if (!describe_shape(*compound.getChildShape(i), local * compound.getChildTransform(i),
                                    &children, error)) {
                    *error = "btCompoundShape child " + std::to_string(i) + ": " + *error;
                    return false;
                }
            }
            out->insert(out->end(), children.begin(), children.end());
            return true;
        }
        case TRIANGLE_MESH_SHAPE_PROXYTYPE:
            if (!triangle_mesh(static_cast<const btBvhTriangleMeshShape&>(shape), local, &spec, error))
                return false;
            break;
        case TERRAIN_SHAPE_PROXYTYPE:
            spec = heightfield(static_cast<const btHeightfieldTerrainShape&>(shape), local);
            break;
        default:
            *error = std::string("Bullet shape '") + shape.getName() + "' has no cloth collider";
            return false;
    }
    out->push_back(std::move(spec));
    return true;
}

cloth_result create_collider(cloth_world_id world, const ColliderSpec& spec, cloth_body_id body,
                             uint32_t group_bits, cloth_collider_id* out_collider) {
    cloth_collider_desc desc = cloth_default_collider_desc();
    desc.body = body;
    desc.group_bits = group_bits;
    to_pose(spec.local, desc.local_position, desc.local_rotation);
    switch (spec.kind) {
        case ColliderKind::kSphere:
            return cloth_collider_create_sphere(world, &desc, spec.radius, out_collider);
        case ColliderKind::kCapsule:
            return cloth_collider_create_capsule(world, &desc, spec.radius, spec.half_height, out_collider);
        case ColliderKind::kBox: {
            const float half[3] = {spec.half_extents.x(), spec.half_extents.y(), spec.half_extents.z()};
            return cloth_collider_create_box(world, &desc, half, out_collider);
        }
        case ColliderKind::kPlane: {
            const float normal[3] = {spec.plane_normal.x(), spec.plane_normal.y(), spec.plane_normal.z()};
            return cloth_collider_create_plane(world, &desc, normal, spec.plane_offset, out_collider);
        }
        case ColliderKind::kConvexHull:
            return cloth_collider_create_convex_hull(world, &desc, spec.points.data(),
                                                     static_cast<uint32_t>(spec.points.size() / 3),
                                                     out_collider);
        case ColliderKind::kTriangleMesh:
            return cloth_collider_create_triangle_mesh(
                world, &desc, spec.points.data(), static_cast<uint32_t>(spec.points.size() / 3),
                spec.indices.data(), static_cast<uint32_t>(spec.indices.size() / 3), out_collider);
        case ColliderKind::kHeightfield: {
            cloth_heightfield_desc field = cloth_default_heightfield_desc();
            field.columns = spec.columns;
            field.rows = spec.rows;
            field.spacing_x = spec.spacing_x;
            field.spacing_z = spec.spacing_z;
            field.heights = spec.heights.data();
            return cloth_collider_create_heightfield(world, &desc, &field, out_collider);
        }
    }
    return CLOTH_ERROR_INVALID_VALUE;
}

}  // namespace cloth_bullet
