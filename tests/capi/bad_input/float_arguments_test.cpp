// Every float a call takes, one table: NaN and infinity are
// CLOTH_ERROR_NOT_FINITE, and a coordinate, offset or length that places
// something in the world beyond CLOTH_MAX_COORDINATE is
// CLOTH_ERROR_INVALID_VALUE; either way nothing changes.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "bad_input/fixture.h"

namespace cloth_bad_input {
namespace {

struct FloatArgument {
    std::string name;
    bool places;  // a coordinate, offset or length that places something in the world
    cloth_test::Logged logged;
    std::function<cloth_result(float)> call;
};

class FloatArguments : public BadInput {
  protected:
    void SetUp() override {
        BadInput::SetUp();
        if (HasFatalFailure()) return;
        // A body in each world, far from the cloths, with nothing on it.
        cloth_body_desc desc = cloth_default_body_desc();
        desc.position[1] = 50.0f;
        ASSERT_EQ(cloth_body_create(a_.world, &desc, &body_), CLOTH_OK);
        cloth_body_id twin{};
        ASSERT_EQ(cloth_body_create(b_.world, &desc, &twin), CLOTH_OK);
        watch_.bodies = {body_};
        twin_watch_.bodies = {twin};
        positions_ = ReadState(a_.cloth).positions;
    }

    std::vector<FloatArgument> Table();

