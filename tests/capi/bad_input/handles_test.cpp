// Null, stale, wrong-generation and out-of-table ids get CLOTH_ERROR_INVALID_HANDLE and change nothing.
#include <cstdint>
#include <cstdio>
#include <iterator>
#include <string>
#include <vector>

#include "bad_input/fixture.h"

namespace cloth_bad_input {
namespace {

struct NamedWorld {
    const char* what;
    cloth_world_id id;
};
struct NamedFabric {
    const char* what;
    cloth_fabric_id id;
};
struct NamedCloth {
    const char* what;
    cloth_id id;
};

TEST_F(BadInput, EveryWorldFunctionRejectsNullStaleAndOutOfTableWorldIdsAndChangesNothing) {
    const cloth_world_id w = a_.world;
    const NamedWorld bad[] = {
        {"null world id", {0, 0}},
        {"world index past the 128-world table", {129, w.generation}},
        {"world index 0xFFFF", {0xFFFF, w.generation}},
        {"wrong generation of a live world slot", {w.index1, static_cast<uint16_t>(w.generation + 1)}},
        {"destroyed world", dead_world_},
    };
    const std::string obj = WriteTempFile("quad.obj", "v 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nf 1 2 3 4\n");
    const float gravity[3] = {0.0f, -1.0f, 0.0f};
    const cloth_grid_desc grid = SmallGrid();
    const cloth_mesh_desc mesh = QuadMesh();
    const cloth_desc desc = ValidClothDesc();
    for (const NamedWorld& b : bad) {
        SCOPED_TRACE(b.what);
        EXPECT_REJECTED_MAYBE_LOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_world_set_gravity(b.id, gravity));
        EXPECT_REJECTED_MAYBE_LOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_world_shift_origin(b.id, gravity));
        EXPECT_REJECTED_MAYBE_LOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_world_set_worker_spin(b.id, 100));
        EXPECT_REJECTED_MAYBE_LOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_step(b.id, kFrame));
        EXPECT_REJECTED_MAYBE_LOGGED(CLOTH_ERROR_INVALID_HANDLE,
                                     cloth_fabric_create_grid(b.id, &grid, &outs_.fabric));
        EXPECT_REJECTED_MAYBE_LOGGED(CLOTH_ERROR_INVALID_HANDLE,
                                     cloth_fabric_create_mesh(b.id, &mesh, &outs_.fabric));
        EXPECT_REJECTED_MAYBE_LOGGED(
            CLOTH_ERROR_INVALID_HANDLE,
            cloth_fabric_create_obj(b.id, obj.c_str(), CLOTH_SPRING_ALL, &outs_.fabric));
        EXPECT_REJECTED_MAYBE_LOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_create(b.id, &desc, &outs_.cloth));
        EXPECT_REJECTED_MAYBE_LOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_world_destroy(b.id));
    }
    std::remove(obj.c_str());
}

