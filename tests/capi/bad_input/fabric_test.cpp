// Bad grid, mesh and OBJ fabric input is rejected with its code and changes nothing.
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <utility>

#include "bad_input/fixture.h"
#include "support/guarded_buffer.h"

namespace cloth_bad_input {
namespace {

TEST_F(BadInput, FabricFunctionsRejectEachNullPointerAndChangeNothing) {
    const cloth_grid_desc grid = SmallGrid();
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_fabric_create_grid(a_.world, nullptr, &outs_.fabric));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_fabric_create_grid(a_.world, &grid, nullptr));

    const cloth_mesh_desc mesh = QuadMesh();
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_fabric_create_mesh(a_.world, nullptr, &outs_.fabric));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_fabric_create_mesh(a_.world, &mesh, nullptr));
    cloth_mesh_desc no_positions = QuadMesh();
    no_positions.positions = nullptr;
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER,
                    cloth_fabric_create_mesh(a_.world, &no_positions, &outs_.fabric));
    cloth_mesh_desc no_indices = QuadMesh();
    no_indices.indices = nullptr;
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_fabric_create_mesh(a_.world, &no_indices, &outs_.fabric));

    const std::string obj = WriteTempFile("null.obj", "v 0 0 0\nv 1 0 0\nv 1 0 1\nf 1 2 3\n");
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER,
                    cloth_fabric_create_obj(a_.world, nullptr, CLOTH_SPRING_ALL, &outs_.fabric));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER,
                    cloth_fabric_create_obj(a_.world, obj.c_str(), CLOTH_SPRING_ALL, nullptr));
    std::remove(obj.c_str());

    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_fabric_get_particle_count(a_.fabric, nullptr));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_fabric_get_triangle_count(a_.fabric, nullptr));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER,
                    cloth_fabric_get_spring_count(a_.fabric, CLOTH_SPRING_ALL, nullptr));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_fabric_read_triangles(a_.fabric, nullptr, 1000));
}

TEST_F(BadInput, CreateGridWithADescNotFromDefaultOrAWrongSizeReturnsInvalidDesc) {
    for (const auto& broken : BrokenDescs(SmallGrid())) {
        SCOPED_TRACE(broken.first);
        const cloth_grid_desc& desc = broken.second;
        EXPECT_REJECTED(CLOTH_ERROR_INVALID_DESC, cloth_fabric_create_grid(a_.world, &desc, &outs_.fabric));
    }
}

TEST_F(BadInput, CreateMeshWithADescNotFromDefaultOrAWrongSizeReturnsInvalidDesc) {
    for (const auto& broken : BrokenDescs(QuadMesh())) {
        SCOPED_TRACE(broken.first);
        const cloth_mesh_desc& desc = broken.second;
        EXPECT_REJECTED(CLOTH_ERROR_INVALID_DESC, cloth_fabric_create_mesh(a_.world, &desc, &outs_.fabric));
    }
}

TEST_F(BadInput, GridWithFewerThanTwoColumnsOrRowsReturnsInvalidCount) {
    const std::pair<uint32_t, uint32_t> bad[] = {{1, 8}, {0, 8}, {8, 1}, {8, 0}, {0, 0}, {1, 1}};
    for (const auto& [columns, rows] : bad) {
        SCOPED_TRACE(std::to_string(columns) + " x " + std::to_string(rows));
        cloth_grid_desc grid = SmallGrid();
        grid.columns = columns;
        grid.rows = rows;
        EXPECT_REJECTED(CLOTH_ERROR_INVALID_COUNT, cloth_fabric_create_grid(a_.world, &grid, &outs_.fabric));
    }
}

TEST_F(BadInputDeathTest, GridWhoseParticleCountOverflowsReturnsInvalidCount) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    cloth_test::bad_inputs() += 3;
    cloth_grid_desc wraps = SmallGrid();  // 65536 * 65536 wraps to 0 in 32 bits
    wraps.columns = 65536;
    wraps.rows = 65536;
    EXPECT_REJECTED_IN_CHILD(CLOTH_ERROR_INVALID_COUNT,
                             cloth_fabric_create_grid(a_.world, &wraps, &outs_.fabric));
    cloth_grid_desc huge = SmallGrid();
    huge.columns = UINT32_MAX;
    huge.rows = 2;
    EXPECT_REJECTED_IN_CHILD(CLOTH_ERROR_INVALID_COUNT,
                             cloth_fabric_create_grid(a_.world, &huge, &outs_.fabric));
    cloth_grid_desc over = SmallGrid();  // 0x55560000 particles: 3 * count > UINT32_MAX
    over.columns = 0x10000;
    over.rows = 0x5556;
    EXPECT_REJECTED_IN_CHILD(CLOTH_ERROR_INVALID_COUNT,
                             cloth_fabric_create_grid(a_.world, &over, &outs_.fabric));
}

