// C API: character cloth (cloth.h section "Character cloth"): a cloth's
// skin, its joint matrices or host-skinned positions, max distances and
// backstops. Every argument is checked before anything changes.
#include <cloth/cloth.h>

#include <cmath>

#include "api_call.h"
#include "api_validation.h"

using namespace cloth;
using namespace cloth::api;

namespace {

// How far a particle's weights may sum from 1.
constexpr float kWeightSumTolerance = 1e-3f;

Status check_particle_count(uint32_t count, const ClothInstance& cloth, const char* what) {
    if (count != cloth.particle_count()) {
        return Status::error(CLOTH_ERROR_INVALID_COUNT, "%s is %u, but the cloth has %u particles", what,
                             count, cloth.particle_count());
    }
    return {};
}

Status check_skin(const cloth_skin_desc& d, const ClothInstance& cloth) {
    Status s = check_particle_count(d.particle_count, cloth, "particle_count");
    if (!s.ok()) return s;
    if (d.joint_count == 0 || d.joint_count > CLOTH_MAX_JOINTS) {
        return Status::error(CLOTH_ERROR_INVALID_COUNT, "joint_count %u is not in 1..%u", d.joint_count,
                             static_cast<uint32_t>(CLOTH_MAX_JOINTS));
    }
    if (d.influences == 0 || d.influences > Skin::kMaxInfluences) {
        return Status::error(CLOTH_ERROR_INVALID_COUNT, "influences %u is not in 1..%u", d.influences,
                             Skin::kMaxInfluences);
    }
    if (!d.joints) return null_error("joints");
    if (!d.weights && d.influences != 1) return null_error("weights (influences above 1)");
    const size_t entries = size_t{d.particle_count} * d.influences;
    for (size_t e = 0; e < entries; ++e) {
        if (d.joints[e] >= d.joint_count) {
            return Status::error(CLOTH_ERROR_INDEX_OUT_OF_RANGE, "joints[%zu] is %u, but joint_count is %u",
                                 e, d.joints[e], d.joint_count);
        }
    }
    if (!d.weights) return {};
    for (uint32_t i = 0; i < d.particle_count; ++i) {
        double sum = 0.0;
        for (uint32_t k = 0; k < d.influences; ++k) {
            const size_t e = size_t{i} * d.influences + k;
            if (!std::isfinite(d.weights[e]))
                return Status::error(CLOTH_ERROR_NOT_FINITE, "weights[%zu] is not finite", e);
            if (d.weights[e] < 0.0f)
                return Status::error(CLOTH_ERROR_INVALID_VALUE, "weights[%zu] is negative", e);
            sum += d.weights[e];
        }
        if (std::fabs(sum - 1.0) > kWeightSumTolerance) {
            return Status::error(CLOTH_ERROR_INVALID_VALUE,
                                 "weights of vertex %u sum to %g, not to 1 within %g", i, sum,
                                 static_cast<double>(kWeightSumTolerance));
        }
    }
    return {};
}

Status check_has_skin(const ClothInstance& cloth) {
    if (cloth.skin().active()) return {};
    return Status::error(CLOTH_ERROR_INVALID_VALUE,
                         "the cloth has no skin: call cloth_set_skin or cloth_set_skinned_positions first");
}

}  // namespace

