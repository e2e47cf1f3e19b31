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
// picture of four moments. Exit status 0 only when every check held. The
// run around the scene (options, budget table, trace, video, exit status)
// is the samples' shared harness (samples/common/sample_run.h).
#include <cloth/cloth.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "course.h"
#include "course_frame.h"
#include "field.h"
#include "flag_rig.h"
#include "picture.h"
#include "render_png.h"
#include "run_options.h"
#include "sample_run.h"
#include "verdict.h"

using namespace vehicle_flag;
using namespace flag_field;

namespace {

constexpr float kDt = 1.0f / 60.0f;
constexpr uint32_t kProfileTasks = 1u << 16;
constexpr int kVideoWidth = 640, kVideoHeight = 360;
constexpr int kMomentFrames[] = {120, 500, 900, 1300};  // the picture's

struct Options {
    // --frames (0: the whole course), --threads, --budget, --png, --video, --trace, --trace-frames
    cloth_samples::RunOptions run;
    uint32_t flags = 32;  // the vehicle's and the field's
    uint32_t max_rate = 8;
    float max_strain = 0.12f;
    float tolerance = 1e-3f;

    Options() {
        run.threads = 2;
        run.budget_ms = 4.0;
        run.png = "flag_field.png";
    }
};

void add_options(CLI::App& app, Options* o) {
    cloth_samples::add_run_options(app, &o->run,
                                   {"the whole course", "picture of four moments", "around frame 300",
                                    "the cloth world's frame budget, ms"});
    app.add_option("--flags", o->flags, "flags in all, the vehicle's included")->check(CLI::Range(1, 200));
    app.add_option("--max-rate", o->max_rate,
                   "the slowest update rate the budget may give a flag (1, 2, 4, 8)")
        ->check(CLI::IsMember({1, 2, 4, 8}));
    app.add_option("--max-strain", o->max_strain, "check: bound on every flag's max structural strain");
    app.add_option("--tolerance", o->tolerance, "check: how far inside a pole, m");
}

// The vehicle's flag over the run: its strain, and the frames it ran at
// full quality (rate 1, at least the iterations and substeps it chose in
// the first frame, before any budget cut).
struct VehicleFlag {
    uint32_t own_iterations = 0, own_substeps = 0;
    int full_frames = 0;
    float worst_strain = 0;
    uint32_t rate = 1;  // the last frame's update rate
    cloth_stats stats{};

    // After frame `frame`'s step; a strain past `max_strain` counts in `checks`.
    void observe(int frame, cloth_id cloth, float max_strain, FieldChecks* checks) {
        stats.struct_size = sizeof stats;
        cloth_get_stats(cloth, &stats);
        cloth_get_update_rate(cloth, &rate, nullptr);
        if (frame == 0) {
            own_iterations = stats.last_max_iterations;
            own_substeps = stats.last_substeps;
        }
        full_frames +=
            rate == 1 && stats.last_max_iterations >= own_iterations && stats.last_substeps >= own_substeps;
        worst_strain = std::max(worst_strain, stats.max_strain);
        checks->strain_frames += !(stats.max_strain <= max_strain);
    }
};

// The progress table's line: each class's mean update rate and iterations
// (the vehicle's flag is near).
void print_rates(int frame, float time, const char* phase, float speed, double step_ms,
                 const VehicleFlag& own, const std::vector<FieldFlag>& flags,
                 const int class_size[kClassCount]) {
    double rate_sum[kClassCount] = {}, iteration_sum[kClassCount] = {};
    rate_sum[kNear] = own.rate;
    iteration_sum[kNear] = own.stats.last_max_iterations;
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
        std::snprintf(cells[c], sizeof cells[c], "%.1f / %.1f", rate_sum[c] / n, iteration_sum[c] / n);
    }
    std::printf("%6d %7.2f %-12s %8.2f %9.3f   %-16s %-16s %-16s\n", frame, time, phase, speed, step_ms,
                cells[kNear], cells[kMid], cells[kFar]);
}

// The flags' rate changes in the frame just stepped, on their classes' tracks.
void trace_rate_changes(const std::vector<FieldFlag>& flags, const std::vector<uint32_t>& old_rates,
                        const int tracks[kClassCount], double at_us, cloth_samples::TraceWriter* trace) {
    static const char* const kRateNames[] = {"", "rate 1", "rate 2", "", "rate 4", "", "", "", "rate 8"};
    for (size_t k = 0; k < flags.size(); ++k) {
        if (flags[k].rate != old_rates[k])
            trace->add(kRateNames[flags[k].rate], tracks[flags[k].flag_class], at_us, 1.0);
    }
}

