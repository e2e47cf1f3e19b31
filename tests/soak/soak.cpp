// A long run with churn allocates nothing in steady frames and its memory does not grow.
//
// A windy flag on a swaying pole (a body the flag is attached to)
// stepped for many frames (100,000 by default) through the C API, with
// churn every few hundred frames (half the flag detached and attached
// again, a sphere collider on the pole and a static box below created and
// destroyed, a second cloth and a mesh fabric created and destroyed, solver
// settings changed between 1 and 2 substeps, self-collision turned on and
// off), measuring what a game cares about over a long session:
//
//   - allocations per frame, through the world's allocator callback and
//     through the C++ heap (this program replaces the global operator new),
//     counted separately for churn frames and steady frames; a steady frame
//     after warm-up must allocate nothing;
//   - the allocator's live and peak bytes: the peak over the whole run must
//     equal the peak at the end of the first churn cycle (every kind of
//     churn done once, and at least 1,000 frames): no growth from churn;
//   - peak RSS (VmHWM) at frame 1,000, after the first cycle and at the end.
//
// Exit status 0 only if all checks hold (the short variant is a ctest test).
// The CG reference solver allocates from the C++ heap in every step (Eigen
// vectors; documented in cloth.h): churn never selects it, so the
// zero-allocation figure is about the JACOBI and EXPLICIT solvers.
//
//   cloth_soak [--frames N] [--churn-every K] [--inject-faults]
//
// --inject-faults plays a careless host, to show that the checks can fail:
// it creates and destroys a fabric in every 50th steady frame, and never
// releases the churn's mesh fabric handles (memory grows each cycle).
#include <cloth/cloth.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <new>
#include <string>
#include <vector>

#include "support/counting_allocator.h"

// ---------------------------------------------------------------- C++ heap counter

namespace {
unsigned long long g_cxx_allocations = 0;  // single-threaded program: a plain counter
}

void* operator new(std::size_t size) {
    ++g_cxx_allocations;
    if (void* p = std::malloc(size ? size : 1)) return p;
    throw std::bad_alloc();
}
void* operator new[](std::size_t size) { return operator new(size); }
void* operator new(std::size_t size, std::align_val_t align) {
    ++g_cxx_allocations;
    const std::size_t a = static_cast<std::size_t>(align);
    if (void* p = std::aligned_alloc(a, (size + a - 1) / a * a)) return p;
    throw std::bad_alloc();
}
void* operator new[](std::size_t size, std::align_val_t align) { return operator new(size, align); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }

namespace {

// Peak resident set size in kB (VmHWM), 0 if unknown.
long peak_rss_kb() {
    FILE* f = std::fopen("/proc/self/status", "r");
    if (!f) return 0;
    char line[256];
    long kb = 0;
    while (std::fgets(line, sizeof line, f)) {
        if (std::strncmp(line, "VmHWM:", 6) == 0) kb = std::strtol(line + 6, nullptr, 10);
    }
    std::fclose(f);
    return kb;
}

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
constexpr bool kSanitized = true;  // sanitizer runtimes keep freed memory (quarantine): RSS is theirs
#else
constexpr bool kSanitized = false;
#endif

[[noreturn]] void fail(const char* what, cloth_result r) {
    std::fprintf(stderr, "soak: %s failed: %s %s\n", what, cloth_result_name(r), cloth_get_last_error());
    std::exit(2);
}

void must(cloth_result r, const char* what) {
    if (r != CLOTH_OK) fail(what, r);
}

constexpr uint32_t kSide = 32;
constexpr float kFrame = 1.0f / 60.0f;
constexpr uint32_t kWarmFrames = 100;
constexpr uint32_t kCheckpoint = 1000;
constexpr uint32_t kChurnKinds = 12;

// A 3 x 3 vertex patch of two-triangle cells, as a mesh fabric.
cloth_fabric_id create_patch(cloth_world_id world) {
    float positions[9 * 3];
    for (uint32_t i = 0; i < 9; ++i) {
        positions[3 * i] = 0.2f * static_cast<float>(i % 3);
        positions[3 * i + 1] = 1.0f - 0.2f * static_cast<float>(i / 3);
        positions[3 * i + 2] = 0.5f;
    }
    uint32_t indices[8 * 3];
    uint32_t t = 0;
    for (uint32_t r = 0; r < 2; ++r) {
        for (uint32_t c = 0; c < 2; ++c) {
            const uint32_t a = r * 3 + c;
            const uint32_t tri[6] = {a, a + 1, a + 3, a + 1, a + 4, a + 3};
            std::memcpy(indices + 3 * t, tri, sizeof tri);
            t += 2;
        }
    }
    cloth_mesh_desc desc = cloth_default_mesh_desc();
    desc.positions = positions;
    desc.vertex_count = 9;
    desc.indices = indices;
    desc.triangle_count = 8;
    cloth_fabric_id fabric{};
    must(cloth_fabric_create_mesh(world, &desc, &fabric), "cloth_fabric_create_mesh");
    return fabric;
}

}  // namespace