TEST_F(BadInput, EveryFabricFunctionRejectsNullStaleWrongGenerationAndOutOfTableFabricIdsAndChangesNothing) {
    const cloth_fabric_id f = a_.fabric;
    const NamedFabric bad[] = {
        {"null fabric id", {0, 0, 0, 0}},
        {"zero index in a live world", {0, f.world1, f.generation, f.world_generation}},
        {"zero world", {f.index1, 0, f.generation, f.world_generation}},
        {"world index past the world table", {f.index1, 0xFFFF, f.generation, f.world_generation}},
        {"wrong world generation",
         {f.index1, f.world1, f.generation, static_cast<uint16_t>(f.world_generation + 1)}},
        {"index past the fabric table", {kMaxFabrics + 1, f.world1, f.generation, f.world_generation}},
        {"index 0xFFFF", {0xFFFF, f.world1, f.generation, f.world_generation}},
        {"wrong generation of a live slot",
         {f.index1, f.world1, static_cast<uint16_t>(f.generation + 1), f.world_generation}},
        {"destroyed fabric whose slot was re-used", a_.stale_fabric},
        {"destroyed fabric whose slot is free", a_.freed_fabric},
        {"fabric of a destroyed world", dead_fabric_},
    };
    for (const NamedFabric& b : bad) {
        SCOPED_TRACE(b.what);
        EXPECT_REJECTED_MAYBE_LOGGED(CLOTH_ERROR_INVALID_HANDLE,
                                     cloth_fabric_get_particle_count(b.id, &outs_.count));
        EXPECT_REJECTED_MAYBE_LOGGED(CLOTH_ERROR_INVALID_HANDLE,
                                     cloth_fabric_get_triangle_count(b.id, &outs_.count));
        EXPECT_REJECTED_MAYBE_LOGGED(CLOTH_ERROR_INVALID_HANDLE,
                                     cloth_fabric_get_spring_count(b.id, CLOTH_SPRING_ALL, &outs_.count));
        EXPECT_REJECTED_MAYBE_LOGGED(CLOTH_ERROR_INVALID_HANDLE,
                                     cloth_fabric_read_triangles(b.id, outs_.uints, std::size(outs_.uints)));
        cloth_desc desc = ValidClothDesc();
        desc.fabric = b.id;
        // The world is valid here, so the error is one of its calls and is logged.
        EXPECT_REJECTED(CLOTH_ERROR_INVALID_HANDLE, cloth_create(a_.world, &desc, &outs_.cloth));
        EXPECT_REJECTED_MAYBE_LOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_fabric_destroy(b.id));
    }
}

TEST_F(BadInput, EveryClothFunctionRejectsNullStaleWrongGenerationAndOutOfTableClothIdsAndChangesNothing) {
    const cloth_id c = a_.cloth;
    const NamedCloth bad[] = {
        {"null cloth id", {0, 0, 0, 0}},
        {"zero index in a live world", {0, c.world1, c.generation, c.world_generation}},
        {"zero world", {c.index1, 0, c.generation, c.world_generation}},
        {"world index past the world table", {c.index1, 0xFFFF, c.generation, c.world_generation}},
        {"wrong world generation",
         {c.index1, c.world1, c.generation, static_cast<uint16_t>(c.world_generation + 1)}},
        {"index past the cloth table", {kMaxCloths + 1, c.world1, c.generation, c.world_generation}},
        {"index 0xFFFF", {0xFFFF, c.world1, c.generation, c.world_generation}},
        {"wrong generation of a live slot",
         {c.index1, c.world1, static_cast<uint16_t>(c.generation + 1), c.world_generation}},
        {"destroyed cloth whose slot was re-used", a_.stale_cloth},
        {"destroyed cloth whose slot is free", a_.freed_cloth},
        {"cloth of a destroyed world", dead_cloth_},
    };
    const uint32_t index[] = {0};
    const float xyz[3] = {0.5f, 0.5f, 0.5f};
    const cloth_solver_settings solver = cloth_default_solver_settings();
    const cloth_aero_params aero = cloth_default_desc().aero;
    const cloth_spring_params spring{10.0f, 0.1f};
    for (const NamedCloth& b : bad) {
        SCOPED_TRACE(b.what);
        const cloth_id id = b.id;
        EXPECT_REJECTED_MAYBE_LOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_get_particle_count(id, &outs_.count));
        EXPECT_REJECTED_MAYBE_LOGGED(CLOTH_ERROR_INVALID_HANDLE,
                                     cloth_read_positions(id, outs_.floats, kFloats));
        EXPECT_REJECTED_MAYBE_LOGGED(CLOTH_ERROR_INVALID_HANDLE,
                                     cloth_read_velocities(id, outs_.floats, kFloats));
        EXPECT_REJECTED_MAYBE_LOGGED(CLOTH_ERROR_INVALID_HANDLE,
                                     cloth_read_normals(id, outs_.floats, kFloats));
        EXPECT_REJECTED_MAYBE_LOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_set_positions(id, index, xyz, 1));
        EXPECT_REJECTED_MAYBE_LOGGED(CLOTH_ERROR_INVALID_HANDLE,
                                     cloth_set_particle_masses(id, index, xyz, 1));
        EXPECT_REJECTED_MAYBE_LOGGED(CLOTH_ERROR_INVALID_HANDLE,
                                     cloth_read_particle_masses(id, outs_.floats, kFloats));
        EXPECT_REJECTED_MAYBE_LOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_pin(id, index, 1));
        EXPECT_REJECTED_MAYBE_LOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_unpin(id, index, 1));
        EXPECT_REJECTED_MAYBE_LOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_set_pin_targets(id, index, xyz, 1));
        EXPECT_REJECTED_MAYBE_LOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_is_pinned(id, 0, OutPinned()));
        EXPECT_REJECTED_MAYBE_LOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_set_solver(id, &solver));
        EXPECT_REJECTED_MAYBE_LOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_get_solver(id, &outs_.solver));
        EXPECT_REJECTED_MAYBE_LOGGED(CLOTH_ERROR_INVALID_HANDLE,
                                     cloth_set_spring_params(id, CLOTH_SPRING_ALL, spring));
        EXPECT_REJECTED_MAYBE_LOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_set_aero(id, &aero));
        EXPECT_REJECTED_MAYBE_LOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_set_wind(id, xyz));
        EXPECT_REJECTED_MAYBE_LOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_get_stats(id, &outs_.stats));
        EXPECT_REJECTED_MAYBE_LOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_destroy(id));
    }
}

