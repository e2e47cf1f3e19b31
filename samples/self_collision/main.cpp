// self_collision: the paper's Fig. 5 scenes, headless, through the public
// C API. Each scene runs twice, with self-collision on and off, and prints
// step times, contacts, regions and how many far-apart parts of the cloth
// ended up inside each other; then writes a PNG of the run with it on.
//
//   wind  a cloth hanging from its two top corners, which are drawn
//         together while gusty wind blows into it: it folds onto itself.
//   pile  a cloth dropped flat onto a sphere standing on the ground: it
//         drapes and bunches up on the ground.
//
// The ground and the sphere are sample-local (particles inside are put on
// the surface with zero velocity between frames through cloth_set_positions)
// until the colliders of the contact issue are on main.
//
//   self_collision [--scene wind|pile] [--resolution N] [--frames F]
//                  [--thickness M] [--regions on|off] [--png PATH]
#include <cloth/cloth.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <string>
#include <vector>

#include "render_png.h"
#include "timing_table.h"

namespace {

using cloth_samples::percentile;

struct Options {
    std::string scene = "pile";
    uint32_t resolution = 40;
    int frames = 240;
    float thickness = 0;  // 0: 0.8 of the grid spacing
    bool regions = true;
    std::string png = "self_collision.png";
};

constexpr float kSize = 1.0f, kDt = 1.0f / 60.0f;
constexpr float kSphere[3] = {0.5f, 0.25f, -0.5f};
constexpr float kSphereRadius = 0.25f;

bool check(cloth_result result, const char* call) {
    if (result == CLOTH_OK) return true;
    std::fprintf(stderr, "%s failed: %s (%s)\n", call, cloth_result_name(result), cloth_get_last_error());
    return false;
}

struct RunResult {
    bool ok = false;
    double stage_ms[CLOTH_MAX_STAGES] = {};  // summed over frames (frame profile)
    double p50_ms = 0, p95_ms = 0;
    uint32_t max_contacts = 0;
    float max_strain = 0;           // over the run, after each step (cloth_stats)
    uint32_t interpenetrating = 0;  // far-apart pairs (> 3 grid steps) closer than thickness / 2
    std::vector<float> positions, normals;
    std::vector<uint32_t> indices;
};

// CPU time of this thread (the world steps on it, worker_count 0): on a
// shared machine it is steadier than wall-clock time.
double thread_cpu_ms() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return 1e3 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
}

// Puts particles below the ground or inside the sphere back on the surface
// (zero velocity), as a stand-in for colliders.
void apply_obstacles(cloth_id cloth, std::vector<float>& x, bool sphere) {
    std::vector<uint32_t> moved;
    std::vector<float> targets;
    for (uint32_t i = 0; i < x.size() / 3; ++i) {
        float p[3] = {x[3 * i], x[3 * i + 1], x[3 * i + 2]};
        bool inside = false;
        if (sphere) {
            const float d[3] = {p[0] - kSphere[0], p[1] - kSphere[1], p[2] - kSphere[2]};
            const float length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            if (length < kSphereRadius && length > 0) {
                for (int k = 0; k < 3; ++k) p[k] = kSphere[k] + d[k] * (kSphereRadius / length);
                inside = true;
            }
        }
        if (p[1] < 0) {
            p[1] = 0;
            inside = true;
        }
        if (!inside) continue;
        moved.push_back(i);
        targets.insert(targets.end(), p, p + 3);
    }
    if (!moved.empty())
        cloth_set_positions(cloth, moved.data(), targets.data(), static_cast<uint32_t>(moved.size()));
}

uint32_t count_interpenetrating(const std::vector<float>& x, uint32_t n, float distance) {
    uint32_t count = 0;
    for (uint32_t i = 0; i < n * n; ++i) {
        for (uint32_t j = i + 1; j < n * n; ++j) {
            const int dc = std::abs(static_cast<int>(i % n) - static_cast<int>(j % n));
            const int dr = std::abs(static_cast<int>(i / n) - static_cast<int>(j / n));
            if (std::max(dc, dr) <= 3) continue;
            const float dx = x[3 * i] - x[3 * j], dy = x[3 * i + 1] - x[3 * j + 1],
                        dz = x[3 * i + 2] - x[3 * j + 2];
            if (dx * dx + dy * dy + dz * dz < distance * distance) ++count;
        }
    }
    return count;
}