int main(int argc, char** argv) {
    uint32_t frames = 100000;
    uint32_t churn_every = 250;
    bool inject_faults = false;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--inject-faults")
            inject_faults = true;
        else if (arg == "--frames" && i + 1 < argc)
            frames = static_cast<uint32_t>(std::strtoul(argv[++i], nullptr, 10));
        else if (arg == "--churn-every" && i + 1 < argc)
            churn_every = static_cast<uint32_t>(std::strtoul(argv[++i], nullptr, 10));
    }
    if (churn_every == 0 || frames <= std::max(kCheckpoint, kChurnKinds * churn_every + 1)) {
        std::fprintf(stderr,
                     "usage: cloth_soak [--frames N] [--churn-every K]: N > max(%u, %u K + 1), K > 0\n",
                     kCheckpoint, kChurnKinds);
        return 2;
    }

    // The C API tests' counting allocator (tests/capi/support): its block
    // table lives on malloc, so the C++ heap count above is the library's.
    cloth_test::CountingAllocator host;
    cloth_world_desc wd = cloth_default_world_desc();
    host.use_for_memory(wd);
    wd.max_cloths = 8;
    wd.max_fabrics = 64;
    cloth_world_id world{};
    must(cloth_world_create(&wd, &world), "cloth_world_create");

    cloth_grid_desc gd = cloth_default_grid_desc();
    gd.columns = kSide;
    gd.rows = kSide;
    gd.origin[1] = 1.5f;
    cloth_fabric_id flag_fabric{};
    must(cloth_fabric_create_grid(world, &gd, &flag_fabric), "cloth_fabric_create_grid");
    cloth_desc cd = cloth_default_desc();
    cd.fabric = flag_fabric;
    cd.area_density = 1.0f;  // 1 kg over 1 m^2
    cloth_id flag{};
    must(cloth_create(world, &cd, &flag), "cloth_create");
    // The pole is a body that sways; the flag's first column is attached to
    // it at the particles' rest positions (the body starts at the origin).
    cloth_body_id pole_body{};
    const cloth_body_desc bd = cloth_default_body_desc();
    must(cloth_body_create(world, &bd, &pole_body), "cloth_body_create");
    std::vector<uint32_t> pole;
    for (uint32_t row = 0; row < kSide; ++row) pole.push_back(row * kSide);
    std::vector<float> pole_offsets(3 * kSide);
    {
        std::vector<float> rest(3 * kSide * kSide);
        must(cloth_read_positions(flag, rest.data(), static_cast<uint32_t>(rest.size())),
             "cloth_read_positions");
        for (uint32_t k = 0; k < kSide; ++k)
            std::memcpy(&pole_offsets[3 * k], &rest[3 * size_t{pole[k]}], 3 * sizeof(float));
    }
    must(cloth_attach(flag, pole_body, pole.data(), pole_offsets.data(), kSide), "cloth_attach");
    const uint32_t half = kSide / 2;  // the lower half of the pole: rows 16..31
    cloth_collider_id sphere{}, ground{};

    std::vector<float> positions(3 * kSide * kSide);
    cloth_id extra{};  // churn: a second cloth on a mesh fabric, alive every other cycle
    cloth_fabric_id extra_fabric{};

    unsigned long long churn_cxx_allocations = 0;  // of churn_allocations, from the C++ heap
    unsigned long long steady_frames = 0, steady_allocations = 0, churn_frames = 0, churn_allocations = 0;
    unsigned long long nonfinite_steps = 0;
    uint32_t first_nonfinite_frame = 0;
    // Every kind of churn has happened once by the end of the first cycle
    // (or by frame 1,000 if that is later): from then on nothing may grow.
    const uint32_t first_cycle_end = std::max(kCheckpoint, kChurnKinds * churn_every + 1);
    size_t peak_bytes_after_cycle = 0;
    long rss_checkpoint_kb = 0, rss_cycle_kb = 0;
    uint32_t churns = 0;

    for (uint32_t frame = 0; frame < frames; ++frame) {
        const unsigned long long before = host.allocations() + g_cxx_allocations;
        const unsigned long long cxx_before = g_cxx_allocations;
        const bool churn = frame > 0 && frame % churn_every == 0;
        if (churn) {
            switch (churns++ % kChurnKinds) {
                case 0:  // detach the lower half of the pole, the flag sags
                    must(cloth_detach(flag, pole.data() + half, kSide - half), "cloth_detach");
                    break;
                case 1:  // a second cloth on a new mesh fabric (whose handle is released at once)
                    extra_fabric = create_patch(world);
                    cd.fabric = extra_fabric;
                    must(cloth_create(world, &cd, &extra), "cloth_create extra");
                    if (!inject_faults) must(cloth_fabric_destroy(extra_fabric), "cloth_fabric_destroy");
                    break;
                case 2: {  // two substeps (two sweeps at this stiffness can diverge: README)
                    cloth_solver_settings s = cloth_default_solver_settings();
                    s.substeps = 2;
                    must(cloth_set_solver(flag, &s), "cloth_set_solver");
                    break;
                }
                case 3: {  // self-collision on (it allocates its buffers now)
                    cloth_self_collision_desc sc = cloth_default_self_collision_desc();
                    sc.enabled = true;
                    must(cloth_set_self_collision(flag, &sc), "cloth_set_self_collision on");
                    break;
                }
                case 4: {  // a sphere on the pole, in the flag's way
                    cloth_collider_desc d = cloth_default_collider_desc();
                    d.body = pole_body;
                    d.local_position[0] = 0.3f;
                    d.local_position[1] = 1.0f;
                    must(cloth_collider_create_sphere(world, &d, 0.15f, &sphere),
                         "cloth_collider_create_sphere");
                    break;
                }
                case 5: {  // a static box under the flag, which the sagging half meets
                    cloth_collider_desc d = cloth_default_collider_desc();
                    d.local_position[0] = 0.5f;
                    d.local_position[1] = 0.2f;
                    const float half_extents[3] = {1.0f, 0.2f, 1.0f};
                    must(cloth_collider_create_box(world, &d, half_extents, &ground),
                         "cloth_collider_create_box");
                    break;
                }
                case 6:  // attach the lower half again at its pole offsets
                    must(cloth_attach(flag, pole_body, pole.data() + half, pole_offsets.data() + 3 * half,
                                      kSide - half),
                         "cloth_attach");
                    break;
                case 7:
                    must(cloth_collider_destroy(sphere), "cloth_collider_destroy sphere");
                    break;
                case 8:  // the second cloth goes (its fabric's memory with it)
                    must(cloth_destroy(extra), "cloth_destroy extra");
                    break;
                case 9: {  // back to one substep
                    const cloth_solver_settings s = cloth_default_solver_settings();
                    must(cloth_set_solver(flag, &s), "cloth_set_solver");
                    break;
                }
                case 10:
                    must(cloth_collider_destroy(ground), "cloth_collider_destroy ground");
                    break;
                default: {  // self-collision off (its buffers are freed)
                    const cloth_self_collision_desc sc = cloth_default_self_collision_desc();
                    must(cloth_set_self_collision(flag, &sc), "cloth_set_self_collision off");
                }
            }
        }
        if (inject_faults && !churn && frame % 50 == 0) cloth_fabric_destroy(create_patch(world));
        // Gusts: wind along the flag, varying smoothly, with a cross breeze.
        const float t = static_cast<float>(frame) * kFrame;
        const float wind[3] = {8.0f + 4.0f * std::sin(0.7f * t), 0.0f, 1.0f + std::sin(1.3f * t)};
        must(cloth_set_wind(flag, wind), "cloth_set_wind");
        // The pole sways 0.3 m sideways and turns up to 0.3 rad about its axis.
        const float angle = 0.3f * std::sin(0.9f * t);
        const float position[3] = {0.0f, 0.0f, 0.3f * std::sin(0.5f * t)};
        const float rotation[4] = {0.0f, std::sin(0.5f * angle), 0.0f, std::cos(0.5f * angle)};
        must(cloth_body_set_pose(pole_body, position, rotation), "cloth_body_set_pose");
        const cloth_result r = cloth_step(world, kFrame);
        if (r == CLOTH_ERROR_NONFINITE_STATE) {
            if (nonfinite_steps++ == 0) {
                first_nonfinite_frame = frame;
                std::printf("  first non-finite step: %s\n", cloth_get_last_error());
            }
        } else if (r != CLOTH_OK) {
            fail("cloth_step", r);
        }
        must(cloth_read_positions(flag, positions.data(), static_cast<uint32_t>(positions.size())),
             "cloth_read_positions");

        const unsigned long long allocated = host.allocations() + g_cxx_allocations - before;
        if (churn) {
            ++churn_frames;
            churn_allocations += allocated;
            churn_cxx_allocations += g_cxx_allocations - cxx_before;
        } else if (frame >= kWarmFrames) {
            ++steady_frames;
            steady_allocations += allocated;
        }
        if (frame + 1 == kCheckpoint) rss_checkpoint_kb = peak_rss_kb();
        if (frame + 1 == first_cycle_end) {
            peak_bytes_after_cycle = host.peak_bytes();
            rss_cycle_kb = peak_rss_kb();
        }
    }
    if (extra.index1) cloth_destroy(extra);  // may already be gone (INVALID_HANDLE then)
    const long rss_end_kb = peak_rss_kb();
    const size_t live_before_destroy = host.live_bytes();
    must(cloth_world_destroy(world), "cloth_world_destroy");

    std::printf("soak: %u frames of a %ux%u windy flag, churn every %u frames (%u churn events)\n", frames,
                kSide, kSide, churn_every, churns);
    std::printf(
        "  steady frames (after %u warm-up): %llu, allocations in them: %llu (host allocator + C++ heap)\n",
        kWarmFrames, steady_frames, steady_allocations);
    std::printf(
        "  churn frames: %llu, allocations in them: %llu (%.1f per churn frame; %llu of them from the C++ "
        "heap, not the host allocator)\n",
        churn_frames, churn_allocations,
        churn_frames ? double(churn_allocations) / double(churn_frames) : 0.0, churn_cxx_allocations);
    std::printf(
        "  host allocator: peak %zu bytes by frame %u (every churn kind done), %zu bytes over the whole "
        "run; %zu live at the end, %zu after cloth_world_destroy; %llu allocations, %llu frees\n",
        peak_bytes_after_cycle, first_cycle_end, host.peak_bytes(), live_before_destroy, host.live_bytes(),
        static_cast<unsigned long long>(host.allocations()), static_cast<unsigned long long>(host.frees()));
    std::printf("  peak RSS (VmHWM): %ld kB at frame %u, %ld kB at frame %u, %ld kB at frame %u%s\n",
                rss_checkpoint_kb, kCheckpoint, rss_cycle_kb, first_cycle_end, rss_end_kb, frames,
                kSanitized ? " (sanitizer build: not checked)" : "");
    std::printf("  steps restored after going non-finite: %llu (first at frame %u)\n", nonfinite_steps,
                first_nonfinite_frame);

    bool ok = true;
    auto check = [&ok](bool holds, const char* what) {
        if (!holds) {
            std::printf("  FAIL: %s\n", what);
            ok = false;
        }
    };
    check(steady_allocations == 0, "a steady frame allocated");
    check(host.peak_bytes() == peak_bytes_after_cycle,
          "the allocator's peak grew after the first churn cycle");
    check(host.live_bytes() == 0 && host.allocations() == host.frees(),
          "memory left after cloth_world_destroy");
    for (const std::string& v : host.violations()) std::printf("  allocator misuse: %s\n", v.c_str());
    check(host.violations().empty(), "the library misused the allocator");
    check(nonfinite_steps == 0, "the flag went non-finite");
    // Fragmentation may add a little; a leak of one cloth per churn would add megabytes.
    check(kSanitized || rss_end_kb - rss_cycle_kb < 2048,
          "peak RSS grew by 2 MB or more after the first churn cycle");
    std::printf("soak: %s\n", ok ? "ok" : "FAILED");
    return ok ? 0 : 1;
}
