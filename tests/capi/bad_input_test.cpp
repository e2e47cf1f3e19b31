// Contract tests of the cloth C API against bad input.
//
// Every rejected call is checked the same way (ExpectRejected):
//   - it returns the specific cloth_result the contract names;
//   - it is made on a fresh thread, so cloth_get_last_error() is "" before it
//     and must be a non-empty message (set by this very call) after it;
//   - if the call's world is valid, the world's log callback received one
//     CLOTH_LOG_ERROR entry with the same code and the same message;
//   - nothing changed: the two cloths of the fixture world are read back
//     (positions, velocities, normals, pins, solver settings, stats) and
//     compared bit for bit, the host allocator holds exactly the bytes it held
//     before, and output arguments were not written;
//   - at the end of each test the fixture world and an identical twin world
//     are stepped together and must stay bit-identical, which catches hidden
//     state (gravity, wind, aerodynamics, spring parameters, pin targets) that
//     a failed call changed.
//
// Link: cloth_static, GTest::gtest_main (and Threads).
//
// Where the header leaves a code open, the intended mapping is:
//   NaN/Inf -> CLOTH_ERROR_NOT_FINITE; negative or out-of-range value ->
//   CLOTH_ERROR_INVALID_VALUE; counts -> CLOTH_ERROR_INVALID_COUNT; indices ->
//   CLOTH_ERROR_INDEX_OUT_OF_RANGE; read buffer too small ->
//   CLOTH_ERROR_INVALID_COUNT.
#include <cloth/cloth.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

// tests/capi/enum_from_int.c: an out-of-range enum passed the way a C caller can.
extern "C" const char* cloth_test_stage_name_of_int(int32_t value);

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr uint32_t kColumns = 8;
constexpr uint32_t kRows = 8;
constexpr uint32_t kParticles = kColumns * kRows;
constexpr uint32_t kFloats = 3 * kParticles;
constexpr uint32_t kMaxCloths = 3;
constexpr uint32_t kMaxFabrics = 3;
constexpr float kFrame = 1.0f / 60.0f;

std::atomic<int> g_bad_inputs{0};
std::atomic<int> g_wrong_user_pointer{0};

std::string Name(cloth_result r) {
    const char* name = cloth_result_name(r);
    std::ostringstream out;
    out << (name ? name : "<NULL name>") << " (" << static_cast<int>(r) << ")";
    return out.str();
}

// ---------------------------------------------------------------------------
// Host callbacks: a counting allocator that can be told to fail, and a log.
// ---------------------------------------------------------------------------

struct LogEntry {
    cloth_log_level level;
    cloth_result code;
    std::string message;
};

struct Host {
    static constexpr uint32_t kMagic = 0xC107'4057u;
    uint32_t magic = kMagic;
    std::map<void*, size_t> live;  // pointer -> size
    size_t live_bytes = 0;
    size_t alloc_calls = 0;
    size_t free_calls = 0;
    long allocations_left = -1;                        // < 0: never fail
    size_t max_single_allocation = size_t{256} << 20;  // refuse absurd requests
    std::vector<std::string> violations;
    std::vector<LogEntry> logs;
};

Host* AsHost(void* user) {
    Host* h = static_cast<Host*>(user);
    if (h == nullptr || h->magic != Host::kMagic) {
        ++g_wrong_user_pointer;
        return nullptr;
    }
    return h;
}

void* HostAlloc(size_t size, size_t alignment, void* user) {
    Host* h = AsHost(user);
    if (h == nullptr) return nullptr;
    if (alignment == 0 || (alignment & (alignment - 1)) != 0 || alignment > 64) {
        h->violations.push_back("alloc with alignment " + std::to_string(alignment));
        return nullptr;
    }
    if (h->allocations_left == 0 || size > h->max_single_allocation) return nullptr;
    if (h->allocations_left > 0) --h->allocations_left;
    void* p = nullptr;
    if (posix_memalign(&p, alignment < sizeof(void*) ? sizeof(void*) : alignment, size == 0 ? 1 : size) !=
        0) {
        return nullptr;
    }
    h->live[p] = size;
    h->live_bytes += size;
    ++h->alloc_calls;
    return p;
}

void HostFree(void* ptr, size_t size, void* user) {
    Host* h = AsHost(user);
    if (h == nullptr) return;
    if (ptr == nullptr) {
        h->violations.push_back("free(NULL)");
        return;
    }
    auto it = h->live.find(ptr);
    if (it == h->live.end()) {
        h->violations.push_back("free of a pointer the allocator did not return (or freed twice)");
        return;
    }
    if (it->second != size) {
        h->violations.push_back("free size " + std::to_string(size) + " for a block of " +
                                std::to_string(it->second));
    }
    h->live_bytes -= it->second;
    h->live.erase(it);
    ++h->free_calls;
    std::free(ptr);
}

void HostLog(cloth_log_level level, cloth_result code, const char* message, void* user) {
    Host* h = AsHost(user);
    if (h == nullptr) return;
    if (message == nullptr) {
        h->violations.push_back("log with a NULL message");
        return;
    }
    h->logs.push_back({level, code, message});
}

cloth_world_desc HostWorldDesc(Host* host) {
    cloth_world_desc desc = cloth_default_world_desc();
    desc.alloc = HostAlloc;
    desc.free = HostFree;
    desc.log = HostLog;
    desc.user = host;
    return desc;
}

// ---------------------------------------------------------------------------
// Reading a cloth's whole observable state.
// ---------------------------------------------------------------------------

struct Snapshot {
    uint32_t count = 0;
    std::vector<float> positions, velocities, normals;
    std::vector<uint8_t> pinned;
    cloth_solver_settings solver{};
    cloth_stats stats{};
};

Snapshot TakeSnapshot(cloth_id id) {
    Snapshot s;
    EXPECT_EQ(cloth_get_particle_count(id, &s.count), CLOTH_OK) << "snapshot: cloth_get_particle_count";
    s.positions.assign(3 * s.count, 0.0f);
    s.velocities.assign(3 * s.count, 0.0f);
    s.normals.assign(3 * s.count, 0.0f);
    EXPECT_EQ(cloth_read_positions(id, s.positions.data(), 3 * s.count), CLOTH_OK) << "snapshot";
    EXPECT_EQ(cloth_read_velocities(id, s.velocities.data(), 3 * s.count), CLOTH_OK) << "snapshot";
    EXPECT_EQ(cloth_read_normals(id, s.normals.data(), 3 * s.count), CLOTH_OK) << "snapshot";
    for (uint32_t i = 0; i < s.count; ++i) {
        bool pinned = false;
        EXPECT_EQ(cloth_is_pinned(id, i, &pinned), CLOTH_OK) << "snapshot: cloth_is_pinned " << i;
        s.pinned.push_back(pinned ? 1 : 0);
    }
    std::memset(&s.solver, 0, sizeof s.solver);
    s.solver.struct_size = sizeof s.solver;
    EXPECT_EQ(cloth_get_solver(id, &s.solver), CLOTH_OK) << "snapshot: cloth_get_solver";
    std::memset(&s.stats, 0, sizeof s.stats);
    s.stats.struct_size = sizeof s.stats;
    EXPECT_EQ(cloth_get_stats(id, &s.stats), CLOTH_OK) << "snapshot: cloth_get_stats";
    return s;
}

template <typename T>
uint64_t Bits(T v) {
    uint64_t out = 0;
    std::memcpy(&out, &v, sizeof v);
    return out;
}

::testing::AssertionResult SameFloats(const char* what, const std::vector<float>& a,
                                      const std::vector<float>& b) {
    if (a.size() != b.size()) return ::testing::AssertionFailure() << what << ": sizes differ";
    for (size_t i = 0; i < a.size(); ++i) {
        if (Bits(a[i]) != Bits(b[i])) {
            return ::testing::AssertionFailure() << what << "[" << i / 3 << "]."
                                                 << "xyz"[i % 3] << " was " << a[i] << ", now " << b[i];
        }
    }
    return ::testing::AssertionSuccess();
}

// Bit-identical state. `compare_step_diagnostics` is off only across a
// cloth_step, which legitimately updates last_step_result and the solver
// diagnostics (last_solver_iterations/residual) even when it restores the state.
::testing::AssertionResult SameState(const Snapshot& a, const Snapshot& b,
                                     bool compare_step_diagnostics = true) {
    if (a.count != b.count) {
        return ::testing::AssertionFailure() << "particle count was " << a.count << ", now " << b.count;
    }
    for (auto r :
         {SameFloats("position", a.positions, b.positions),
          SameFloats("velocity", a.velocities, b.velocities), SameFloats("normal", a.normals, b.normals)}) {
        if (!r) return r;
    }
    for (size_t i = 0; i < a.pinned.size(); ++i) {
        if (a.pinned[i] != b.pinned[i]) {
            return ::testing::AssertionFailure() << "pin state of particle " << i << " was "
                                                 << int(a.pinned[i]) << ", now " << int(b.pinned[i]);
        }
    }
    const cloth_solver_settings& x = a.solver;
    const cloth_solver_settings& y = b.solver;
    if (x.kind != y.kind || x.iterations != y.iterations || x.substeps != y.substeps ||
        Bits(x.cg_tolerance) != Bits(y.cg_tolerance) || x.cg_max_iterations != y.cg_max_iterations ||
        x.compression_safe_jacobian != y.compression_safe_jacobian) {
        return ::testing::AssertionFailure()
               << "solver settings changed: kind " << x.kind << "->" << y.kind << ", iterations "
               << x.iterations << "->" << y.iterations << ", substeps " << x.substeps << "->" << y.substeps
               << ", cg_tolerance " << x.cg_tolerance << "->" << y.cg_tolerance << ", cg_max_iterations "
               << x.cg_max_iterations << "->" << y.cg_max_iterations;
    }
    const cloth_stats& s = a.stats;
    const cloth_stats& t = b.stats;
    if (Bits(s.kinetic_energy) != Bits(t.kinetic_energy) ||
        Bits(s.gravity_energy) != Bits(t.gravity_energy) ||
        Bits(s.elastic_energy) != Bits(t.elastic_energy) || Bits(s.max_strain) != Bits(t.max_strain) ||
        Bits(s.mean_strain) != Bits(t.mean_strain) || Bits(s.max_speed) != Bits(t.max_speed) ||
        (compare_step_diagnostics && (s.last_solver_iterations != t.last_solver_iterations ||
                                      Bits(s.last_solver_residual) != Bits(t.last_solver_residual) ||
                                      s.last_step_result != t.last_step_result))) {
        return ::testing::AssertionFailure()
               << "stats changed: kinetic " << s.kinetic_energy << "->" << t.kinetic_energy << ", gravity "
               << s.gravity_energy << "->" << t.gravity_energy << ", elastic " << s.elastic_energy << "->"
               << t.elastic_energy << ", max_strain " << s.max_strain << "->" << t.max_strain
               << ", mean_strain " << s.mean_strain << "->" << t.mean_strain << ", max_speed " << s.max_speed
               << "->" << t.max_speed << ", last_solver_iterations " << s.last_solver_iterations << "->"
               << t.last_solver_iterations << ", last_solver_residual " << s.last_solver_residual << "->"
               << t.last_solver_residual << ", last_step_result " << Name(s.last_step_result) << "->"
               << Name(t.last_step_result);
    }
    return ::testing::AssertionSuccess();
}

