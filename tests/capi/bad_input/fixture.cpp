// The fixture of the C API bad-input tests (see fixture.h).
#include "bad_input/fixture.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>

namespace cloth_bad_input {

const float kQuadPositions[12] = {0, 0, 0, 1, 0, 0, 1, 0, 1, 0, 0, 1};
const uint32_t kQuadIndices[6] = {0, 1, 2, 0, 2, 3};

cloth_mesh_desc QuadMesh() {
    cloth_mesh_desc desc = cloth_default_mesh_desc();
    desc.positions = kQuadPositions;
    desc.vertex_count = 4;
    desc.indices = kQuadIndices;
    desc.triangle_count = 2;
    return desc;
}

cloth_grid_desc SmallGrid() {
    cloth_grid_desc desc = cloth_default_grid_desc();
    desc.columns = kColumns;
    desc.rows = kRows;
    return desc;
}

std::string WriteTempFile(const std::string& name, const std::string& text) {
    const std::string path = ::testing::TempDir() + "cloth_capi_" + std::to_string(::getpid()) + "_" + name;
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out << text;
    return path;
}

bool operator==(const cloth_id& a, const cloth_id& b) { return cloth_id_equal(a, b); }
bool operator==(const cloth_fabric_id& a, const cloth_fabric_id& b) { return cloth_fabric_id_equal(a, b); }

void BadInput::SetUp() {
    BuildScene(a_);
    if (HasFatalFailure()) return;
    BuildScene(b_);
    if (HasFatalFailure()) return;
    ASSERT_TRUE(cloth_test::SameState(cloth_test::ReadState(a_.cloth), cloth_test::ReadState(b_.cloth)))
        << "two worlds built by identical calls differ (determinism)";
    watch_.world = a_.world;
    watch_.cloths = {a_.cloth, a_.other};
    watch_.memory = &a_.host;
    watch_.outputs = {{&outs_, sizeof outs_, "an output argument"}};
    twin_watch_.world = b_.world;
    twin_watch_.cloths = {b_.cloth, b_.other};
    MakeDeadWorld();
    ResetOuts();
}

void BadInput::TearDown() {
    if (check_twin_) {
        EXPECT_TRUE(cloth_test::SameFutureAsTwin(watch_, twin_watch_, 3));
    }
    for (Scene* s : {&a_, &b_}) {
        if (s->world.index1 != 0) {
            EXPECT_EQ(cloth_world_destroy(s->world), CLOTH_OK);
        }
        cloth_test::ExpectAllReturned(s->host);
    }
}

void BadInput::BuildScene(Scene& s) {
    cloth_world_desc wd = s.host.world_desc();
    wd.max_cloths = kMaxCloths;
    wd.max_fabrics = kMaxFabrics;
    ASSERT_EQ(cloth_world_create(&wd, &s.world), CLOTH_OK) << cloth_get_last_error();
    const cloth_grid_desc grid = SmallGrid();
    ASSERT_EQ(cloth_fabric_create_grid(s.world, &grid, &s.fabric), CLOTH_OK) << cloth_get_last_error();

    // Fill the fabric table, free one slot, re-use exactly that slot, free another.
    cloth_grid_desc small = cloth_default_grid_desc();
    small.columns = 3;
    small.rows = 3;
    ASSERT_EQ(cloth_fabric_create_grid(s.world, &small, &s.stale_fabric), CLOTH_OK);
    ASSERT_EQ(cloth_fabric_create_grid(s.world, &small, &s.freed_fabric), CLOTH_OK);
    ASSERT_EQ(cloth_fabric_destroy(s.stale_fabric), CLOTH_OK);
    ASSERT_EQ(cloth_fabric_create_grid(s.world, &small, &s.other_fabric), CLOTH_OK);
    ASSERT_EQ(cloth_fabric_destroy(s.freed_fabric), CLOTH_OK);

    // The same for cloths.
    cloth_desc desc = cloth_default_desc();
    desc.fabric = s.fabric;
    ASSERT_EQ(cloth_create(s.world, &desc, &s.cloth), CLOTH_OK) << cloth_get_last_error();
    ASSERT_EQ(cloth_create(s.world, &desc, &s.stale_cloth), CLOTH_OK) << cloth_get_last_error();
    ASSERT_EQ(cloth_create(s.world, &desc, &s.freed_cloth), CLOTH_OK) << cloth_get_last_error();
    ASSERT_EQ(cloth_destroy(s.stale_cloth), CLOTH_OK);
    ASSERT_EQ(cloth_create(s.world, &desc, &s.other), CLOTH_OK) << cloth_get_last_error();
    ASSERT_EQ(cloth_destroy(s.freed_cloth), CLOTH_OK);

    const uint32_t corners[] = {0, kColumns - 1};
    ASSERT_EQ(cloth_pin(s.cloth, corners, 2), CLOTH_OK);
    std::vector<uint32_t> top_row;
    for (uint32_t c = 0; c < kColumns; ++c) top_row.push_back(c);
    ASSERT_EQ(cloth_pin(s.other, top_row.data(), kColumns), CLOTH_OK);
    const float wind[3] = {2.0f, 0.0f, 3.0f};
    const float other_wind[3] = {-1.0f, 0.0f, 2.0f};
    ASSERT_EQ(cloth_set_wind(s.cloth, wind), CLOTH_OK);
    ASSERT_EQ(cloth_set_wind(s.other, other_wind), CLOTH_OK);
    for (int i = 0; i < 5; ++i) ASSERT_EQ(cloth_step(s.world, kFrame), CLOTH_OK) << cloth_get_last_error();
    for (const LogEntry& e : s.host.logs()) {
        ASSERT_NE(e.level, CLOTH_LOG_ERROR)
            << "an error was logged while building a valid scene: " << e.message;
    }
    s.host.clear_logs();
}

// A world with a fabric and a cloth, destroyed: its ids must stay invalid.
void BadInput::MakeDeadWorld() {
    const cloth_world_desc wd = cloth_default_world_desc();
    ASSERT_EQ(cloth_world_create(&wd, &dead_world_), CLOTH_OK);
    const cloth_grid_desc grid = SmallGrid();
    ASSERT_EQ(cloth_fabric_create_grid(dead_world_, &grid, &dead_fabric_), CLOTH_OK);
    cloth_desc desc = cloth_default_desc();
    desc.fabric = dead_fabric_;
    ASSERT_EQ(cloth_create(dead_world_, &desc, &dead_cloth_), CLOTH_OK);
    ASSERT_EQ(cloth_world_destroy(dead_world_), CLOTH_OK);
}

void BadInput::ResetOuts() {
    std::memset(&outs_, 0xA5, sizeof outs_);
    outs_.stats.struct_size = sizeof(cloth_stats);
}

void BadInput::ExpectRejected(cloth_result expected, const std::string& what,
                              const std::function<cloth_result()>& call, cloth_test::Logged logged) {
    ResetOuts();
    cloth_test::ExpectRejected(watch_, a_.host, expected, what, call, logged);
}

cloth_desc BadInput::ValidClothDesc() const {
    cloth_desc desc = cloth_default_desc();
    desc.fabric = a_.fabric;
    return desc;
}

void BadInputDeathTest::RejectInChild(cloth_result expected, const std::function<cloth_result()>& call) {
    ResetOuts();
    std::string broken;
    {
        const cloth_test::Unchanged unchanged(watch_);
        const size_t logs_before = a_.host.logs().size();
        const cloth_test::CallOutcome o = cloth_test::call_on_fresh_thread(call);
        for (const std::string& problem : cloth_test::rejection_problems(
                 expected, o, a_.host.errors_since(logs_before), cloth_test::Logged::kYes))
            broken += problem + "; ";
        broken += unchanged.what_changed();
        std::fprintf(stderr, "result=%s;contract=%s;\n", cloth_result_name(o.result),
                     broken.empty() ? "kept" : broken.c_str());
    }
    std::fflush(stderr);
    std::_Exit(0);
}

BadValues<cloth_solver_settings> BadSolver() {
    using S = cloth_solver_settings;
    BadValues<S> out;
    out.emplace_back(
        "kind 6 (unknown)", [](S& s) { s.kind = static_cast<cloth_solver_kind>(6); },
        CLOTH_ERROR_INVALID_VALUE);
    out.emplace_back(
        "kind FORCE_U32", [](S& s) { s.kind = CLOTH_SOLVER_KIND_FORCE_U32; }, CLOTH_ERROR_INVALID_VALUE);
    out.emplace_back(
        "iterations 0", [](S& s) { s.iterations = 0; }, CLOTH_ERROR_INVALID_VALUE);
    out.emplace_back(
        "iterations 257", [](S& s) { s.iterations = 257; }, CLOTH_ERROR_INVALID_VALUE);
    out.emplace_back(
        "substeps 0", [](S& s) { s.substeps = 0; }, CLOTH_ERROR_INVALID_VALUE);
    out.emplace_back(
        "substeps 65", [](S& s) { s.substeps = 65; }, CLOTH_ERROR_INVALID_VALUE);
    out.emplace_back(
        "cg_tolerance 0", [](S& s) { s.cg_tolerance = 0.0f; }, CLOTH_ERROR_INVALID_VALUE);
    out.emplace_back(
        "cg_tolerance 1", [](S& s) { s.cg_tolerance = 1.0f; }, CLOTH_ERROR_INVALID_VALUE);
    out.emplace_back(
        "cg_tolerance -1e-6", [](S& s) { s.cg_tolerance = -1e-6f; }, CLOTH_ERROR_INVALID_VALUE);
    out.emplace_back(
        "cg_tolerance NaN", [](S& s) { s.cg_tolerance = kNaN; }, CLOTH_ERROR_NOT_FINITE);
    out.emplace_back(
        "cg_tolerance inf", [](S& s) { s.cg_tolerance = kInf; }, CLOTH_ERROR_NOT_FINITE);
    out.emplace_back(
        "cg_max_iterations 0", [](S& s) { s.cg_max_iterations = 0; }, CLOTH_ERROR_INVALID_VALUE);
    out.emplace_back(
        "cg_max_iterations 100001", [](S& s) { s.cg_max_iterations = 100001; }, CLOTH_ERROR_INVALID_VALUE);
    return out;
}

BadValues<cloth_aero_params> BadAero() {
    using A = cloth_aero_params;
    BadValues<A> out;
    for (int axis = 0; axis < 3; ++axis) {
        out.emplace_back(
            "wind[" + std::to_string(axis) + "] = NaN", [axis](A& a) { a.wind[axis] = kNaN; },
            CLOTH_ERROR_NOT_FINITE);
        out.emplace_back(
            "wind[" + std::to_string(axis) + "] = -inf", [axis](A& a) { a.wind[axis] = -kInf; },
            CLOTH_ERROR_NOT_FINITE);
    }
    out.emplace_back(
        "air_density = -1", [](A& a) { a.air_density = -1.0f; }, CLOTH_ERROR_INVALID_VALUE);
    out.emplace_back(
        "air_density = NaN", [](A& a) { a.air_density = kNaN; }, CLOTH_ERROR_NOT_FINITE);
    out.emplace_back(
        "drag_coefficient = -0.1", [](A& a) { a.drag_coefficient = -0.1f; }, CLOTH_ERROR_INVALID_VALUE);
    out.emplace_back(
        "drag_coefficient = inf", [](A& a) { a.drag_coefficient = kInf; }, CLOTH_ERROR_NOT_FINITE);
    out.emplace_back(
        "lift_coefficient = -0.1", [](A& a) { a.lift_coefficient = -0.1f; }, CLOTH_ERROR_INVALID_VALUE);
    out.emplace_back(
        "lift_coefficient = NaN", [](A& a) { a.lift_coefficient = kNaN; }, CLOTH_ERROR_NOT_FINITE);
    out.emplace_back(
        "linear_drag = -0.02", [](A& a) { a.linear_drag = -0.02f; }, CLOTH_ERROR_INVALID_VALUE);
    out.emplace_back(
        "linear_drag = inf", [](A& a) { a.linear_drag = kInf; }, CLOTH_ERROR_NOT_FINITE);
    return out;
}

}  // namespace cloth_bad_input