TEST_F(BadInput, DestroyedSlotsAreReusedWithANewGenerationSoStaleIdsDifferFromLiveOnes) {
    // The fixture filled both 3-slot tables before freeing one slot and
    // creating again, so the new object must sit in the freed slot. This makes
    // "stale id whose slot was re-used" above mean what it says.
    EXPECT_EQ(a_.other.index1, a_.stale_cloth.index1);
    EXPECT_EQ(a_.other.world1, a_.stale_cloth.world1);
    EXPECT_NE(a_.other.generation, a_.stale_cloth.generation);
    EXPECT_EQ(a_.other_fabric.index1, a_.stale_fabric.index1);
    EXPECT_NE(a_.other_fabric.generation, a_.stale_fabric.generation);
    // And the new occupant is alive.
    uint32_t count = 0;
    EXPECT_EQ(cloth_get_particle_count(a_.other, &count), CLOTH_OK);
    EXPECT_EQ(count, kParticles);
    EXPECT_EQ(cloth_fabric_get_particle_count(a_.other_fabric, &count), CLOTH_OK);
    EXPECT_EQ(count, 9u);
}

TEST_F(BadInput, CreateClothFromAFabricOfAnotherWorldReturnsInvalidHandleAndChangesNothing) {
    cloth_desc desc = ValidClothDesc();
    desc.fabric = b_.fabric;  // alive, but in the twin world
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_HANDLE, cloth_create(a_.world, &desc, &outs_.cloth));
}

// The message of a call that fails on this thread.
std::string MessageOf(cloth_result result) {
    EXPECT_NE(result, CLOTH_OK);
    return cloth_get_last_error();
}

bool Contains(const std::string& text, const char* part) { return text.find(part) != std::string::npos; }