bool AllFinite(const std::vector<float>& v) {
    for (float f : v) {
        if (!std::isfinite(f)) return false;
    }
    return true;
}

// ---------------------------------------------------------------------------
// Calls made on a fresh thread, so that the last error seen is this call's.
// ---------------------------------------------------------------------------

struct Outcome {
    cloth_result result = CLOTH_OK;
    bool error_before_null = false;
    bool error_after_null = false;
    std::string error_before;
    std::string error_after;
};

Outcome RunOnFreshThread(const std::function<cloth_result()>& call) {
    Outcome o;
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

// ---------------------------------------------------------------------------
// Handy valid inputs.
// ---------------------------------------------------------------------------

// A 1 m x 1 m square in the x-z plane, two triangles.
const float kQuadPositions[] = {0, 0, 0, 1, 0, 0, 1, 0, 1, 0, 0, 1};
const uint32_t kQuadIndices[] = {0, 1, 2, 0, 2, 3};

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

bool operator==(const cloth_id& a, const cloth_id& b) {
    return a.index1 == b.index1 && a.world1 == b.world1 && a.generation == b.generation &&
           a.world_generation == b.world_generation;
}
bool operator==(const cloth_fabric_id& a, const cloth_fabric_id& b) {
    return a.index1 == b.index1 && a.world1 == b.world1 && a.generation == b.generation &&
           a.world_generation == b.world_generation;
}

// ---------------------------------------------------------------------------
// The fixture: a world with an 8x8 grid fabric, two cloths with pins and
// wind, stepped a few frames; an identical twin world; and ids of every bad
// kind (stale in a re-used slot, stale in a free slot, of a destroyed world).
// ---------------------------------------------------------------------------

struct Scene {
    Host host;
    cloth_world_id world{};
    cloth_fabric_id fabric{};        // the 8x8 grid the cloths use
    cloth_fabric_id other_fabric{};  // re-uses stale_fabric's slot
    cloth_fabric_id stale_fabric{};  // destroyed; its slot now holds other_fabric
    cloth_fabric_id freed_fabric{};  // destroyed; its slot is free
    cloth_id cloth{};                // main cloth: corners of the top row pinned
    cloth_id other{};                // second cloth: whole top row pinned; re-uses stale_cloth's slot
    cloth_id stale_cloth{};          // destroyed; its slot now holds `other`
    cloth_id freed_cloth{};          // destroyed; its slot is free
};

enum class Logged { kYes, kNotChecked };

#define EXPECT_REJECTED(expected, call) \
    ExpectRejected((expected), #call, [&]() -> cloth_result { return (call); })
#define EXPECT_REJECTED_UNLOGGED(expected, call) \
    ExpectRejected((expected), #call, [&]() -> cloth_result { return (call); }, Logged::kNotChecked)

class BadInput : public ::testing::Test {
  protected:
    void SetUp() override {
        BuildScene(a_);
        if (HasFatalFailure()) return;
        BuildScene(b_);
        if (HasFatalFailure()) return;
        ASSERT_TRUE(SameState(TakeSnapshot(a_.cloth), TakeSnapshot(b_.cloth)))
            << "two worlds built by identical calls differ (determinism)";
        MakeDeadWorld();
        ResetOuts();
    }

    void TearDown() override {
        if (check_twin_) ExpectSameFutureAsTwin();
        for (Scene* s : {&a_, &b_}) {
            if (s->world.index1 != 0) {
                EXPECT_EQ(cloth_world_destroy(s->world), CLOTH_OK);
            }
            EXPECT_EQ(s->host.live_bytes, 0u) << "bytes still allocated after cloth_world_destroy";
            EXPECT_EQ(s->host.alloc_calls, s->host.free_calls);
            for (const std::string& v : s->host.violations) ADD_FAILURE() << "allocator/log misuse: " << v;
        }
        EXPECT_EQ(g_wrong_user_pointer.load(), 0)
            << "a callback received a user pointer that is not desc.user";
    }

    void BuildScene(Scene& s) {
        const cloth_world_desc wd = [&] {
            cloth_world_desc d = HostWorldDesc(&s.host);
            d.max_cloths = kMaxCloths;
            d.max_fabrics = kMaxFabrics;
            return d;
        }();
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
        for (int i = 0; i < 5; ++i)
            ASSERT_EQ(cloth_step(s.world, kFrame), CLOTH_OK) << cloth_get_last_error();
        for (const LogEntry& e : s.host.logs) {
            ASSERT_NE(e.level, CLOTH_LOG_ERROR)
                << "an error was logged while building a valid scene: " << e.message;
        }
        s.host.logs.clear();
    }

    // A world with a fabric and a cloth, destroyed: its ids must stay invalid.
    void MakeDeadWorld() {
        const cloth_world_desc wd = cloth_default_world_desc();
        ASSERT_EQ(cloth_world_create(&wd, &dead_world_), CLOTH_OK);
        const cloth_grid_desc grid = SmallGrid();
        ASSERT_EQ(cloth_fabric_create_grid(dead_world_, &grid, &dead_fabric_), CLOTH_OK);
        cloth_desc desc = cloth_default_desc();
        desc.fabric = dead_fabric_;
        ASSERT_EQ(cloth_create(dead_world_, &desc, &dead_cloth_), CLOTH_OK);
        ASSERT_EQ(cloth_world_destroy(dead_world_), CLOTH_OK);
    }

    // Steps the fixture world and its twin together: both must stay bit-identical.
    void ExpectSameFutureAsTwin() {
        for (int i = 0; i < 3; ++i) {
            EXPECT_EQ(cloth_step(a_.world, kFrame), CLOTH_OK) << cloth_get_last_error();
            EXPECT_EQ(cloth_step(b_.world, kFrame), CLOTH_OK) << cloth_get_last_error();
        }
        EXPECT_TRUE(SameState(TakeSnapshot(b_.cloth), TakeSnapshot(a_.cloth)))
            << "main cloth: after the rejected calls, the world no longer evolves like its untouched twin";
        EXPECT_TRUE(SameState(TakeSnapshot(b_.other), TakeSnapshot(a_.other)))
            << "second cloth: after the rejected calls, the world no longer evolves like its untouched twin";
    }

    // Output arguments: filled with a pattern before each call; a rejected
    // call must leave them as they were.
    struct Outs {
        cloth_world_id world;
        cloth_fabric_id fabric;
        cloth_id cloth;
        uint32_t count;
        unsigned char pinned_byte;  // written through a bool*; only compared as a byte
        cloth_solver_settings solver;
        cloth_stats stats;
        float floats[kFloats + 8];
        uint32_t uints[3 * 2 * (kColumns - 1) * (kRows - 1) + 8];
    };

    void ResetOuts() {
        std::memset(&outs_, 0xA5, sizeof outs_);
        outs_.stats.struct_size = sizeof(cloth_stats);
        std::memcpy(&pristine_outs_, &outs_, sizeof outs_);
    }
    bool OutsUnchanged() const { return std::memcmp(&outs_, &pristine_outs_, sizeof outs_) == 0; }
    bool* OutPinned() { return reinterpret_cast<bool*>(&outs_.pinned_byte); }

    void ExpectRejected(cloth_result expected, const std::string& what,
                        const std::function<cloth_result()>& call, Logged logged = Logged::kYes) {
        SCOPED_TRACE(what);
        ++g_bad_inputs;
        const Snapshot cloth_before = TakeSnapshot(a_.cloth);
        const Snapshot other_before = TakeSnapshot(a_.other);
        const size_t live_before = a_.host.live_bytes;
        const size_t logs_before = a_.host.logs.size();
        ResetOuts();

        const Outcome o = RunOnFreshThread(call);

        EXPECT_EQ(o.result, expected)
            << "\n    call: " << what << "\n    expected " << Name(expected) << ", got " << Name(o.result)
            << (o.error_after.empty() ? "" : "\n    message: " + o.error_after);
        EXPECT_FALSE(o.error_before_null) << "cloth_get_last_error() returned NULL on a fresh thread";
        EXPECT_EQ(o.error_before, "") << "cloth_get_last_error() is not \"\" on a thread that made no call";
        EXPECT_FALSE(o.error_after_null) << what << ": cloth_get_last_error() returned NULL";
        EXPECT_NE(o.error_after, "") << what << ": failed, but cloth_get_last_error() is empty";
        if (logged == Logged::kYes) {
            const LogEntry* last_error = nullptr;
            for (size_t i = logs_before; i < a_.host.logs.size(); ++i) {
                if (a_.host.logs[i].level == CLOTH_LOG_ERROR) last_error = &a_.host.logs[i];
            }
            if (last_error == nullptr) {
                ADD_FAILURE() << what << ": the world's log callback did not receive the error";
            } else {
                EXPECT_EQ(last_error->code, o.result)
                    << what << ": logged code differs from the returned one";
                EXPECT_EQ(last_error->message, o.error_after)
                    << what << ": logged message differs from cloth_get_last_error()";
            }
        }
        EXPECT_TRUE(OutsUnchanged()) << what << ": a rejected call wrote to an output argument";
        EXPECT_TRUE(SameState(cloth_before, TakeSnapshot(a_.cloth))) << what << ": main cloth changed";
        EXPECT_TRUE(SameState(other_before, TakeSnapshot(a_.other))) << what << ": second cloth changed";
        EXPECT_EQ(a_.host.live_bytes, live_before) << what << ": allocated memory changed";
    }

    cloth_desc ValidClothDesc() const {
        cloth_desc desc = cloth_default_desc();
        desc.fabric = a_.fabric;
        return desc;
    }

    Scene a_;  // the world every test works on
    Scene b_;  // its twin, never touched by a test
    cloth_world_id dead_world_{};
    cloth_fabric_id dead_fabric_{};
    cloth_id dead_cloth_{};
    Outs outs_{};
    Outs pristine_outs_{};
    bool check_twin_ = true;
};

// ===========================================================================
// Handles
// ===========================================================================

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
        EXPECT_REJECTED_UNLOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_world_set_gravity(b.id, gravity));
        EXPECT_REJECTED_UNLOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_world_shift_origin(b.id, gravity));
        EXPECT_REJECTED_UNLOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_world_set_worker_spin(b.id, 100));
        EXPECT_REJECTED_UNLOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_step(b.id, kFrame));
        EXPECT_REJECTED_UNLOGGED(CLOTH_ERROR_INVALID_HANDLE,
                                 cloth_fabric_create_grid(b.id, &grid, &outs_.fabric));
        EXPECT_REJECTED_UNLOGGED(CLOTH_ERROR_INVALID_HANDLE,
                                 cloth_fabric_create_mesh(b.id, &mesh, &outs_.fabric));
        EXPECT_REJECTED_UNLOGGED(CLOTH_ERROR_INVALID_HANDLE,
                                 cloth_fabric_create_obj(b.id, obj.c_str(), CLOTH_SPRING_ALL, &outs_.fabric));
        EXPECT_REJECTED_UNLOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_create(b.id, &desc, &outs_.cloth));
        EXPECT_REJECTED_UNLOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_world_destroy(b.id));
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
        EXPECT_REJECTED_UNLOGGED(CLOTH_ERROR_INVALID_HANDLE,
                                 cloth_fabric_get_particle_count(b.id, &outs_.count));
        EXPECT_REJECTED_UNLOGGED(CLOTH_ERROR_INVALID_HANDLE,
                                 cloth_fabric_get_triangle_count(b.id, &outs_.count));
        EXPECT_REJECTED_UNLOGGED(CLOTH_ERROR_INVALID_HANDLE,
                                 cloth_fabric_get_spring_count(b.id, CLOTH_SPRING_ALL, &outs_.count));
        EXPECT_REJECTED_UNLOGGED(CLOTH_ERROR_INVALID_HANDLE,
                                 cloth_fabric_read_triangles(b.id, outs_.uints, std::size(outs_.uints)));
        cloth_desc desc = ValidClothDesc();
        desc.fabric = b.id;
        // The world is valid here, so the error is one of its calls and is logged.
        EXPECT_REJECTED(CLOTH_ERROR_INVALID_HANDLE, cloth_create(a_.world, &desc, &outs_.cloth));
        EXPECT_REJECTED_UNLOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_fabric_destroy(b.id));
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
        EXPECT_REJECTED_UNLOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_get_particle_count(id, &outs_.count));
        EXPECT_REJECTED_UNLOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_read_positions(id, outs_.floats, kFloats));
        EXPECT_REJECTED_UNLOGGED(CLOTH_ERROR_INVALID_HANDLE,
                                 cloth_read_velocities(id, outs_.floats, kFloats));
        EXPECT_REJECTED_UNLOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_read_normals(id, outs_.floats, kFloats));
        EXPECT_REJECTED_UNLOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_set_positions(id, index, xyz, 1));
        EXPECT_REJECTED_UNLOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_pin(id, index, 1));
        EXPECT_REJECTED_UNLOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_unpin(id, index, 1));
        EXPECT_REJECTED_UNLOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_set_pin_targets(id, index, xyz, 1));
        EXPECT_REJECTED_UNLOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_is_pinned(id, 0, OutPinned()));
        EXPECT_REJECTED_UNLOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_set_solver(id, &solver));
        EXPECT_REJECTED_UNLOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_get_solver(id, &outs_.solver));
        EXPECT_REJECTED_UNLOGGED(CLOTH_ERROR_INVALID_HANDLE,
                                 cloth_set_spring_params(id, CLOTH_SPRING_ALL, spring));
        EXPECT_REJECTED_UNLOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_set_aero(id, &aero));
        EXPECT_REJECTED_UNLOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_set_wind(id, xyz));
        EXPECT_REJECTED_UNLOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_get_stats(id, &outs_.stats));
        EXPECT_REJECTED_UNLOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_destroy(id));
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