extern "C" {

CLOTH_API cloth_skin_desc cloth_default_skin_desc(void) {
    cloth_skin_desc d{};
    d.struct_size = sizeof(cloth_skin_desc);
    d.influences = 1;
    d.internal_cookie = kCookie;
    return d;
}

CLOTH_API cloth_result cloth_set_skin(cloth_id id, const cloth_skin_desc* desc) {
    return with_cloth(__func__, id, [&](ClothInstance& cloth) -> Status {
        if (!desc) return null_error("desc");
        Status s =
            check_desc(desc->struct_size, sizeof(cloth_skin_desc), desc->internal_cookie, "cloth_skin_desc");
        if (s.ok()) s = check_skin(*desc, cloth);
        if (!s.ok()) return s;
        // By particle: the host's arrays are by vertex.
        const uint32_t n = cloth.particle_count(), m = desc->influences;
        const Fabric& fabric = cloth.fabric();
        HostVector<uint32_t> joints(size_t{n} * m, 0u, HostAllocator<uint32_t>(fabric.memory));
        HostVector<float> weights(desc->weights ? size_t{n} * m : 0, 0.0f,
                                  HostAllocator<float>(fabric.memory));
        for (uint32_t v = 0; v < n; ++v) {
            const uint32_t p = fabric.particle(v);
            for (uint32_t k = 0; k < m; ++k) {
                joints[size_t{p} * m + k] = desc->joints[size_t{v} * m + k];
                if (desc->weights) weights[size_t{p} * m + k] = desc->weights[size_t{v} * m + k];
            }
        }
        cloth.bind_skin(desc->joint_count, m, joints.data(), desc->weights ? weights.data() : nullptr);
        return {};
    });
}

CLOTH_API cloth_result cloth_set_joint_matrices(cloth_id id, const float* matrices, uint32_t matrix_count,
                                                cloth_matrix_layout layout) {
    return with_cloth(__func__, id, [&](ClothInstance& cloth) -> Status {
        if (!matrices) return null_error("matrices");
        const int32_t l = enum_bits(layout);
        if (l != CLOTH_MATRIX_COLUMN_MAJOR_4X4 && l != CLOTH_MATRIX_ROW_MAJOR_3X4)
            return Status::error(CLOTH_ERROR_INVALID_VALUE, "layout %d is not a cloth_matrix_layout", l);
        const uint32_t joints = cloth.skin().joint_count();
        if (joints == 0 || cloth.skin().source() == Skin::Source::kNone)
            return Status::error(CLOTH_ERROR_INVALID_VALUE,
                                 "the cloth has no joints: call cloth_set_skin first");
        if (matrix_count < joints) {
            return Status::error(CLOTH_ERROR_INVALID_COUNT,
                                 "matrix_count %u is less than the skin's joint_count %u", matrix_count,
                                 joints);
        }
        const uint32_t stride = l == CLOTH_MATRIX_COLUMN_MAJOR_4X4 ? 16 : 12;
        for (size_t f = 0; f < size_t{joints} * stride; ++f) {
            if (!std::isfinite(matrices[f]))
                return Status::error(CLOTH_ERROR_NOT_FINITE, "matrices[%zu] is not finite", f);
        }
        cloth.set_joint_matrices(matrices, l == CLOTH_MATRIX_COLUMN_MAJOR_4X4);
        return {};
    });
}

CLOTH_API cloth_result cloth_set_skinned_positions(cloth_id id, const float* positions_xyz,
                                                   const float* normals_xyz, uint32_t count) {
    return with_cloth(__func__, id, [&](ClothInstance& cloth) -> Status {
        Status s = check_particle_count(count, cloth, "count");
        if (s.ok()) s = check_points(positions_xyz, count, "positions_xyz");
        if (s.ok() && !normals_xyz) s = null_error("normals_xyz");
        if (!s.ok()) return s;
        for (uint32_t v = 0; v < count; ++v) {
            const float* n = normals_xyz + 3 * size_t{v};
            if (!finite3(n)) return Status::error(CLOTH_ERROR_NOT_FINITE, "normals_xyz[%u] is not finite", v);
            if (!(Vec3(n[0], n[1], n[2]).norm() > 1e-6f))
                return Status::error(CLOTH_ERROR_INVALID_VALUE,
                                     "normals_xyz[%u] has a length of 1e-6 or less", v);
        }
        cloth.set_skinned(positions_xyz, normals_xyz);
        return {};
    });
}

CLOTH_API cloth_result cloth_read_skinned_positions(cloth_id id, float* out_positions_xyz,
                                                    float* out_normals_xyz, uint32_t capacity) {
    return with_cloth(__func__, id, [&](ClothInstance& cloth) -> Status {
        const size_t needed = 3 * static_cast<size_t>(cloth.particle_count());
        Status s = check_capacity(out_positions_xyz, capacity, needed);
        if (!s.ok()) return s;
        if (!cloth.skin().active() || !cloth.skin().primed())
            return Status::error(CLOTH_ERROR_INVALID_VALUE, "no step has skinned the cloth yet");
        const Fabric& fabric = cloth.fabric();
        for (uint32_t v = 0; v < cloth.particle_count(); ++v) {
            const uint32_t p = fabric.particle(v);
            const Vec3 x = cloth.skin().position(p, 1.0f), n = cloth.skin().normal(p, 1.0f);
            for (int c = 0; c < 3; ++c) {
                out_positions_xyz[3 * size_t{v} + c] = x[c];
                if (out_normals_xyz) out_normals_xyz[3 * size_t{v} + c] = n[c];
            }
        }
        return {};
    });
}

CLOTH_API cloth_result cloth_set_max_distances(cloth_id id, const float* distances, uint32_t count) {
    return with_cloth(__func__, id, [&](ClothInstance& cloth) -> Status {
        if (!distances) return null_error("distances");
        Status s = check_particle_count(count, cloth, "count");
        if (s.ok()) s = check_has_skin(cloth);
        if (!s.ok()) return s;
        const Fabric& fabric = cloth.fabric();
        for (uint32_t v = 0; v < count; ++v) {
            if (std::isnan(distances[v]))
                return Status::error(CLOTH_ERROR_NOT_FINITE, "distances[%u] is NaN", v);
            if (distances[v] < 0.0f)
                return Status::error(CLOTH_ERROR_INVALID_VALUE, "distances[%u] is negative", v);
            if (distances[v] == 0.0f && cloth.contact().is_attached(fabric.particle(v))) {
                return Status::error(CLOTH_ERROR_INVALID_VALUE,
                                     "distances[%u] is 0, but that particle is attached to a body", v);
            }
        }
        HostVector<float> by_particle(count, 0.0f, HostAllocator<float>(fabric.memory));
        for (uint32_t v = 0; v < count; ++v) by_particle[fabric.particle(v)] = distances[v];
        cloth.set_max_distances(by_particle.data());
        return {};
    });
}

CLOTH_API cloth_result cloth_set_backstops(cloth_id id, const float* distances, const float* radii,
                                           uint32_t count) {
    return with_cloth(__func__, id, [&](ClothInstance& cloth) -> Status {
        if (!distances) return null_error("distances");
        if (!radii) return null_error("radii");
        Status s = check_particle_count(count, cloth, "count");
        if (s.ok()) s = check_has_skin(cloth);
        if (!s.ok()) return s;
        for (uint32_t v = 0; v < count; ++v) {
            if (!std::isfinite(distances[v]))
                return Status::error(CLOTH_ERROR_NOT_FINITE, "distances[%u] is not finite", v);
            if (!std::isfinite(radii[v]))
                return Status::error(CLOTH_ERROR_NOT_FINITE, "radii[%u] is not finite", v);
            if (distances[v] < 0.0f || radii[v] < 0.0f) {
                return Status::error(CLOTH_ERROR_INVALID_VALUE, "distances[%u] or radii[%u] is negative", v,
                                     v);
            }
            if (radii[v] == 0.0f && distances[v] > 0.0f) {
                return Status::error(CLOTH_ERROR_INVALID_VALUE,
                                     "radii[%u] is 0 with distances[%u] above 0 (a backstop needs a radius)",
                                     v, v);
            }
        }
        const Fabric& fabric = cloth.fabric();
        HostVector<float> d(count, 0.0f, HostAllocator<float>(fabric.memory)), r(d.get_allocator());
        r.assign(count, 0.0f);
        for (uint32_t v = 0; v < count; ++v) {
            d[fabric.particle(v)] = distances[v];
            r[fabric.particle(v)] = radii[v];
        }
        cloth.set_backstops(d.data(), r.data());
        return {};
    });
}

}  // extern "C"
