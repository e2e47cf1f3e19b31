// The "nothing changed" contract of the C API (see contract.h).
#include "support/contract.h"

#include <cstring>
#include <sstream>
#include <thread>

namespace cloth_test {
namespace {

constexpr int kLastResultCode = CLOTH_ERROR_CORRUPT_SNAPSHOT;

template <typename T>
std::string str(const T& value) {
    std::ostringstream out;
    out << value;
    return out.str();
}

template <typename T>
bool same_bits(const T& a, const T& b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

// A settings or stats struct read through its getter: zeroed, struct_size set.
template <class T, class Id>
cloth_result read_struct(cloth_result (*get)(Id, T*), Id id, T& out) {
    std::memset(&out, 0, sizeof out);
    out.struct_size = sizeof out;
    return get(id, &out);
}

std::string read_failed(const char* call, cloth_result r) {
    return std::string(call) + " failed while reading the state: " + result_name(r) + " " +
           cloth_get_last_error();
}

template <typename T>
std::string field_difference(const char* what, const T& a, const T& b) {
    if (same_bits(a, b)) return "";
    return std::string(what) + " was " + str(+a) + ", now " + str(+b);
}

}  // namespace

std::string result_name(cloth_result result) {
    const char* name = cloth_result_name(result);
    return std::string(name ? name : "<NULL name>") + " (" + str(static_cast<int>(result)) + ")";
}

std::string float_difference(const char* what, const std::vector<float>& a, const std::vector<float>& b) {
    if (a.size() != b.size()) return std::string(what) + ": sizes differ";
    for (size_t i = 0; i < a.size(); ++i) {
        if (!same_bits(a[i], b[i])) {
            return std::string(what) + "[" + str(i / 3) + "]." + "xyz"[i % 3] + " was " + str(a[i]) +
                   ", now " + str(b[i]);
        }
    }
    return "";
}

std::string read_cloth_state(cloth_id cloth, ClothState* out) {
    ClothState& s = *out;
    cloth_result r = cloth_get_particle_count(cloth, &s.count);
    if (r != CLOTH_OK) return read_failed("cloth_get_particle_count", r);
    const uint32_t floats = 3 * s.count;
    s.positions.assign(floats, 0.0f);
    s.velocities.assign(floats, 0.0f);
    s.normals.assign(floats, 0.0f);
    if ((r = cloth_read_positions(cloth, s.positions.data(), floats)) != CLOTH_OK)
        return read_failed("cloth_read_positions", r);
    if ((r = cloth_read_velocities(cloth, s.velocities.data(), floats)) != CLOTH_OK)
        return read_failed("cloth_read_velocities", r);
    if ((r = cloth_read_normals(cloth, s.normals.data(), floats)) != CLOTH_OK)
        return read_failed("cloth_read_normals", r);
    s.masses.assign(s.count, 0.0f);
    if ((r = cloth_read_particle_masses(cloth, s.masses.data(), s.count)) != CLOTH_OK)
        return read_failed("cloth_read_particle_masses", r);
    s.pinned.assign(s.count, 0);
    s.attached_to.assign(s.count, cloth_body_id{});
    s.attach_offsets.assign(floats, 0.0f);
    for (uint32_t i = 0; i < s.count; ++i) {
        if ((r = read_flag(cloth_is_pinned, cloth, i, &s.pinned[i])) != CLOTH_OK)
            return read_failed("cloth_is_pinned", r);
        if ((r = cloth_get_attachment(cloth, i, &s.attached_to[i], &s.attach_offsets[3 * size_t{i}])) !=
            CLOTH_OK)
            return read_failed("cloth_get_attachment", r);
    }
    if ((r = read_struct(cloth_get_solver, cloth, s.solver)) != CLOTH_OK)
        return read_failed("cloth_get_solver", r);
    if ((r = read_struct(cloth_get_strain_limit, cloth, s.strain_limit)) != CLOTH_OK)
        return read_failed("cloth_get_strain_limit", r);
    if ((r = read_struct(cloth_get_stats, cloth, s.stats)) != CLOTH_OK)
        return read_failed("cloth_get_stats", r);
    if ((r = read_struct(cloth_get_collision, cloth, s.collision)) != CLOTH_OK)
        return read_failed("cloth_get_collision", r);
    if ((r = read_struct(cloth_get_self_collision, cloth, s.self_collision)) != CLOTH_OK)
        return read_failed("cloth_get_self_collision", r);
    if ((r = read_flag(cloth_get_teleported, cloth, &s.teleported)) != CLOTH_OK)
        return read_failed("cloth_get_teleported", r);
    if ((r = read_flag(cloth_is_sleeping, cloth, &s.sleeping)) != CLOTH_OK)
        return read_failed("cloth_is_sleeping", r);
    if ((r = cloth_get_importance(cloth, &s.importance)) != CLOTH_OK)
        return read_failed("cloth_get_importance", r);
    if ((r = cloth_get_update_rate(cloth, &s.update_rate, &s.update_phase)) != CLOTH_OK)
        return read_failed("cloth_get_update_rate", r);
    size_t bytes = 0;
    if ((r = cloth_get_snapshot_size(cloth, &bytes)) != CLOTH_OK)
        return read_failed("cloth_get_snapshot_size", r);
    s.snapshot.assign(bytes, 0);
    if ((r = cloth_save_snapshot(cloth, s.snapshot.data(), bytes)) != CLOTH_OK)
        return read_failed("cloth_save_snapshot", r);
    return "";
}

std::string read_body_state(cloth_body_id body, BodyState* out) {
    const cloth_result r = cloth_body_get_pose(body, out->position, out->rotation);
    return r == CLOTH_OK ? "" : read_failed("cloth_body_get_pose", r);
}

std::string first_difference(const ClothState& a, const ClothState& b, Compare compare) {
    if (a.count != b.count) return "particle count was " + str(a.count) + ", now " + str(b.count);
    for (const std::string& d : {float_difference("position", a.positions, b.positions),
                                 float_difference("velocity", a.velocities, b.velocities),
                                 float_difference("normal", a.normals, b.normals),
                                 float_difference("attachment offset", a.attach_offsets, b.attach_offsets)}) {
        if (!d.empty()) return d;
    }
    for (uint32_t i = 0; i < a.count; ++i) {
        if (!same_bits(a.masses[i], b.masses[i]))
            return "mass of particle " + str(i) + " was " + str(a.masses[i]) + ", now " + str(b.masses[i]);
        if (a.pinned[i] != b.pinned[i]) {
            return "pin state of particle " + str(i) + " was " + str(int(a.pinned[i])) + ", now " +
                   str(int(b.pinned[i]));
        }
        const cloth_body_id& x = a.attached_to[i];
        const cloth_body_id& y = b.attached_to[i];
        if (x.index1 != y.index1 || x.generation != y.generation ||
            (compare.world_of_body_ids &&
             (x.world1 != y.world1 || x.world_generation != y.world_generation))) {
            return "body of particle " + str(i) + " was index1 " + str(x.index1) + ", now " + str(y.index1);
        }
    }
    const cloth_solver_settings& s = a.solver;
    const cloth_solver_settings& t = b.solver;
    for (const std::string& d :
         {field_difference("solver kind", static_cast<int>(s.kind), static_cast<int>(t.kind)),
          field_difference("solver iterations", s.iterations, t.iterations),
          field_difference("solver substeps", s.substeps, t.substeps),
          field_difference("solver cg_tolerance", s.cg_tolerance, t.cg_tolerance),
          field_difference("solver cg_max_iterations", s.cg_max_iterations, t.cg_max_iterations),
          field_difference("solver compression_safe_jacobian", int(s.compression_safe_jacobian),
                           int(t.compression_safe_jacobian)),
          field_difference("strain limit max_strain", a.strain_limit.max_strain, b.strain_limit.max_strain),
          field_difference("strain limit iterations", a.strain_limit.iterations,
                           b.strain_limit.iterations)}) {
        if (!d.empty()) return d;
    }
    const cloth_stats& u = a.stats;
    const cloth_stats& v = b.stats;
    for (const std::string& d : {field_difference("kinetic energy", u.kinetic_energy, v.kinetic_energy),
                                 field_difference("gravity energy", u.gravity_energy, v.gravity_energy),
                                 field_difference("elastic energy", u.elastic_energy, v.elastic_energy),
                                 field_difference("max strain", u.max_strain, v.max_strain),
                                 field_difference("mean strain", u.mean_strain, v.mean_strain),
                                 field_difference("max speed", u.max_speed, v.max_speed)}) {
        if (!d.empty()) return d;
    }
    if (compare.step_diagnostics) {
        for (const std::string& d :
             {field_difference("last_solver_iterations", u.last_solver_iterations, v.last_solver_iterations),
              field_difference("last_solver_residual", u.last_solver_residual, v.last_solver_residual)}) {
            if (!d.empty()) return d;
        }
        if (u.last_step_result != v.last_step_result) {
            return "last_step_result was " + result_name(u.last_step_result) + ", now " +
                   result_name(v.last_step_result);
        }
    }
    const cloth_self_collision_desc& p = a.self_collision;
    const cloth_self_collision_desc& q = b.self_collision;
    for (const std::string& d :
         {field_difference("collision thickness", a.collision.thickness, b.collision.thickness),
          field_difference("collision friction", a.collision.friction, b.collision.friction),
          field_difference("collision collider_mask", a.collision.collider_mask, b.collision.collider_mask),
          field_difference("self-collision enabled", int(p.enabled), int(q.enabled)),
          field_difference("self-collision thickness", p.thickness, q.thickness),
          field_difference("self-collision friction", p.friction, q.friction),
          field_difference("self-collision use_regions", int(p.use_regions), int(q.use_regions)),
          field_difference("self-collision passes", p.passes, q.passes),
          field_difference("teleported flag", int(a.teleported), int(b.teleported)),
          field_difference("sleeping flag", int(a.sleeping), int(b.sleeping)),
          field_difference("importance", a.importance, b.importance),
          field_difference("update rate", a.update_rate, b.update_rate),
          field_difference("update phase", a.update_phase, b.update_phase)}) {
        if (!d.empty()) return d;
    }
    if (a.snapshot != b.snapshot) {
        return "the snapshot (pin targets, air, wind, sleep state) differs (" + str(a.snapshot.size()) +
               " bytes, now " + str(b.snapshot.size()) + ")";
    }
    return "";
}

std::string first_difference(const BodyState& a, const BodyState& b) {
    for (int k = 0; k < 3; ++k) {
        std::string d = field_difference("body position", a.position[k], b.position[k]);
        if (!d.empty()) return d;
    }
    for (int k = 0; k < 4; ++k) {
        std::string d = field_difference("body rotation", a.rotation[k], b.rotation[k]);
        if (!d.empty()) return d;
    }
    return "";
}

Unchanged::Unchanged(const Watch& watch, Compare compare) : watch_(watch), compare_(compare) {
    before_ = capture();
}

Unchanged::Captured Unchanged::capture() const {
    Captured c;
    c.cloths.resize(watch_.cloths.size());
    for (size_t i = 0; i < watch_.cloths.size() && c.read_error.empty(); ++i)
        c.read_error = read_cloth_state(watch_.cloths[i], &c.cloths[i]);
    c.bodies.resize(watch_.bodies.size());
    for (size_t i = 0; i < watch_.bodies.size() && c.read_error.empty(); ++i)
        c.read_error = read_body_state(watch_.bodies[i], &c.bodies[i]);
    if (watch_.memory != nullptr) {
        c.live_bytes = watch_.memory->live_bytes();
        c.live_blocks = watch_.memory->live_blocks();
    }
    for (const Watch::Bytes& out : watch_.outputs) {
        const auto* p = static_cast<const unsigned char*>(out.data);
        c.outputs.emplace_back(p, p + out.size);
    }
    return c;
}

std::string Unchanged::what_changed() const {
    if (!before_.read_error.empty()) return "before the call: " + before_.read_error;
    const Captured after = capture();
    if (!after.read_error.empty()) return "after the call: " + after.read_error;
    for (size_t i = 0; i < after.cloths.size(); ++i) {
        const std::string d = first_difference(before_.cloths[i], after.cloths[i], compare_);
        if (!d.empty()) return "cloth " + str(i) + " of the watch changed: " + d;
    }
    for (size_t i = 0; i < after.bodies.size(); ++i) {
        const std::string d = first_difference(before_.bodies[i], after.bodies[i]);
        if (!d.empty()) return "body " + str(i) + " of the watch changed: " + d;
    }
    if (after.live_bytes != before_.live_bytes || after.live_blocks != before_.live_blocks) {
        return "the world's memory changed: " + str(before_.live_bytes) + " bytes in " +
               str(before_.live_blocks) + " blocks, now " + str(after.live_bytes) + " in " +
               str(after.live_blocks);
    }
    for (size_t i = 0; i < after.outputs.size(); ++i) {
        if (after.outputs[i] != before_.outputs[i])
            return std::string("an output argument was written: ") + watch_.outputs[i].what;
    }
    return "";
}

std::string report_problem(cloth_result result) {
    const int code = static_cast<int>(result);
    if (code < 0 || code > kLastResultCode) return "returned an unknown code " + str(code);
    const char* name = cloth_result_name(result);
    if (name == nullptr || *name == '\0') return "returned a code without a name";
    if (result != CLOTH_OK) {
        const char* message = cloth_get_last_error();
        if (message == nullptr) return "failed, and cloth_get_last_error() returned NULL";
        if (*message == '\0') return "failed without a message in cloth_get_last_error()";
    }
    return "";
}

CallOutcome call_on_fresh_thread(const std::function<cloth_result()>& call) {
    CallOutcome o;
    std::thread thread([&] {
        const char* before = cloth_get_last_error();
        o.error_before_null = before == nullptr;
        o.error_before = before ? before : "";
        o.result = call();
        const char* after = cloth_get_last_error();
        o.error_after_null = after == nullptr;
        o.error_after = after ? after : "";
    });
    thread.join();
    return o;
}

std::vector<std::string> rejection_problems(cloth_result expected, const CallOutcome& o,
                                            const std::vector<LogEntry>& errors, Logged logged) {
    std::vector<std::string> problems;
    if (o.result != expected) {
        problems.push_back("expected " + result_name(expected) + ", got " + result_name(o.result) +
                           (o.error_after.empty() ? "" : "\n    message: " + o.error_after));
    }
    if (o.error_before_null) problems.push_back("cloth_get_last_error() returned NULL on a fresh thread");
    if (!o.error_before.empty())
        problems.push_back("cloth_get_last_error() is not \"\" on a thread that made no call");
    if (o.error_after_null) problems.push_back("cloth_get_last_error() returned NULL after the call");
    if (o.error_after.empty()) problems.push_back("the call failed, but cloth_get_last_error() is empty");
    if (logged == Logged::kNo) {
        if (!errors.empty()) {
            problems.push_back("the call names no live world, yet a world's log received \"" +
                               errors.back().message + "\"");
        }
        return problems;
    }
    if (logged == Logged::kYes || !errors.empty()) {
        if (errors.size() != 1) {
            problems.push_back("the world's log received " + str(errors.size()) +
                               " errors; a rejected call logs exactly one");
        }
        if (!errors.empty()) {
            if (errors.back().code != o.result) {
                problems.push_back("the logged code " + result_name(errors.back().code) +
                                   " differs from the returned one");
            }
            if (errors.back().message != o.error_after) {
                problems.push_back("the logged message \"" + errors.back().message +
                                   "\" differs from cloth_get_last_error()");
            }
        }
    }
    return problems;
}

std::string twin_divergence(const Watch& a, const Watch& b, int frames,
                            const std::function<void(int frame)>& before_each) {
    if (a.cloths.size() != b.cloths.size() || a.bodies.size() != b.bodies.size())
        return "the two watches name different numbers of cloths or bodies";
    constexpr float kFrame = 1.0f / 60.0f;
    for (int frame = 0; frame < frames; ++frame) {
        if (before_each) before_each(frame);
        for (const Watch* w : {&a, &b}) {
            const cloth_result r = cloth_step(w->world, kFrame);
            if (r != CLOTH_OK) {
                return std::string("cloth_step of the ") + (w == &a ? "world" : "twin") + " returned " +
                       result_name(r) + ": " + cloth_get_last_error();
            }
        }
    }
    const Compare across_worlds{true, false};
    for (size_t i = 0; i < a.cloths.size(); ++i) {
        ClothState x, y;
        std::string d = read_cloth_state(a.cloths[i], &x);
        if (d.empty()) d = read_cloth_state(b.cloths[i], &y);
        if (d.empty()) d = first_difference(y, x, across_worlds);
        if (!d.empty()) return "cloth " + str(i) + ": " + d;
    }
    for (size_t i = 0; i < a.bodies.size(); ++i) {
        BodyState x, y;
        std::string d = read_body_state(a.bodies[i], &x);
        if (d.empty()) d = read_body_state(b.bodies[i], &y);
        if (d.empty()) d = first_difference(y, x);
        if (!d.empty()) return "body " + str(i) + ": " + d;
    }
    return "";
}

}  // namespace cloth_test