TEST_F(BadInput, DestroyingTwiceReturnsInvalidHandleTheSecondTime) {
    check_twin_ = false;
    cloth_id extra{};
    cloth_desc desc = ValidClothDesc();
    ASSERT_EQ(cloth_create(a_.world, &desc, &extra), CLOTH_OK);
    ASSERT_EQ(cloth_destroy(extra), CLOTH_OK);
    EXPECT_REJECTED_UNLOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_destroy(extra));

    ASSERT_EQ(cloth_fabric_destroy(a_.other_fabric), CLOTH_OK);
    EXPECT_REJECTED_UNLOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_fabric_destroy(a_.other_fabric));

    Host host;
    const cloth_world_desc wd = HostWorldDesc(&host);
    cloth_world_id world{};
    ASSERT_EQ(cloth_world_create(&wd, &world), CLOTH_OK);
    ASSERT_EQ(cloth_world_destroy(world), CLOTH_OK);
    EXPECT_REJECTED_UNLOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_world_destroy(world));
    EXPECT_EQ(host.live_bytes, 0u);
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

    EXPECT_REJECTED_UNLOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_get_particle_count(dead_cloth_, &outs_.count));
    EXPECT_REJECTED_UNLOGGED(CLOTH_ERROR_INVALID_HANDLE,
                             cloth_fabric_get_particle_count(dead_fabric_, &outs_.count));
    EXPECT_REJECTED_UNLOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_world_destroy(dead_world_));
    EXPECT_REJECTED_UNLOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_destroy(dead_cloth_));
    EXPECT_REJECTED_UNLOGGED(CLOTH_ERROR_INVALID_HANDLE, cloth_fabric_destroy(dead_fabric_));
    // The new objects are untouched by all of that.
    uint32_t count = 0;
    EXPECT_EQ(cloth_get_particle_count(cloth, &count), CLOTH_OK);
    EXPECT_EQ(count, kParticles);
    EXPECT_EQ(cloth_fabric_get_particle_count(fabric, &count), CLOTH_OK);
    EXPECT_EQ(cloth_step(reused, kFrame), CLOTH_OK);
    for (const cloth_world_id& w : created) EXPECT_EQ(cloth_world_destroy(w), CLOTH_OK);
}

// ===========================================================================
// Null pointers: every pointer argument of every function.
// ===========================================================================

TEST_F(BadInput, WorldFunctionsRejectEachNullPointerAndChangeNothing) {
    Host host;
    const cloth_world_desc wd = HostWorldDesc(&host);
    EXPECT_REJECTED_UNLOGGED(CLOTH_ERROR_NULL_POINTER, cloth_world_create(nullptr, &outs_.world));
    EXPECT_REJECTED_UNLOGGED(CLOTH_ERROR_NULL_POINTER, cloth_world_create(&wd, nullptr));
    EXPECT_EQ(host.live_bytes, 0u) << "a rejected cloth_world_create kept memory";
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_world_set_gravity(a_.world, nullptr));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_world_shift_origin(a_.world, nullptr));
}

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

TEST_F(BadInput, ClothFunctionsRejectEachNullPointerAndChangeNothing) {
    const cloth_desc desc = ValidClothDesc();
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_create(a_.world, nullptr, &outs_.cloth));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_create(a_.world, &desc, nullptr));
    const cloth_id c = a_.cloth;
    const uint32_t pinned[] = {0};
    const float xyz[3] = {0.1f, 0.2f, 0.3f};
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_get_particle_count(c, nullptr));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_read_positions(c, nullptr, kFloats));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_read_velocities(c, nullptr, kFloats));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_read_normals(c, nullptr, kFloats));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_set_positions(c, nullptr, xyz, 1));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_set_positions(c, pinned, nullptr, 1));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_pin(c, nullptr, 1));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_unpin(c, nullptr, 1));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_set_pin_targets(c, nullptr, xyz, 1));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_set_pin_targets(c, pinned, nullptr, 1));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_is_pinned(c, 0, nullptr));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_set_solver(c, nullptr));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_get_solver(c, nullptr));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_set_aero(c, nullptr));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_set_wind(c, nullptr));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_get_stats(c, nullptr));
}

// ===========================================================================
// Descriptions not from cloth_default_*(), or with a wrong struct_size
// ===========================================================================