RunResult run(const Options& o, bool self_collision, bool print) {
    RunResult out;
    const uint32_t n = o.resolution;
    const bool wind = o.scene == "wind";
    cloth_world_desc wd = cloth_default_world_desc();
    cloth_world_id world;
    if (!check(cloth_world_create(&wd, &world), "cloth_world_create")) return out;
    if (!check(cloth_world_set_profiling(world, 4096), "cloth_world_set_profiling")) return out;
    cloth_grid_desc grid = cloth_default_grid_desc();
    grid.columns = grid.rows = n;
    if (wind) {  // hanging, top edge at 1.6 m
        grid.origin[1] = 1.6f;
    } else {  // flat, 0.8 m up, centred over the sphere
        grid.origin[1] = 0.8f;
        grid.v[1] = 0;
        grid.v[2] = -kSize;
    }
    cloth_fabric_id fabric;
    if (!check(cloth_fabric_create_grid(world, &grid, &fabric), "cloth_fabric_create_grid")) return out;
    cloth_desc desc = cloth_default_desc();
    desc.fabric = fabric;
    desc.structural = {300.0f, 0.1f};
    desc.shear = {60.0f, 0.05f};
    desc.bend = {2.0f, 0.01f};
    desc.solver.substeps = 4;
    cloth_id cloth;
    if (!check(cloth_create(world, &desc, &cloth), "cloth_create")) return out;
    const float spacing = kSize / static_cast<float>(n - 1);
    const float thickness = o.thickness > 0 ? o.thickness : 0.8f * spacing;
    cloth_self_collision_desc sd = cloth_default_self_collision_desc();
    sd.enabled = self_collision;
    sd.thickness = thickness;
    sd.friction = 0.3f;
    sd.use_regions = o.regions;
    if (!check(cloth_set_self_collision(cloth, &sd), "cloth_set_self_collision")) return out;
    const uint32_t corners[2] = {0, n - 1};
    if (wind && !check(cloth_pin(cloth, corners, 2), "cloth_pin")) return out;

    if (print) {
        std::printf("%s, %ux%u, thickness %.4f m, regions %s, self-collision %s\n", o.scene.c_str(), n, n,
                    thickness, o.regions ? "on" : "off", self_collision ? "on" : "off");
        std::printf("%6s %9s %9s %9s %7s\n", "frame", "cpu_ms", "contacts", "regions", "passes");
    }
    std::vector<double> step_ms;
    std::vector<float> x(3 * n * n);
    for (int frame = 0; frame < o.frames; ++frame) {
        const float t = static_cast<float>(frame) * kDt;
        if (wind) {
            // The corners close to a third of the width over two seconds; gusts into the cloth.
            const float closing = std::min(1.0f, t / 2.0f) * 0.33f * kSize;
            const float targets[6] = {closing, 1.6f, 0.0f, kSize - closing, 1.6f, 0.0f};
            cloth_set_pin_targets(cloth, corners, targets, 2);
            const float gust = 6.0f + 3.0f * std::sin(1.3f * t) + 2.0f * std::sin(3.1f * t);
            const float air[3] = {1.5f * std::sin(0.9f * t), 0.0f, -gust};
            cloth_set_wind(cloth, air);
        }
        const double start = thread_cpu_ms();
        const cloth_result result = cloth_step(world, kDt);
        step_ms.push_back(thread_cpu_ms() - start);
        if (result != CLOTH_OK) std::fprintf(stderr, "frame %d: %s\n", frame, cloth_get_last_error());
        cloth_frame_profile profile{};
        profile.struct_size = sizeof profile;
        cloth_world_get_frame_profile(world, &profile);
        for (int s = 0; s < CLOTH_MAX_STAGES; ++s) out.stage_ms[s] += profile.stage_ms[s];
        cloth_read_positions(cloth, x.data(), static_cast<uint32_t>(x.size()));
        if (!wind) apply_obstacles(cloth, x, true);
        cloth_self_collision_stats stats{};
        stats.struct_size = sizeof stats;
        cloth_get_self_collision_stats(cloth, &stats);
        out.max_contacts = std::max(out.max_contacts, stats.contacts);
        cloth_stats cloth_stats{};
        cloth_stats.struct_size = sizeof cloth_stats;
        cloth_get_stats(cloth, &cloth_stats);
        out.max_strain = std::max(out.max_strain, cloth_stats.max_strain);
        if (print && (frame % 30 == 0 || frame == o.frames - 1)) {
            std::printf("%6d %9.3f %9u %4u/%-4u %7u\n", frame, step_ms.back(), stats.contacts,
                        stats.valid_regions, stats.regions, stats.passes);
        }
    }
    out.p50_ms = percentile(step_ms, 0.5);
    out.p95_ms = percentile(step_ms, 0.95);
    cloth_read_positions(cloth, x.data(), static_cast<uint32_t>(x.size()));
    out.interpenetrating = count_interpenetrating(x, n, 0.5f * thickness);
    out.positions = x;
    out.normals.resize(x.size());
    cloth_read_normals(cloth, out.normals.data(), static_cast<uint32_t>(out.normals.size()));
    uint32_t triangles = 0;
    cloth_fabric_get_triangle_count(fabric, &triangles);
    out.indices.resize(3 * triangles);
    cloth_fabric_read_triangles(fabric, out.indices.data(), static_cast<uint32_t>(out.indices.size()));
    cloth_world_destroy(world);
    out.ok = true;
    return out;
}