// The run's head line (the flags, their classes, the budget) and the
// progress table's.
void print_head(const Options& o, const std::vector<FieldFlag>& flags, const int class_size[kClassCount]) {
    std::printf(
        "flag_field: %u flags of %ux%u (the vehicle's and %zu on poles, %.0f to %.0f m from the course: %d "
        "near, "
        "%d mid, %d far), CLOTH_SOLVER_DEFAULT, budget %.2f ms, rates up to %u, %u thread(s)\n",
        o.flags, FlagField::kColumns, FlagField::kRows, flags.size(),
        flags.empty() ? 0.0 : flags.front().distance, flags.empty() ? 0.0 : flags.back().distance,
        class_size[kNear], class_size[kMid], class_size[kFar], o.run.budget_ms, o.max_rate, o.run.threads);
    std::printf("%6s %7s %-12s %8s %9s   %-16s %-16s %-16s\n", "frame", "time_s", "phase", "speed", "step_ms",
                "near rate/iter", "mid rate/iter", "far rate/iter");
}

// The class of the cloth `id` (the vehicle's flag is near), -1 for none.
int class_of(cloth_id id, const FlagRig& rig, const std::vector<FieldFlag>& flags) {
    if (cloth_id_equal(id, rig.cloth())) return kNear;
    for (const FieldFlag& f : flags)
        if (cloth_id_equal(id, f.cloth)) return f.flag_class;
    return -1;
}

// The viewer on the vehicle's chassis (Bullet's frame), in the cloth world's frame.
cloth_result set_viewer(const FlagRig& rig, const btVector3& chassis) {
    const double* origin = rig.origin();
    const float viewer[3] = {static_cast<float>(chassis.x() - origin[0]),
                             static_cast<float>(chassis.y() - origin[1]),
                             static_cast<float>(chassis.z() - origin[2])};
    return cloth_world_set_viewer(rig.world(), viewer);
}

// "checks over N frames:" and a line for each check.
void print_checks(int frames, const FieldChecks& checks, const VehicleFlag& own, const Options& o,
                  int failed_calls) {
    std::printf("\nchecks over %d frames:\n", frames);
    std::printf("  max strain: worst %.3f (the vehicle's %.3f), flag-frames past %.3g: %ld\n",
                checks.worst_strain, own.worst_strain, o.max_strain, checks.strain_frames);
    std::printf("  particles inside a pole (deeper than %.3g m), summed over frames: %ld (deepest %.3g m)\n",
                o.tolerance, checks.inside_pole, checks.deepest_in_pole);
    std::printf(
        "  changes of rate: %ld; with a jump (a move over twice the most in the two calls around): %ld, "
        "worst ratio %.2f\n",
        checks.rate_changes, checks.jumps, checks.worst_jump_ratio);
    std::printf("  cloth calls that failed: %d\n", failed_calls);
}

// One moment of the run: every flag's reported positions and the camera.
struct Moment {
    std::string label;
    double eye[3], target[3];
    std::vector<std::vector<float>> flags;
};