// Mutations that make any description invalid: zeroed, struct sizes no
// version of the header can produce, and a damaged cookie.
template <typename Desc>
std::vector<std::pair<std::string, Desc>> BrokenDescs(const Desc& valid) {
    std::vector<std::pair<std::string, Desc>> out;
    Desc zero;
    std::memset(&zero, 0, sizeof zero);
    out.emplace_back("memset to zero", zero);
    Desc d = valid;
    d.struct_size = 0;
    out.emplace_back("struct_size 0", d);
    d = valid;
    d.struct_size = sizeof(Desc) - 1;
    out.emplace_back("struct_size sizeof - 1", d);
    d = valid;
    d.struct_size = sizeof(Desc) + 1;
    out.emplace_back("struct_size sizeof + 1", d);
    d = valid;
    d.struct_size = UINT32_MAX;
    out.emplace_back("struct_size UINT32_MAX", d);
    d = valid;
    d.internal_cookie ^= 0x1u;
    out.emplace_back("internal_cookie changed", d);
    d = valid;
    d.internal_cookie = 0;
    out.emplace_back("internal_cookie 0 (filled by hand)", d);
    return out;
}

TEST_F(BadInput, CreateWorldWithADescNotFromDefaultOrAWrongSizeReturnsInvalidDesc) {
    Host host;
    for (const auto& broken : BrokenDescs(HostWorldDesc(&host))) {
        SCOPED_TRACE(broken.first);
        const cloth_world_desc& desc = broken.second;
        EXPECT_REJECTED_UNLOGGED(CLOTH_ERROR_INVALID_DESC, cloth_world_create(&desc, &outs_.world));
    }
    EXPECT_EQ(host.live_bytes, 0u);
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

TEST_F(BadInput, CreateClothWithADescNotFromDefaultOrAWrongSizeReturnsInvalidDesc) {
    for (const auto& broken : BrokenDescs(ValidClothDesc())) {
        SCOPED_TRACE(broken.first);
        const cloth_desc& desc = broken.second;
        EXPECT_REJECTED(CLOTH_ERROR_INVALID_DESC, cloth_create(a_.world, &desc, &outs_.cloth));
    }
    // The nested solver settings carry their own struct_size.
    for (uint32_t size :
         {0u, uint32_t(sizeof(cloth_solver_settings) - 1), uint32_t(sizeof(cloth_solver_settings) + 1)}) {
        SCOPED_TRACE("desc.solver.struct_size " + std::to_string(size));
        cloth_desc desc = ValidClothDesc();
        desc.solver.struct_size = size;
        EXPECT_REJECTED(CLOTH_ERROR_INVALID_DESC, cloth_create(a_.world, &desc, &outs_.cloth));
    }
}

TEST_F(BadInput, SetSolverWithAWrongStructSizeReturnsInvalidDescAndKeepsTheSolver) {
    cloth_solver_settings zero;
    std::memset(&zero, 0, sizeof zero);
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_DESC, cloth_set_solver(a_.cloth, &zero));
    for (uint32_t size :
         {0u, uint32_t(sizeof(cloth_solver_settings) - 1), uint32_t(sizeof(cloth_solver_settings) + 1)}) {
        SCOPED_TRACE("struct_size " + std::to_string(size));
        cloth_solver_settings s = cloth_default_solver_settings();
        s.kind = CLOTH_SOLVER_CG;  // a visible change, if it were accepted
        s.struct_size = size;
        EXPECT_REJECTED(CLOTH_ERROR_INVALID_DESC, cloth_set_solver(a_.cloth, &s));
    }
}

TEST_F(BadInput, GetStatsWithAWrongStructSizeReturnsInvalidDescAndWritesNothing) {
    for (uint32_t size : {0u, uint32_t(sizeof(cloth_stats) - 1), uint32_t(sizeof(cloth_stats) + 1)}) {
        SCOPED_TRACE("struct_size " + std::to_string(size));
        cloth_stats stats;
        std::memset(&stats, 0x5A, sizeof stats);
        stats.struct_size = size;
        cloth_stats copy;
        std::memcpy(&copy, &stats, sizeof stats);
        EXPECT_REJECTED(CLOTH_ERROR_INVALID_DESC, cloth_get_stats(a_.cloth, &stats));
        EXPECT_EQ(std::memcmp(&stats, &copy, sizeof stats), 0)
            << "cloth_get_stats wrote into a rejected struct";
    }
}

// ===========================================================================
// World values
// ===========================================================================

TEST_F(BadInput, CreateWorldWithNonFiniteGravityReturnsNotFinite) {
    Host host;
    for (int axis = 0; axis < 3; ++axis) {
        for (float bad : {kNaN, kInf, -kInf}) {
            SCOPED_TRACE("gravity[" + std::to_string(axis) + "] = " + std::to_string(bad));
            cloth_world_desc desc = HostWorldDesc(&host);
            desc.gravity[axis] = bad;
            EXPECT_REJECTED_UNLOGGED(CLOTH_ERROR_NOT_FINITE, cloth_world_create(&desc, &outs_.world));
        }
    }
    EXPECT_EQ(host.live_bytes, 0u);
}

TEST_F(BadInput, CreateWorldWithOnlyOneOfAllocAndFreeReturnsInvalidValue) {
    Host host;
    cloth_world_desc only_alloc = HostWorldDesc(&host);
    only_alloc.free = nullptr;
    EXPECT_REJECTED_UNLOGGED(CLOTH_ERROR_INVALID_VALUE, cloth_world_create(&only_alloc, &outs_.world));
    cloth_world_desc only_free = HostWorldDesc(&host);
    only_free.alloc = nullptr;
    EXPECT_REJECTED_UNLOGGED(CLOTH_ERROR_INVALID_VALUE, cloth_world_create(&only_free, &outs_.world));
    EXPECT_EQ(host.alloc_calls, 0u);
}

TEST_F(BadInput, CreateWorldWithZeroOrTooLargeTableCapacityReturnsInvalidCount) {
    Host host;
    for (uint32_t bad : {0u, 65536u, UINT32_MAX}) {
        cloth_world_desc desc = HostWorldDesc(&host);
        desc.max_cloths = bad;
        SCOPED_TRACE("max_cloths " + std::to_string(bad));
        EXPECT_REJECTED_UNLOGGED(CLOTH_ERROR_INVALID_COUNT, cloth_world_create(&desc, &outs_.world));
        desc = HostWorldDesc(&host);
        desc.max_fabrics = bad;
        SCOPED_TRACE("max_fabrics " + std::to_string(bad));
        EXPECT_REJECTED_UNLOGGED(CLOTH_ERROR_INVALID_COUNT, cloth_world_create(&desc, &outs_.world));
    }
    EXPECT_EQ(host.live_bytes, 0u);
}

TEST_F(BadInput, SetGravityNonFiniteReturnsNotFiniteAndKeepsTheOldGravity) {
    // The twin check at the end proves the world still uses its old gravity.
    for (int axis = 0; axis < 3; ++axis) {
        for (float bad : {kNaN, kInf, -kInf}) {
            SCOPED_TRACE("gravity[" + std::to_string(axis) + "] = " + std::to_string(bad));
            float g[3] = {0.0f, -20.0f, 0.0f};
            g[axis] = bad;
            EXPECT_REJECTED(CLOTH_ERROR_NOT_FINITE, cloth_world_set_gravity(a_.world, g));
        }
    }
}

TEST_F(BadInput, ShiftOriginNonFiniteReturnsNotFiniteAndMovesNothing) {
    for (int axis = 0; axis < 3; ++axis) {
        for (float bad : {kNaN, kInf, -kInf}) {
            SCOPED_TRACE("shift[" + std::to_string(axis) + "] = " + std::to_string(bad));
            float shift[3] = {32.0f, 0.0f, -64.0f};
            shift[axis] = bad;
            EXPECT_REJECTED(CLOTH_ERROR_NOT_FINITE, cloth_world_shift_origin(a_.world, shift));
        }
    }
}

TEST_F(BadInput, WorkerSpinOverOneSecondReturnsInvalidValue) {
    for (uint32_t spin : {1000001u, 0xFFFFFFFFu}) {
        SCOPED_TRACE("spin = " + std::to_string(spin));
        EXPECT_REJECTED(CLOTH_ERROR_INVALID_VALUE, cloth_world_set_worker_spin(a_.world, spin));
    }
}

TEST_F(BadInput, StepWithDtNotInZeroToOneReturnsInvalidValueAndAdvancesNothing) {
    for (float dt : {0.0f, -0.0f, -kFrame, -1.0f, std::nextafter(1.0f, 2.0f), 2.0f, 1e30f}) {
        SCOPED_TRACE("dt = " + std::to_string(dt));
        EXPECT_REJECTED(CLOTH_ERROR_INVALID_VALUE, cloth_step(a_.world, dt));
    }
}

TEST_F(BadInput, StepWithNonFiniteDtReturnsNotFiniteAndAdvancesNothing) {
    for (float dt : {kNaN, kInf, -kInf}) {
        SCOPED_TRACE("dt = " + std::to_string(dt));
        EXPECT_REJECTED(CLOTH_ERROR_NOT_FINITE, cloth_step(a_.world, dt));
    }
}

TEST_F(BadInput, CreatingMoreThan128WorldsReturnsCapacityAndLeavesTheOthersWorking) {
    const cloth_world_desc wd = [] {
        cloth_world_desc d = cloth_default_world_desc();
        d.max_cloths = 1;
        d.max_fabrics = 1;
        return d;
    }();
    std::vector<cloth_world_id> created;
    cloth_result r = CLOTH_OK;
    for (int i = 0; i < 200; ++i) {
        cloth_world_id w{};
        r = cloth_world_create(&wd, &w);
        if (r != CLOTH_OK) break;
        created.push_back(w);
    }
    EXPECT_EQ(r, CLOTH_ERROR_CAPACITY) << Name(r);
    EXPECT_EQ(created.size() + 2, 128u) << "the fixture holds 2 worlds; at most 128 may exist at once";
    EXPECT_REJECTED_UNLOGGED(CLOTH_ERROR_CAPACITY, cloth_world_create(&wd, &outs_.world));
    // Freeing one slot makes room for exactly one more.
    if (!created.empty()) {
        EXPECT_EQ(cloth_world_destroy(created.back()), CLOTH_OK);
        EXPECT_EQ(cloth_world_create(&wd, &created.back()), CLOTH_OK);
    }
    for (const cloth_world_id& w : created) EXPECT_EQ(cloth_world_destroy(w), CLOTH_OK);
}

