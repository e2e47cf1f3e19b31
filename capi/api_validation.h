// Argument checks and conversions shared by the C API's files. Each check
// returns a Status naming the bad argument; none changes anything.
#pragma once

#include <cloth/cloth.h>

#include <cmath>
#include <cstdio>
#include <cstring>

#include "api_call.h"
#include "forces/aerodynamics.h"
#include "forces/material.h"
#include "solve/solver_settings.h"

namespace cloth::api {
// ---------------------------------------------------------------- validation

// The integer a host passed in an enum-typed argument or field. A C caller
// may pass any int there, and in C++ loading an enum object that holds a
// value outside its enumerators is undefined, so checks read the bits.
template <class Enum>
int32_t enum_bits(const Enum& value) {
    static_assert(sizeof(Enum) == sizeof(int32_t), "C enums are int-sized");
    int32_t bits;
    std::memcpy(&bits, &value, sizeof bits);
    return bits;
}

inline bool finite3(const float* v) {
    return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}

// A coordinate, offset or length that places something in the world:
// finite (else CLOTH_ERROR_NOT_FINITE) and within CLOTH_MAX_COORDINATE
// (else CLOTH_ERROR_INVALID_VALUE), cloth.h "Coordinates".
inline Status check_coordinate(float value, const char* what) {
    if (!std::isfinite(value)) return Status::error(CLOTH_ERROR_NOT_FINITE, "%s is not finite", what);
    if (std::abs(value) > CLOTH_MAX_COORDINATE) {
        return Status::error(CLOTH_ERROR_INVALID_VALUE, "%s = %g is beyond CLOTH_MAX_COORDINATE (%g m)", what,
                             double(value), double(CLOTH_MAX_COORDINATE));
    }
    return {};
}

// The same for the three coordinates of a point.
inline Status check_coordinates(const float* v, const char* what) {
    if (!finite3(v)) return Status::error(CLOTH_ERROR_NOT_FINITE, "%s is not finite", what);
    for (int k = 0; k < 3; ++k) {
        if (std::abs(v[k]) > CLOTH_MAX_COORDINATE) {
            return Status::error(CLOTH_ERROR_INVALID_VALUE,
                                 "%s[%d] = %g is beyond CLOTH_MAX_COORDINATE (%g m)", what, k, double(v[k]),
                                 double(CLOTH_MAX_COORDINATE));
        }
    }
    return {};
}

inline Status check_desc(uint32_t struct_size, size_t expected, uint32_t cookie, const char* what) {
    if (cookie != kCookie) {
        return Status::error(CLOTH_ERROR_INVALID_DESC,
                             "%s was not initialised by its cloth_default_*() function", what);
    }
    if (struct_size != expected) {
        return Status::error(CLOTH_ERROR_INVALID_DESC, "%s.struct_size is %u, expected %zu", what,
                             struct_size, expected);
    }
    return {};
}

inline Status check_finite(float value, const char* what) {
    if (!std::isfinite(value)) return Status::error(CLOTH_ERROR_NOT_FINITE, "%s is not finite", what);
    return {};
}

// A non-negative finite parameter.
inline Status check_non_negative(float value, const char* what) {
    if (!std::isfinite(value)) return Status::error(CLOTH_ERROR_NOT_FINITE, "%s is not finite", what);
    if (value < 0)
        return Status::error(CLOTH_ERROR_INVALID_VALUE, "%s is negative (%g)", what, double(value));
    return {};
}

inline Status check_spring_params(const cloth_spring_params& p, const char* what) {
    char name[64];
    std::snprintf(name, sizeof name, "%s stiffness", what);
    Status s = check_non_negative(p.stiffness, name);
    if (!s.ok()) return s;
    std::snprintf(name, sizeof name, "%s damping", what);
    return check_non_negative(p.damping, name);
}

inline Status check_solver(const cloth_solver_settings& s) {
    if (s.struct_size != sizeof(cloth_solver_settings)) {
        return Status::error(CLOTH_ERROR_INVALID_DESC,
                             "cloth_solver_settings.struct_size is %u, expected %zu", s.struct_size,
                             sizeof(cloth_solver_settings));
    }
    const int32_t kind = enum_bits(s.kind);
    if (kind != CLOTH_SOLVER_DEFAULT && kind != CLOTH_SOLVER_JACOBI && kind != CLOTH_SOLVER_CG &&
        kind != CLOTH_SOLVER_EXPLICIT && kind != CLOTH_SOLVER_PCG && kind != CLOTH_SOLVER_CHEBYSHEV) {
        return Status::error(CLOTH_ERROR_INVALID_VALUE, "unknown solver kind %d", kind);
    }
    if (s.iterations < 1 || s.iterations > CLOTH_MAX_ITERATIONS) {
        return Status::error(CLOTH_ERROR_INVALID_VALUE, "iterations %u is not in 1..256", s.iterations);
    }
    if (s.substeps < 1 || s.substeps > CLOTH_MAX_SUBSTEPS) {
        return Status::error(CLOTH_ERROR_INVALID_VALUE, "substeps %u is not in 1..64", s.substeps);
    }
    if (!std::isfinite(s.cg_tolerance))
        return Status::error(CLOTH_ERROR_NOT_FINITE, "cg_tolerance is not finite");
    if (!(s.cg_tolerance > 0 && s.cg_tolerance < 1)) {
        return Status::error(CLOTH_ERROR_INVALID_VALUE, "cg_tolerance %g is not in (0, 1)",
                             double(s.cg_tolerance));
    }
    if (s.cg_max_iterations < 1 || s.cg_max_iterations > CLOTH_MAX_CG_ITERATIONS) {
        return Status::error(CLOTH_ERROR_INVALID_VALUE, "cg_max_iterations %u is not in 1..100000",
                             s.cg_max_iterations);
    }
    return {};
}

inline Status check_strain_limit(const cloth_strain_limit& l) {
    if (l.struct_size != sizeof(cloth_strain_limit)) {
        return Status::error(CLOTH_ERROR_INVALID_DESC, "cloth_strain_limit.struct_size is %u, expected %zu",
                             l.struct_size, sizeof(cloth_strain_limit));
    }
    Status s = check_non_negative(l.max_strain, "max_strain");
    if (!s.ok()) return s;
    if (l.iterations < 1 || l.iterations > CLOTH_MAX_STRAIN_LIMIT_ITERATIONS) {
        return Status::error(CLOTH_ERROR_INVALID_VALUE, "strain limit iterations %u is not in 1..64",
                             l.iterations);
    }
    return {};
}

inline Status check_aero(const cloth_aero_params& a) {
    if (!finite3(a.wind)) return Status::error(CLOTH_ERROR_NOT_FINITE, "wind is not finite");
    Status s = check_non_negative(a.air_density, "air_density");
    if (s.ok()) s = check_non_negative(a.drag_coefficient, "drag_coefficient");
    if (s.ok()) s = check_non_negative(a.lift_coefficient, "lift_coefficient");
    if (s.ok()) s = check_non_negative(a.linear_drag, "linear_drag");
    return s;
}

inline Status check_indices(const uint32_t* indices, uint32_t count, uint32_t particle_count) {
    if (!indices) return null_error("indices");
    if (count == 0 || count > particle_count) {
        return Status::error(CLOTH_ERROR_INVALID_COUNT, "count %u is not in 1..%u", count, particle_count);
    }
    for (uint32_t k = 0; k < count; ++k) {
        if (indices[k] >= particle_count) {
            return Status::error(CLOTH_ERROR_INDEX_OUT_OF_RANGE,
                                 "indices[%u] = %u, but the cloth has %u particles", k, indices[k],
                                 particle_count);
        }
    }
    return {};
}

// `count` points that place something in the world: every one finite
// (CLOTH_ERROR_NOT_FINITE, before any range is looked at) and within
// CLOTH_MAX_COORDINATE (CLOTH_ERROR_INVALID_VALUE).
inline Status check_points(const float* xyz, uint32_t count, const char* what) {
    if (!xyz) return null_error(what);
    for (uint32_t k = 0; k < count; ++k) {
        if (!finite3(xyz + 3 * k))
            return Status::error(CLOTH_ERROR_NOT_FINITE, "%s[%u] is not finite", what, k);
    }
    for (uint32_t k = 0; k < count; ++k) {
        char name[64];
        std::snprintf(name, sizeof name, "%s[%u]", what, k);
        Status s = check_coordinates(xyz + 3 * k, name);
        if (!s.ok()) return s;
    }
    return {};
}

// A unit quaternion (x, y, z, w) within 1e-2, normalised into *out.
inline Status check_rotation(const float* q, const char* what, Quat* out) {
    if (!q) return null_error(what);
    for (int k = 0; k < 4; ++k) {
        if (!std::isfinite(q[k])) return Status::error(CLOTH_ERROR_NOT_FINITE, "%s is not finite", what);
    }
    const float length = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (std::abs(length - 1.0f) > 1e-2f) {
        return Status::error(CLOTH_ERROR_INVALID_VALUE,
                             "%s has length %g; a unit quaternion (x, y, z, w) is needed", what,
                             double(length));
    }
    *out = Quat(q[3], q[0], q[1], q[2]).normalized();
    return {};
}

inline Status check_vector(const float* v, const char* what, Vec3* out) {
    if (!v) return null_error(what);
    if (!finite3(v)) return Status::error(CLOTH_ERROR_NOT_FINITE, "%s is not finite", what);
    *out = Vec3(v[0], v[1], v[2]);
    return {};
}

// A vector that places something (a position, an offset, extents): as
// check_vector, and within CLOTH_MAX_COORDINATE.
inline Status check_position(const float* v, const char* what, Vec3* out) {
    if (!v) return null_error(what);
    Status s = check_coordinates(v, what);
    if (s.ok()) *out = Vec3(v[0], v[1], v[2]);
    return s;
}

// Every non-finite value of a pose is CLOTH_ERROR_NOT_FINITE before any
// range error of the other part.
inline Status check_pose(const float* position, const float* rotation, const char* position_name,
                         const char* rotation_name, Pose* out) {
    if (!position) return null_error(position_name);
    if (!rotation) return null_error(rotation_name);
    if (!finite3(position)) return Status::error(CLOTH_ERROR_NOT_FINITE, "%s is not finite", position_name);
    for (int k = 0; k < 4; ++k) {
        if (!std::isfinite(rotation[k]))
            return Status::error(CLOTH_ERROR_NOT_FINITE, "%s is not finite", rotation_name);
    }
    Status s = check_position(position, position_name, &out->position);
    if (s.ok()) s = check_rotation(rotation, rotation_name, &out->rotation);
    return s;
}

inline Status check_capacity(const void* out, uint32_t capacity, size_t needed) {
    if (!out) return null_error("output buffer");
    if (capacity < needed) {
        return Status::error(CLOTH_ERROR_INVALID_COUNT, "capacity %u is less than the %zu values needed",
                             capacity, needed);
    }
    return {};
}

// The fields cloth_solver_settings carries, written over `core`'s (the
// rest, the strain limit, has its own call). CLOTH_SOLVER_DEFAULT stays as
// it is: the core resolves it per step from gamma (src/solve/solver_default.h).
inline SolverSettings to_core(const cloth_solver_settings& s, SolverSettings core = {}) {
    core.kind = s.kind;
    core.iterations = s.iterations;
    core.substeps = s.substeps;
    core.cg_tolerance = s.cg_tolerance;
    core.cg_max_iterations = s.cg_max_iterations;
    core.compression_safe_jacobian = s.compression_safe_jacobian != 0;
    return core;
}

inline AeroParams to_core(const cloth_aero_params& a) {
    AeroParams out;
    out.wind = Vec3(a.wind[0], a.wind[1], a.wind[2]);
    out.air_density = a.air_density;
    out.drag_coefficient = a.drag_coefficient;
    out.lift_coefficient = a.lift_coefficient;
    out.linear_drag = a.linear_drag;
    return out;
}

// Per-particle vectors out in the host's vertex order.
inline void copy_out(const Vec3Soa& values, const Fabric& fabric, float* out) {
    for (uint32_t i = 0; i < static_cast<uint32_t>(values.size()); ++i) {
        const size_t v = fabric.vertex(i);
        out[3 * v] = values.x[i];
        out[3 * v + 1] = values.y[i];
        out[3 * v + 2] = values.z[i];
    }
}

}  // namespace cloth::api