// cloth.h, "Which log hears of an error": a handle whose world part names a
// live world reports to that world's log, even when the object it names is
// gone; one that names no live world reports to no log. Each message says
// which of null, no live world, no live object or another world it is.
TEST_F(BadInput, InvalidHandlesAreLoggedToTheWorldTheyNameAndTheMessageSaysWhatIsWrong) {
    const cloth_id c = a_.cloth;
    const NamedCloth in_live_world[] = {
        {"zero index in a live world", {0, c.world1, c.generation, c.world_generation}},
        {"index past the cloth table", {kMaxCloths + 1, c.world1, c.generation, c.world_generation}},
        {"wrong generation of a live slot",
         {c.index1, c.world1, static_cast<uint16_t>(c.generation + 1), c.world_generation}},
        {"destroyed cloth whose slot was re-used", a_.stale_cloth},
        {"destroyed cloth whose slot is free", a_.freed_cloth},
    };
    for (const NamedCloth& b : in_live_world) {
        SCOPED_TRACE(b.what);
        EXPECT_REJECTED(CLOTH_ERROR_INVALID_HANDLE, cloth_get_particle_count(b.id, &outs_.count));
        EXPECT_REJECTED(CLOTH_ERROR_INVALID_HANDLE, cloth_destroy(b.id));
        const std::string m = MessageOf(cloth_get_particle_count(b.id, &outs_.count));
        EXPECT_TRUE(Contains(m, "no live cloth")) << m;
    }
    const NamedCloth in_no_world[] = {
        {"zero world", {c.index1, 0, c.generation, c.world_generation}},
        {"world index past the world table", {c.index1, 0xFFFF, c.generation, c.world_generation}},
        {"wrong world generation",
         {c.index1, c.world1, c.generation, static_cast<uint16_t>(c.world_generation + 1)}},
        {"cloth of a destroyed world", dead_cloth_},
    };
    for (const NamedCloth& b : in_no_world) {
        SCOPED_TRACE(b.what);
        EXPECT_REJECTED_NOT_LOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_get_particle_count(b.id, &outs_.count));
        EXPECT_REJECTED_NOT_LOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_destroy(b.id));
        const std::string m = MessageOf(cloth_get_particle_count(b.id, &outs_.count));
        EXPECT_TRUE(Contains(m, "no live world")) << m;
    }
    EXPECT_REJECTED_NOT_LOGGED(CLOTH_ERROR_INVALID_HANDLE,
                               cloth_get_particle_count(cloth_null_id, &outs_.count));
    EXPECT_TRUE(
        Contains(MessageOf(cloth_get_particle_count(cloth_null_id, &outs_.count)), "cloth handle is null"));

    // Fabrics the same way.
    const cloth_fabric_id f = a_.fabric;
    const cloth_fabric_id stale_fabric_in_live_world = {
        f.index1, f.world1, static_cast<uint16_t>(f.generation + 1), f.world_generation};
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_HANDLE,
                    cloth_fabric_get_particle_count(stale_fabric_in_live_world, &outs_.count));
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_HANDLE,
                    cloth_fabric_get_particle_count(a_.freed_fabric, &outs_.count));
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_HANDLE, cloth_fabric_destroy(a_.freed_fabric));
    EXPECT_TRUE(Contains(MessageOf(cloth_fabric_get_particle_count(a_.freed_fabric, &outs_.count)),
                         "no live fabric"));
    EXPECT_REJECTED_NOT_LOGGED(CLOTH_ERROR_INVALID_HANDLE,
                               cloth_fabric_get_particle_count(dead_fabric_, &outs_.count));
    EXPECT_REJECTED_NOT_LOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_fabric_destroy(dead_fabric_));
    EXPECT_REJECTED_NOT_LOGGED(CLOTH_ERROR_INVALID_HANDLE,
                               cloth_fabric_get_particle_count(cloth_null_fabric_id, &outs_.count));

    // Worlds: a bad world handle names no live world.
    const float gravity[3] = {0.0f, -1.0f, 0.0f};
    EXPECT_REJECTED_NOT_LOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_world_set_gravity(dead_world_, gravity));
    EXPECT_REJECTED_NOT_LOGGED(CLOTH_ERROR_INVALID_HANDLE,
                               cloth_world_set_gravity(cloth_null_world_id, gravity));
    EXPECT_TRUE(
        Contains(MessageOf(cloth_world_set_gravity(cloth_null_world_id, gravity)), "world handle is null"));
    EXPECT_TRUE(Contains(MessageOf(cloth_world_set_gravity(dead_world_, gravity)), "no live world"));

    // Bodies and colliders: none exist in this world, so any id of it names no live one.
    const cloth_body_id body{1, a_.world.index1, 1, a_.world.generation};
    const float p[3] = {0, 0, 0}, q[4] = {0, 0, 0, 1};
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_HANDLE, cloth_body_set_pose(body, p, q));
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_HANDLE, cloth_body_destroy(body));
    EXPECT_TRUE(Contains(MessageOf(cloth_body_set_pose(body, p, q)), "no live body"));
    EXPECT_REJECTED_NOT_LOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_body_set_pose(cloth_null_body_id, p, q));
    const cloth_collider_id collider{1, a_.world.index1, 1, a_.world.generation};
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_HANDLE, cloth_collider_set_group_bits(collider, 3));
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_HANDLE, cloth_collider_destroy(collider));
    EXPECT_TRUE(Contains(MessageOf(cloth_collider_set_group_bits(collider, 3)), "no live collider"));
    EXPECT_REJECTED_NOT_LOGGED(CLOTH_ERROR_INVALID_HANDLE,
                               cloth_collider_set_group_bits(cloth_null_collider_id, 3));

    // A handle argument beside a live one: the call's world logs it.
    const uint32_t index[] = {0};
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_HANDLE,
                    cloth_attach(a_.cloth, cloth_null_body_id, index, nullptr, 1));
    EXPECT_TRUE(Contains(MessageOf(cloth_attach(a_.cloth, cloth_null_body_id, index, nullptr, 1)),
                         "body handle is null"));
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_HANDLE, cloth_attach(a_.cloth, body, index, nullptr, 1));
    cloth_collider_desc on_body = cloth_default_collider_desc();
    on_body.body = body;
    cloth_collider_id out_collider{};
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_HANDLE,
                    cloth_collider_create_sphere(a_.world, &on_body, 1.0f, &out_collider));
    EXPECT_TRUE(Contains(MessageOf(cloth_collider_create_sphere(a_.world, &on_body, 1.0f, &out_collider)),
                         "no live body"));
}