// ===========================================================================
// Fabric values
// ===========================================================================

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

// The particle count must fit the uint32 float capacity of cloth_read_positions
// (3 * count <= UINT32_MAX), so larger grids are "too large" counts. A library
// that does not check would try to build them; these run in a child process.
class BadInputDeathTest : public BadInput {};

void ExpectRejectedInChild(const std::function<cloth_result()>& call, const Snapshot& before,
                           const std::function<Snapshot()>& now, const Host& host, size_t live_before) {
    const Outcome o = RunOnFreshThread(call);
    std::fprintf(stderr, "result=%s;message=%s;state=%s;memory=%s;\n", cloth_result_name(o.result),
                 o.error_after.empty() ? "empty" : "set", SameState(before, now()) ? "same" : "changed",
                 host.live_bytes == live_before ? "same" : "changed");
    std::fflush(stderr);
    std::_Exit(0);
}

#define EXPECT_REJECTED_IN_CHILD(expected_name, call)                                                       \
    EXPECT_EXIT(ExpectRejectedInChild([&]() -> cloth_result { return (call); }, TakeSnapshot(a_.cloth),     \
                                      [&] { return TakeSnapshot(a_.cloth); }, a_.host, a_.host.live_bytes), \
                ::testing::ExitedWithCode(0),                                                               \
                "result=" expected_name ";message=set;state=same;memory=same;")                             \
        << #call

TEST_F(BadInputDeathTest, GridWhoseParticleCountOverflowsReturnsInvalidCount) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    g_bad_inputs += 3;
    cloth_grid_desc wraps = SmallGrid();  // 65536 * 65536 wraps to 0 in 32 bits
    wraps.columns = 65536;
    wraps.rows = 65536;
    EXPECT_REJECTED_IN_CHILD("CLOTH_ERROR_INVALID_COUNT",
                             cloth_fabric_create_grid(a_.world, &wraps, &outs_.fabric));
    cloth_grid_desc huge = SmallGrid();
    huge.columns = UINT32_MAX;
    huge.rows = 2;
    EXPECT_REJECTED_IN_CHILD("CLOTH_ERROR_INVALID_COUNT",
                             cloth_fabric_create_grid(a_.world, &huge, &outs_.fabric));
    cloth_grid_desc over = SmallGrid();  // 0x55560000 particles: 3 * count > UINT32_MAX
    over.columns = 0x10000;
    over.rows = 0x5556;
    EXPECT_REJECTED_IN_CHILD("CLOTH_ERROR_INVALID_COUNT",
                             cloth_fabric_create_grid(a_.world, &over, &outs_.fabric));
}

TEST_F(BadInputDeathTest, MeshWithHugeCountsReturnsInvalidCountWithoutReadingTheArrays) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    g_bad_inputs += 2;
    cloth_mesh_desc vertices = QuadMesh();
    vertices.vertex_count = UINT32_MAX;
    EXPECT_REJECTED_IN_CHILD("CLOTH_ERROR_INVALID_COUNT",
                             cloth_fabric_create_mesh(a_.world, &vertices, &outs_.fabric));
    cloth_mesh_desc triangles = QuadMesh();
    triangles.triangle_count = UINT32_MAX;
    EXPECT_REJECTED_IN_CHILD("CLOTH_ERROR_INVALID_COUNT",
                             cloth_fabric_create_mesh(a_.world, &triangles, &outs_.fabric));
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

// ===========================================================================
// Cloth description values
// ===========================================================================

struct DescCase {
    std::string what;
    std::function<void(cloth_desc&)> change;
    cloth_result expected;
};

void AddSpringCases(std::vector<DescCase>& cases) {
    using P = cloth_spring_params cloth_desc::*;
    const std::pair<const char*, P> kinds[] = {
        {"structural", &cloth_desc::structural}, {"shear", &cloth_desc::shear}, {"bend", &cloth_desc::bend}};
    for (const auto& [name, member] : kinds) {
        const std::string n = name;
        const P m = member;
        cases.push_back({n + ".stiffness = -1", [m](cloth_desc& d) { (d.*m).stiffness = -1.0f; },
                         CLOTH_ERROR_INVALID_VALUE});
        cases.push_back({n + ".damping = -0.5", [m](cloth_desc& d) { (d.*m).damping = -0.5f; },
                         CLOTH_ERROR_INVALID_VALUE});
        cases.push_back({n + ".stiffness = NaN", [m](cloth_desc& d) { (d.*m).stiffness = kNaN; },
                         CLOTH_ERROR_NOT_FINITE});
        cases.push_back({n + ".stiffness = inf", [m](cloth_desc& d) { (d.*m).stiffness = kInf; },
                         CLOTH_ERROR_NOT_FINITE});
        cases.push_back(
            {n + ".damping = inf", [m](cloth_desc& d) { (d.*m).damping = kInf; }, CLOTH_ERROR_NOT_FINITE});
        cases.push_back(
            {n + ".damping = NaN", [m](cloth_desc& d) { (d.*m).damping = kNaN; }, CLOTH_ERROR_NOT_FINITE});
    }
}