// Frame `frame`, seen from high behind the vehicle, looking down the course.
Moment capture(int frame, const btVector3& chassis, FlagRig& rig, const std::vector<FieldFlag>& flags) {
    Moment m;
    m.label = "frame " + std::to_string(frame);
    const double eye[3] = {chassis.x() + 4.0, chassis.y() + 9.0, chassis.z() - 18.0};
    const double target[3] = {chassis.x(), chassis.y() + 1.0, chassis.z() + 25.0};
    std::copy(eye, eye + 3, m.eye);
    std::copy(target, target + 3, m.target);
    m.flags.push_back(rig.positions());
    for (const FieldFlag& f : flags) m.flags.push_back(f.last);
    return m;
}

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
    add_options(app, &o);
    CLI11_PARSE(app, argc, argv);

    const Terrain terrain;
    VehicleWorld vehicle(terrain);
    CourseDriver driver(terrain.layout().ramp_start_z);
    FlagSettings settings;
    settings.threads = o.run.threads;
    settings.profile_tasks = kProfileTasks;
    // Task records count from the cloth world's creation, the first thing FlagRig does.
    cloth_samples::SampleRun run(o.run, kProfileTasks);
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
        cloth_world_set_frame_budget(rig.world(), static_cast<float>(o.run.budget_ms)) != CLOTH_OK) {
        std::fprintf(stderr, "budget: %s\n", cloth_get_last_error());
        return 1;
    }
    std::vector<FieldFlag>& flags = field.flags();
    int class_size[kClassCount] = {1, 0, 0};  // the vehicle's flag is near
    for (const FieldFlag& f : flags) ++class_size[f.flag_class];
    print_head(o, flags, class_size);

    // The budget table's rows and the trace's tracks, in their order.
    std::vector<double>* class_ms[kClassCount];
    for (int c = 0; c < kClassCount; ++c) {
        const FlagClass flag_class = static_cast<FlagClass>(c);
        class_ms[c] = run.table().add_row(std::string("  ") + class_name(flag_class) + " (" +
                                          std::to_string(class_size[c]) + ")");
    }
    cloth_samples::FrameTimer& timer = run.timer();
    const auto cloth_part = timer.part("cloth step", "cloth_step", "cloth");
    int decision_tracks[kClassCount];
    for (int c = 0; c < kClassCount; ++c)
        decision_tracks[c] =
            run.trace().track(std::string("rates: ") + class_name(static_cast<FlagClass>(c)));
    FieldChecks checks;
    VehicleFlag own;
    int frames_run = 0, failed_steps = 0, overruns_after_60 = 0;
    cloth_samples::Picture<Moment> picture(o.run.png);
    const auto draw = [&](const Moment& m, int width, int height, std::vector<uint8_t>* rgb,
                          std::string* error) {
        return render(m, terrain, field.triangles(), width, height, rgb, error);
    };
    if (!run.open_video(kVideoWidth, kVideoHeight)) return 1;

    for (int frame = 0; run.more_frames(frame, driver.done()); ++frame) {
        const float time = frame * kDt;
        run.begin_frame(frame);
        drive_course_frame(
            time, driver, vehicle, rig, [&] { vehicle.step(kDt); }, &failed_steps);
        field.set_wind(time);
        const btVector3 chassis = vehicle.chassis_pose().getOrigin();
        if (set_viewer(rig, chassis) != CLOTH_OK) ++failed_steps;

        const cloth_result step = timer.time(cloth_part, [&] { return rig.step(kDt); });
        run.end_frame();
        if (step != CLOTH_OK && step != CLOTH_ERROR_OVER_BUDGET) {
            ++failed_steps;
            std::fprintf(stderr, "frame %d: cloth_step: %s (%s)\n", frame, cloth_result_name(step),
                         cloth_get_last_error());
        }
        overruns_after_60 += frame >= 60 && cloth_part.row->back() > o.run.budget_ms;
        // Each class's task time, and the tasks on the trace.
        double class_time[kClassCount] = {};
        for (const cloth_task_record& task : run.profile().record(rig.world())) {
            const int c = class_of(task.cloth, rig, flags);
            if (c >= 0) class_time[c] += (task.end_us - task.start_us) * 1e-3;
        }
        for (int c = 0; c < kClassCount; ++c) class_ms[c]->push_back(class_time[c]);

        // Checks (outside the timing).
        cloth_frame_profile profile{};
        profile.struct_size = sizeof profile;
        cloth_world_get_frame_profile(rig.world(), &profile);
        std::vector<uint32_t> old_rates;
        for (const FieldFlag& f : flags) old_rates.push_back(f.rate);
        field.observe(profile.frame, rig.origin(), o.max_strain, o.tolerance, &checks);
        trace_rate_changes(flags, old_rates, decision_tracks, timer.last_end_us(), &run.trace());
        own.observe(frame, rig.cloth(), o.max_strain, &checks);
        ++frames_run;

        if (frame % 60 == 0) {
            print_rates(frame, time, phase_name(driver.phase()), vehicle.forward_speed(),
                        cloth_part.row->back(), own, flags, class_size);
        }
        const int* moment =
            picture.due(kMomentFrames, [&](int moment_frame) { return moment_frame == frame; });
        if (moment || run.video().due(frame)) {
            Moment m = capture(frame, chassis, rig, flags);
            const auto draw_now = [&](int width, int height, auto* rgb, auto* error) {
                return draw(m, width, height, rgb, error);
            };
            if (run.video().due(frame) && !run.video().add(draw_now, "frame " + std::to_string(frame)))
                return 1;
            if (moment) picture.add(std::move(m));
        }
    }
    field.check_jumps(&checks);

    std::printf("\ncourse: %d frames (%.1f s)\n", frames_run, frames_run * kDt);
    run.print_timings("task time per class and the cloth step", "", 18);
    std::printf("overruns after the first 60 frames: %d\n", overruns_after_60);
    const double full_share = static_cast<double>(own.full_frames) / std::max(frames_run, 1);
    std::printf(
        "the vehicle's flag at full quality (rate 1, its own %u iterations and %u substeps) in %.1f %% of "
        "frames\n",
        own.own_iterations, own.own_substeps, 100.0 * full_share);

    print_checks(frames_run, checks, own, o, failed_steps);
    cloth_samples::Verdict verdict({"calls", "strain", "pole", "jumps"});
    verdict.set("calls", failed_steps == 0);
    verdict.set("strain", checks.strain_frames == 0);
    verdict.set("pole", checks.inside_pole == 0);
    verdict.set("jumps", checks.jumps == 0);

    if (!run.write_trace(std::min(300, frames_run / 2))) verdict.fail_output();
    if (!run.video().finish()) verdict.fail_output();
    if (!picture.moments().empty()) {
        std::string frame_list;
        for (int f : kMomentFrames) frame_list += (frame_list.empty() ? "" : ", ") + std::to_string(f);
        if (cloth_samples::write_moment_panels(o.run.png, picture.moments(), 640, 360, draw, &error)) {
            std::printf("wrote %s (frames %s)\n", o.run.png.c_str(), frame_list.c_str());
        } else {
            std::fprintf(stderr, "%s\n", error.c_str());
            verdict.fail_output();
        }
    }
    return verdict.finish();
}