TEST_F(BadInputDeathTest, MeshWithHugeCountsReturnsInvalidCountWithoutReadingTheArrays) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    cloth_test::bad_inputs() += 2;
    cloth_mesh_desc vertices = QuadMesh();
    vertices.vertex_count = UINT32_MAX;
    EXPECT_REJECTED_IN_CHILD(CLOTH_ERROR_INVALID_COUNT,
                             cloth_fabric_create_mesh(a_.world, &vertices, &outs_.fabric));
    cloth_mesh_desc triangles = QuadMesh();
    triangles.triangle_count = UINT32_MAX;
    EXPECT_REJECTED_IN_CHILD(CLOTH_ERROR_INVALID_COUNT,
                             cloth_fabric_create_mesh(a_.world, &triangles, &outs_.fabric));
}

// Every count the header limits is refused one past its CLOTH_MAX_* macro
// before the buffer it sizes is read: each buffer here holds what a small
// valid call needs and ends at an inaccessible page, so a read past it
// crashes the test.
TEST_F(BadInput, CountsOnePastTheirStatedLimitAreRefusedBeforeTheBufferIsRead) {
    using cloth_test::GuardedBuffer;
    const GuardedBuffer positions(kQuadPositions, sizeof kQuadPositions);
    const GuardedBuffer indices(kQuadIndices, sizeof kQuadIndices);
    ASSERT_TRUE(positions.ok() && indices.ok());

    cloth_mesh_desc mesh = QuadMesh();
    mesh.positions = positions.as<float>();
    mesh.indices = indices.as<uint32_t>();
    mesh.vertex_count = CLOTH_MAX_PARTICLES + 1;
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_COUNT, cloth_fabric_create_mesh(a_.world, &mesh, &outs_.fabric));
    mesh.vertex_count = 4;
    mesh.triangle_count = CLOTH_MAX_TRIANGLES + 1;
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_COUNT, cloth_fabric_create_mesh(a_.world, &mesh, &outs_.fabric));
    // Every count between the collider limit (2^24) and the old unstated
    // one (2^26) was read, whatever buffer came with it.
    mesh.triangle_count = (1u << 26) - 1;
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_COUNT, cloth_fabric_create_mesh(a_.world, &mesh, &outs_.fabric));

    const cloth_collider_desc collider = cloth_default_collider_desc();
    cloth_collider_id out{};
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_COUNT,
                    cloth_collider_create_convex_hull(a_.world, &collider, positions.as<float>(),
                                                      CLOTH_MAX_HULL_POINTS + 1, &out));
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_COUNT,
                    cloth_collider_create_triangle_mesh(a_.world, &collider, positions.as<float>(),
                                                        CLOTH_MAX_MESH_COLLIDER_VERTICES + 1,
                                                        indices.as<uint32_t>(), 2, &out));
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_COUNT,
                    cloth_collider_create_triangle_mesh(a_.world, &collider, positions.as<float>(), 4,
                                                        indices.as<uint32_t>(),
                                                        CLOTH_MAX_MESH_COLLIDER_TRIANGLES + 1, &out));
    cloth_heightfield_desc field = cloth_default_heightfield_desc();
    field.heights = positions.as<float>();
    field.columns = CLOTH_MAX_HEIGHTFIELD_SIDE + 1;
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_COUNT,
                    cloth_collider_create_heightfield(a_.world, &collider, &field, &out));
    field.columns = 2;
    field.rows = CLOTH_MAX_HEIGHTFIELD_SIDE + 1;
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_COUNT,
                    cloth_collider_create_heightfield(a_.world, &collider, &field, &out));

    EXPECT_REJECTED(CLOTH_ERROR_INVALID_COUNT,
                    cloth_world_set_profiling(a_.world, CLOTH_MAX_PROFILED_TASKS + 1));
    cloth_world_desc world = a_.host.world_desc();
    world.max_cloths = CLOTH_MAX_CLOTHS + 1;
    EXPECT_REJECTED_NOT_LOGGED(CLOTH_ERROR_INVALID_COUNT, cloth_world_create(&world, &outs_.world));
    world.max_cloths = 4;
    world.max_fabrics = CLOTH_MAX_FABRICS + 1;
    EXPECT_REJECTED_NOT_LOGGED(CLOTH_ERROR_INVALID_COUNT, cloth_world_create(&world, &outs_.world));
    world.max_fabrics = 4;
    world.worker_count = CLOTH_MAX_WORKERS + 1;
    EXPECT_REJECTED_NOT_LOGGED(CLOTH_ERROR_INVALID_COUNT, cloth_world_create(&world, &outs_.world));
}