TEST_F(BadInput, ANullFabricInAClothDescIsReportedAsNullAndAForeignOneAsOfAnotherWorld) {
    cloth_desc desc = ValidClothDesc();
    desc.fabric = cloth_null_fabric_id;
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_HANDLE, cloth_create(a_.world, &desc, &outs_.cloth));
    std::string m = MessageOf(cloth_create(a_.world, &desc, &outs_.cloth));
    EXPECT_TRUE(Contains(m, "fabric handle is null")) << m;
    EXPECT_FALSE(Contains(m, "another world")) << m;

    desc.fabric = b_.fabric;  // alive, in the twin world
    m = MessageOf(cloth_create(a_.world, &desc, &outs_.cloth));
    EXPECT_TRUE(Contains(m, "another world")) << m;

    desc.fabric = a_.freed_fabric;  // this world's, destroyed
    m = MessageOf(cloth_create(a_.world, &desc, &outs_.cloth));
    EXPECT_TRUE(Contains(m, "no live fabric")) << m;
    EXPECT_FALSE(Contains(m, "another world")) << m;

    cloth_collider_desc on_null_world_body = cloth_default_collider_desc();
    on_null_world_body.body = cloth_body_id{1, 0, 1, 0};
    cloth_collider_id out{};
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_HANDLE,
                    cloth_collider_create_sphere(a_.world, &on_null_world_body, 1.0f, &out));
    m = MessageOf(cloth_collider_create_sphere(a_.world, &on_null_world_body, 1.0f, &out));
    EXPECT_TRUE(Contains(m, "another world")) << m;
}