// Solver settings out of their documented ranges (shared by create and set_solver).
std::vector<std::tuple<std::string, std::function<void(cloth_solver_settings&)>, cloth_result>> BadSolver() {
    using S = cloth_solver_settings;
    std::vector<std::tuple<std::string, std::function<void(S&)>, cloth_result>> out;
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

// Aerodynamic parameters out of range (shared by create and set_aero).
std::vector<std::tuple<std::string, std::function<void(cloth_aero_params&)>, cloth_result>> BadAero() {
    std::vector<std::tuple<std::string, std::function<void(cloth_aero_params&)>, cloth_result>> out;
    for (int axis = 0; axis < 3; ++axis) {
        out.emplace_back(
            "wind[" + std::to_string(axis) + "] = NaN", [axis](cloth_aero_params& a) { a.wind[axis] = kNaN; },
            CLOTH_ERROR_NOT_FINITE);
        out.emplace_back(
            "wind[" + std::to_string(axis) + "] = -inf",
            [axis](cloth_aero_params& a) { a.wind[axis] = -kInf; }, CLOTH_ERROR_NOT_FINITE);
    }
    out.emplace_back(
        "air_density = -1", [](cloth_aero_params& a) { a.air_density = -1.0f; }, CLOTH_ERROR_INVALID_VALUE);
    out.emplace_back(
        "air_density = NaN", [](cloth_aero_params& a) { a.air_density = kNaN; }, CLOTH_ERROR_NOT_FINITE);
    out.emplace_back(
        "drag_coefficient = -0.1", [](cloth_aero_params& a) { a.drag_coefficient = -0.1f; },
        CLOTH_ERROR_INVALID_VALUE);
    out.emplace_back(
        "drag_coefficient = inf", [](cloth_aero_params& a) { a.drag_coefficient = kInf; },
        CLOTH_ERROR_NOT_FINITE);
    out.emplace_back(
        "lift_coefficient = -0.1", [](cloth_aero_params& a) { a.lift_coefficient = -0.1f; },
        CLOTH_ERROR_INVALID_VALUE);
    out.emplace_back(
        "lift_coefficient = NaN", [](cloth_aero_params& a) { a.lift_coefficient = kNaN; },
        CLOTH_ERROR_NOT_FINITE);
    out.emplace_back(
        "linear_drag = -0.02", [](cloth_aero_params& a) { a.linear_drag = -0.02f; },
        CLOTH_ERROR_INVALID_VALUE);
    out.emplace_back(
        "linear_drag = inf", [](cloth_aero_params& a) { a.linear_drag = kInf; }, CLOTH_ERROR_NOT_FINITE);
    return out;
}

TEST_F(BadInput, CreateClothWithNonPositiveOrNonFiniteAreaDensityIsRejected) {
    const std::pair<float, cloth_result> cases[] = {
        {0.0f, CLOTH_ERROR_INVALID_VALUE},  {-0.0f, CLOTH_ERROR_INVALID_VALUE},
        {-0.2f, CLOTH_ERROR_INVALID_VALUE}, {kNaN, CLOTH_ERROR_NOT_FINITE},
        {kInf, CLOTH_ERROR_NOT_FINITE},     {-kInf, CLOTH_ERROR_NOT_FINITE},
    };
    for (const auto& [density, expected] : cases) {
        SCOPED_TRACE("area_density = " + std::to_string(density));
        cloth_desc desc = ValidClothDesc();
        desc.area_density = density;
        EXPECT_REJECTED(expected, cloth_create(a_.world, &desc, &outs_.cloth));
    }
}

TEST_F(BadInput, CreateClothWithNegativeOrNonFiniteParticleMassIsRejected) {
    const std::pair<float, cloth_result> cases[] = {
        {-0.01f, CLOTH_ERROR_INVALID_VALUE},
        {-kInf, CLOTH_ERROR_NOT_FINITE},
        {kNaN, CLOTH_ERROR_NOT_FINITE},
        {kInf, CLOTH_ERROR_NOT_FINITE},
    };
    for (const auto& [mass, expected] : cases) {
        SCOPED_TRACE("particle_mass = " + std::to_string(mass));
        cloth_desc desc = ValidClothDesc();
        desc.particle_mass = mass;
        EXPECT_REJECTED(expected, cloth_create(a_.world, &desc, &outs_.cloth));
    }
}

TEST_F(BadInput, CreateClothWithANonFiniteInitialPositionReturnsNotFinite) {
    std::vector<float> start(kFloats);
    ASSERT_EQ(cloth_read_positions(a_.cloth, start.data(), kFloats), CLOTH_OK);
    for (uint32_t i : {0u, kFloats / 2 + 1, kFloats - 1}) {
        for (float bad : {kNaN, kInf, -kInf}) {
            SCOPED_TRACE("initial_positions[" + std::to_string(i) + "] = " + std::to_string(bad));
            std::vector<float> positions = start;
            positions[i] = bad;
            cloth_desc desc = ValidClothDesc();
            desc.initial_positions = positions.data();
            EXPECT_REJECTED(CLOTH_ERROR_NOT_FINITE, cloth_create(a_.world, &desc, &outs_.cloth));
        }
    }
}

TEST_F(BadInput, CreateClothWithNegativeOrNonFiniteSpringParamsIsRejected) {
    std::vector<DescCase> cases;
    AddSpringCases(cases);
    for (const DescCase& c : cases) {
        SCOPED_TRACE(c.what);
        cloth_desc desc = ValidClothDesc();
        c.change(desc);
        EXPECT_REJECTED(c.expected, cloth_create(a_.world, &desc, &outs_.cloth));
    }
}

TEST_F(BadInput, CreateClothWithOutOfRangeSolverSettingsIsRejected) {
    for (const auto& [what, change, expected] : BadSolver()) {
        SCOPED_TRACE("desc.solver: " + what);
        cloth_desc desc = ValidClothDesc();
        change(desc.solver);
        EXPECT_REJECTED(expected, cloth_create(a_.world, &desc, &outs_.cloth));
    }
}

TEST_F(BadInput, CreateClothWithOutOfRangeAeroParamsIsRejected) {
    for (const auto& [what, change, expected] : BadAero()) {
        SCOPED_TRACE("desc.aero: " + what);
        cloth_desc desc = ValidClothDesc();
        change(desc.aero);
        EXPECT_REJECTED(expected, cloth_create(a_.world, &desc, &outs_.cloth));
    }
}

TEST_F(BadInput, CreatingMoreClothsThanMaxClothsReturnsCapacity) {
    check_twin_ = false;
    const cloth_desc desc = ValidClothDesc();
    cloth_id third{};
    ASSERT_EQ(cloth_create(a_.world, &desc, &third), CLOTH_OK) << "the fixture leaves one slot free";
    EXPECT_REJECTED(CLOTH_ERROR_CAPACITY, cloth_create(a_.world, &desc, &outs_.cloth));
}

// ===========================================================================
// Cloth run-time setters
// ===========================================================================

TEST_F(BadInput, SetSolverOutOfRangeIsRejectedAndTheSolverIsUnchanged) {
    for (const auto& [what, change, expected] : BadSolver()) {
        SCOPED_TRACE(what);
        cloth_solver_settings s = cloth_default_solver_settings();
        s.substeps = 3;  // a visible change, if it were accepted...
        change(s);       // ...but one field is out of range
        EXPECT_REJECTED(expected, cloth_set_solver(a_.cloth, &s));
    }
}

TEST_F(BadInput, SetSpringParamsNegativeOrNonFiniteIsRejectedAndKeepsTheOldParams) {
    const std::pair<cloth_spring_params, cloth_result> cases[] = {
        {{-1.0f, 0.5f}, CLOTH_ERROR_INVALID_VALUE}, {{1000.0f, -0.5f}, CLOTH_ERROR_INVALID_VALUE},
        {{kNaN, 0.5f}, CLOTH_ERROR_NOT_FINITE},     {{kInf, 0.5f}, CLOTH_ERROR_NOT_FINITE},
        {{1000.0f, kNaN}, CLOTH_ERROR_NOT_FINITE},  {{1000.0f, -kInf}, CLOTH_ERROR_NOT_FINITE},
    };
    for (uint32_t kinds : {uint32_t{CLOTH_SPRING_STRUCTURAL},
                           uint32_t{CLOTH_SPRING_SHEAR | CLOTH_SPRING_BEND}, uint32_t{CLOTH_SPRING_ALL}}) {
        for (const auto& c : cases) {
            const cloth_spring_params params = c.first;
            SCOPED_TRACE("kinds " + std::to_string(kinds) + " {" + std::to_string(params.stiffness) + ", " +
                         std::to_string(params.damping) + "}");
            EXPECT_REJECTED(c.second, cloth_set_spring_params(a_.cloth, kinds, params));
        }
    }
}

TEST_F(BadInput, SetAeroOutOfRangeIsRejectedAndKeepsTheOldAero) {
    for (const auto& [what, change, expected] : BadAero()) {
        SCOPED_TRACE(what);
        cloth_aero_params aero = cloth_default_desc().aero;
        aero.wind[1] = 5.0f;  // a visible change, if it were accepted
        change(aero);
        EXPECT_REJECTED(expected, cloth_set_aero(a_.cloth, &aero));
    }
}

TEST_F(BadInput, SetWindNonFiniteReturnsNotFiniteAndKeepsTheOldWind) {
    for (int axis = 0; axis < 3; ++axis) {
        for (float bad : {kNaN, kInf, -kInf}) {
            SCOPED_TRACE("wind[" + std::to_string(axis) + "] = " + std::to_string(bad));
            float wind[3] = {10.0f, 10.0f, 10.0f};
            wind[axis] = bad;
            EXPECT_REJECTED(CLOTH_ERROR_NOT_FINITE, cloth_set_wind(a_.cloth, wind));
        }
    }
}

TEST_F(BadInput, ReadWithTooSmallCapacityReturnsInvalidCountAndWritesNothing) {
    for (uint32_t capacity : {0u, 3u, kFloats - 1}) {
        SCOPED_TRACE("capacity " + std::to_string(capacity));
        EXPECT_REJECTED(CLOTH_ERROR_INVALID_COUNT, cloth_read_positions(a_.cloth, outs_.floats, capacity));
        EXPECT_REJECTED(CLOTH_ERROR_INVALID_COUNT, cloth_read_velocities(a_.cloth, outs_.floats, capacity));
        EXPECT_REJECTED(CLOTH_ERROR_INVALID_COUNT, cloth_read_normals(a_.cloth, outs_.floats, capacity));
    }
}

TEST_F(BadInput, SetPositionsWithZeroCountOrBadIndexOrNonFiniteValueMovesNoParticle) {
    const uint32_t one[] = {20};
    const float xyz[6] = {0.3f, -0.2f, 0.1f, 0.4f, -0.5f, 0.6f};
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_COUNT, cloth_set_positions(a_.cloth, one, xyz, 0));
    for (uint32_t bad : {kParticles, kParticles + 1, UINT32_MAX}) {
        SCOPED_TRACE("index " + std::to_string(bad));
        const uint32_t alone[] = {bad};
        EXPECT_REJECTED(CLOTH_ERROR_INDEX_OUT_OF_RANGE, cloth_set_positions(a_.cloth, alone, xyz, 1));
        // A valid index first: it must not move either.
        const uint32_t second_bad[] = {20, bad};
        EXPECT_REJECTED(CLOTH_ERROR_INDEX_OUT_OF_RANGE, cloth_set_positions(a_.cloth, second_bad, xyz, 2));
    }
    const uint32_t two[] = {20, 21};
    for (int i : {0, 4}) {
        for (float bad : {kNaN, kInf, -kInf}) {
            SCOPED_TRACE("positions[" + std::to_string(i) + "] = " + std::to_string(bad));
            float values[6];
            std::memcpy(values, xyz, sizeof values);
            values[i] = bad;
            EXPECT_REJECTED(CLOTH_ERROR_NOT_FINITE, cloth_set_positions(a_.cloth, two, values, 2));
        }
    }
}

TEST_F(BadInput, PinWithOutOfRangeIndexReturnsIndexErrorAndChangesNothing) {
    const uint32_t one[] = {20};
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_COUNT, cloth_pin(a_.cloth, one, 0));
    for (uint32_t bad : {kParticles, UINT32_MAX}) {
        SCOPED_TRACE("index " + std::to_string(bad));
        const uint32_t alone[] = {bad};
        EXPECT_REJECTED(CLOTH_ERROR_INDEX_OUT_OF_RANGE, cloth_pin(a_.cloth, alone, 1));
        const uint32_t second_bad[] = {20, bad};  // 20 is free and must stay free
        EXPECT_REJECTED(CLOTH_ERROR_INDEX_OUT_OF_RANGE, cloth_pin(a_.cloth, second_bad, 2));
    }
}

TEST_F(BadInput, UnpinWithOutOfRangeIndexReturnsIndexErrorAndChangesNothing) {
    const uint32_t one[] = {0};
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_COUNT, cloth_unpin(a_.cloth, one, 0));
    for (uint32_t bad : {kParticles, UINT32_MAX}) {
        SCOPED_TRACE("index " + std::to_string(bad));
        const uint32_t alone[] = {bad};
        EXPECT_REJECTED(CLOTH_ERROR_INDEX_OUT_OF_RANGE, cloth_unpin(a_.cloth, alone, 1));
        const uint32_t second_bad[] = {0, bad};  // 0 is pinned and must stay pinned
        EXPECT_REJECTED(CLOTH_ERROR_INDEX_OUT_OF_RANGE, cloth_unpin(a_.cloth, second_bad, 2));
    }
}

TEST_F(BadInput, SetPinTargetsOnANonPinnedParticleReturnsInvalidValueAndChangesNothing) {
    const float targets[6] = {0.1f, 0.5f, 0.2f, 0.9f, 0.5f, 0.2f};
    const uint32_t free_particle[] = {20};
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_VALUE, cloth_set_pin_targets(a_.cloth, free_particle, targets, 1));
    // Particle 0 is pinned; its target must not be taken either (the twin check sees it).
    const uint32_t pinned_then_free[] = {0, 20};
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_VALUE, cloth_set_pin_targets(a_.cloth, pinned_then_free, targets, 2));
}