TEST_F(BadInput, GridWithNonFiniteOriginOrEdgeReturnsNotFinite) {
    for (int field = 0; field < 3; ++field) {
        for (float bad : {kNaN, kInf}) {
            cloth_grid_desc grid = SmallGrid();
            float* v = field == 0 ? grid.origin : field == 1 ? grid.u : grid.v;
            v[field] = bad;  // a different component of each vector
            SCOPED_TRACE(std::string(field == 0   ? "origin"
                                     : field == 1 ? "u"
                                                  : "v") +
                         "[" + std::to_string(field) + "] = " + std::to_string(bad));
            EXPECT_REJECTED(CLOTH_ERROR_NOT_FINITE, cloth_fabric_create_grid(a_.world, &grid, &outs_.fabric));
        }
    }
}

TEST_F(BadInput, GridWithAZeroOrParallelEdgeReturnsDegenerateGeometry) {
    cloth_grid_desc zero_u = SmallGrid();
    zero_u.u[0] = zero_u.u[1] = zero_u.u[2] = 0.0f;
    EXPECT_REJECTED(CLOTH_ERROR_DEGENERATE_GEOMETRY,
                    cloth_fabric_create_grid(a_.world, &zero_u, &outs_.fabric));
    cloth_grid_desc zero_v = SmallGrid();
    zero_v.v[0] = zero_v.v[1] = zero_v.v[2] = 0.0f;
    EXPECT_REJECTED(CLOTH_ERROR_DEGENERATE_GEOMETRY,
                    cloth_fabric_create_grid(a_.world, &zero_v, &outs_.fabric));
    cloth_grid_desc parallel = SmallGrid();  // u = (1,0,0), v = (-2,0,0): zero-area triangles
    parallel.v[0] = -2.0f;
    parallel.v[1] = 0.0f;
    parallel.v[2] = 0.0f;
    EXPECT_REJECTED(CLOTH_ERROR_DEGENERATE_GEOMETRY,
                    cloth_fabric_create_grid(a_.world, &parallel, &outs_.fabric));
}

TEST_F(BadInput, UnknownSpringKindBitsReturnInvalidValue) {
    const std::string obj =
        WriteTempFile("kinds.obj", "v 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nf 1 2 3\nf 1 3 4\n");
    for (uint32_t kinds : {8u, 0x80000000u, CLOTH_SPRING_ALL | 16u}) {
        SCOPED_TRACE("spring kinds " + std::to_string(kinds));
        cloth_grid_desc grid = SmallGrid();
        grid.spring_kinds = kinds;
        EXPECT_REJECTED(CLOTH_ERROR_INVALID_VALUE, cloth_fabric_create_grid(a_.world, &grid, &outs_.fabric));
        cloth_mesh_desc mesh = QuadMesh();
        mesh.spring_kinds = kinds;
        EXPECT_REJECTED(CLOTH_ERROR_INVALID_VALUE, cloth_fabric_create_mesh(a_.world, &mesh, &outs_.fabric));
        EXPECT_REJECTED(CLOTH_ERROR_INVALID_VALUE,
                        cloth_fabric_create_obj(a_.world, obj.c_str(), kinds, &outs_.fabric));
        EXPECT_REJECTED(CLOTH_ERROR_INVALID_VALUE,
                        cloth_fabric_get_spring_count(a_.fabric, kinds, &outs_.count));
        EXPECT_REJECTED(CLOTH_ERROR_INVALID_VALUE,
                        cloth_set_spring_params(a_.cloth, kinds, cloth_spring_params{1.0f, 0.0f}));
    }
    std::remove(obj.c_str());
}