TEST_F(BadInput, DestroyingTwiceReturnsInvalidHandleTheSecondTime) {
    check_twin_ = false;
    cloth_id extra{};
    cloth_desc desc = ValidClothDesc();
    ASSERT_EQ(cloth_create(a_.world, &desc, &extra), CLOTH_OK);
    ASSERT_EQ(cloth_destroy(extra), CLOTH_OK);
    EXPECT_REJECTED_MAYBE_LOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_destroy(extra));

    ASSERT_EQ(cloth_fabric_destroy(a_.other_fabric), CLOTH_OK);
    EXPECT_REJECTED_MAYBE_LOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_fabric_destroy(a_.other_fabric));

    CountingAllocator host;
    const cloth_world_desc wd = HostWorldDesc(&host);
    cloth_world_id world{};
    ASSERT_EQ(cloth_world_create(&wd, &world), CLOTH_OK);
    ASSERT_EQ(cloth_world_destroy(world), CLOTH_OK);
    EXPECT_REJECTED_MAYBE_LOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_world_destroy(world));
    EXPECT_EQ(host.live_bytes(), 0u);
}

TEST_F(BadInput, IdsOfADestroyedWorldStayInvalidWhenItsSlotIsReused) {
    check_twin_ = false;
    // Create worlds until one lands in the dead world's slot.
    std::vector<cloth_world_id> created;
    cloth_world_id reused{};
    const cloth_world_desc wd = cloth_default_world_desc();
    for (int i = 0; i < 128; ++i) {
        cloth_world_id w{};
        if (cloth_world_create(&wd, &w) != CLOTH_OK) break;
        created.push_back(w);
        if (w.index1 == dead_world_.index1) {
            reused = w;
            break;
        }
    }
    ASSERT_EQ(reused.index1, dead_world_.index1) << "no new world re-used the destroyed world's slot";
    EXPECT_NE(reused.generation, dead_world_.generation);

    // The same recipe as the dead world: a fabric and a cloth in its first slots.
    const cloth_grid_desc grid = SmallGrid();
    cloth_fabric_id fabric{};
    ASSERT_EQ(cloth_fabric_create_grid(reused, &grid, &fabric), CLOTH_OK);
    cloth_desc desc = cloth_default_desc();
    desc.fabric = fabric;
    cloth_id cloth{};
    ASSERT_EQ(cloth_create(reused, &desc, &cloth), CLOTH_OK);

    EXPECT_FALSE(cloth == dead_cloth_)
        << "the new world's cloth has the very id of the destroyed world's cloth; cloth_id carries no world "
           "generation, so the library must keep slot generations unique across world re-use";
    EXPECT_FALSE(fabric == dead_fabric_)
        << "the new world's fabric has the very id of the destroyed world's fabric";

    EXPECT_REJECTED_MAYBE_LOGGED(CLOTH_ERROR_INVALID_HANDLE,
                                 cloth_get_particle_count(dead_cloth_, &outs_.count));
    EXPECT_REJECTED_MAYBE_LOGGED(CLOTH_ERROR_INVALID_HANDLE,
                                 cloth_fabric_get_particle_count(dead_fabric_, &outs_.count));
    EXPECT_REJECTED_MAYBE_LOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_world_destroy(dead_world_));
    EXPECT_REJECTED_MAYBE_LOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_destroy(dead_cloth_));
    EXPECT_REJECTED_MAYBE_LOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_fabric_destroy(dead_fabric_));
    // The new objects are untouched by all of that.
    uint32_t count = 0;
    EXPECT_EQ(cloth_get_particle_count(cloth, &count), CLOTH_OK);
    EXPECT_EQ(count, kParticles);
    EXPECT_EQ(cloth_fabric_get_particle_count(fabric, &count), CLOTH_OK);
    EXPECT_EQ(cloth_step(reused, kFrame), CLOTH_OK);
    for (const cloth_world_id& w : created) EXPECT_EQ(cloth_world_destroy(w), CLOTH_OK);
}

}  // namespace
}  // namespace cloth_bad_input