TEST_F(BadInput, SetPinTargetsWithZeroCountOrBadIndexOrNonFiniteTargetChangesNothing) {
    const float targets[6] = {0.1f, 0.5f, 0.2f, 0.9f, 0.5f, 0.2f};
    const uint32_t corners[] = {0, kColumns - 1};
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_COUNT, cloth_set_pin_targets(a_.cloth, corners, targets, 0));
    for (uint32_t bad : {kParticles, UINT32_MAX}) {
        SCOPED_TRACE("index " + std::to_string(bad));
        const uint32_t alone[] = {bad};
        EXPECT_REJECTED(CLOTH_ERROR_INDEX_OUT_OF_RANGE, cloth_set_pin_targets(a_.cloth, alone, targets, 1));
        const uint32_t second_bad[] = {0, bad};
        EXPECT_REJECTED(CLOTH_ERROR_INDEX_OUT_OF_RANGE,
                        cloth_set_pin_targets(a_.cloth, second_bad, targets, 2));
    }
    for (int i : {1, 5}) {
        for (float bad : {kNaN, kInf, -kInf}) {
            SCOPED_TRACE("targets[" + std::to_string(i) + "] = " + std::to_string(bad));
            float values[6];
            std::memcpy(values, targets, sizeof values);
            values[i] = bad;
            EXPECT_REJECTED(CLOTH_ERROR_NOT_FINITE, cloth_set_pin_targets(a_.cloth, corners, values, 2));
        }
    }
}

TEST_F(BadInput, IsPinnedWithOutOfRangeIndexReturnsIndexErrorAndWritesNothing) {
    for (uint32_t bad : {kParticles, kParticles + 100, UINT32_MAX}) {
        SCOPED_TRACE("index " + std::to_string(bad));
        EXPECT_REJECTED(CLOTH_ERROR_INDEX_OUT_OF_RANGE, cloth_is_pinned(a_.cloth, bad, OutPinned()));
    }
}

// ===========================================================================
// A simulation that goes non-finite
// ===========================================================================

TEST_F(BadInput, StepThatGoesNonFiniteRestoresThatClothAndStillAdvancesTheOthers) {
    check_twin_ = false;
    // Explicit integration of springs a million times too stiff for the step.
    cloth_solver_settings explicit_solver = cloth_default_solver_settings();
    explicit_solver.kind = CLOTH_SOLVER_EXPLICIT;
    explicit_solver.substeps = 64;
    ASSERT_EQ(cloth_set_solver(a_.cloth, &explicit_solver), CLOTH_OK);
    ASSERT_EQ(cloth_set_spring_params(a_.cloth, CLOTH_SPRING_ALL, cloth_spring_params{1e9f, 0.0f}), CLOTH_OK);
    const Snapshot bad_before = TakeSnapshot(a_.cloth);
    const Snapshot other_before = TakeSnapshot(a_.other);
    const size_t logs_before = a_.host.logs.size();

    ++g_bad_inputs;
    const Outcome o = RunOnFreshThread([&] { return cloth_step(a_.world, 0.1f); });
    ASSERT_EQ(o.result, CLOTH_ERROR_NONFINITE_STATE) << Name(o.result) << ": " << o.error_after;
    EXPECT_NE(o.error_after, "") << "cloth_step failed but cloth_get_last_error() is empty";
    bool logged = false;
    for (size_t i = logs_before; i < a_.host.logs.size(); ++i) {
        logged |=
            a_.host.logs[i].level == CLOTH_LOG_ERROR && a_.host.logs[i].code == CLOTH_ERROR_NONFINITE_STATE;
    }
    EXPECT_TRUE(logged) << "the log callback did not receive CLOTH_ERROR_NONFINITE_STATE";

    // The exploded cloth is back to its state before the call, bit for bit.
    const Snapshot bad_after = TakeSnapshot(a_.cloth);
    EXPECT_TRUE(SameFloats("position", bad_before.positions, bad_after.positions));
    EXPECT_TRUE(SameFloats("velocity", bad_before.velocities, bad_after.velocities));
    EXPECT_TRUE(SameState(bad_before, bad_after, /*compare_step_diagnostics=*/false));
    EXPECT_EQ(bad_after.stats.last_step_result, CLOTH_ERROR_NONFINITE_STATE)
        << Name(bad_after.stats.last_step_result);

    // The healthy cloth advanced in the same call, exactly as it does in the
    // twin world where nothing blew up.
    const Snapshot other_after = TakeSnapshot(a_.other);
    EXPECT_FALSE(SameFloats("position", other_before.positions, other_after.positions))
        << "the healthy cloth did not advance";
    EXPECT_TRUE(AllFinite(other_after.positions));
    EXPECT_TRUE(AllFinite(other_after.velocities));
    EXPECT_EQ(other_after.stats.last_step_result, CLOTH_OK) << Name(other_after.stats.last_step_result);
    ASSERT_EQ(cloth_step(b_.world, 0.1f), CLOTH_OK) << cloth_get_last_error();
    EXPECT_TRUE(SameState(TakeSnapshot(b_.other), other_after))
        << "the healthy cloth did not advance as it does in an identical world without the blow-up";

    // With sane settings the restored cloth steps again and reports OK.
    const cloth_desc defaults = cloth_default_desc();
    ASSERT_EQ(cloth_set_solver(a_.cloth, &defaults.solver), CLOTH_OK);
    ASSERT_EQ(cloth_set_spring_params(a_.cloth, CLOTH_SPRING_STRUCTURAL, defaults.structural), CLOTH_OK);
    ASSERT_EQ(cloth_set_spring_params(a_.cloth, CLOTH_SPRING_SHEAR, defaults.shear), CLOTH_OK);
    ASSERT_EQ(cloth_set_spring_params(a_.cloth, CLOTH_SPRING_BEND, defaults.bend), CLOTH_OK);
    EXPECT_EQ(cloth_step(a_.world, kFrame), CLOTH_OK) << cloth_get_last_error();
    const Snapshot recovered = TakeSnapshot(a_.cloth);
    EXPECT_TRUE(AllFinite(recovered.positions));
    EXPECT_EQ(recovered.stats.last_step_result, CLOTH_OK) << Name(recovered.stats.last_step_result);
}

// ===========================================================================
// Allocation failure
// ===========================================================================

TEST_F(BadInput, CreateClothWhenTheAllocatorFailsReturnsOutOfMemoryLeaksNothingAndTheWorldStillWorks) {
    check_twin_ = false;
    const cloth_desc desc = ValidClothDesc();
    int failures = 0;
    bool created = false;
    cloth_id cloth{};
    for (long n = 0; n < 10000 && !created; ++n) {
        a_.host.allocations_left = n;
        SCOPED_TRACE("allocator fails after " + std::to_string(n) + " allocations");
        const size_t live_before = a_.host.live_bytes;
        const size_t calls_before = a_.host.alloc_calls;
        const Snapshot before = TakeSnapshot(a_.cloth);
        cloth_id out = cloth_id{0xA5A5, 0xA5A5, 0xA5A5, 0xA5A5};
        const Outcome o = RunOnFreshThread([&] { return cloth_create(a_.world, &desc, &out); });
        a_.host.allocations_left = -1;
        if (o.result == CLOTH_OK) {
            created = true;
            cloth = out;
            EXPECT_EQ(a_.host.alloc_calls - calls_before, static_cast<size_t>(n))
                << "cloth_create succeeded after a NULL from the allocator";
            break;
        }
        ++failures;
        ++g_bad_inputs;
        EXPECT_EQ(o.result, CLOTH_ERROR_OUT_OF_MEMORY) << Name(o.result);
        EXPECT_NE(o.error_after, "");
        EXPECT_EQ(a_.host.live_bytes, live_before) << "memory leaked by a failed cloth_create";
        EXPECT_TRUE(out == (cloth_id{0xA5A5, 0xA5A5, 0xA5A5, 0xA5A5})) << "out_cloth written on failure";
        EXPECT_TRUE(SameState(before, TakeSnapshot(a_.cloth)));
        ASSERT_FALSE(HasFailure()) << "stopping at the first failing allocation count";
    }
    EXPECT_GE(failures, 1) << "cloth_create never used the world's allocator";
    ASSERT_TRUE(created);
    // The world still works: it steps, and the new cloth is a full cloth.
    EXPECT_EQ(cloth_step(a_.world, kFrame), CLOTH_OK) << cloth_get_last_error();
    const Snapshot s = TakeSnapshot(cloth);
    EXPECT_EQ(s.count, kParticles);
    EXPECT_TRUE(AllFinite(s.positions));
    EXPECT_EQ(cloth_destroy(cloth), CLOTH_OK);
}

TEST_F(BadInput, CreateFabricWhenTheAllocatorFailsReturnsOutOfMemoryAndLeaksNothing) {
    check_twin_ = false;
    const cloth_grid_desc grid = SmallGrid();
    int failures = 0;
    cloth_fabric_id fabric{};
    bool created = false;
    for (long n = 0; n < 10000 && !created; ++n) {
        a_.host.allocations_left = n;
        SCOPED_TRACE("allocator fails after " + std::to_string(n) + " allocations");
        const size_t live_before = a_.host.live_bytes;
        const Outcome o =
            RunOnFreshThread([&] { return cloth_fabric_create_grid(a_.world, &grid, &fabric); });
        a_.host.allocations_left = -1;
        if (o.result == CLOTH_OK) {
            created = true;
            break;
        }
        ++failures;
        ++g_bad_inputs;
        EXPECT_EQ(o.result, CLOTH_ERROR_OUT_OF_MEMORY) << Name(o.result);
        EXPECT_EQ(a_.host.live_bytes, live_before) << "memory leaked by a failed cloth_fabric_create_grid";
        ASSERT_FALSE(HasFailure());
    }
    EXPECT_GE(failures, 1) << "cloth_fabric_create_grid never used the world's allocator";
    ASSERT_TRUE(created);
    uint32_t count = 0;
    EXPECT_EQ(cloth_fabric_get_particle_count(fabric, &count), CLOTH_OK);
    EXPECT_EQ(count, kParticles);
}