    cloth_body_id body_{};
    std::vector<float> positions_;  // a_.cloth's, at the start
};

using cloth_test::Logged;

// `count` entries "name[k]" that put the value into element k of a copy of `valid`.
void AddArray(std::vector<FloatArgument>& table, const std::string& name, bool places, const float* valid,
              size_t count, const std::function<cloth_result(const float*)>& call,
              Logged logged = Logged::kYes) {
    const std::vector<float> base(valid, valid + count);
    for (size_t k = 0; k < count; ++k) {
        table.push_back({name + "[" + std::to_string(k) + "]", places, logged, [=](float value) {
                             std::vector<float> v = base;
                             v[k] = value;
                             return call(v.data());
                         }});
    }
}

// One entry per field of a struct: `set(desc, value)` puts the value in.
template <typename Desc>
void AddField(std::vector<FloatArgument>& table, const std::string& name, bool places, const Desc& valid,
              const std::function<void(Desc&, float)>& set,
              const std::function<cloth_result(const Desc&)>& call, Logged logged = Logged::kYes) {
    table.push_back({name, places, logged, [=](float value) {
                         Desc d = valid;
                         set(d, value);
                         return call(d);
                     }});
}

std::vector<FloatArgument> FloatArguments::Table() {
    std::vector<FloatArgument> t;
    const cloth_world_id world = a_.world;
    const cloth_id cloth = a_.cloth;
    const cloth_body_id body = body_;
    Outs* outs = &outs_;

    // ---- world
    const cloth_world_desc world_desc = a_.host.world_desc();
    AddArray(
        t, "cloth_world_desc.gravity", false, world_desc.gravity, 3,
        [=](const float* g) {
            cloth_world_desc d = world_desc;
            for (int k = 0; k < 3; ++k) d.gravity[k] = g[k];
            return cloth_world_create(&d, &outs->world);
        },
        Logged::kNo);
    const float gravity[3] = {0.0f, -9.81f, 0.0f};
    AddArray(t, "cloth_world_set_gravity gravity", false, gravity, 3,
             [=](const float* g) { return cloth_world_set_gravity(world, g); });
    const float shift[3] = {32.0f, 0.0f, -32.0f};
    AddArray(t, "cloth_world_shift_origin shift", true, shift, 3,
             [=](const float* s) { return cloth_world_shift_origin(world, s); });
    t.push_back({"cloth_step dt", false, Logged::kYes, [=](float dt) { return cloth_step(world, dt); }});
    t.push_back({"cloth_world_set_frame_budget milliseconds", false, Logged::kYes,
                 [=](float ms) { return cloth_world_set_frame_budget(world, ms); }});

    // ---- fabrics
    const cloth_grid_desc grid = SmallGrid();
    for (const char* field : {"origin", "u", "v"}) {
        const std::string which = field;
        const float* valid = which == "origin" ? grid.origin : which == "u" ? grid.u : grid.v;
        AddArray(t, "cloth_grid_desc." + which, true, valid, 3, [=](const float* value) {
            cloth_grid_desc d = grid;
            float* target = which == "origin" ? d.origin : which == "u" ? d.u : d.v;
            for (int k = 0; k < 3; ++k) target[k] = value[k];
            return cloth_fabric_create_grid(world, &d, &outs->fabric);
        });
    }
    const cloth_mesh_desc mesh = QuadMesh();
    AddArray(t, "cloth_mesh_desc.positions", true, kQuadPositions, 12, [=](const float* p) {
        cloth_mesh_desc d = mesh;
        d.positions = p;
        return cloth_fabric_create_mesh(world, &d, &outs->fabric);
    });

    // ---- cloths
    using D = cloth_desc;
    const D desc = ValidClothDesc();
    auto create = [=](const D& d) { return cloth_create(world, &d, &outs->cloth); };
    AddField<D>(
        t, "cloth_desc.area_density", false, desc, [](D& d, float v) { d.area_density = v; }, create);
    AddField<D>(
        t, "cloth_desc.particle_mass", false, desc, [](D& d, float v) { d.particle_mass = v; }, create);
    AddField<D>(
        t, "cloth_desc.structural.stiffness", false, desc, [](D& d, float v) { d.structural.stiffness = v; },
        create);
    AddField<D>(
        t, "cloth_desc.structural.damping", false, desc, [](D& d, float v) { d.structural.damping = v; },
        create);
    AddField<D>(
        t, "cloth_desc.shear.stiffness", false, desc, [](D& d, float v) { d.shear.stiffness = v; }, create);
    AddField<D>(
        t, "cloth_desc.shear.damping", false, desc, [](D& d, float v) { d.shear.damping = v; }, create);
    AddField<D>(
        t, "cloth_desc.bend.stiffness", false, desc, [](D& d, float v) { d.bend.stiffness = v; }, create);
    AddField<D>(
        t, "cloth_desc.bend.damping", false, desc, [](D& d, float v) { d.bend.damping = v; }, create);
    AddField<D>(
        t, "cloth_desc.solver.cg_tolerance", false, desc, [](D& d, float v) { d.solver.cg_tolerance = v; },
        create);
    AddArray(t, "cloth_desc.aero.wind", false, desc.aero.wind, 3, [=](const float* w) {
        D d = desc;
        for (int k = 0; k < 3; ++k) d.aero.wind[k] = w[k];
        return create(d);
    });
    AddField<D>(
        t, "cloth_desc.aero.air_density", false, desc, [](D& d, float v) { d.aero.air_density = v; }, create);
    AddField<D>(
        t, "cloth_desc.aero.drag_coefficient", false, desc,
        [](D& d, float v) { d.aero.drag_coefficient = v; }, create);
    AddField<D>(
        t, "cloth_desc.aero.lift_coefficient", false, desc,
        [](D& d, float v) { d.aero.lift_coefficient = v; }, create);
    AddField<D>(
        t, "cloth_desc.aero.linear_drag", false, desc, [](D& d, float v) { d.aero.linear_drag = v; }, create);
    const std::vector<float> positions = positions_;
    for (size_t k : {size_t{0}, size_t{4}, positions.size() - 1}) {
        t.push_back(
            {"cloth_desc.initial_positions[" + std::to_string(k) + "]", true, Logged::kYes, [=](float value) {
                 std::vector<float> p = positions;
                 p[k] = value;
                 D d = desc;
                 d.initial_positions = p.data();
                 return create(d);
             }});
    }
    static const uint32_t kTwo[] = {1, 2};
    const float two_positions[6] = {positions[3], positions[4], positions[5],
                                    positions[6], positions[7], positions[8]};
    AddArray(t, "cloth_set_positions positions", true, two_positions, 6,
             [=](const float* p) { return cloth_set_positions(cloth, kTwo, p, 2); });
    static const float kTwoMasses[2] = {0.01f, 0.02f};
    AddArray(t, "cloth_set_particle_masses masses", false, kTwoMasses, 2,
             [=](const float* m) { return cloth_set_particle_masses(cloth, kTwo, m, 2); });
    static const uint32_t kPinned[] = {0};
    AddArray(t, "cloth_set_pin_targets targets", true, positions.data(), 3,
             [=](const float* p) { return cloth_set_pin_targets(cloth, kPinned, p, 1); });
    const cloth_solver_settings solver = cloth_default_solver_settings();
    AddField<cloth_solver_settings>(
        t, "cloth_set_solver cg_tolerance", false, solver,
        [](cloth_solver_settings& s, float v) { s.cg_tolerance = v; },
        [=](const cloth_solver_settings& s) { return cloth_set_solver(cloth, &s); });
    const cloth_strain_limit limit = cloth_default_strain_limit();
    AddField<cloth_strain_limit>(
        t, "cloth_set_strain_limit max_strain", false, limit,
        [](cloth_strain_limit& l, float v) { l.max_strain = v; },
        [=](const cloth_strain_limit& l) { return cloth_set_strain_limit(cloth, &l); });
    const cloth_spring_params spring{100.0f, 0.1f};
    AddField<cloth_spring_params>(
        t, "cloth_set_spring_params stiffness", false, spring,
        [](cloth_spring_params& p, float v) { p.stiffness = v; },
        [=](const cloth_spring_params& p) { return cloth_set_spring_params(cloth, CLOTH_SPRING_ALL, p); });
    AddField<cloth_spring_params>(
        t, "cloth_set_spring_params damping", false, spring,
        [](cloth_spring_params& p, float v) { p.damping = v; },
        [=](const cloth_spring_params& p) { return cloth_set_spring_params(cloth, CLOTH_SPRING_ALL, p); });
    using A = cloth_aero_params;
    const A aero = desc.aero;
    auto set_aero = [=](const A& a) { return cloth_set_aero(cloth, &a); };
    AddArray(t, "cloth_set_aero wind", false, aero.wind, 3, [=](const float* w) {
        A a = aero;
        for (int k = 0; k < 3; ++k) a.wind[k] = w[k];
        return set_aero(a);
    });
    AddField<A>(
        t, "cloth_set_aero air_density", false, aero, [](A& a, float v) { a.air_density = v; }, set_aero);
    AddField<A>(
        t, "cloth_set_aero drag_coefficient", false, aero, [](A& a, float v) { a.drag_coefficient = v; },
        set_aero);
    AddField<A>(
        t, "cloth_set_aero lift_coefficient", false, aero, [](A& a, float v) { a.lift_coefficient = v; },
        set_aero);
    AddField<A>(
        t, "cloth_set_aero linear_drag", false, aero, [](A& a, float v) { a.linear_drag = v; }, set_aero);
    const float wind[3] = {1.0f, 0.0f, 1.0f};
    AddArray(t, "cloth_set_wind wind", false, wind, 3,
             [=](const float* w) { return cloth_set_wind(cloth, w); });
    const cloth_sleep_params sleep = cloth_default_sleep_params();
    AddField<cloth_sleep_params>(
        t, "cloth_set_sleep max_speed", false, sleep, [](cloth_sleep_params& p, float v) { p.max_speed = v; },
        [=](const cloth_sleep_params& p) { return cloth_set_sleep(cloth, &p); });
    using C = cloth_collision_params;
    const C collision = cloth_default_collision_params();
    auto set_collision = [=](const C& c) { return cloth_set_collision(cloth, &c); };
    AddField<C>(
        t, "cloth_set_collision thickness", true, collision, [](C& c, float v) { c.thickness = v; },
        set_collision);
    AddField<C>(
        t, "cloth_set_collision friction", false, collision, [](C& c, float v) { c.friction = v; },
        set_collision);
    using S = cloth_self_collision_desc;
    S self = cloth_default_self_collision_desc();
    self.enabled = 1;
    auto set_self = [=](const S& s) { return cloth_set_self_collision(cloth, &s); };
    AddField<S>(
        t, "cloth_set_self_collision thickness", false, self, [](S& s, float v) { s.thickness = v; },
        set_self);
    AddField<S>(
        t, "cloth_set_self_collision friction", false, self, [](S& s, float v) { s.friction = v; }, set_self);
    using K = cloth_carrier_desc;
    const K carrier = cloth_default_carrier_desc();
    auto set_carrier = [=](const K& k) { return cloth_set_carrier(cloth, body, &k); };
    AddField<K>(
        t, "cloth_set_carrier linear_inertia", false, carrier, [](K& k, float v) { k.linear_inertia = v; },
        set_carrier);
    AddField<K>(
        t, "cloth_set_carrier angular_inertia", false, carrier, [](K& k, float v) { k.angular_inertia = v; },
        set_carrier);
    AddField<K>(
        t, "cloth_set_carrier centrifugal_inertia", false, carrier,
        [](K& k, float v) { k.centrifugal_inertia = v; }, set_carrier);
    AddField<K>(
        t, "cloth_set_carrier max_relative_speed", false, carrier,
        [](K& k, float v) { k.max_relative_speed = v; }, set_carrier);
    AddField<K>(
        t, "cloth_set_carrier teleport_distance", false, carrier,
        [](K& k, float v) { k.teleport_distance = v; }, set_carrier);
    AddField<K>(
        t, "cloth_set_carrier teleport_rotation", false, carrier,
        [](K& k, float v) { k.teleport_rotation = v; }, set_carrier);
    static const uint32_t kAttached[] = {1};
    const float offset[3] = {0.0f, -1.0f, 0.0f};
    AddArray(t, "cloth_attach local_offsets", true, offset, 3,
             [=](const float* o) { return cloth_attach(cloth, body, kAttached, o, 1); });

    // ---- bodies
    using B = cloth_body_desc;
    const B body_desc = cloth_default_body_desc();
    auto create_body = [=](const B& b) {
        static cloth_body_id out;
        return cloth_body_create(world, &b, &out);
    };
    const float p0[3] = {0.0f, 50.0f, 0.0f}, q0[4] = {0.0f, 0.0f, 0.0f, 1.0f}, v0[3] = {0.5f, 0.0f, 0.0f};
    AddArray(t, "cloth_body_desc.position", true, p0, 3, [=](const float* v) {
        B b = body_desc;
        for (int k = 0; k < 3; ++k) b.position[k] = v[k];
        return create_body(b);
    });
    AddArray(t, "cloth_body_desc.rotation", false, q0, 4, [=](const float* v) {
        B b = body_desc;
        for (int k = 0; k < 4; ++k) b.rotation[k] = v[k];
        return create_body(b);
    });
    AddArray(t, "cloth_body_desc.linear_velocity", false, v0, 3, [=](const float* v) {
        B b = body_desc;
        for (int k = 0; k < 3; ++k) b.linear_velocity[k] = v[k];
        return create_body(b);
    });
    AddArray(t, "cloth_body_desc.angular_velocity", false, v0, 3, [=](const float* v) {
        B b = body_desc;
        for (int k = 0; k < 3; ++k) b.angular_velocity[k] = v[k];
        return create_body(b);
    });
    AddArray(t, "cloth_body_set_pose position", true, p0, 3,
             [=](const float* v) { return cloth_body_set_pose(body, v, q0); });
    AddArray(t, "cloth_body_set_pose rotation", false, q0, 4,
             [=](const float* v) { return cloth_body_set_pose(body, p0, v); });
    AddArray(t, "cloth_body_teleport position", true, p0, 3,
             [=](const float* v) { return cloth_body_teleport(body, v, q0); });
    AddArray(t, "cloth_body_teleport rotation", false, q0, 4,
             [=](const float* v) { return cloth_body_teleport(body, p0, v); });
    AddArray(t, "cloth_body_set_velocity linear", false, v0, 3,
             [=](const float* v) { return cloth_body_set_velocity(body, v, v0); });
    AddArray(t, "cloth_body_set_velocity angular", false, v0, 3,
             [=](const float* v) { return cloth_body_set_velocity(body, v0, v); });

    // ---- colliders (static, far below the cloths)
    cloth_collider_desc collider = cloth_default_collider_desc();
    collider.local_position[1] = -100.0f;
    cloth_collider_id* out = nullptr;
    static cloth_collider_id out_collider;
    out = &out_collider;
    AddArray(t, "cloth_collider_desc.local_position", true, collider.local_position, 3, [=](const float* v) {
        cloth_collider_desc c = collider;
        for (int k = 0; k < 3; ++k) c.local_position[k] = v[k];
        return cloth_collider_create_sphere(world, &c, 1.0f, out);
    });
    AddArray(t, "cloth_collider_desc.local_rotation", false, collider.local_rotation, 4, [=](const float* v) {
        cloth_collider_desc c = collider;
        for (int k = 0; k < 4; ++k) c.local_rotation[k] = v[k];
        return cloth_collider_create_sphere(world, &c, 1.0f, out);
    });
    t.push_back({"cloth_collider_create_sphere radius", true, Logged::kYes,
                 [=](float r) { return cloth_collider_create_sphere(world, &collider, r, out); }});
    t.push_back({"cloth_collider_create_capsule radius", true, Logged::kYes,
                 [=](float r) { return cloth_collider_create_capsule(world, &collider, r, 1.0f, out); }});
    t.push_back({"cloth_collider_create_capsule half_height", true, Logged::kYes,
                 [=](float h) { return cloth_collider_create_capsule(world, &collider, 0.5f, h, out); }});
    t.push_back({"cloth_collider_create_tapered_capsule bottom_radius", true, Logged::kYes, [=](float r) {
                     return cloth_collider_create_tapered_capsule(world, &collider, r, 0.5f, 1.0f, out);
                 }});
    t.push_back({"cloth_collider_create_tapered_capsule top_radius", true, Logged::kYes, [=](float r) {
                     return cloth_collider_create_tapered_capsule(world, &collider, 0.5f, r, 1.0f, out);
                 }});
    t.push_back({"cloth_collider_create_tapered_capsule half_height", true, Logged::kYes, [=](float h) {
                     return cloth_collider_create_tapered_capsule(world, &collider, 0.5f, 0.5f, h, out);
                 }});
    const float extents[3] = {1.0f, 2.0f, 3.0f};
    AddArray(t, "cloth_collider_create_box half_extents", true, extents, 3,
             [=](const float* e) { return cloth_collider_create_box(world, &collider, e, out); });
    const float up[3] = {0.0f, 1.0f, 0.0f};
    AddArray(t, "cloth_collider_create_plane normal", false, up, 3,
             [=](const float* n) { return cloth_collider_create_plane(world, &collider, n, -1.0f, out); });
    t.push_back({"cloth_collider_create_plane offset", true, Logged::kYes,
                 [=](float o) { return cloth_collider_create_plane(world, &collider, up, o, out); }});
    static const float kTetra[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    AddArray(t, "cloth_collider_create_convex_hull points", true, kTetra, 12,
             [=](const float* p) { return cloth_collider_create_convex_hull(world, &collider, p, 4, out); });
    AddArray(t, "cloth_collider_create_triangle_mesh vertices", true, kQuadPositions, 12,
             [=](const float* v) {
                 return cloth_collider_create_triangle_mesh(world, &collider, v, 4, kQuadIndices, 2, out);
             });
    cloth_heightfield_desc field = cloth_default_heightfield_desc();
    static const float kHeights[4] = {0.0f, 0.1f, 0.2f, 0.3f};
    field.heights = kHeights;
    using H = cloth_heightfield_desc;
    auto create_field = [=](const H& h) {
        return cloth_collider_create_heightfield(world, &collider, &h, out);
    };
    AddField<H>(
        t, "cloth_heightfield_desc.spacing_x", true, field, [](H& h, float v) { h.spacing_x = v; },
        create_field);
    AddField<H>(
        t, "cloth_heightfield_desc.spacing_z", true, field, [](H& h, float v) { h.spacing_z = v; },
        create_field);
    AddArray(t, "cloth_heightfield_desc.heights", true, kHeights, 4, [=](const float* v) {
        H h = field;
        h.heights = v;
        return create_field(h);
    });
    return t;
}

TEST_F(FloatArguments, EveryFloatArgumentRejectsNaNAndInfinityWithNotFiniteAndChangesNothing) {
    const std::vector<FloatArgument> table = Table();
    for (const FloatArgument& arg : table) {
        for (float value : {kNaN, kInf, -kInf}) {
            ExpectRejected(
                CLOTH_ERROR_NOT_FINITE, arg.name + " = " + std::to_string(value),
                [&] { return arg.call(value); }, arg.logged);
        }
    }
    std::printf("[ cloth    ] %zu float arguments\n", table.size());
}

TEST_F(FloatArguments, EveryCoordinateBeyondTheMaximumIsRefusedWithInvalidValueAndChangesNothing) {
    const float beyond[] = {std::nextafter(CLOTH_MAX_COORDINATE, 2 * CLOTH_MAX_COORDINATE),
                            -2 * CLOTH_MAX_COORDINATE, 3e38f, -3e38f};
    int placements = 0;
    for (const FloatArgument& arg : Table()) {
        if (!arg.places) continue;
        ++placements;
        for (float value : beyond) {
            ExpectRejected(
                CLOTH_ERROR_INVALID_VALUE, arg.name + " = " + std::to_string(value),
                [&] { return arg.call(value); }, arg.logged);
        }
    }
    EXPECT_GT(placements, 20);
}

// The bound itself is inside the range: a cloth moved there and a body
// placed there are taken, and the world steps on finitely.
TEST_F(FloatArguments, CoordinatesAtTheMaximumAreTakenAndTheWorldStepsOnFinitely) {
    check_twin_ = false;
    std::vector<uint32_t> all(kParticles);
    std::vector<float> far = positions_;
    for (uint32_t i = 0; i < kParticles; ++i) {
        all[i] = i;
        far[3 * i] = std::fmin(far[3 * i] + CLOTH_MAX_COORDINATE - 1.0f, CLOTH_MAX_COORDINATE);
    }
    EXPECT_EQ(cloth_set_positions(a_.other, all.data(), far.data(), kParticles), CLOTH_OK)
        << cloth_get_last_error();
    const float corner[3] = {CLOTH_MAX_COORDINATE, -CLOTH_MAX_COORDINATE, CLOTH_MAX_COORDINATE};
    const float q[4] = {0, 0, 0, 1};
    EXPECT_EQ(cloth_body_set_pose(body_, corner, q), CLOTH_OK) << cloth_get_last_error();
    for (int frame = 0; frame < 3; ++frame) {
        const cloth_result r = cloth_step(a_.world, kFrame);
        EXPECT_TRUE(r == CLOTH_OK || r == CLOTH_ERROR_SOLVER_FAILED) << cloth_get_last_error();
    }
    EXPECT_TRUE(AllFinite(ReadState(a_.other).positions));
}

}  // namespace
}  // namespace cloth_bad_input
