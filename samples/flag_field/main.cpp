// flag_field: a scene's cloth in one frame budget. The Bullet vehicle of
// vehicle_flag drives its course past a field of flags on poles (the same
// 48x32 flag, 2 m to about 170 m from the course, gusting wind), the
// vehicle's own flag among them, all in one cloth world with one frame
// budget; the viewer rides on the vehicle. Every flag has a quality
// policy that may slow its update rate: the world lowers the flags the
// viewer sees least first (docs/scene_budget.md). Headless. Each frame it
// checks every flag (strain, its pole, no jump at a change of rate); at
// the end it prints the budget table per class (near, mid, far), the
// classes' rates and iterations over time, and the checks, and writes a
// picture of four moments. Exit status 0 only when every check held.
#include <cloth/cloth.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "course.h"
#include "field.h"
#include "flag_rig.h"
#include "render_png.h"
#include "timing_table.h"
#include "trace_writer.h"
#include "video_writer.h"

using namespace vehicle_flag;
using namespace flag_field;
using cloth_samples::percentile;
using cloth_samples::print_timing_row;

namespace {

constexpr float kDt = 1.0f / 60.0f;
constexpr uint32_t kProfileTasks = 1u << 16;

struct Options {
    int frames = 0;  // 0: the whole course
    uint32_t threads = 2;
    uint32_t flags = 32;  // the vehicle's and the field's
    double budget_ms = 4.0;
    uint32_t max_rate = 8;
    std::string png = "flag_field.png";
    std::string video;
    std::string trace;
    std::string trace_frames;
    float max_strain = 0.12f;
    float tolerance = 1e-3f;
};

// One moment of the run: every flag's reported positions and the camera.
struct Moment {
    std::string label;
    double eye[3], target[3];
    std::vector<std::vector<float>> flags;
};

bool render(const Moment& m, const Terrain& terrain, const std::vector<uint32_t>& triangles, int width,
            int height, std::vector<uint8_t>* rgb, std::string* error) {
    std::vector<float> ground;
    std::vector<uint32_t> ground_indices;
    terrain.patch_mesh(static_cast<float>(m.target[0]), static_cast<float>(m.target[2]), 40.0f, &ground,
                       &ground_indices);
    std::vector<cloth_samples::RenderMesh> meshes;
    meshes.push_back({ground.data(),
                      nullptr,
                      static_cast<uint32_t>(ground.size() / 3),
                      ground_indices.data(),
                      static_cast<uint32_t>(ground_indices.size() / 3),
                      {150, 170, 120}});
    for (size_t k = 0; k < m.flags.size(); ++k) {
        const uint8_t red = k == 0 ? 200 : 60;  // the vehicle's flag in red
        meshes.push_back({m.flags[k].data(),
                          nullptr,
                          static_cast<uint32_t>(m.flags[k].size() / 3),
                          triangles.data(),
                          static_cast<uint32_t>(triangles.size() / 3),
                          {red, 60, static_cast<uint8_t>(k == 0 ? 50 : 170)}});
    }
    cloth_samples::Camera camera{};
    for (int a = 0; a < 3; ++a) {
        camera.eye[a] = static_cast<float>(m.eye[a]);
        camera.target[a] = static_cast<float>(m.target[a]);
    }
    camera.up[1] = 1.0f;
    camera.fov_y_degrees = 60.0f;
    cloth_samples::RenderOptions options;
    options.width = width;
    options.height = height;
    options.draw_ground_grid = false;
    return cloth_samples::render_rgb(camera, meshes.data(), meshes.size(), options, rgb, error);
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    CLI::App app{
        "A field of flags and the vehicle's own in one cloth frame budget; checks, timings, a picture"};
    app.add_option("--frames", o.frames, "frames at 60 Hz (0: the whole course)")
        ->check(CLI::Range(0, 1000000));
    app.add_option("--threads", o.threads, "cloth worker threads (1: the calling thread only)")
        ->check(CLI::Range(1, 256));
    app.add_option("--flags", o.flags, "flags in all, the vehicle's included")->check(CLI::Range(1, 200));
    app.add_option("--budget", o.budget_ms, "the cloth world's frame budget, ms")->check(CLI::PositiveNumber);
    app.add_option("--max-rate", o.max_rate,
                   "the slowest update rate the budget may give a flag (1, 2, 4, 8)")
        ->check(CLI::IsMember({1, 2, 4, 8}));
    app.add_option("--png", o.png, "picture of four moments (empty: none)")
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
    app.add_option("--video", o.video, "MP4 of the run at 30 fps through ffmpeg (empty: none)")
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
    app.add_option("--trace", o.trace, "Chrome trace-event JSON of a window of the run (empty: none)")
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
    app.add_option("--trace-frames", o.trace_frames,
                   "frames the trace keeps, FIRST:LAST (default: around frame 300)");
    app.add_option("--max-strain", o.max_strain, "check: bound on every flag's max structural strain");
    app.add_option("--tolerance", o.tolerance, "check: how far inside a pole, m");
    CLI11_PARSE(app, argc, argv);

    const Terrain terrain;
    VehicleWorld vehicle(terrain);
    CourseDriver driver(terrain.layout().ramp_start_z);
    FlagSettings settings;
    settings.threads = o.threads;
    settings.profile_tasks = kProfileTasks;
    cloth_samples::TraceWriter trace;
    const double world_zero_us = trace.now_us();
    FlagRig rig(settings, vehicle);
    FlagField field;
    std::string error;
    if (!rig.ok()) {
        std::fprintf(stderr, "%s\n", rig.error().c_str());
        return 1;
    }
    if (!field.create(rig.world(), rig.origin(), terrain, o.flags - 1, o.max_rate, &error)) {
        std::fprintf(stderr, "%s\n", error.c_str());
        return 1;
    }
    // The vehicle's flag is the one the player looks at: it counts four
    // times a field flag as near.
    cloth_quality_policy policy = cloth_default_quality_policy();
    policy.enabled = 1;
    policy.max_update_rate = o.max_rate;
    if (cloth_set_quality_policy(rig.cloth(), &policy) != CLOTH_OK ||
        cloth_set_importance(rig.cloth(), 4.0f) != CLOTH_OK ||
        cloth_world_set_frame_budget(rig.world(), static_cast<float>(o.budget_ms)) != CLOTH_OK) {
        std::fprintf(stderr, "budget: %s\n", cloth_get_last_error());
        return 1;
    }
    std::vector<FieldFlag>& flags = field.flags();
    int class_size[kClassCount] = {1, 0, 0};  // the vehicle's flag is near
    for (const FieldFlag& f : flags) ++class_size[f.flag_class];
    std::printf(
        "flag_field: %u flags of %ux%u (the vehicle's and %zu on poles, %.0f to %.0f m from the course: %d "
        "near, "
        "%d mid, %d far), CLOTH_SOLVER_DEFAULT, budget %.2f ms, rates up to %u, %u thread(s)\n",
        o.flags, FlagField::kColumns, FlagField::kRows, flags.size(),
        flags.empty() ? 0.0 : flags.front().distance, flags.empty() ? 0.0 : flags.back().distance,
        class_size[kNear], class_size[kMid], class_size[kFar], o.budget_ms, o.max_rate, o.threads);
    std::printf("%6s %7s %-12s %8s %9s   %-16s %-16s %-16s\n", "frame", "time_s", "phase", "speed", "step_ms",
                "near rate/iter", "mid rate/iter", "far rate/iter");

    // cloth id -> class, for the task records.
    auto class_of = [&](cloth_id id) -> int {
        if (cloth_id_equal(id, rig.cloth())) return kNear;
        for (const FieldFlag& f : flags)
            if (cloth_id_equal(id, f.cloth)) return f.flag_class;
        return -1;
    };
    const int frame_track = trace.track("frame"), cloth_track = trace.track("cloth");
    int decision_tracks[kClassCount];
    for (int c = 0; c < kClassCount; ++c)
        decision_tracks[c] = trace.track(std::string("rates: ") + class_name(static_cast<FlagClass>(c)));
    std::vector<int> worker_tracks;
    std::vector<cloth_task_record> tasks(kProfileTasks);
    std::vector<double> step_ms, class_ms[kClassCount];
    FieldChecks checks;
    uint32_t own_iterations = 0, own_substeps = 0;  // the vehicle's flag's own choice, before any budget cut
    int vehicle_full = 0, frames_run = 0, failed_steps = 0, overruns_after_60 = 0;
    float vehicle_strain = 0;
    std::vector<Moment> moments;
    const int moment_frames[] = {120, 500, 900, 1300};
    constexpr int kVideoWidth = 640, kVideoHeight = 360, kVideoFps = 30;
    cloth_samples::VideoWriter video;
    if (!o.video.empty() && !video.open(o.video, kVideoWidth, kVideoHeight, kVideoFps, &error)) {
        std::fprintf(stderr, "%s\n", error.c_str());
        return 1;
    }

    for (int frame = 0; o.frames == 0 || frame < o.frames; ++frame) {
        if (o.frames == 0 && driver.done()) break;
        const float time = frame * kDt;
        trace.set_frame(frame);
        const double frame_start_us = trace.now_us();
        const Controls controls = driver.drive(time, vehicle);
        if (controls.teleport) {
            vehicle.teleport(vehicle.start_pose());
            if (rig.teleport_chassis() != CLOTH_OK) ++failed_steps;
        }
        vehicle.set_controls(controls.engine, controls.brake, controls.steering);
        vehicle.step(kDt);
        const float wind[3] = {3.0f + 1.5f * std::sin(0.8f * time), 0.0f,
                               -4.0f + 2.0f * std::sin(1.7f * time + 1.0f)};
        rig.set_wind(wind);
        field.set_wind(time);
        if (rig.sync() != CLOTH_OK) ++failed_steps;
        // The viewer on the vehicle, in the cloth world's frame.
        const btVector3 chassis = vehicle.chassis_pose().getOrigin();
        const double* origin = rig.origin();
        const float viewer[3] = {static_cast<float>(chassis.x() - origin[0]),
                                 static_cast<float>(chassis.y() - origin[1]),
                                 static_cast<float>(chassis.z() - origin[2])};
        if (cloth_world_set_viewer(rig.world(), viewer) != CLOTH_OK) ++failed_steps;

        const double start_us = trace.now_us();
        const cloth_result step = rig.step(kDt);
        const double end_us = trace.now_us();
        step_ms.push_back((end_us - start_us) * 1e-3);
        trace.add("cloth_step", cloth_track, start_us, end_us - start_us);
        trace.add("frame", frame_track, frame_start_us, end_us - frame_start_us);
        if (step != CLOTH_OK && step != CLOTH_ERROR_OVER_BUDGET) {
            ++failed_steps;
            std::fprintf(stderr, "frame %d: cloth_step: %s (%s)\n", frame, cloth_result_name(step),
                         cloth_get_last_error());
        }
        overruns_after_60 += frame >= 60 && step_ms.back() > o.budget_ms;
        // Each class's task time, and the tasks on the trace.
        double class_time[kClassCount] = {};
        uint32_t count = 0;
        if (cloth_world_read_task_records(rig.world(), tasks.data(), kProfileTasks, &count) == CLOTH_OK) {
            for (uint32_t i = 0; i < count; ++i) {
                const cloth_task_record& task = tasks[i];
                const int c = class_of(task.cloth);
                if (c >= 0) class_time[c] += (task.end_us - task.start_us) * 1e-3;
                while (worker_tracks.size() <= task.worker)
                    worker_tracks.push_back(
                        trace.track("cloth worker " + std::to_string(worker_tracks.size())));
                trace.add(cloth_stage_name(task.stage), worker_tracks[task.worker],
                          world_zero_us + task.start_us, task.end_us - task.start_us);
            }
        }
        for (int c = 0; c < kClassCount; ++c) class_ms[c].push_back(class_time[c]);

        // Checks (outside the timing).
        cloth_frame_profile profile{};
        profile.struct_size = sizeof profile;
        cloth_world_get_frame_profile(rig.world(), &profile);
        std::vector<uint32_t> old_rates;
        for (const FieldFlag& f : flags) old_rates.push_back(f.rate);
        field.observe(profile.frame, rig.origin(), o.max_strain, o.tolerance, &checks);
        static const char* const kRateNames[] = {"", "rate 1", "rate 2", "", "rate 4", "", "", "", "rate 8"};
        for (size_t k = 0; k < flags.size(); ++k) {
            if (flags[k].rate != old_rates[k])
                trace.add(kRateNames[flags[k].rate], decision_tracks[flags[k].flag_class], end_us, 1.0);
        }
        cloth_stats stats{};
        stats.struct_size = sizeof stats;
        cloth_get_stats(rig.cloth(), &stats);
        uint32_t vehicle_rate = 1;
        cloth_get_update_rate(rig.cloth(), &vehicle_rate, nullptr);
        if (frame == 0) {
            own_iterations = stats.last_max_iterations;
            own_substeps = stats.last_substeps;
        }
        vehicle_full += vehicle_rate == 1 && stats.last_max_iterations >= own_iterations &&
                        stats.last_substeps >= own_substeps;
        vehicle_strain = std::max(vehicle_strain, stats.max_strain);
        checks.strain_frames += !(stats.max_strain <= o.max_strain);
        ++frames_run;

        if (frame % 60 == 0) {
            double rate_sum[kClassCount] = {}, iteration_sum[kClassCount] = {};
            rate_sum[kNear] = vehicle_rate;
            iteration_sum[kNear] = stats.last_max_iterations;
            for (const FieldFlag& f : flags) {
                cloth_stats s{};
                s.struct_size = sizeof s;
                cloth_get_stats(f.cloth, &s);
                rate_sum[f.flag_class] += f.rate;
                iteration_sum[f.flag_class] += s.last_max_iterations;
            }
            char cells[kClassCount][32];
            for (int c = 0; c < kClassCount; ++c) {
                const double n = std::max(class_size[c], 1);
                std::snprintf(cells[c], sizeof cells[c], "%.1f / %.1f", rate_sum[c] / n,
                              iteration_sum[c] / n);
            }
            std::printf("%6d %7.2f %-12s %8.2f %9.3f   %-16s %-16s %-16s\n", frame, time,
                        phase_name(driver.phase()), vehicle.forward_speed(), step_ms.back(), cells[kNear],
                        cells[kMid], cells[kFar]);
        }
        const bool moment =
            std::find(std::begin(moment_frames), std::end(moment_frames), frame) != std::end(moment_frames);
        const bool video_frame = video.is_open() && frame % (60 / kVideoFps) == 0;
        if (moment || video_frame) {
            Moment m;
            m.label = "frame " + std::to_string(frame);
            // High behind the vehicle, looking down the course.
            const double eye[3] = {chassis.x() + 4.0, chassis.y() + 9.0, chassis.z() - 18.0};
            const double target[3] = {chassis.x(), chassis.y() + 1.0, chassis.z() + 25.0};
            std::copy(eye, eye + 3, m.eye);
            std::copy(target, target + 3, m.target);
            m.flags.push_back(rig.positions());
            for (const FieldFlag& f : flags) m.flags.push_back(f.last);
            if (video_frame) {
                std::vector<uint8_t> rgb;
                if (!render(m, terrain, field.triangles(), kVideoWidth, kVideoHeight, &rgb, &error) ||
                    !video.add(rgb)) {
                    std::fprintf(stderr, "video frame %d: %s\n", frame, error.c_str());
                    return 1;
                }
            }
            if (moment) moments.push_back(std::move(m));
        }
    }
    field.check_jumps(&checks);

    std::printf("\ncourse: %d frames (%.1f s)\n", frames_run, frames_run * kDt);
    std::printf("\ntask time per class and the cloth step, ms (shared machine: noisy); budget %.2f ms\n",
                o.budget_ms);
    std::printf("%-18s %9s %9s %9s %9s %9s\n", "", "p50", "p95", "p99", "max", "overruns");
    for (int c = 0; c < kClassCount; ++c) {
        const std::string name = std::string("  ") + class_name(static_cast<FlagClass>(c)) + " (" +
                                 std::to_string(class_size[c]) + ")";
        print_timing_row(name.c_str(), class_ms[c], o.budget_ms, 18);
    }
    print_timing_row("cloth step", step_ms, o.budget_ms, 18);
    std::printf("overruns after the first 60 frames: %d\n", overruns_after_60);
    const double full_share = static_cast<double>(vehicle_full) / std::max(frames_run, 1);
    std::printf(
        "the vehicle's flag at full quality (rate 1, its own %u iterations and %u substeps) in %.1f %% of "
        "frames\n",
        own_iterations, own_substeps, 100.0 * full_share);

    std::printf("\nchecks over %d frames:\n", frames_run);
    std::printf("  max strain: worst %.3f (the vehicle's %.3f), flag-frames past %.3g: %ld\n",
                checks.worst_strain, vehicle_strain, o.max_strain, checks.strain_frames);
    std::printf("  particles inside a pole (deeper than %.3g m), summed over frames: %ld (deepest %.3g m)\n",
                o.tolerance, checks.inside_pole, checks.deepest_in_pole);
    std::printf(
        "  changes of rate: %ld; with a jump (a move over twice the most in the two calls around): %ld, "
        "worst ratio %.2f\n",
        checks.rate_changes, checks.jumps, checks.worst_jump_ratio);
    std::printf("  cloth calls that failed: %d\n", failed_steps);
    const bool passed =
        failed_steps == 0 && checks.strain_frames == 0 && checks.inside_pole == 0 && checks.jumps == 0;
    int status = passed ? 0 : 1;

    if (!o.trace.empty() && !trace.write_window(o.trace, o.trace_frames, std::min(300, frames_run / 2)))
        status = 1;
    if (video.is_open() && !video.close_and_report(o.video, kVideoFps)) status = 1;
    if (!o.png.empty() && !moments.empty()) {
        constexpr int kPanelWidth = 640, kPanelHeight = 360;
        std::vector<std::vector<uint8_t>> panels(moments.size());
        bool drawn = true;
        for (size_t i = 0; i < moments.size() && drawn; ++i)
            drawn =
                render(moments[i], terrain, field.triangles(), kPanelWidth, kPanelHeight, &panels[i], &error);
        if (drawn && cloth_samples::write_panels_png(o.png, panels, kPanelWidth, kPanelHeight, &error)) {
            std::printf("wrote %s (frames 120, 500, 900, 1300)\n", o.png.c_str());
        } else {
            std::fprintf(stderr, "%s\n", error.c_str());
            status = 1;
        }
    }
    std::printf("%s\n", status == 0 ? "all checks passed" : "CHECKS FAILED");
    return status;
}