TEST_F(BadInput, CreateWorldWhenTheAllocatorFailsReturnsOutOfMemoryAndLeaksNothing) {
    Host host;
    const cloth_world_desc wd = HostWorldDesc(&host);
    cloth_world_id world{};
    bool created = false;
    for (long n = 0; n < 10000 && !created; ++n) {
        host.allocations_left = n;
        SCOPED_TRACE("allocator fails after " + std::to_string(n) + " allocations");
        const Outcome o = RunOnFreshThread([&] { return cloth_world_create(&wd, &world); });
        host.allocations_left = -1;
        if (o.result == CLOTH_OK) {
            created = true;
            break;
        }
        ++g_bad_inputs;
        EXPECT_EQ(o.result, CLOTH_ERROR_OUT_OF_MEMORY) << Name(o.result);
        EXPECT_EQ(host.live_bytes, 0u) << "memory leaked by a failed cloth_world_create";
        ASSERT_FALSE(HasFailure());
    }
    ASSERT_TRUE(created);
    const cloth_grid_desc grid = SmallGrid();
    cloth_fabric_id fabric{};
    EXPECT_EQ(cloth_fabric_create_grid(world, &grid, &fabric), CLOTH_OK);
    EXPECT_EQ(cloth_world_destroy(world), CLOTH_OK);
    EXPECT_EQ(host.live_bytes, 0u);
    EXPECT_TRUE(host.violations.empty());
}

TEST_F(BadInput, StepAndPinAllocateNothingSoTheySucceedWhileTheAllocatorFails) {
    check_twin_ = false;
    const Snapshot before = TakeSnapshot(a_.cloth);
    const size_t live_before = a_.host.live_bytes;
    a_.host.allocations_left = 0;
    const Outcome o = RunOnFreshThread([&] { return cloth_step(a_.world, kFrame); });
    EXPECT_EQ(o.result, CLOTH_OK) << Name(o.result) << " " << o.error_after;
    EXPECT_FALSE(SameFloats("position", before.positions, TakeSnapshot(a_.cloth).positions))
        << "the step advanced";
    std::vector<uint32_t> all(kParticles);
    for (uint32_t i = 0; i < kParticles; ++i) all[i] = i;
    EXPECT_EQ(cloth_pin(a_.cloth, all.data(), kParticles), CLOTH_OK) << cloth_get_last_error();
    EXPECT_EQ(cloth_unpin(a_.cloth, all.data(), kParticles), CLOTH_OK) << cloth_get_last_error();
    a_.host.allocations_left = -1;
    EXPECT_EQ(a_.host.live_bytes, live_before) << "no host memory taken or released";
}

// ===========================================================================
// Error reporting
// ===========================================================================

TEST_F(BadInput, LogCallbackReceivesEachErrorWithItsCodeAndTheLastErrorMessage) {
    const float nan_wind[3] = {kNaN, 0.0f, 0.0f};
    const uint32_t bad_index[] = {kParticles};
    struct Call {
        cloth_result expected;
        std::function<cloth_result()> call;
    };
    const Call calls[] = {
        {CLOTH_ERROR_NOT_FINITE, [&] { return cloth_set_wind(a_.cloth, nan_wind); }},
        {CLOTH_ERROR_INDEX_OUT_OF_RANGE, [&] { return cloth_pin(a_.cloth, bad_index, 1); }},
        {CLOTH_ERROR_INVALID_VALUE, [&] { return cloth_step(a_.world, 0.0f); }},
        {CLOTH_ERROR_NULL_POINTER, [&] { return cloth_world_set_gravity(a_.world, nullptr); }},
    };
    for (const Call& c : calls) {
        const size_t before = a_.host.logs.size();
        const cloth_result r = c.call();
        EXPECT_EQ(r, c.expected) << Name(r);
        size_t errors = 0;
        for (size_t i = before; i < a_.host.logs.size(); ++i)
            errors += a_.host.logs[i].level == CLOTH_LOG_ERROR;
        ASSERT_EQ(errors, 1u) << "expected exactly one error logged for " << Name(c.expected);
        const LogEntry& e = a_.host.logs.back();
        EXPECT_EQ(e.level, CLOTH_LOG_ERROR);
        EXPECT_EQ(e.code, c.expected) << Name(e.code);
        EXPECT_EQ(e.message, std::string(cloth_get_last_error()));
        EXPECT_NE(e.message, "");
    }
    // Successful calls log no error.
    const size_t before = a_.host.logs.size();
    ASSERT_EQ(cloth_step(a_.world, kFrame), CLOTH_OK);
    ASSERT_EQ(cloth_step(b_.world, kFrame), CLOTH_OK);
    for (size_t i = before; i < a_.host.logs.size(); ++i) EXPECT_NE(a_.host.logs[i].level, CLOTH_LOG_ERROR);
    // The twin world saw none of the errors above.
    for (const LogEntry& e : b_.host.logs) EXPECT_NE(e.level, CLOTH_LOG_ERROR) << e.message;
}

TEST_F(BadInput, LastErrorIsPerThread) {
    const float nan_wind[3] = {kNaN, 0.0f, 0.0f};
    std::string main_message;
    std::string other_before, other_after;
    std::thread first([&] {
        EXPECT_EQ(cloth_set_wind(a_.cloth, nan_wind), CLOTH_ERROR_NOT_FINITE);
        main_message = cloth_get_last_error();
        std::thread second([&] {
            other_before = cloth_get_last_error();
            EXPECT_EQ(cloth_step(a_.world, -1.0f), CLOTH_ERROR_INVALID_VALUE);
            other_after = cloth_get_last_error();
        });
        second.join();
        EXPECT_EQ(std::string(cloth_get_last_error()), main_message)
            << "another thread's failure replaced this thread's last error";
    });
    first.join();
    EXPECT_NE(main_message, "");
    EXPECT_EQ(other_before, "") << "a thread sees another thread's last error";
    EXPECT_NE(other_after, "");
    EXPECT_NE(other_after, main_message);
}

TEST_F(BadInput, LastErrorKeepsTheMessageOfTheLastFailedCallAcrossSuccessfulCalls) {
    std::string failed, after_success;
    std::thread t([&] {
        EXPECT_EQ(cloth_step(a_.world, 0.0f), CLOTH_ERROR_INVALID_VALUE);
        failed = cloth_get_last_error();
        uint32_t count = 0;
        EXPECT_EQ(cloth_get_particle_count(a_.cloth, &count), CLOTH_OK);
        after_success = cloth_get_last_error();
    });
    t.join();
    EXPECT_NE(failed, "");
    EXPECT_EQ(after_success, failed)
        << "the header: \"the message of the last failed call made on this thread\"";
}

// A C host may pass any int where the header says cloth_stage (or any other
// enum): the library reads it without undefined behaviour (UBSan checks this
// in the sanitizer build; the fuzzer once found it) and answers "?".
TEST_F(BadInput, StageNameOfAnIntOutsideTheEnumIsAQuestionMark) {
    for (int32_t bad : {int32_t{-1}, int32_t{99}, int32_t{0x7FFFFFFF}, static_cast<int32_t>(0x8000057Au)}) {
        ++g_bad_inputs;
        const char* name = cloth_test_stage_name_of_int(bad);
        ASSERT_NE(name, nullptr) << bad;
        EXPECT_STREQ(name, "?") << bad;
    }
    EXPECT_STREQ(cloth_stage_name(CLOTH_STAGE_AIR), "air");
}

TEST_F(BadInput, ResultNameIsTheEnumeratorNameAndNeverNull) {
    const std::pair<cloth_result, const char*> names[] = {
        {CLOTH_OK, "CLOTH_OK"},
        {CLOTH_ERROR_NULL_POINTER, "CLOTH_ERROR_NULL_POINTER"},
        {CLOTH_ERROR_INVALID_HANDLE, "CLOTH_ERROR_INVALID_HANDLE"},
        {CLOTH_ERROR_INVALID_DESC, "CLOTH_ERROR_INVALID_DESC"},
        {CLOTH_ERROR_INVALID_COUNT, "CLOTH_ERROR_INVALID_COUNT"},
        {CLOTH_ERROR_INDEX_OUT_OF_RANGE, "CLOTH_ERROR_INDEX_OUT_OF_RANGE"},
        {CLOTH_ERROR_NOT_FINITE, "CLOTH_ERROR_NOT_FINITE"},
        {CLOTH_ERROR_INVALID_VALUE, "CLOTH_ERROR_INVALID_VALUE"},
        {CLOTH_ERROR_DEGENERATE_GEOMETRY, "CLOTH_ERROR_DEGENERATE_GEOMETRY"},
        {CLOTH_ERROR_OUT_OF_MEMORY, "CLOTH_ERROR_OUT_OF_MEMORY"},
        {CLOTH_ERROR_CAPACITY, "CLOTH_ERROR_CAPACITY"},
        {CLOTH_ERROR_IO, "CLOTH_ERROR_IO"},
        {CLOTH_ERROR_NONFINITE_STATE, "CLOTH_ERROR_NONFINITE_STATE"},
        {CLOTH_ERROR_SOLVER_FAILED, "CLOTH_ERROR_SOLVER_FAILED"},
        {CLOTH_ERROR_INTERNAL, "CLOTH_ERROR_INTERNAL"},
        {CLOTH_ERROR_OVER_BUDGET, "CLOTH_ERROR_OVER_BUDGET"},
    };
    for (const auto& [code, name] : names) {
        const char* got = cloth_result_name(code);
        ASSERT_NE(got, nullptr) << static_cast<int>(code);
        EXPECT_STREQ(got, name);
    }
    for (int bad : {16, 99, -1, 0x7FFFFFFF}) {
        ++g_bad_inputs;
        const char* got = cloth_result_name(static_cast<cloth_result>(bad));
        ASSERT_NE(got, nullptr) << "cloth_result_name(" << bad << ") returned NULL";
        EXPECT_NE(std::string(got), "") << bad;
    }
}

// Prints how many bad inputs the run exercised.
class CountReporter : public ::testing::Environment {
  public:
    void TearDown() override {
        std::printf("[ cloth    ] %d bad inputs exercised through the C API\n", g_bad_inputs.load());
    }
};
[[maybe_unused]] const auto* const kReporter = ::testing::AddGlobalTestEnvironment(new CountReporter);

}  // namespace