void make_sphere(std::vector<float>& positions, std::vector<uint32_t>& indices) {
    const uint32_t rings = 24, sectors = 48;
    const float pi = 3.14159265f;
    for (uint32_t r = 0; r <= rings; ++r) {
        for (uint32_t s = 0; s <= sectors; ++s) {
            const float theta = pi * static_cast<float>(r) / rings,
                        phi = 2 * pi * static_cast<float>(s) / sectors;
            // Slightly smaller than the obstacle, so the cloth on it is not hidden.
            const float radius = 0.97f * kSphereRadius;
            positions.insert(positions.end(), {kSphere[0] + radius * std::sin(theta) * std::cos(phi),
                                               kSphere[1] + radius * std::cos(theta),
                                               kSphere[2] + radius * std::sin(theta) * std::sin(phi)});
        }
    }
    for (uint32_t r = 0; r < rings; ++r) {
        for (uint32_t s = 0; s < sectors; ++s) {
            const uint32_t a = r * (sectors + 1) + s, b = a + sectors + 1;
            indices.insert(indices.end(), {a, b, a + 1, a + 1, b, b + 1});
        }
    }
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    std::string regions = "on";
    CLI::App app{"Self-collision scenes (paper Fig. 5): timings, contacts and a PNG"};
    app.add_option("--scene", o.scene, "wind or pile")->check(CLI::IsMember({"wind", "pile"}));
    app.add_option("--resolution", o.resolution, "particles along each side")->check(CLI::Range(8, 512));
    app.add_option("--frames", o.frames, "frames at 60 Hz")->check(CLI::Range(1, 100000));
    app.add_option("--thickness", o.thickness, "theta_c in m (0: 0.8 grid spacings)");
    app.add_option("--regions", regions, "collision-free regions")->check(CLI::IsMember({"on", "off"}));
    app.add_option("--png", o.png, "picture of the run with self-collision (empty: none)");
    CLI11_PARSE(app, argc, argv);
    o.regions = regions == "on";

    const RunResult on = run(o, true, true);
    const RunResult off = run(o, false, false);
    if (!on.ok || !off.ok) return 1;
    std::printf(
        "step CPU time p50 / p95: %.3f / %.3f ms with self-collision, %.3f / %.3f ms without "
        "(shared, noisy machine: compare the two, not across runs)\n",
        on.p50_ms, on.p95_ms, off.p50_ms, off.p95_ms);
    std::printf("most contacts in a frame: %u\n", on.max_contacts);
    std::printf("max strain over the run: %.3f with, %.3f without self-collision\n", on.max_strain,
                off.max_strain);
    // Frame profile: where the time of the run with self-collision went.
    double total = 0;
    for (double ms : on.stage_ms) total += ms;
    std::printf("frame profile, share of stage time over the run with self-collision:");
    for (int s = 0; s < CLOTH_MAX_STAGES; ++s) {
        if (on.stage_ms[s] > 0)
            std::printf(" %s %.0f%%", cloth_stage_name(cloth_stage(s)), 100.0 * on.stage_ms[s] / total);
    }
    std::printf("\n");
    std::printf(
        "pairs more than 3 grid steps apart and closer than thickness / 2 at the end: %u with, %u "
        "without self-collision\n",
        on.interpenetrating, off.interpenetrating);
    if (!o.png.empty()) {
        std::vector<float> sphere_positions;
        std::vector<uint32_t> sphere_indices;
        if (o.scene == "pile") make_sphere(sphere_positions, sphere_indices);
        const uint32_t n = o.resolution * o.resolution;
        std::vector<cloth_samples::RenderMesh> meshes = {{on.positions.data(),
                                                          on.normals.data(),
                                                          n,
                                                          on.indices.data(),
                                                          static_cast<uint32_t>(on.indices.size() / 3),
                                                          {60, 110, 190}}};
        if (!sphere_indices.empty()) {
            meshes.push_back({sphere_positions.data(),
                              nullptr,
                              static_cast<uint32_t>(sphere_positions.size() / 3),
                              sphere_indices.data(),
                              static_cast<uint32_t>(sphere_indices.size() / 3),
                              {200, 190, 170}});
        }
        const cloth_samples::Camera camera =
            o.scene == "pile"
                ? cloth_samples::Camera{{1.9f, 1.4f, 0.9f}, {0.5f, 0.2f, -0.5f}, {0.0f, 1.0f, 0.0f}, 40.0f}
                : cloth_samples::Camera{{1.5f, 2.2f, 1.6f}, {0.5f, 1.65f, -0.2f}, {0.0f, 1.0f, 0.0f}, 38.0f};
        cloth_samples::RenderOptions options;
        options.draw_ground_grid = o.scene == "pile";
        std::string error;
        if (!cloth_samples::render_png(o.png, camera, meshes.data(), meshes.size(), options, &error)) {
            std::fprintf(stderr, "render_png: %s\n", error.c_str());
            return 1;
        }
        std::printf("wrote %s\n", o.png.c_str());
    }
    return 0;
}