TEST_F(BadInput, MeshWithTooFewVerticesOrTrianglesReturnsInvalidCount) {
    cloth_mesh_desc no_vertices = QuadMesh();
    no_vertices.vertex_count = 0;
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_COUNT,
                    cloth_fabric_create_mesh(a_.world, &no_vertices, &outs_.fabric));
    cloth_mesh_desc two_vertices = QuadMesh();
    two_vertices.vertex_count = 2;
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_COUNT,
                    cloth_fabric_create_mesh(a_.world, &two_vertices, &outs_.fabric));
    cloth_mesh_desc no_triangles = QuadMesh();
    no_triangles.triangle_count = 0;
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_COUNT,
                    cloth_fabric_create_mesh(a_.world, &no_triangles, &outs_.fabric));
}

TEST_F(BadInput, MeshWithAnIndexOutOfRangeReturnsIndexOutOfRange) {
    for (uint32_t bad : {4u, 5u, UINT32_MAX}) {
        for (int slot : {0, 5}) {  // in the first and in the last triangle
            SCOPED_TRACE("index " + std::to_string(bad) + " at " + std::to_string(slot));
            uint32_t indices[6];
            std::memcpy(indices, kQuadIndices, sizeof indices);
            indices[slot] = bad;
            cloth_mesh_desc mesh = QuadMesh();
            mesh.indices = indices;
            EXPECT_REJECTED(CLOTH_ERROR_INDEX_OUT_OF_RANGE,
                            cloth_fabric_create_mesh(a_.world, &mesh, &outs_.fabric));
        }
    }
}

TEST_F(BadInput, MeshWithANonFinitePositionReturnsNotFinite) {
    for (int i : {0, 7, 11}) {
        for (float bad : {kNaN, kInf, -kInf}) {
            SCOPED_TRACE("positions[" + std::to_string(i) + "] = " + std::to_string(bad));
            float positions[12];
            std::memcpy(positions, kQuadPositions, sizeof positions);
            positions[i] = bad;
            cloth_mesh_desc mesh = QuadMesh();
            mesh.positions = positions;
            EXPECT_REJECTED(CLOTH_ERROR_NOT_FINITE, cloth_fabric_create_mesh(a_.world, &mesh, &outs_.fabric));
        }
    }
}

TEST_F(BadInput, MeshWithADegenerateTriangleReturnsDegenerateGeometry) {
    // Five vertices: the quad plus (2,0,0), on the line through vertices 0 and 1.
    const float positions[] = {0, 0, 0, 1, 0, 0, 1, 0, 1, 0, 0, 1, 2, 0, 0};
    // And a copy of vertex 2 at the same place, for a zero-length edge.
    const float coincident[] = {0, 0, 0, 1, 0, 0, 1, 0, 1, 0, 0, 1, 1, 0, 1};
    struct Case {
        const char* what;
        const float* positions;
        uint32_t vertex_count;
        uint32_t indices[6];
    };
    const Case cases[] = {
        {"repeated vertex index (0, 0, 1)", kQuadPositions, 4, {0, 0, 1, 0, 2, 3}},
        {"repeated vertex index (0, 2, 2)", kQuadPositions, 4, {0, 1, 2, 0, 2, 2}},
        {"zero-area triangle of three collinear vertices", positions, 5, {0, 1, 2, 0, 1, 4}},
        {"zero-length edge between two coincident vertices", coincident, 5, {0, 1, 2, 0, 2, 4}},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.what);
        cloth_mesh_desc mesh = QuadMesh();
        mesh.positions = c.positions;
        mesh.vertex_count = c.vertex_count;
        mesh.indices = c.indices;
        EXPECT_REJECTED(CLOTH_ERROR_DEGENERATE_GEOMETRY,
                        cloth_fabric_create_mesh(a_.world, &mesh, &outs_.fabric));
    }
}

TEST_F(BadInput, ObjThatDoesNotExistReturnsIoError) {
    EXPECT_REJECTED(CLOTH_ERROR_IO, cloth_fabric_create_obj(a_.world, "/nonexistent/cloth_capi/none.obj",
                                                            CLOTH_SPRING_ALL, &outs_.fabric));
    EXPECT_REJECTED(CLOTH_ERROR_IO, cloth_fabric_create_obj(a_.world, "", CLOTH_SPRING_ALL, &outs_.fabric));
}

