// Decoder and contract checks of the C API fuzz harness (see api_sequence.h).
// One file over 400 lines: every op shares the harness's state and checks,
// and one decoder keeps the byte-to-op mapping (the corpus) in one place.
//
// Bounded work per input, so that executions stay fast: at most kMaxCalls
// calls, grids of at most 16 x 16 particles, meshes of at most 48 vertices,
// and steps only while the estimated solver work (particles x substeps x
// iterations) stays under a budget. Bad values (NaN, Inf, huge counts,
// out-of-range indices, stale and garbage handles) are drawn often; the
// bounds only keep accepted inputs small.
#include "api_sequence.h"

#include <cloth/cloth.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <memory>
#include <string>

#include "support/contract.h"
#include "support/counting_allocator.h"

namespace cloth_fuzz {
namespace {

constexpr size_t kMaxCalls = 64;
constexpr uint32_t kWorldSlots = 2;
constexpr uint32_t kFabricSlots = 6;
constexpr uint32_t kClothSlots = 8;
constexpr uint32_t kBodySlots = 4;
constexpr uint32_t kColliderSlots = 6;
constexpr uint32_t kMaxGridSide = 16;
constexpr uint32_t kMaxMeshVertices = 48;
constexpr uint32_t kMaxMeshTriangles = 96;
constexpr uint64_t kStepWorkBudget = 100'000;   // particle-iterations per cloth_step call
constexpr uint64_t kInputWorkBudget = 300'000;  // per input

// The harness passes a count larger than its buffer only when the library
// must refuse it before reading: an in-range count over `buffered` becomes
// `limit + 1`, so no call can read past a harness buffer.
uint32_t past_limit_if_unbuffered(uint32_t count, uint32_t buffered, uint32_t limit) {
    return count <= buffered || count > limit ? count : limit + 1;
}

[[noreturn]] void broken(const char* what, const char* detail = "") {
    std::fprintf(stderr, "cloth fuzz: contract broken: %s %s\n", what, detail);
    std::fflush(stderr);
    std::abort();
}

// ---------------------------------------------------------------- bytes

class Bytes {
  public:
    Bytes(const uint8_t* data, size_t size) : data_(data), size_(size) {}

    bool empty() const { return pos_ >= size_; }
    uint8_t u8() { return pos_ < size_ ? data_[pos_++] : 0; }
    uint16_t u16() { return static_cast<uint16_t>(u8() | (u8() << 8)); }
    uint32_t u32() { return static_cast<uint32_t>(u16()) | (static_cast<uint32_t>(u16()) << 16); }

    // Mostly edge values and small sane numbers, sometimes raw bits.
    float any_float() {
        static const float kEdge[] = {0.0f,
                                      -0.0f,
                                      1.0f,
                                      -1.0f,
                                      0.5f,
                                      1.0f / 60.0f,
                                      1e-30f,
                                      1e30f,
                                      std::numeric_limits<float>::max(),
                                      -std::numeric_limits<float>::max(),
                                      std::numeric_limits<float>::denorm_min(),
                                      std::numeric_limits<float>::infinity(),
                                      -std::numeric_limits<float>::infinity(),
                                      std::numeric_limits<float>::quiet_NaN(),
                                      1e-7f,
                                      1e6f};
        constexpr uint8_t kEdgeCount = sizeof kEdge / sizeof kEdge[0];
        const uint8_t b = u8();
        if (b < 64) return kEdge[b % kEdgeCount];
        if (b < 224) return (static_cast<float>(u8()) - 128.0f) / 16.0f;  // -8 .. 8
        uint32_t bits = u32();
        float f;
        std::memcpy(&f, &bits, sizeof f);
        return f;
    }
    void floats(float* out, size_t n) {
        for (size_t i = 0; i < n; ++i) out[i] = any_float();
    }

    // A count: mostly in 0..small_max, sometimes one past `limit` or huge.
    uint32_t count(uint32_t small_max, uint32_t limit) {
        const uint8_t b = u8();
        if (b < 224) return b % (small_max + 1);
        switch (b % 4) {
            case 0:
                return limit;
            case 1:
                return limit + 1;
            case 2:
                return 0xFFFFFFFFu;
            default:
                return 0x80000000u;
        }
    }

  private:
    const uint8_t* data_;
    size_t size_;
    size_t pos_ = 0;
};

// ---------------------------------------------------------------- host

// The worlds' allocator and log are the tests' counting allocator
// (tests/capi/support): a misused callback (a bad alignment, a foreign or
// double free, a wrong size, a log without a message) ends the run.
void callback_misused(const char* what) { broken("allocator or log callback misused:", what); }

// A host job system that defers each task to its finish call and runs the
// ranges there in reverse order, as worker 0 (results must not depend on
// the split or the order). The world calls enqueue and finish from the
// thread that steps it, so one pending task per world suffices.
struct HostTask {
    cloth_task_fn* task = nullptr;
    uint32_t item_count = 0;
    uint32_t min_range = 0;
    void* context = nullptr;
    bool pending = false;
};

void* host_enqueue(cloth_task_fn* task, uint32_t item_count, uint32_t min_range, void* context, void* user) {
    HostTask* t = static_cast<HostTask*>(user);
    if (t->pending) broken("enqueue_task before the previous task was finished");
    if (!task) broken("enqueue_task without a task");
    if (item_count == 0) {
        return nullptr;
    }
    *t = HostTask{task, item_count, min_range, context, true};
    return t;
}

void host_finish(void* handle, void* user) {
    HostTask* t = static_cast<HostTask*>(user);
    if (handle != t || !t->pending) broken("finish_task with a handle enqueue_task did not return");
    const uint32_t range = std::max(t->min_range, 1u);
    for (uint32_t end = t->item_count; end > 0;) {
        const uint32_t begin = end > range ? end - range : 0;
        t->task(begin, end, 0, t->context);
        end = begin;
    }
    t->pending = false;
}

// ---------------------------------------------------------------- state

struct WorldSlot {
    cloth_world_id id{};
    std::unique_ptr<cloth_test::CountingAllocator> host = std::make_unique<cloth_test::CountingAllocator>();
    HostTask tasks;
    bool live = false;
    bool counted = false;  // uses the counting allocator
};

class Harness {
  public:
    Harness(const uint8_t* data, size_t size) : in_(data, size) {
        cloth_test::CountingAllocator::violation_handler() = callback_misused;
    }
    ~Harness();

    RunStats run();

  private:
    // Every call goes through here: a known code and, on failure, a message.
    cloth_result check(cloth_result r, const char* call);
    // What a rejected call on objects of this world (and this cloth) must
    // leave alone: the world's live cloths and bodies, and its memory if the
    // counting allocator is its allocator.
    cloth_test::Watch watch_of(uint16_t world1, uint16_t world_generation) const;
    cloth_test::Watch watch_of(cloth_id cloth) const {
        return watch_of(cloth.world1, cloth.world_generation);
    }
    // check(call()), and if the library rejected the call, nothing `watch`
    // names changed (tests/capi/support/contract.h).
    template <typename Call>
    cloth_result guarded(const cloth_test::Watch& watch, const char* name, Call call);
    void check_cloths_finite(uint32_t world_slot);

    cloth_world_id pick_world();
    cloth_fabric_id pick_fabric();
    cloth_id pick_cloth();
    uint32_t particles_of(cloth_id id);

    void world_create();
    void world_destroy();
    void world_set_gravity();
    void world_shift_origin();
    void fabric_grid();
    void fabric_mesh();
    void fabric_obj();
    void fabric_destroy();
    void fabric_query();
    void cloth_create_call();
    void cloth_destroy_call();
    void step();
    void particle_edit();
    void is_pinned();
    void solver();
    void material();
    void read();
    void stats();
    void allocator_schedule();
    void null_arguments();
    void self_collision();
    void cloth_contact();
    void level_of_detail();
    void profiling();
    void body();
    void character();
    void collider();
    void attachment();
    void snapshot();

    cloth_body_id pick_body();
    cloth_collider_id pick_collider();
    void rotation(float q[4]);

    void add_fabric(cloth_fabric_id id) { fabrics_[next_fabric_++ % kFabricSlots] = id; }
    void add_cloth(cloth_id id) { cloths_[next_cloth_++ % kClothSlots] = id; }

