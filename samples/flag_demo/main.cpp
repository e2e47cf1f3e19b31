// flag_demo: a flag on a pole in gusty wind, headless. Prints per-frame step
// timings and writes a picture of the flag (PNG). It uses only the public C
// API through the shared library, as a game would.
//
//   flag_demo [--frames N] [--columns C] [--rows R] [--solver jacobi|cg|explicit]
//             [--iterations K] [--substeps S] [--stiffness K] [--png PATH]
#include <cloth/cloth.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "render_png.h"
#include "timing_table.h"

namespace {

using cloth_samples::percentile;

struct Options {
    int frames = 300;
    uint32_t columns = 48;
    uint32_t rows = 32;
    std::string solver = "jacobi";
    uint32_t iterations = 1;
    uint32_t substeps = 1;
    float stiffness = 1000.0f;
    std::string png = "flag_demo.png";
};

bool check(cloth_result result, const char* call) {
    if (result == CLOTH_OK) return true;
    std::fprintf(stderr, "%s failed: %s (%s)\n", call, cloth_result_name(result), cloth_get_last_error());
    return false;
}

// A thin box standing on the ground from y = 0 to `height` at (x, z).
void make_pole(float x, float z, float height, float half_width, std::vector<float>& positions,
               std::vector<uint32_t>& indices) {
    for (int corner = 0; corner < 8; ++corner) {
        positions.push_back(x + ((corner & 1) ? half_width : -half_width));
        positions.push_back((corner & 2) ? height : 0.0f);
        positions.push_back(z + ((corner & 4) ? half_width : -half_width));
    }
    const uint32_t faces[6][4] = {{0, 1, 3, 2}, {4, 6, 7, 5}, {0, 4, 5, 1},
                                  {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 5, 7, 3}};
    for (const auto& f : faces) indices.insert(indices.end(), {f[0], f[1], f[2], f[0], f[2], f[3]});
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    CLI::App app{"Flag in gusty wind: per-frame step timings and a PNG of the flag"};
    app.add_option("--frames", o.frames, "frames at 60 Hz")->check(CLI::Range(1, 1000000));
    app.add_option("--columns", o.columns, "particles along the flag")->check(CLI::Range(2, 4096));
    app.add_option("--rows", o.rows, "particles up the pole")->check(CLI::Range(2, 4096));
    app.add_option("--solver", o.solver, "jacobi, cg or explicit")
        ->check(CLI::IsMember({"jacobi", "cg", "explicit"}));
    app.add_option("--iterations", o.iterations, "Jacobi iterations per substep");
    app.add_option("--substeps", o.substeps, "substeps per frame");
    app.add_option("--stiffness", o.stiffness, "structural stiffness, N/m");
    app.add_option("--png", o.png, "picture of the last frame (empty: none)");
    CLI11_PARSE(app, argc, argv);

    const float flag_width = 1.5f, flag_height = 1.0f, pole_height = 3.0f, dt = 1.0f / 60.0f;

    cloth_world_desc world_desc = cloth_default_world_desc();
    cloth_world_id world;
    if (!check(cloth_world_create(&world_desc, &world), "cloth_world_create")) return 1;

    cloth_grid_desc grid = cloth_default_grid_desc();
    grid.columns = o.columns;
    grid.rows = o.rows;
    grid.origin[1] = pole_height;
    grid.u[0] = flag_width;
    grid.v[1] = -flag_height;
    cloth_fabric_id fabric;
    if (!check(cloth_fabric_create_grid(world, &grid, &fabric), "cloth_fabric_create_grid")) return 1;

    cloth_desc desc = cloth_default_desc();
    desc.fabric = fabric;
    desc.area_density = 0.25f;
    desc.structural.stiffness = o.stiffness;
    desc.shear.stiffness = 0.2f * o.stiffness;
    desc.bend.stiffness = 0.02f * o.stiffness;
    desc.solver.kind = o.solver == "cg"         ? CLOTH_SOLVER_CG
                       : o.solver == "explicit" ? CLOTH_SOLVER_EXPLICIT
                                                : CLOTH_SOLVER_JACOBI;
    desc.solver.iterations = o.iterations;
    desc.solver.substeps = o.substeps;
    cloth_id flag;
    if (!check(cloth_create(world, &desc, &flag), "cloth_create")) return 1;

    std::vector<uint32_t> pole_side;
    for (uint32_t r = 0; r < o.rows; ++r) pole_side.push_back(r * o.columns);
    if (!check(cloth_pin(flag, pole_side.data(), static_cast<uint32_t>(pole_side.size())), "cloth_pin"))
        return 1;

    uint32_t particles = 0, springs = 0;
    cloth_get_particle_count(flag, &particles);
    cloth_fabric_get_spring_count(fabric, CLOTH_SPRING_ALL, &springs);
    std::printf("flag %ux%u: %u particles, %u springs, solver %s, iterations %u, substeps %u, k %.0f N/m\n",
                o.columns, o.rows, particles, springs, o.solver.c_str(), o.iterations, o.substeps,
                o.stiffness);
    std::printf("%8s %10s %10s %10s %10s\n", "frame", "step_ms", "max_strain", "max_speed", "wind_m/s");

    std::vector<double> step_ms;
    int failed_frames = 0;
    for (int frame = 0; frame < o.frames; ++frame) {
        // Gusts: 10 m/s along the flag, varying speed and a slow swing across.
        const float t = static_cast<float>(frame) * dt;
        const float speed = 10.0f + 3.0f * std::sin(0.7f * t) + 1.5f * std::sin(2.3f * t);
        const float wind[3] = {speed, 0.0f, 2.0f * std::sin(0.4f * t)};
        cloth_set_wind(flag, wind);

        const auto start = std::chrono::steady_clock::now();
        const cloth_result result = cloth_step(world, dt);
        step_ms.push_back(
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
        if (result != CLOTH_OK) {
            ++failed_frames;
            std::fprintf(stderr, "frame %d: %s\n", frame, cloth_get_last_error());
        }

        if (frame % 30 == 0 || frame == o.frames - 1) {
            cloth_stats stats{};
            stats.struct_size = sizeof stats;
            cloth_get_stats(flag, &stats);
            std::printf("%8d %10.3f %10.3f %10.2f %10.1f\n", frame, step_ms.back(), stats.max_strain,
                        stats.max_speed, speed);
        }
    }
    std::printf("step time over %d frames: p50 %.3f ms, p95 %.3f ms, max %.3f ms\n", o.frames,
                percentile(step_ms, 0.5), percentile(step_ms, 0.95), percentile(step_ms, 1.0));

    if (failed_frames) std::printf("%d of %d frames reported an error\n", failed_frames, o.frames);
    int status = failed_frames == 0 ? 0 : 1;
    if (!o.png.empty()) {
        std::vector<float> positions(3 * particles), normals(3 * particles);
        uint32_t triangles = 0;
        cloth_fabric_get_triangle_count(fabric, &triangles);
        std::vector<uint32_t> indices(3 * triangles);
        cloth_read_positions(flag, positions.data(), static_cast<uint32_t>(positions.size()));
        cloth_read_normals(flag, normals.data(), static_cast<uint32_t>(normals.size()));
        cloth_fabric_read_triangles(fabric, indices.data(), static_cast<uint32_t>(indices.size()));

        std::vector<float> pole_positions;
        std::vector<uint32_t> pole_indices;
        make_pole(0.0f, 0.0f, pole_height + 0.1f, 0.03f, pole_positions, pole_indices);

        const cloth_samples::RenderMesh meshes[] = {
            {positions.data(), normals.data(), particles, indices.data(), triangles, {200, 40, 45}},
            {pole_positions.data(),
             nullptr,
             8,
             pole_indices.data(),
             static_cast<uint32_t>(pole_indices.size() / 3),
             {120, 120, 128}},
        };
        const cloth_samples::Camera camera{{2.6f, 2.2f, 3.6f}, {0.8f, 2.3f, 0.0f}, {0.0f, 1.0f, 0.0f}, 45.0f};
        cloth_samples::RenderOptions options;
        std::string error;
        if (cloth_samples::render_png(o.png, camera, meshes, 2, options, &error)) {
            std::printf("wrote %s\n", o.png.c_str());
        } else {
            std::fprintf(stderr, "%s\n", error.c_str());
            status = 1;
        }
    }
    cloth_world_destroy(world);
    return status;
}