TEST_F(BadInput, ObjWithADegenerateFaceReturnsDegenerateGeometry) {
    const std::string path = WriteTempFile("degenerate.obj", "v 0 0 0\nv 1 0 0\nv 1 0 1\nf 1 2 3\nf 1 1 2\n");
    EXPECT_REJECTED(CLOTH_ERROR_DEGENERATE_GEOMETRY,
                    cloth_fabric_create_obj(a_.world, path.c_str(), CLOTH_SPRING_ALL, &outs_.fabric));
    std::remove(path.c_str());
}

// The control for the two OBJ tests above: the same kind of file, well formed, loads.
TEST_F(BadInput, ObjWithOneQuadLoadsAsTwoTriangles) {
    check_twin_ = false;
    const std::string path = WriteTempFile("good.obj", "v 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nf 1 2 3 4\n");
    cloth_fabric_id fabric{};
    ASSERT_EQ(cloth_fabric_create_obj(a_.world, path.c_str(), CLOTH_SPRING_ALL, &fabric), CLOTH_OK)
        << cloth_get_last_error();
    uint32_t count = 0;
    EXPECT_EQ(cloth_fabric_get_triangle_count(fabric, &count), CLOTH_OK);
    EXPECT_EQ(count, 2u);
    EXPECT_EQ(cloth_fabric_get_particle_count(fabric, &count), CLOTH_OK);
    EXPECT_EQ(count, 4u);
    std::remove(path.c_str());
}

TEST_F(BadInput, ReadTrianglesWithTooSmallCapacityReturnsInvalidCountAndWritesNothing) {
    uint32_t triangles = 0;
    ASSERT_EQ(cloth_fabric_get_triangle_count(a_.fabric, &triangles), CLOTH_OK);
    ASSERT_EQ(triangles, 2 * (kColumns - 1) * (kRows - 1));
    for (uint32_t capacity : {0u, 1u, 3 * triangles - 1}) {
        SCOPED_TRACE("capacity " + std::to_string(capacity));
        EXPECT_REJECTED(CLOTH_ERROR_INVALID_COUNT,
                        cloth_fabric_read_triangles(a_.fabric, outs_.uints, capacity));
    }
}

TEST_F(BadInput, CreatingMoreFabricsThanMaxFabricsReturnsCapacity) {
    check_twin_ = false;
    const cloth_grid_desc grid = SmallGrid();
    cloth_fabric_id third{};
    ASSERT_EQ(cloth_fabric_create_grid(a_.world, &grid, &third), CLOTH_OK)
        << "the fixture leaves one slot free";
    EXPECT_REJECTED(CLOTH_ERROR_CAPACITY, cloth_fabric_create_grid(a_.world, &grid, &outs_.fabric));
    const cloth_mesh_desc mesh = QuadMesh();
    EXPECT_REJECTED(CLOTH_ERROR_CAPACITY, cloth_fabric_create_mesh(a_.world, &mesh, &outs_.fabric));
}

TEST_F(BadInput, CreateFabricWhenTheAllocatorFailsReturnsOutOfMemoryAndLeaksNothing) {
    check_twin_ = false;
    const cloth_grid_desc grid = SmallGrid();
    int failures = 0;
    cloth_fabric_id fabric{};
    bool created = false;
    for (long n = 0; n < 10000 && !created; ++n) {
        a_.host.fail_after(n);
        SCOPED_TRACE("allocator fails after " + std::to_string(n) + " allocations");
        const size_t live_before = a_.host.live_bytes();
        const cloth_test::CallOutcome o = cloth_test::call_on_fresh_thread(
            [&] { return cloth_fabric_create_grid(a_.world, &grid, &fabric); });
        a_.host.fail_after(-1);
        if (o.result == CLOTH_OK) {
            created = true;
            break;
        }
        ++failures;
        ++cloth_test::bad_inputs();
        EXPECT_EQ(o.result, CLOTH_ERROR_OUT_OF_MEMORY) << result_name(o.result);
        EXPECT_EQ(a_.host.live_bytes(), live_before) << "memory leaked by a failed cloth_fabric_create_grid";
        ASSERT_FALSE(HasFailure());
    }
    EXPECT_GE(failures, 1) << "cloth_fabric_create_grid never used the world's allocator";
    ASSERT_TRUE(created);
    uint32_t count = 0;
    EXPECT_EQ(cloth_fabric_get_particle_count(fabric, &count), CLOTH_OK);
    EXPECT_EQ(count, kParticles);
}

}  // namespace
}  // namespace cloth_bad_input