    Bytes in_;
    RunStats stats_;
    WorldSlot worlds_[kWorldSlots];
    cloth_fabric_id fabrics_[kFabricSlots]{};
    cloth_id cloths_[kClothSlots]{};
    cloth_body_id bodies_[kBodySlots]{};
    cloth_collider_id colliders_[kColliderSlots]{};
    uint32_t next_fabric_ = 0;
    uint32_t next_cloth_ = 0;
    uint32_t next_body_ = 0;
    uint32_t next_collider_ = 0;
    uint64_t work_ = 0;
};

Harness::~Harness() {
    for (WorldSlot& w : worlds_) {
        if (!w.live) continue;
        w.host->fail_after(-1);
        if (cloth_world_destroy(w.id) != CLOTH_OK) broken("cloth_world_destroy of a live world failed");
        if (w.counted && w.host->live_blocks() != 0)
            broken("memory still allocated after cloth_world_destroy");
    }
}

cloth_result Harness::check(cloth_result r, const char* call) {
    ++stats_.calls;
    static const bool trace = std::getenv("CLOTH_FUZZ_TRACE") != nullptr;  // print every call
    if (trace)
        std::fprintf(stderr, "  %s -> %s %s\n", call, cloth_result_name(r), r ? cloth_get_last_error() : "");
    const std::string problem = cloth_test::report_problem(r);
    if (!problem.empty()) broken(call, problem.c_str());
    if (r != CLOTH_OK) ++stats_.rejected;
    return r;
}

cloth_test::Watch Harness::watch_of(uint16_t world1, uint16_t world_generation) const {
    cloth_test::Watch watch;
    for (const WorldSlot& w : worlds_) {
        if (!w.live || w.id.index1 != world1 || w.id.generation != world_generation) continue;
        watch.world = w.id;
        if (w.counted) watch.memory = w.host.get();
    }
    if (watch.world.index1 == 0) return watch;  // no live world: nothing of it to watch
    uint32_t n = 0;
    for (const cloth_id& c : cloths_) {
        if (c.world1 == world1 && c.world_generation == world_generation &&
            cloth_get_particle_count(c, &n) == CLOTH_OK)
            watch.cloths.push_back(c);
    }
    float position[3], rotation[4];
    for (const cloth_body_id& b : bodies_) {
        if (b.world1 == world1 && b.world_generation == world_generation &&
            cloth_body_get_pose(b, position, rotation) == CLOTH_OK)
            watch.bodies.push_back(b);
    }
    return watch;
}

template <typename Call>
cloth_result Harness::guarded(const cloth_test::Watch& watch, const char* name, Call call) {
    const cloth_test::Unchanged unchanged(watch);
    const cloth_result r = check(call(), name);
    if (r != CLOTH_OK) {
        const std::string changed = unchanged.what_changed();
        if (!changed.empty()) broken(name, ("was rejected, but " + changed).c_str());
    }
    return r;
}

cloth_world_id Harness::pick_world() {
    const uint8_t b = in_.u8();
    if (b >= 240) return cloth_world_id{static_cast<uint16_t>(in_.u8()), in_.u16()};  // garbage
    return worlds_[b % kWorldSlots].id;  // live, destroyed (stale) or null
}

cloth_fabric_id Harness::pick_fabric() {
    const uint8_t b = in_.u8();
    if (b >= 240) return cloth_fabric_id{static_cast<uint16_t>(in_.u8()), in_.u16(), in_.u16(), in_.u16()};
    return fabrics_[b % kFabricSlots];
}

cloth_id Harness::pick_cloth() {
    const uint8_t b = in_.u8();
    if (b >= 240) return cloth_id{static_cast<uint16_t>(in_.u8()), in_.u16(), in_.u16(), in_.u16()};
    return cloths_[b % kClothSlots];
}

// Particle count of a cloth, 0 if the handle is not live.
uint32_t Harness::particles_of(cloth_id id) {
    uint32_t n = 0;
    if (check(cloth_get_particle_count(id, &n), "cloth_get_particle_count") != CLOTH_OK) return 0;
    if (n == 0) broken("a live cloth has no particles");
    return n;
}

// After any step: every cloth of the world is finite (a cloth that went
// non-finite must have been restored).
void Harness::check_cloths_finite(uint32_t world_slot) {
    const cloth_world_id w = worlds_[world_slot].id;
    for (const cloth_id& c : cloths_) {
        if (c.world1 != w.index1 || c.world_generation != w.generation) continue;
        const uint32_t n = particles_of(c);
        if (n == 0) continue;
        std::vector<float> values(3 * size_t{n});
        if (check(cloth_read_positions(c, values.data(), 3 * n), "cloth_read_positions") != CLOTH_OK)
            broken("reading a live cloth failed");
        for (float v : values)
            if (!std::isfinite(v)) broken("a cloth has a non-finite position after cloth_step");
        if (check(cloth_read_velocities(c, values.data(), 3 * n), "cloth_read_velocities") != CLOTH_OK)
            broken("reading a live cloth failed");
        for (float v : values)
            if (!std::isfinite(v)) broken("a cloth has a non-finite velocity after cloth_step");
    }
}

// ---------------------------------------------------------------- world

void Harness::world_create() {
    uint32_t slot = kWorldSlots;
    for (uint32_t i = kWorldSlots; i-- > 0;)
        if (!worlds_[i].live) slot = i;  // the first free slot
    const uint8_t flags = in_.u8();
    if (slot == kWorldSlots) return;  // keep at most two worlds (the process table holds 128)
    WorldSlot& w = worlds_[slot];
    w.host = std::make_unique<cloth_test::CountingAllocator>();
    w.host->set_max_single_allocation(size_t{64} << 20);  // a bounded host
    cloth_world_desc desc = cloth_default_world_desc();
    w.counted = flags & 1;
    if (w.counted) {
        w.host->use_for_memory(desc);
        if (flags & 2) w.host->fail_after(in_.u8() % 16);
    }
    if (flags & 4) w.host->use_for_log(desc);
    if (flags & 8) in_.floats(desc.gravity, 3);
    if (flags & 16) {
        desc.max_cloths = in_.count(8, 65535);
        desc.max_fabrics = in_.count(6, 65535);
    } else {
        desc.max_cloths = 8;
        desc.max_fabrics = 6;
    }
    // Jobs: the world's own threads (a few), or the host job system above.
    const uint8_t jobs = in_.u8();
    static const uint32_t kBadWorkers[] = {257, 1000, 0xFFFFFFFFu, 0x80000000u};
    desc.worker_count = jobs < 240 ? jobs % 4 : kBadWorkers[jobs % 4];
    if (jobs & 4) {
        w.tasks = HostTask{};
        desc.enqueue_task = host_enqueue;
        desc.finish_task = host_finish;
        desc.task_user = &w.tasks;
        if (jobs & 8) {  // only one of the two: rejected
            if (jobs & 16)
                desc.enqueue_task = nullptr;
            else
                desc.finish_task = nullptr;
        }
    }
    if (flags & 32) desc.struct_size = in_.u8();
    if (flags & 64) desc.internal_cookie ^= in_.u32() | 1;
    if (flags & 128) {
        if (in_.u8() & 1)
            desc.alloc = nullptr;
        else
            desc.free = nullptr;
    }
    cloth_world_id id{};
    if (check(cloth_world_create(&desc, &id), "cloth_world_create") == CLOTH_OK) {
        if (id.index1 == 0) broken("cloth_world_create returned a null id");
        w.id = id;
        w.live = true;
    } else if (w.counted && w.host->live_blocks() != 0) {
        broken("a failed cloth_world_create kept memory");
    }
}

void Harness::world_destroy() {
    const cloth_world_id id = pick_world();
    const cloth_result r = check(cloth_world_destroy(id), "cloth_world_destroy");
    for (WorldSlot& w : worlds_) {
        if (!w.live || w.id.index1 != id.index1 || w.id.generation != id.generation) continue;
        if (r != CLOTH_OK) broken("cloth_world_destroy of a live world failed");
        w.live = false;  // the id stays in the table as a stale handle
        if (w.counted && w.host->live_blocks() != 0)
            broken("memory still allocated after cloth_world_destroy");
    }
}

void Harness::world_set_gravity() {
    const cloth_world_id id = pick_world();
    float g[3];
    in_.floats(g, 3);
    guarded(watch_of(id.index1, id.generation), "cloth_world_set_gravity",
            [&] { return cloth_world_set_gravity(id, g); });
}

void Harness::world_shift_origin() {
    const cloth_world_id id = pick_world();
    float shift[3];
    in_.floats(shift, 3);
    guarded(watch_of(id.index1, id.generation), "cloth_world_shift_origin",
            [&] { return cloth_world_shift_origin(id, shift); });
}

// ---------------------------------------------------------------- fabric

void Harness::fabric_grid() {
    const cloth_world_id world = pick_world();
    cloth_grid_desc desc = cloth_default_grid_desc();
    const uint8_t flags = in_.u8();
    // Huge sides only in combinations the library must reject (> 2^24 particles).
    static const uint32_t kHuge[] = {1u << 24, 1u << 31, 0xFFFFFFFFu};
    auto side = [&]() -> uint32_t {
        const uint8_t b = in_.u8();
        return b < 240 ? b % (kMaxGridSide + 1) : kHuge[b % 3];
    };
    desc.columns = side();
    desc.rows = side();
    if (flags & 1) in_.floats(desc.origin, 3);
    if (flags & 2) in_.floats(desc.u, 3);
    if (flags & 4) in_.floats(desc.v, 3);
    if (flags & 8) desc.spring_kinds = in_.u8() & 0x0F;
    if (flags & 16) desc.struct_size = in_.u8();
    if (flags & 32) desc.internal_cookie = in_.u32();
    cloth_fabric_id id{};
    if (guarded(watch_of(world.index1, world.generation), "cloth_fabric_create_grid",
                [&] { return cloth_fabric_create_grid(world, &desc, &id); }) == CLOTH_OK)
        add_fabric(id);
}

void Harness::fabric_mesh() {
    const cloth_world_id world = pick_world();
    cloth_mesh_desc desc = cloth_default_mesh_desc();
    const uint8_t flags = in_.u8();
    desc.vertex_count = in_.count(kMaxMeshVertices, (1u << 24) + 1);
    desc.triangle_count = in_.count(kMaxMeshTriangles, (1u << 26) + 1);
    // Arrays exactly as long as the counts claim (ASan sees any over-read);
    // a huge count must be rejected before the arrays are read at all.
    const uint32_t vertices = desc.vertex_count <= kMaxMeshVertices ? desc.vertex_count : 1;
    const uint32_t triangles = desc.triangle_count <= kMaxMeshTriangles ? desc.triangle_count : 1;
    std::vector<float> positions(3 * size_t{vertices});
    std::vector<uint32_t> indices(3 * size_t{triangles});
    constexpr uint32_t kRow = 7;
    for (uint32_t i = 0; i < vertices; ++i) {
        positions[3 * i] = 0.1f * static_cast<float>(i % kRow);
        positions[3 * i + 1] = -0.1f * static_cast<float>(i / kRow);
        positions[3 * i + 2] = 0.0f;
    }
    // Triangles of a strip over that lattice, then fuzzed overrides.
    for (uint32_t t = 0; t < triangles; ++t) {
        const uint32_t i = t / 2;
        const uint32_t a = i, b = i + 1, c = i + kRow, d = i + kRow + 1;
        const uint32_t n = std::max(vertices, 1u);
        const uint32_t tri[3] = {(t % 2 ? b : a) % n, (t % 2 ? d : b) % n, c % n};
        std::copy(tri, tri + 3, &indices[3 * t]);
    }
    const uint32_t float_edits = flags & 7, index_edits = (flags >> 3) & 7;
    for (uint32_t k = 0; k < float_edits && !positions.empty(); ++k)
        positions[in_.u16() % positions.size()] = in_.any_float();
    for (uint32_t k = 0; k < index_edits && !indices.empty(); ++k) {
        const uint32_t at = in_.u16() % indices.size();
        indices[at] = in_.u8() < 200 ? in_.u8() % (vertices + 2) : in_.u32();
    }
    if (flags & 64) desc.spring_kinds = in_.u8() & 0x0F;
    const bool null_arrays = (flags & 128) && (in_.u8() & 1);
    desc.positions = null_arrays ? nullptr : positions.data();
    desc.indices = null_arrays ? nullptr : indices.data();
    cloth_fabric_id id{};
    if (guarded(watch_of(world.index1, world.generation), "cloth_fabric_create_mesh",
                [&] { return cloth_fabric_create_mesh(world, &desc, &id); }) == CLOTH_OK)
        add_fabric(id);
}

// An OBJ file made of fuzz bytes, behind a memfd (no file system writes).
void Harness::fabric_obj() {
    const cloth_world_id world = pick_world();
    const uint8_t flags = in_.u8();
    const uint32_t kinds = flags & 1 ? in_.u8() & 0x0F : CLOTH_SPRING_ALL;
    std::string text;
    if (flags & 2) text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n";
    const uint32_t length = in_.u8();
    for (uint32_t i = 0; i < length && !in_.empty(); ++i) text.push_back(static_cast<char>(in_.u8()));
    if (flags & 4) {
        cloth_fabric_id id{};
        guarded(watch_of(world.index1, world.generation), "cloth_fabric_create_obj",
                [&] { return cloth_fabric_create_obj(world, "/nonexistent/cloth-fuzz.obj", kinds, &id); });
        return;
    }
    const int fd = memfd_create("cloth-fuzz-obj", 0);
    if (fd < 0) return;
    if (write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size())) {
        char path[64];
        std::snprintf(path, sizeof path, "/proc/self/fd/%d", fd);
        cloth_fabric_id id{};
        if (guarded(watch_of(world.index1, world.generation), "cloth_fabric_create_obj",
                    [&] { return cloth_fabric_create_obj(world, path, kinds, &id); }) == CLOTH_OK)
            add_fabric(id);
    }
    close(fd);
}

void Harness::fabric_destroy() {
    const cloth_fabric_id id = pick_fabric();
    guarded(watch_of(id.world1, id.world_generation), "cloth_fabric_destroy",
            [&] { return cloth_fabric_destroy(id); });
}

void Harness::fabric_query() {
    const cloth_fabric_id id = pick_fabric();
    uint32_t n = 0;
    cloth_test::Watch watch = watch_of(id.world1, id.world_generation);
    watch.outputs = {{&n, sizeof n, "the count"}};
    switch (in_.u8() % 4) {
        case 0:
            guarded(watch, "cloth_fabric_get_particle_count",
                    [&] { return cloth_fabric_get_particle_count(id, &n); });
            break;
        case 1:
            guarded(watch, "cloth_fabric_get_triangle_count",
                    [&] { return cloth_fabric_get_triangle_count(id, &n); });
            break;
        case 2: {
            const uint32_t kinds = in_.u8() & 0x0F;
            guarded(watch, "cloth_fabric_get_spring_count",
                    [&] { return cloth_fabric_get_spring_count(id, kinds, &n); });
            break;
        }
        default: {
            // A buffer of exactly the capacity claimed: ASan sees any overflow.
            const uint32_t capacity = in_.u16() % 2048;
            std::vector<uint32_t> out(std::max(capacity, 1u));
            watch.outputs = {{out.data(), out.size() * sizeof(uint32_t), "the triangles"}};
            guarded(watch, "cloth_fabric_read_triangles",
                    [&] { return cloth_fabric_read_triangles(id, out.data(), capacity); });
        }
    }
}

// ---------------------------------------------------------------- cloth

void Harness::cloth_create_call() {
    const cloth_world_id world = pick_world();
    cloth_desc desc = cloth_default_desc();
    desc.fabric = pick_fabric();
    const uint8_t flags = in_.u8();
    if (flags & 1) desc.area_density = in_.any_float();
    if (flags & 2) desc.particle_mass = in_.any_float();
    if (flags & 4) {
        desc.structural = {in_.any_float(), in_.any_float()};
        desc.shear = {in_.any_float(), in_.any_float()};
        desc.bend = {in_.any_float(), in_.any_float()};
    }
    if (flags & 8) {
        desc.solver.kind = static_cast<cloth_solver_kind>(in_.u8() % 5);
        desc.solver.iterations = in_.count(8, 256);
        desc.solver.substeps = in_.count(4, 64);
        desc.solver.cg_tolerance = in_.any_float();
        desc.solver.cg_max_iterations = in_.count(50, 100000);
        desc.solver.compression_safe_jacobian = in_.u8() & 1;
    }
    if (flags & 16) {
        in_.floats(desc.aero.wind, 3);
        desc.aero.air_density = in_.any_float();
        desc.aero.drag_coefficient = in_.any_float();
        desc.aero.lift_coefficient = in_.any_float();
        desc.aero.linear_drag = in_.any_float();
    }
    std::vector<float> initial;
    if (flags & 32) {
        uint32_t n = 0;
        if (cloth_fabric_get_particle_count(desc.fabric, &n) != CLOTH_OK) n = 1;
        initial.assign(3 * size_t{n}, 0.0f);
        for (size_t i = 0; i < initial.size(); ++i) initial[i] = 0.05f * static_cast<float>(i % 17);
        const uint32_t edits = in_.u8() % 4;
        for (uint32_t k = 0; k < edits; ++k) initial[in_.u16() % initial.size()] = in_.any_float();
        desc.initial_positions = initial.data();
    }
    if (flags & 64) desc.struct_size = in_.u8();
    if (flags & 128) desc.internal_cookie = in_.u32();
    cloth_id id{};
    if (guarded(watch_of(world.index1, world.generation), "cloth_create",
                [&] { return cloth_create(world, &desc, &id); }) == CLOTH_OK)
        add_cloth(id);
}

void Harness::cloth_destroy_call() {
    const cloth_id id = pick_cloth();
    guarded(watch_of(id), "cloth_destroy", [&] { return cloth_destroy(id); });
}

void Harness::step() {
    const uint8_t b = in_.u8();
    const uint32_t slot = b % kWorldSlots;
    const cloth_world_id world = b >= 240 ? cloth_world_id{in_.u8(), in_.u16()} : worlds_[slot].id;
    const uint8_t d = in_.u8();
    float dt = d < 128 ? 1.0f / 60.0f : d < 192 ? static_cast<float>(d - 127) / 64.0f : in_.any_float();
    // Bound the solver work: estimate it from each cloth's settings.
    uint64_t work = 0;
    for (const cloth_id& c : cloths_) {
        if (c.world1 != world.index1 || c.world_generation != world.generation) continue;
        cloth_solver_settings s{};
        uint32_t n = 0;
        if (cloth_get_particle_count(c, &n) != CLOTH_OK || cloth_get_solver(c, &s) != CLOTH_OK) continue;
        uint64_t per_substep = s.kind == CLOTH_SOLVER_CG ? s.cg_max_iterations + 1 : s.iterations + 1;
        cloth_self_collision_desc sc{};
        sc.struct_size = sizeof sc;
        if (cloth_get_self_collision(c, &sc) == CLOTH_OK && sc.enabled) per_substep += 4 + sc.passes;
        work += uint64_t{n} * s.substeps * per_substep;
    }
    if (work > kStepWorkBudget || work_ + work > kInputWorkBudget) return;
    work_ += work;
    const cloth_result r = check(cloth_step(world, dt), "cloth_step");
    const bool advanced = r == CLOTH_OK || r == CLOTH_ERROR_NONFINITE_STATE ||
                          r == CLOTH_ERROR_SOLVER_FAILED || r == CLOTH_ERROR_OUT_OF_MEMORY ||
                          r == CLOTH_ERROR_OVER_BUDGET;
    if (advanced) ++stats_.steps;
    if (b < 240 && worlds_[slot].live) check_cloths_finite(slot);
}

void Harness::particle_edit() {
    const cloth_id id = pick_cloth();
    const uint8_t what = in_.u8();
    const uint32_t particles = particles_of(id);
    // Buffers exactly as long as the count claims; a count above the
    // particle count must be rejected before the buffer is read.
    const uint32_t count = in_.count(8, particles);
    const size_t length = count <= 4096 ? count : 1;
    std::vector<uint32_t> indices(std::max<size_t>(length, 1));
    for (size_t k = 0; k < length; ++k) {
        const uint8_t b = in_.u8();
        indices[k] = b < 224 ? b % std::max(particles, 1u) : b < 240 ? particles : in_.u32();
    }
    std::vector<float> xyz(3 * indices.size());
    for (size_t k = 0; k < xyz.size(); ++k) xyz[k] = k < 6 ? in_.any_float() : 0.01f * static_cast<float>(k);
    const uint32_t* idx = (what & 0x80) ? nullptr : indices.data();
    const cloth_test::Watch watch = watch_of(id);
    switch (what % 4) {
        case 0:
            guarded(watch, "cloth_pin", [&] { return cloth_pin(id, idx, count); });
            break;
        case 1:
            guarded(watch, "cloth_unpin", [&] { return cloth_unpin(id, idx, count); });
            break;
        case 2:
            if (what & 0x40) {  // the same indices and floats as masses
                guarded(watch, "cloth_set_particle_masses",
                        [&] { return cloth_set_particle_masses(id, idx, xyz.data(), count); });
            } else {
                guarded(watch, "cloth_set_positions",
                        [&] { return cloth_set_positions(id, idx, xyz.data(), count); });
            }
            break;
        default:
            guarded(watch, "cloth_set_pin_targets",
                    [&] { return cloth_set_pin_targets(id, idx, xyz.data(), count); });
    }
}

void Harness::is_pinned() {
    const cloth_id id = pick_cloth();
    unsigned char pinned = 0xA5;
    const uint8_t b = in_.u8();
    const uint32_t index = b < 200 ? b : in_.u32();
    cloth_test::Watch watch = watch_of(id);
    watch.outputs = {{&pinned, 1, "the pin flag"}};
    guarded(watch, "cloth_is_pinned",
            [&] { return cloth_is_pinned(id, index, cloth_test::FlagOut{&pinned}); });
}

void Harness::solver() {
    const cloth_id id = pick_cloth();
    cloth_solver_settings s = cloth_default_solver_settings();
    const uint8_t flags = in_.u8();
    cloth_test::Watch watch = watch_of(id);
    if (flags & 1) {
        watch.outputs = {{&s, sizeof s, "the solver settings"}};
        guarded(watch, "cloth_get_solver", [&] { return cloth_get_solver(id, &s); });
        return;
    }
    s.kind = static_cast<cloth_solver_kind>(in_.u8() % 5);
    s.iterations = in_.count(8, 256);
    s.substeps = in_.count(4, 64);
    if (flags & 2) s.cg_tolerance = in_.any_float();
    s.cg_max_iterations = in_.count(50, 100000);
    s.compression_safe_jacobian = (flags & 4) != 0;
    if (flags & 8) s.struct_size = in_.u8();
    guarded(watch, "cloth_set_solver", [&] { return cloth_set_solver(id, &s); });
}

void Harness::material() {
    const cloth_id id = pick_cloth();
    const uint8_t what = in_.u8();
    const cloth_test::Watch watch = watch_of(id);
    switch (what % 3) {
        case 0: {
            const uint32_t kinds = in_.u8() & 0x0F;
            const cloth_spring_params p{in_.any_float(), in_.any_float()};
            guarded(watch, "cloth_set_spring_params", [&] { return cloth_set_spring_params(id, kinds, p); });
            break;
        }
        case 1: {
            cloth_aero_params a{};
            in_.floats(a.wind, 3);
            a.air_density = in_.any_float();
            a.drag_coefficient = in_.any_float();
            a.lift_coefficient = in_.any_float();
            a.linear_drag = in_.any_float();
            guarded(watch, "cloth_set_aero", [&] { return cloth_set_aero(id, &a); });
            break;
        }
        default: {
            float wind[3];
            in_.floats(wind, 3);
            guarded(watch, "cloth_set_wind", [&] { return cloth_set_wind(id, wind); });
        }
    }
}

void Harness::read() {
    const cloth_id id = pick_cloth();
    const uint8_t what = in_.u8();
    const uint32_t particles = particles_of(id);
    const uint8_t b = in_.u8();
    // Capacity: exact, one short, or anything small; the buffer is exactly that long.
    const uint32_t capacity = b < 128   ? 3 * particles
                              : b < 192 ? (3 * particles) - (particles > 0)
                                        : in_.u16() % 2048;
    std::vector<float> out(std::max(capacity, 1u));
    cloth_test::Watch watch = watch_of(id);
    watch.outputs = {{out.data(), out.size() * sizeof(float), "the read buffer"}};
    switch (what % 3) {
        case 0:
            guarded(watch, "cloth_read_positions",
                    [&] { return cloth_read_positions(id, out.data(), capacity); });
            break;
        case 1:
            guarded(watch, "cloth_read_velocities",
                    [&] { return cloth_read_velocities(id, out.data(), capacity); });
            break;
        default:
            if (what & 0x40) {  // one float a particle: capacities below 3 n may hold them
                guarded(watch, "cloth_read_particle_masses",
                        [&] { return cloth_read_particle_masses(id, out.data(), capacity); });
            } else {
                guarded(watch, "cloth_read_normals",
                        [&] { return cloth_read_normals(id, out.data(), capacity); });
            }
    }
}

void Harness::stats() {
    const cloth_id id = pick_cloth();
    cloth_stats s{};
    s.struct_size = in_.u8() < 224 ? sizeof s : in_.u8();
    cloth_test::Watch watch = watch_of(id);
    watch.outputs = {{&s, sizeof s, "the stats"}};
    guarded(watch, "cloth_get_stats", [&] { return cloth_get_stats(id, &s); });
}

void Harness::allocator_schedule() {
    WorldSlot& w = worlds_[in_.u8() % kWorldSlots];
    const uint8_t b = in_.u8();
    w.host->fail_after(b < 128 ? b % 8 : -1);
}

void Harness::null_arguments() {
    const cloth_world_id world = pick_world();
    const cloth_id cloth = pick_cloth();
    const cloth_fabric_id fabric = pick_fabric();
    const cloth_test::Watch of_world = watch_of(world.index1, world.generation);
    const cloth_test::Watch of_cloth = watch_of(cloth);
    const cloth_test::Watch of_fabric = watch_of(fabric.world1, fabric.world_generation);
    const char* name = "";
    cloth_result r = CLOTH_OK;
    auto made = [&](const cloth_test::Watch& watch, const char* call_name, auto call) {
        name = call_name;
        r = guarded(watch, call_name, call);
    };
    switch (in_.u8() % 12) {
        case 0:
            made(of_world, "cloth_world_create", [&] { return cloth_world_create(nullptr, nullptr); });
            break;
        case 1:
            made(of_world, "cloth_world_set_gravity",
                 [&] { return cloth_world_set_gravity(world, nullptr); });
            break;
        case 2:
            made(of_world, "cloth_fabric_create_grid",
                 [&] { return cloth_fabric_create_grid(world, nullptr, nullptr); });
            break;
        case 3:
            made(of_world, "cloth_fabric_create_mesh",
                 [&] { return cloth_fabric_create_mesh(world, nullptr, nullptr); });
            break;
        case 4:
            made(of_world, "cloth_fabric_create_obj",
                 [&] { return cloth_fabric_create_obj(world, nullptr, 0, nullptr); });
            break;
        case 5:
            made(of_world, "cloth_create", [&] { return cloth_create(world, nullptr, nullptr); });
            break;
        case 6:
            made(of_cloth, "cloth_read_positions",
                 [&] { return cloth_read_positions(cloth, nullptr, 0xFFFFFFFFu); });
            break;
        case 7:
            made(of_cloth, "cloth_set_wind", [&] { return cloth_set_wind(cloth, nullptr); });
            break;
        case 8:
            made(of_cloth, "cloth_set_aero", [&] { return cloth_set_aero(cloth, nullptr); });
            break;
        case 9:
            made(of_cloth, "cloth_get_stats", [&] { return cloth_get_stats(cloth, nullptr); });
            break;
        case 10:
            made(of_fabric, "cloth_fabric_read_triangles",
                 [&] { return cloth_fabric_read_triangles(fabric, nullptr, 0xFFFFFFFFu); });
            break;
        default:
            made(of_cloth, "cloth_set_solver", [&] { return cloth_set_solver(cloth, nullptr); });
    }
    if (r == CLOTH_OK) broken(name, "accepted a NULL argument");
}

void Harness::self_collision() {
    const cloth_id id = pick_cloth();
    const uint8_t what = in_.u8();
    cloth_test::Watch watch = watch_of(id);
    switch (what % 3) {
        case 0: {
            cloth_self_collision_desc d = cloth_default_self_collision_desc();
            const uint8_t flags = in_.u8();
            d.enabled = flags & 1;
            if (flags & 2) d.thickness = in_.any_float();
            if (flags & 4) d.friction = in_.any_float();
            if (flags & 8) d.use_regions = !d.use_regions;
            if (flags & 16) d.passes = in_.count(16, 16);
            if (flags & 32) d.struct_size = in_.u8();
            if (flags & 64) d.internal_cookie = in_.u32();
            guarded(watch, "cloth_set_self_collision", [&] { return cloth_set_self_collision(id, &d); });
            break;
        }
        case 1: {
            cloth_self_collision_desc d{};
            d.struct_size = sizeof d;
            watch.outputs = {{&d, sizeof d, "the self-collision settings"}};
            guarded(watch, "cloth_get_self_collision",
                    [&] { return cloth_get_self_collision(id, (what & 0x80) ? nullptr : &d); });
            break;
        }
        default: {
            cloth_self_collision_stats st{};
            st.struct_size = in_.u8() < 224 ? sizeof st : in_.u8();
            watch.outputs = {{&st, sizeof st, "the self-collision stats"}};
            guarded(watch, "cloth_get_self_collision_stats",
                    [&] { return cloth_get_self_collision_stats(id, (what & 0x80) ? nullptr : &st); });
        }
    }
}

// Contact between two cloths: any pair (a cloth and itself, cloths of two
// worlds, stale or garbage handles), any values, read back and counted.
void Harness::cloth_contact() {
    const cloth_id a = pick_cloth(), b = pick_cloth();
    const uint8_t what = in_.u8();
    cloth_test::Watch watch = watch_of(a);
    switch (what % 3) {
        case 0: {
            cloth_cloth_contact_desc d = cloth_default_cloth_contact_desc();
            const uint8_t flags = in_.u8();
            d.enabled = flags & 1;
            // Within the small grids' two rest edges unless any float is asked for.
            d.thickness = (flags & 2) ? in_.any_float() : 0.01f * static_cast<float>(1 + in_.u8() % 8);
            if (flags & 4) d.friction = in_.any_float();
            if (flags & 8) d.passes = in_.count(16, 16);
            if (flags & 16) d.struct_size = in_.u8();
            if (flags & 32) d.internal_cookie = in_.u32();
            guarded(watch, "cloth_set_cloth_contact",
                    [&] { return cloth_set_cloth_contact(a, b, (what & 0x80) ? nullptr : &d); });
            break;
        }
        case 1: {
            cloth_cloth_contact_desc d{};
            watch.outputs = {{&d, sizeof d, "the contact settings"}};
            guarded(watch, "cloth_get_cloth_contact",
                    [&] { return cloth_get_cloth_contact(a, b, (what & 0x80) ? nullptr : &d); });
            break;
        }
        default: {
            uint32_t contacts = 0, passes = 0;
            watch.outputs = {{&contacts, sizeof contacts, "the contact count"},
                             {&passes, sizeof passes, "the passes"}};
            guarded(watch, "cloth_get_cloth_contact_count", [&] {
                return cloth_get_cloth_contact_count(a, b, (what & 0x80) ? nullptr : &contacts,
                                                     (what & 0x40) ? nullptr : &passes);
            });
        }
    }
}

void Harness::level_of_detail() {
    const uint8_t what = in_.u8();
    if (what % 6 == 2) {
        const cloth_world_id world = pick_world();
        cloth_test::Watch watch = watch_of(world.index1, world.generation);
        const float viewer[3] = {in_.any_float(), in_.any_float(), in_.any_float()};
        guarded(watch, "cloth_world_set_viewer",
                [&] { return cloth_world_set_viewer(world, (what & 0x80) ? nullptr : viewer); });
        return;
    }
    const cloth_id cloth = pick_cloth();
    cloth_test::Watch watch = watch_of(cloth);
    switch (what % 6) {
        case 0: {
            const float importance =
                (what & 0x40) ? in_.any_float() : 0.25f * static_cast<float>(in_.u8() % 8);
            guarded(watch, "cloth_set_importance", [&] { return cloth_set_importance(cloth, importance); });
            break;
        }
        case 1: {
            float importance = 0;
            watch.outputs = {{&importance, sizeof importance, "the importance"}};
            guarded(watch, "cloth_get_importance",
                    [&] { return cloth_get_importance(cloth, (what & 0x80) ? nullptr : &importance); });
            break;
        }
        case 3: {
            // Mostly a valid rate; any value otherwise.
            const uint32_t rate = (what & 0x40) ? in_.u32() : 1u << (in_.u8() % 4);
            guarded(watch, "cloth_set_update_rate", [&] { return cloth_set_update_rate(cloth, rate); });
            break;
        }
        case 5:
            if ((what & 0x20) && (what & 0x40)) {
                // Mostly a level the fabric may have; any value otherwise.
                const uint32_t level = (what & 0x80) ? in_.u32() : in_.u8() % 4;
                guarded(watch, "cloth_set_lod_level", [&] { return cloth_set_lod_level(cloth, level); });
            } else if (what & 0x20) {
                uint32_t level = 0, count = 0;
                watch.outputs = {{&level, sizeof level, "the level"},
                                 {&count, sizeof count, "the level count"}};
                guarded(watch, "cloth_get_lod_level", [&] {
                    return cloth_get_lod_level(cloth, (what & 0x80) ? nullptr : &level,
                                               (what & 0x10) ? nullptr : &count);
                });
            } else if (what & 0x80) {
                guarded(watch, "cloth_sleep", [&] { return cloth_sleep(cloth); });
            } else {
                guarded(watch, "cloth_wake", [&] { return cloth_wake(cloth); });
            }
            break;
        default: {
            uint32_t rate = 0, phase = 0;
            watch.outputs = {{&rate, sizeof rate, "the rate"}, {&phase, sizeof phase, "the phase"}};
            guarded(watch, "cloth_get_update_rate", [&] {
                return cloth_get_update_rate(cloth, (what & 0x80) ? nullptr : &rate,
                                             (what & 0x40) ? nullptr : &phase);
            });
        }
    }
}

// ---------------------------------------------------------------- contact

cloth_body_id Harness::pick_body() {
    const uint8_t b = in_.u8();
    if (b >= 240) return cloth_body_id{static_cast<uint16_t>(in_.u8()), in_.u16(), in_.u16(), in_.u16()};
    return bodies_[b % kBodySlots];
}

cloth_collider_id Harness::pick_collider() {
    const uint8_t b = in_.u8();
    if (b >= 240) return cloth_collider_id{static_cast<uint16_t>(in_.u8()), in_.u16(), in_.u16(), in_.u16()};
    return colliders_[b % kColliderSlots];
}

// Mostly the identity or a unit quaternion, sometimes anything (too long,
// zero, NaN: must be rejected).
void Harness::rotation(float q[4]) {
    const uint8_t b = in_.u8();
    q[0] = q[1] = q[2] = 0.0f;
    q[3] = 1.0f;
    if (b < 128) return;
    in_.floats(q, 4);
    if (b < 224) {
        const float length = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
        if (std::isfinite(length) && length > 1e-3f)
            for (int k = 0; k < 4; ++k) q[k] /= length;
    }
}

void Harness::body() {
    const uint8_t what = in_.u8();
    float position[3], q[4], w[3];
    in_.floats(position, 3);
    rotation(q);
    switch (what % 6) {
        case 0: {
            cloth_body_desc d = cloth_default_body_desc();
            std::copy(position, position + 3, d.position);
            std::copy(q, q + 4, d.rotation);
            if (what & 0x10) in_.floats(d.linear_velocity, 3);
            if (what & 0x20) in_.floats(d.angular_velocity, 3);
            if (what & 0x40) d.struct_size = in_.u8();
            cloth_body_id id{};
            const cloth_world_id world = pick_world();
            if (guarded(watch_of(world.index1, world.generation), "cloth_body_create", [&] {
                    return cloth_body_create(world, (what & 0x80) ? nullptr : &d, &id);
                }) == CLOTH_OK)
                bodies_[next_body_++ % kBodySlots] = id;
            break;
        }
        case 1: {
            const cloth_body_id body = pick_body();
            guarded(watch_of(body.world1, body.world_generation), "cloth_body_destroy",
                    [&] { return cloth_body_destroy(body); });
            break;
        }
        case 2: {
            const cloth_body_id body = pick_body();
            guarded(watch_of(body.world1, body.world_generation), "cloth_body_set_pose",
                    [&] { return cloth_body_set_pose(body, position, (what & 0x80) ? nullptr : q); });
            break;
        }
        case 3: {
            const cloth_body_id body = pick_body();
            guarded(watch_of(body.world1, body.world_generation), "cloth_body_teleport",
                    [&] { return cloth_body_teleport(body, position, q); });
            break;
        }
        case 4: {
            in_.floats(w, 3);
            const cloth_body_id body = pick_body();
            guarded(watch_of(body.world1, body.world_generation), "cloth_body_set_velocity",
                    [&] { return cloth_body_set_velocity(body, position, w); });
            break;
        }
        default: {
            const cloth_body_id body = pick_body();
            cloth_test::Watch watch = watch_of(body.world1, body.world_generation);
            watch.outputs = {{position, sizeof position, "the position"}, {q, sizeof q, "the rotation"}};
            guarded(watch, "cloth_body_get_pose",
                    [&] { return cloth_body_get_pose(body, position, (what & 0x80) ? nullptr : q); });
        }
    }
}

void Harness::collider() {
    const uint8_t what = in_.u8();
    if (what % 9 == 7) {
        const cloth_collider_id id = pick_collider();
        guarded(watch_of(id.world1, id.world_generation), "cloth_collider_destroy",
                [&] { return cloth_collider_destroy(id); });
        return;
    }
    if (what % 9 == 8) {
        const cloth_collider_id id = pick_collider();
        const uint32_t bits = in_.u32();
        guarded(watch_of(id.world1, id.world_generation), "cloth_collider_set_group_bits",
                [&] { return cloth_collider_set_group_bits(id, bits); });
        return;
    }
    const cloth_world_id world = pick_world();
    const cloth_test::Watch of_world = watch_of(world.index1, world.generation);
    cloth_collider_desc d = cloth_default_collider_desc();
    if (what & 0x10) d.body = pick_body();
    if (what & 0x20) in_.floats(d.local_position, 3);
    rotation(d.local_rotation);
    if (what & 0x40) d.struct_size = in_.u8();
    const cloth_collider_desc* desc = (what & 0x80) && in_.u8() < 32 ? nullptr : &d;
    // Shape sizes: small sane values or edge values, point counts within the
    // harness's bounds or past the library's limits.
    float a = in_.u8() < 192 ? 0.05f + static_cast<float>(in_.u8()) / 64.0f : in_.any_float();
    float v[3];
    for (float& x : v) x = in_.u8() < 192 ? 0.05f + static_cast<float>(in_.u8()) / 64.0f : in_.any_float();
    cloth_collider_id id{};
    cloth_result r = CLOTH_OK;
    switch (what % 9) {
        case 0:
            r = guarded(of_world, "cloth_collider_create_sphere",
                        [&] { return cloth_collider_create_sphere(world, desc, a, &id); });
            break;
        case 1:
            r = guarded(of_world, "cloth_collider_create_capsule",
                        [&] { return cloth_collider_create_capsule(world, desc, a, v[0], &id); });
            break;
        case 2:
            r = guarded(of_world, "cloth_collider_create_box",
                        [&] { return cloth_collider_create_box(world, desc, v, &id); });
            break;
        case 3:
            r = guarded(of_world, "cloth_collider_create_plane",
                        [&] { return cloth_collider_create_plane(world, desc, v, a, &id); });
            break;
        case 4: {
            // Every in-range count gets its full buffer (4096 points is small);
            // a count past the limit must be rejected before any read.
            const uint32_t count = in_.count(16, 4096);
            std::vector<float> points(3 * size_t{count <= 4096 ? count : 1});
            for (float& x : points)
                x = in_.u8() < 224 ? static_cast<float>(in_.u8()) / 32.0f : in_.any_float();
            r = guarded(of_world, "cloth_collider_create_convex_hull", [&] {
                return cloth_collider_create_convex_hull(world, desc, points.data(), count, &id);
            });
            break;
        }
        case 5: {
            // A buffer of 2^24 vertices is too big for the fuzzer, so a large
            // claim is always one the library must reject before reading.
            const uint32_t vertices = past_limit_if_unbuffered(in_.count(12, 1u << 24), 64, 1u << 24);
            const uint32_t triangles = past_limit_if_unbuffered(in_.count(12, 1u << 24), 64, 1u << 24);
            std::vector<float> xyz(3 * size_t{vertices <= 64 ? vertices : 1});
            for (float& x : xyz) x = in_.u8() < 224 ? static_cast<float>(in_.u8()) / 32.0f : in_.any_float();
            std::vector<uint32_t> indices(3 * size_t{triangles <= 64 ? triangles : 1});
            for (uint32_t& i : indices) {
                const uint8_t b = in_.u8();
                i = b < 240 ? b % std::max(vertices, 1u) : in_.u32();
            }
            r = guarded(of_world, "cloth_collider_create_triangle_mesh", [&] {
                return cloth_collider_create_triangle_mesh(world, desc, xyz.data(), vertices, indices.data(),
                                                           triangles, &id);
            });
            break;
        }
        case 6: {
            cloth_heightfield_desc h = cloth_default_heightfield_desc();
            h.columns = in_.count(8, 65537);
            h.rows = in_.count(8, 65537);
            h.spacing_x = a;
            h.spacing_z = v[0];
            const uint64_t samples = uint64_t{h.columns} * h.rows;
            std::vector<float> heights(samples <= 64 ? std::max<uint64_t>(samples, 1) : 1);
            for (float& x : heights)
                x = in_.u8() < 224 ? static_cast<float>(in_.u8()) / 64.0f : in_.any_float();
            const uint8_t flags = in_.u8();
            h.heights = (flags & 1) ? nullptr : heights.data();
            if (samples > 64 && (flags & 2) == 0) h.columns = 0;  // never let a huge claim be read
            if (flags & 4) h.struct_size = in_.u8();
            r = guarded(of_world, "cloth_collider_create_heightfield", [&] {
                return cloth_collider_create_heightfield(world, desc, (flags & 8) ? nullptr : &h, &id);
            });
            break;
        }
        case 7:
            r = guarded(of_world, "cloth_collider_create_tapered_capsule", [&] {
                return cloth_collider_create_tapered_capsule(world, desc, a, v[0], v[1], &id);
            });
            break;
    }
    if (r == CLOTH_OK) colliders_[next_collider_++ % kColliderSlots] = id;
}

void Harness::attachment() {
    const cloth_id cloth = pick_cloth();
    const uint8_t what = in_.u8();
    const uint32_t particles = particles_of(cloth);
    cloth_test::Watch watch = watch_of(cloth);
    switch (what % 6) {
        case 0:
        case 1: {
            const uint32_t count = in_.count(8, particles);
            const size_t length = count <= 4096 ? std::max<uint32_t>(count, 1) : 1;
            std::vector<uint32_t> indices(length);
            for (uint32_t& i : indices) {
                const uint8_t b = in_.u8();
                i = b < 224 ? b % std::max(particles, 1u) : b < 240 ? particles : in_.u32();
            }
            const uint32_t* idx = (what & 0x80) ? nullptr : indices.data();
            if (what % 6 == 0) {
                std::vector<float> offsets(3 * length);
                for (size_t k = 0; k < offsets.size(); ++k)
                    offsets[k] = k < 6 ? in_.any_float() : 0.01f * static_cast<float>(k);
                const cloth_body_id body = pick_body();
                guarded(watch, "cloth_attach", [&] {
                    return cloth_attach(cloth, body, idx, (what & 0x40) ? nullptr : offsets.data(), count);
                });
            } else {
                guarded(watch, "cloth_detach", [&] { return cloth_detach(cloth, idx, count); });
            }
            break;
        }
        case 2: {
            cloth_body_id body{};
            float offset[3];
            const uint8_t b = in_.u8();
            const uint32_t index = b < 224 ? b % std::max(particles, 1u) : in_.u32();
            watch.outputs = {{&body, sizeof body, "the body"}, {offset, sizeof offset, "the offset"}};
            guarded(watch, "cloth_get_attachment", [&] {
                return cloth_get_attachment(cloth, index, (what & 0x80) ? nullptr : &body, offset);
            });
            break;
        }
        case 3: {
            cloth_collision_params p = cloth_default_collision_params();
            const uint8_t flags = in_.u8();
            if (flags & 1) p.thickness = in_.any_float();
            if (flags & 2) p.friction = in_.any_float();
            if (flags & 4) p.collider_mask = in_.u32();
            if (flags & 8) p.struct_size = in_.u8();
            guarded(watch, "cloth_set_collision",
                    [&] { return cloth_set_collision(cloth, (flags & 16) ? nullptr : &p); });
            break;
        }
        case 4: {
            cloth_carrier_desc d = cloth_default_carrier_desc();
            const uint8_t flags = in_.u8();
            if (flags & 1) d.linear_inertia = in_.any_float();
            if (flags & 2) d.angular_inertia = in_.any_float();
            if (flags & 4) d.centrifugal_inertia = in_.any_float();
            if (flags & 8) d.max_relative_speed = in_.any_float();
            if (flags & 16) d.teleport_distance = in_.any_float();
            if (flags & 32) d.teleport_rotation = in_.any_float();
            if (flags & 64) {
                const int32_t mode = static_cast<int32_t>(in_.u32() % 4 == 0 ? in_.u32() : in_.u8() % 3);
                std::memcpy(&d.teleport_mode, &mode, sizeof mode);  // any int a C host could pass
            }
            if (flags & 128) d.struct_size = in_.u8();
            const cloth_body_id body = pick_body();
            guarded(watch, "cloth_set_carrier",
                    [&] { return cloth_set_carrier(cloth, body, (what & 0x80) ? nullptr : &d); });
            break;
        }
        default: {
            unsigned char teleported = 0xA5;
            watch.outputs = {{&teleported, 1, "the teleported flag"}};
            guarded(watch, "cloth_get_teleported", [&] {
                return (what & 0x80) ? cloth_get_teleported(cloth, nullptr)
                                     : cloth_get_teleported(cloth, cloth_test::FlagOut{&teleported});
            });
        }
    }
}

// Zone callbacks may run on several workers at once: they only check their
// arguments.
void zone_check(const char* name, uint32_t worker, void*) {
    if (!name || !*name) broken("a profiler zone without a name");
    if (worker >= CLOTH_MAX_WORKERS) broken("a profiler zone with a worker index out of range");
}

void Harness::profiling() {
    const cloth_world_id world = pick_world();
    const uint8_t what = in_.u8();
    cloth_test::Watch watch = watch_of(world.index1, world.generation);
    switch (what % 6) {
        case 0: {
            // Small capacities, or ones the library must refuse (> 2^24).
            const uint8_t b = in_.u8();
            static const uint32_t kBig[] = {(1u << 24) + 1, 0xFFFFFFFFu, 4096, 0x80000000u};
            const uint32_t max_tasks = b < 224 ? b % 65 : kBig[b % 4];
            guarded(watch, "cloth_world_set_profiling",
                    [&] { return cloth_world_set_profiling(world, max_tasks); });
            // Worker polling time: none, short, the default, or over the 1 s limit.
            static const uint32_t kSpins[] = {0, 7, 500, 1000001u};
            guarded(watch, "cloth_world_set_worker_spin",
                    [&] { return cloth_world_set_worker_spin(world, kSpins[b % 4]); });
            break;
        }
        case 1: {
            cloth_frame_profile p{};
            p.struct_size = in_.u8() < 224 ? sizeof p : in_.u8();
            watch.outputs = {{&p, sizeof p, "the frame profile"}};
            guarded(watch, "cloth_world_get_frame_profile",
                    [&] { return cloth_world_get_frame_profile(world, (what & 0x80) ? nullptr : &p); });
            break;
        }
        case 2: {
            const uint32_t capacity = in_.u8() % 80;  // the buffer is exactly this long
            std::vector<cloth_task_record> records(std::max(capacity, 1u));
            uint32_t count = 0;
            watch.outputs = {{records.data(), records.size() * sizeof(cloth_task_record), "the task records"},
                             {&count, sizeof count, "the count"}};
            const cloth_result r = guarded(watch, "cloth_world_read_task_records", [&] {
                return cloth_world_read_task_records(world, records.data(), capacity,
                                                     (what & 0x80) ? nullptr : &count);
            });
            if (r == CLOTH_OK && count > capacity)
                broken("cloth_world_read_task_records reported more than capacity");
            break;
        }
        case 3: {
            // Size query, then a buffer of exactly the capacity claimed (maybe short).
            size_t size = 0;
            watch.outputs = {{&size, sizeof size, "the size"}};
            if (guarded(watch, "cloth_world_write_trace_json",
                        [&] { return cloth_world_write_trace_json(world, nullptr, 0, &size); }) != CLOTH_OK)
                break;
            const size_t capacity = in_.u8() < 192 ? size : size / 2;
            std::vector<char> text(std::max<size_t>(capacity, 1), '\x7f');
            watch.outputs.push_back({text.data(), text.size(), "the text"});
            const cloth_result r = guarded(watch, "cloth_world_write_trace_json", [&] {
                return cloth_world_write_trace_json(world, text.data(), capacity, &size);
            });
            if (r == CLOTH_OK && (capacity == 0 || std::memchr(text.data(), '\0', capacity) == nullptr))
                broken("cloth_world_write_trace_json wrote no terminating NUL");
            break;
        }
        case 4: {
            // A frame budget (tiny ones make every step over budget) and a cloth's quality policy.
            const uint8_t b = in_.u8();
            const float ms = b < 128 ? static_cast<float>(b) / 64.0f : b < 160 ? 1e-6f : in_.any_float();
            guarded(watch, "cloth_world_set_frame_budget",
                    [&] { return cloth_world_set_frame_budget(world, ms); });
            cloth_quality_policy policy = cloth_default_quality_policy();
            policy.enabled = (what & 0x40) != 0;
            if (what & 0x20) {
                policy.min_iterations = in_.count(4, 257);
                policy.max_iterations = in_.count(16, 257);
                policy.min_substeps = in_.count(4, 65);
                policy.max_substeps = in_.count(4, 65);
            }
            if (what & 0x10) policy.struct_size = in_.u8();
            const cloth_id cloth = pick_cloth();
            guarded(watch_of(cloth), "cloth_set_quality_policy",
                    [&] { return cloth_set_quality_policy(cloth, (what & 0x80) ? nullptr : &policy); });
            break;
        }
        default: {
            const bool on = what & 0x40;
            guarded(watch, "cloth_world_set_zone_callbacks", [&] {
                return cloth_world_set_zone_callbacks(world, on ? zone_check : nullptr,
                                                      (on || (what & 0x20)) ? zone_check : nullptr, nullptr);
            });
            if (!cloth_stage_name(static_cast<cloth_stage>(in_.u32())))
                broken("cloth_stage_name returned NULL");
        }
    }
}

// Character cloth: a skin (joints past the count, weights off 1, another
// particle count, five influences), joint matrices (too few, a bad
// layout, any float), host-skinned positions and normals, max distances
// and backstops (any float, a radius of 0), the skinned positions read
// back, and many bodies' poses in one call. Buffers are exactly as long as
// the count claims, so a count the library must refuse is never read past.
void Harness::character() {
    const cloth_id id = pick_cloth();
    const uint8_t what = in_.u8();
    const uint32_t particles = particles_of(id);
    const uint32_t n = std::max(particles, 1u);
    cloth_test::Watch watch = watch_of(id);
    switch (what % 7) {
        case 0: {
            const uint32_t joints = 1 + in_.u8() % 4;
            const uint32_t influences = (what & 0x40) ? 5 : 1 + in_.u8() % 4;
            const uint32_t count = (what & 0x20) ? n + 1 : n;
            std::vector<uint32_t> joint(size_t{count} * influences);
            std::vector<float> weight(joint.size(), 1.0f / static_cast<float>(influences));
            for (uint32_t& j : joint) j = in_.u8() % (joints + 1);  // joints itself is out of range
            if (what & 0x10) weight[in_.u8() % weight.size()] = in_.any_float();
            cloth_skin_desc d = cloth_default_skin_desc();
            d.particle_count = count;
            d.joint_count = joints;
            d.influences = influences;
            d.joints = joint.data();
            d.weights = (what & 0x08) ? nullptr : weight.data();
            if (what & 0x04) d.struct_size = in_.u8();
            guarded(watch, "cloth_set_skin",
                    [&] { return cloth_set_skin(id, (what & 0x80) ? nullptr : &d); });
            break;
        }
        case 1: {
            const uint32_t count = in_.u8() % 6;
            std::vector<float> m(16 * size_t{std::max(count, 1u)}, 0.0f);
            for (size_t k = 0; k < m.size(); k += 16) m[k] = m[k + 5] = m[k + 10] = m[k + 15] = 1.0f;
            if (what & 0x10) m[in_.u8() % m.size()] = in_.any_float();
            const auto layout = static_cast<cloth_matrix_layout>(in_.u8() % 3);
            guarded(watch, "cloth_set_joint_matrices", [&] {
                return cloth_set_joint_matrices(id, (what & 0x80) ? nullptr : m.data(), count, layout);
            });
            break;
        }
        case 2: {
            const uint32_t count = (what & 0x20) ? n - 1 : n;
            std::vector<float> x(3 * size_t{n}), normal(3 * size_t{n}, 0.0f);
            for (size_t k = 0; k < x.size(); ++k) x[k] = 0.01f * static_cast<float>(k % 97);
            for (size_t k = 2; k < normal.size(); k += 3) normal[k] = 1.0f;
            if (what & 0x10) x[in_.u8() % x.size()] = in_.any_float();
            if (what & 0x08) normal[in_.u8() % normal.size()] = in_.any_float();
            guarded(watch, "cloth_set_skinned_positions", [&] {
                return cloth_set_skinned_positions(id, (what & 0x80) ? nullptr : x.data(), normal.data(),
                                                   count);
            });
            break;
        }
        case 3:
        case 4: {
            const uint32_t count = (what & 0x20) ? n - 1 : n;
            std::vector<float> distance(n), radius(n);
            for (uint32_t k = 0; k < n; ++k) {
                distance[k] = 0.01f * static_cast<float>(k % 5);
                radius[k] = distance[k] > 0.0f ? 0.5f * distance[k] : 0.0f;
            }
            if (what & 0x10) distance[in_.u8() % n] = in_.any_float();
            if (what & 0x08) radius[in_.u8() % n] = in_.any_float();
            if (what % 7 == 3) {
                guarded(watch, "cloth_set_max_distances", [&] {
                    return cloth_set_max_distances(id, (what & 0x80) ? nullptr : distance.data(), count);
                });
            } else {
                guarded(watch, "cloth_set_backstops", [&] {
                    return cloth_set_backstops(id, distance.data(), (what & 0x80) ? nullptr : radius.data(),
                                               count);
                });
            }
            break;
        }
        case 5: {
            std::vector<float> x(3 * size_t{n} + 1, 7.0f), normal(3 * size_t{n} + 1, 7.0f);
            const uint32_t capacity = (what & 0x20) ? 3 * n - 1 : 3 * n;
            watch.outputs = {{x.data(), x.size() * sizeof(float), "the skinned positions"},
                             {normal.data(), normal.size() * sizeof(float), "the skinned normals"}};
            guarded(watch, "cloth_read_skinned_positions", [&] {
                return cloth_read_skinned_positions(id, x.data(), (what & 0x10) ? nullptr : normal.data(),
                                                    capacity);
            });
            break;
        }
        default: {
            const uint32_t count = in_.u8() % (kBodySlots + 1);
            cloth_body_id bodies[kBodySlots] = {};
            float position[3 * kBodySlots], q[4 * kBodySlots];
            for (uint32_t k = 0; k < kBodySlots; ++k) {
                bodies[k] = pick_body();
                in_.floats(position + 3 * k, 3);
                rotation(q + 4 * k);
            }
            const cloth_world_id world = pick_world();
            guarded(watch_of(world.index1, world.generation), "cloth_world_set_body_poses", [&] {
                return cloth_world_set_body_poses(world, (what & 0x80) ? nullptr : bodies, position, q,
                                                  count);
            });
        }
    }
}

// ---------------------------------------------------------------- snapshots

// A snapshot saved, then restored as it is, with bytes changed, cut short,
// lengthened, or into another cloth. A restore is either refused with
// nothing changed, or takes the snapshot exactly: the cloth then saves the
// very bytes it was given. A changed snapshot is never taken.
void Harness::snapshot() {
    const cloth_id id = pick_cloth();
    const uint8_t what = in_.u8();
    size_t size = 0;
    if (check(cloth_get_snapshot_size(id, &size), "cloth_get_snapshot_size") != CLOTH_OK) return;
    std::vector<unsigned char> saved(size);
    const size_t capacity = (what & 1) ? size - 1 : size;
    if (guarded(watch_of(id), "cloth_save_snapshot",
                [&] { return cloth_save_snapshot(id, saved.data(), capacity); }) != CLOTH_OK)
        return;
    std::vector<unsigned char> input = saved;
    switch (in_.u8() % 5) {
        case 0:  // intact
            break;
        case 1: {  // a few bytes changed
            const uint32_t changes = 1 + in_.u8() % 4;
            for (uint32_t k = 0; k < changes; ++k)
                input[in_.u16() % size] ^= static_cast<unsigned char>(in_.u8() | 1);
            break;
        }
        case 2:  // cut short
            input.resize(in_.u16() % size);
            break;
        case 3:  // lengthened
            input.push_back(in_.u8());
            break;
        default: {  // a float written over one of its values (the same value leaves it intact)
            const float value = in_.any_float();
            const size_t at = (in_.u16() % (size / sizeof(float))) * sizeof(float);
            std::memcpy(input.data() + at, &value, sizeof value);
        }
    }
    const cloth_id target = (what & 2) ? pick_cloth() : id;
    if (input.empty()) input.reserve(1);  // data() of an empty vector may be NULL
    const cloth_result r = guarded(watch_of(target), "cloth_restore_snapshot", [&] {
        return cloth_restore_snapshot(target, input.empty() ? saved.data() : input.data(), input.size());
    });
    if (r != CLOTH_OK) {
        if (r == CLOTH_ERROR_CORRUPT_SNAPSHOT && input == saved)
            broken("cloth_restore_snapshot refused an intact snapshot as corrupt");
        return;
    }
    if (input != saved) broken("cloth_restore_snapshot took a snapshot with changed bytes");
    std::vector<unsigned char> again(input.size());
    if (check(cloth_save_snapshot(target, again.data(), again.size()), "cloth_save_snapshot") != CLOTH_OK ||
        again != input)
        broken("a restored cloth does not save the snapshot it was given");
}

RunStats Harness::run() {
    for (size_t calls = 0; calls < kMaxCalls && !in_.empty(); ++calls) {
        // -Werror=switch (CMakeLists.txt): every opcode must have its case.
        switch (static_cast<Op>(in_.u8() % kOpCount)) {
            case kWorldCreate:
                world_create();
                break;
            case kWorldDestroy:
                world_destroy();
                break;
            case kWorldSetGravity:
                world_set_gravity();
                break;
            case kFabricGrid:
                fabric_grid();
                break;
            case kFabricMesh:
                fabric_mesh();
                break;
            case kFabricObj:
                fabric_obj();
                break;
            case kFabricDestroy:
                fabric_destroy();
                break;
            case kFabricQuery:
                fabric_query();
                break;
            case kClothCreate:
                cloth_create_call();
                break;
            case kClothDestroy:
                cloth_destroy_call();
                break;
            case kStep:
                step();
                break;
            case kParticleEdit:
                particle_edit();
                break;
            case kIsPinned:
                is_pinned();
                break;
            case kSolver:
                solver();
                break;
            case kMaterial:
                material();
                break;
            case kRead:
                read();
                break;
            case kStats:
                stats();
                break;
            case kAllocatorSchedule:
                allocator_schedule();
                break;
            case kNullArguments:
                null_arguments();
                break;
            case kSelfCollision:
                self_collision();
                break;
            case kProfiling:
                profiling();
                break;
            case kBody:
                body();
                break;
            case kCollider:
                collider();
                break;
            case kAttachment:
                attachment();
                break;
            case kWorldShiftOrigin:
                world_shift_origin();
                break;
            case kSnapshot:
                snapshot();
                break;
            case kCharacter:
                character();
                break;
            case kClothContact:
                cloth_contact();
                break;
            case kLevelOfDetail:
                level_of_detail();
                break;
            case kOpCount:
                break;
        }
    }
    return stats_;
}

}  // namespace

RunStats run_api_sequence(const uint8_t* data, size_t size) {
    Harness harness(data, size);
    return harness.run();  // the destructor destroys the worlds and checks for leaks
}

}  // namespace cloth_fuzz
