// Over 400 lines because it is a sample a user reads whole: the frame
// loop (clip, body, skin, step, checks, budget table, outputs) on one page.
// character_cloth: a procedurally animated character (17 joints, a body of
// tapered capsules and spheres on them) wearing a cape and a skirt,
// through a clip of idle, walk, run, a sharp turn, a jump with its
// landing, a 360-degree spin and a teleport back to the start. Headless.
// Every frame it checks the garments (each particle within its max
// distance of its skinned position, outside its backstop, not inside the
// body, strain and speed bounded, kinetic energy relative to the skin
// within what the skin's own motion brings); at the end it prints the
// budget table and the checks, one line per check with its pass or FAIL,
// and writes a picture of four moments. Exit status 0 only when every
// check held (or every one --require names).
#include <cloth/cloth.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "body.h"
#include "contact_check.h"
#include "motion_checks.h"
#include "render_png.h"
#include "skeleton.h"
#include "solver_options.h"
#include "timing_table.h"
#include "trace_writer.h"
#include "video_writer.h"
#include "wardrobe.h"

using namespace character_cloth;
using cloth_samples::percentile;
using cloth_samples::print_timing_row;

namespace {

constexpr float kDt = 1.0f / 60.0f;
constexpr uint32_t kProfileTasks = 8192;
constexpr int kStages = CLOTH_STAGE_CLOTH_CONTACT_RESPOND + 1;

struct Options {
    int frames = 0;  // 0: the whole clip
    uint32_t threads = 1;
    // --solver, --iterations, --substeps (0: see solver_plan), --quality-policy, --policy-max-substeps,
    // as vehicle_flag's, for both garments
    cloth_samples::SolverOptions solving;
    double budget_ms = 1.0;
    std::string png = "character_cloth.png";
    std::string video;
    std::string trace;
    std::string trace_frames;  // "FIRST:LAST"; empty: the second around the jump
    float max_strain = 0.12f;
    float max_speed = 40.0f;
    float energy_margin_speed = 1.0f;   // m/s: the energy bound's margin, 1/2 M v^2 (motion_checks.h)
    float hem_trailing = 0.9f;          // fraction of running frames with the cape's hem behind
    float tolerance = 1e-3f;            // m: a particle this far inside the body or past a constraint
    float body_clearance = 5e-3f;       // m: the colliders' thickness less what the check forgives
    float garment_contact = 0.02f;      // m: the cape and the skirt's contact thickness (0: off)
    float stiffness_offset = 0;         // N/m added to both garments' structural stiffness
    float cape_self_collision = 0.01f;  // m: the cape's self-collision thickness (0: off)
    std::string require = "all";        // the checks that decide the exit status (kCheckNames)
};

// The checks, each reported on a line of its own ("check NAME: pass" or
// "FAIL"); --require picks those that decide the exit status.
constexpr const char* kCheckNames[] = {"calls", "max_distance",    "backstop",   "body",   "stretch",
                                       "speed", "garment_contact", "cape_folds", "energy", "hem_trailing"};

// Iterations and substeps per solver kind when --iterations or --substeps
// is 0: vehicle_flag's for the same kinds (docs/vehicle_flag.md), at the
// same 60 Hz and structural stiffness (1000 N/m), not tuned for the
// garments. The default picks its own; the explicit kind needs the light
// spring damping vehicle_flag gives it, which the garments do not have.
struct SolverPlan {
    uint32_t iterations, substeps;
    const char* why;
};

SolverPlan solver_plan(cloth_solver_kind kind) {
    switch (kind) {
        case CLOTH_SOLVER_JACOBI:
            return {1, 8, "vehicle_flag's: one sweep, the paper's method"};
        case CLOTH_SOLVER_CG:
            return {1, 3, "vehicle_flag's: solved to tolerance"};
        case CLOTH_SOLVER_EXPLICIT:
            return {1, 64, "vehicle_flag's: the most allowed"};
        case CLOTH_SOLVER_PCG:
            return {16, 3, "vehicle_flag's: at most 16 iterations"};
        case CLOTH_SOLVER_CHEBYSHEV:
            return {16, 8, "vehicle_flag's: 16 iterations"};
        default:
            return {1, 1, "the library picks iterations and substeps"};
    }
}

// The names of --require ("all" or a comma-separated list of kCheckNames),
// one flag per check; false with a message for an unknown name.
bool parse_required(const std::string& list, bool required[], std::string* error) {
    const size_t count = std::size(kCheckNames);
    std::fill(required, required + count, list == "all");
    if (list == "all") return true;
    std::stringstream names(list);
    std::string name;
    bool any = false;
    while (std::getline(names, name, ',')) {
        const auto* found = std::find(std::begin(kCheckNames), std::end(kCheckNames), name);
        if (found == std::end(kCheckNames)) {
            *error = "--require: no check named '" + name + "'";
            return false;
        }
        required[found - std::begin(kCheckNames)] = any = true;
    }
    if (!any) *error = "--require: no check named";
    return any;
}

// The largest stretch of the pairs (the triangles' edges) at positions
// `x`, max of |a - b| / rest - 1 (0 when none is stretched), the measure
// the stretch check applies to the garment and the line beside it to the
// skin; infinite when a position is not finite.
float max_stretch(const std::vector<float>& x, const std::vector<std::pair<uint32_t, uint32_t>>& pairs,
                  const std::vector<float>& rest_length) {
    float stretch = 0;
    for (size_t k = 0; k < pairs.size(); ++k) {
        const Eigen::Vector3f a(&x[3 * pairs[k].first]), b(&x[3 * pairs[k].second]);
        const float s = (a - b).norm() / rest_length[k] - 1.0f;
        if (!std::isfinite(s)) return INFINITY;
        stretch = std::max(stretch, s);
    }
    return stretch;
}

// What the checks found in one garment over the run.
struct GarmentChecks {
    float worst_max_distance = 0, worst_backstop = 0, deepest = 0, worst_strain = 0;
    float worst_skin_strain = 0;  // the skinned positions' own, by the same measure
    long past_max_distance = 0, inside_backstop = 0, inside_body = 0;
};

// Checks one garment at the end of a frame; returns whether every check
// held (false, counted in `failed_calls`, if it cannot be read).
bool check_garment(const Garment& g, const Pose& pose, const Options& o, GarmentChecks* c,
                   int* failed_calls) {
    std::vector<float> x(3 * g.count), s(3 * g.count), n(3 * g.count);
    if (cloth_read_positions(g.cloth, x.data(), 3 * g.count) != CLOTH_OK ||
        cloth_read_skinned_positions(g.cloth, s.data(), n.data(), 3 * g.count) != CLOTH_OK) {
        ++*failed_calls;
        return false;
    }
    c->worst_skin_strain = std::max(c->worst_skin_strain, max_stretch(s, g.structural, g.rest_length));
    const float stretch =
        max_stretch(x, g.structural, g.rest_length);  // this frame's; infinite if not finite
    c->worst_strain = std::max(c->worst_strain, stretch);
    if (!std::isfinite(stretch)) return false;
    bool ok = true;
    for (uint32_t i = 0; i < g.count; ++i) {
        const Eigen::Vector3f p(&x[3 * i]), skinned(&s[3 * i]), normal(&n[3 * i]);
        const float past = (p - skinned).norm() - g.max_distance[i];
        c->worst_max_distance = std::max(c->worst_max_distance, past);
        if (past > o.tolerance) ++c->past_max_distance, ok = false;
        if (g.back_radius[i] > 0.0f) {
            const float inside = g.back_radius[i] - (p - (skinned - g.back_distance[i] * normal)).norm();
            c->worst_backstop = std::max(c->worst_backstop, inside);
            if (inside > o.tolerance) ++c->inside_backstop, ok = false;
        }
        if (g.max_distance[i] > 0.0f) {
            const float depth = -CharacterBody::distance(pose, &x[3 * i], g.collider_mask);
            c->deepest = std::max(c->deepest, depth);
            if (depth > o.tolerance) ++c->inside_body, ok = false;
        }
    }
    return ok && stretch <= o.max_strain;
}

// One moment of the run, drawn after the fact.
struct Moment {
    std::string label;
    float time = 0;
    Pose pose;
    std::vector<float> cape, skirt;
};

bool render_moment(const Moment& m, const Garment& cape, const Garment& skirt, int width, int height,
                   std::vector<uint8_t>* rgb, std::string* error) {
    std::vector<float> body_x, body_n;
    std::vector<uint32_t> body_i;
    CharacterBody::append_mesh(m.pose, &body_x, &body_n, &body_i);
    const cloth_samples::RenderMesh meshes[] = {
        {body_x.data(),
         body_n.data(),
         static_cast<uint32_t>(body_x.size() / 3),
         body_i.data(),
         static_cast<uint32_t>(body_i.size() / 3),
         {200, 190, 175}},
        {m.cape.data(),
         nullptr,
         cape.count,
         cape.triangles.data(),
         static_cast<uint32_t>(cape.triangles.size() / 3),
         {170, 40, 45}},
        {m.skirt.data(),
         nullptr,
         skirt.count,
         skirt.triangles.data(),
         static_cast<uint32_t>(skirt.triangles.size() / 3),
         {50, 80, 160}},
    };
    // Behind and to the left of the character, looking at its hips.
    const Eigen::Vector3f root = m.pose.world[kPelvis].translation();
    cloth_samples::Camera camera{{root.x() + 1.8f, 1.7f, root.z() - 2.6f},
                                 {root.x(), root.y() + 0.1f, root.z()},
                                 {0.0f, 1.0f, 0.0f},
                                 40.0f};
    cloth_samples::RenderOptions options;
    options.width = width;
    options.height = height;
    return cloth_samples::render_rgb(camera, meshes, 3, options, rgb, error);
}

bool write_moments(const std::string& path, const std::vector<Moment>& moments, const Garment& cape,
                   const Garment& skirt, std::string* error) {
    constexpr int kPanelWidth = 480, kPanelHeight = 400;
    std::vector<std::vector<uint8_t>> panels(moments.size());
    for (size_t i = 0; i < moments.size(); ++i) {
        if (!render_moment(moments[i], cape, skirt, kPanelWidth, kPanelHeight, &panels[i], error))
            return false;
    }
    return cloth_samples::write_panels_png(path, panels, kPanelWidth, kPanelHeight, error);
}

std::vector<float> positions(const Garment& g) {
    std::vector<float> x(3 * g.count);
    cloth_read_positions(g.cloth, x.data(), 3 * g.count);
    return x;
}

struct MomentPlan {
    float time;
    const char* label;
};
constexpr MomentPlan kMoments[] = {{6.0f, "run"}, {7.3f, "sharp turn"}, {8.95f, "jump"}, {10.8f, "spin"}};

}  // namespace

int main(int argc, char** argv) {
    Options o;
    CLI::App app{
        "A character wearing a cape and a skirt through a scripted clip; checks, timings and a picture"};
    app.add_option("--frames", o.frames, "frames at 60 Hz (0: the whole clip)")
        ->check(CLI::Range(0, 1000000));
    app.add_option("--threads", o.threads, "cloth worker threads (1: the calling thread only)")
        ->check(CLI::Range(1, 256));
    cloth_samples::add_solver_options(app, &o.solving);
    app.add_option("--budget", o.budget_ms, "frame budget for the cloth step, ms (counts overruns)")
        ->check(CLI::PositiveNumber);
    cloth_samples::add_quality_policy_options(app, &o.solving, "the garments'");
    app.add_option("--png", o.png, "picture of four moments of the clip (empty: none)")
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
    app.add_option("--video", o.video, "MP4 of the run at 30 fps through ffmpeg (empty: none)")
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
    app.add_option("--trace", o.trace, "Chrome trace-event JSON of a window of the run (empty: none)")
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
    app.add_option("--trace-frames", o.trace_frames,
                   "frames the trace keeps, FIRST:LAST (default: the second around the jump)");
    app.add_option("--max-strain", o.max_strain, "check: bound on the garments' max stretch");
    app.add_option("--max-speed", o.max_speed, "check: bound on the garments' max particle speed, m/s");
    app.add_option(
           "--energy-margin-speed", o.energy_margin_speed,
           "check: the garments' free particles' kinetic energy relative to the skin stays within the "
           "skin's own peak over the last second plus 1/2 M v^2 with this v, m/s (M: the garments' "
           "mass)")
        ->check(CLI::NonNegativeNumber);
    app.add_option("--hem-trailing", o.hem_trailing,
                   "check: fraction of running frames with the cape's hem behind the shoulders");
    app.add_option("--stiffness-offset", o.stiffness_offset,
                   "N/m added to both garments' structural stiffness (1000 N/m): the clip's figures are "
                   "chaotic, and a few hundredths of a N/m show how far they move");
    app.add_option("--garment-contact", o.garment_contact,
                   "contact thickness between the cape and the skirt, m (0: off; the check asks for half "
                   "of it between any two of their particles)")
        ->check(CLI::NonNegativeNumber);
    app.add_option("--cape-self-collision", o.cape_self_collision,
                   "self-collision thickness of the cape, which the spin folds onto itself, m (0: off)")
        ->check(CLI::NonNegativeNumber);
    app.add_option("--tolerance", o.tolerance,
                   "check: how far past a max distance, into a backstop or into the body, m");
    app.add_option("--require", o.require,
                   "the checks whose failure fails the run, comma-separated, or all: calls, max_distance, "
                   "backstop, body, stretch, speed, garment_contact, cape_folds, energy, hem_trailing "
                   "(each is reported either way)");
    CLI11_PARSE(app, argc, argv);
    bool required[std::size(kCheckNames)];
    std::string error;
    if (!parse_required(o.require, required, &error)) {
        std::fprintf(stderr, "%s\n", error.c_str());
        return 2;
    }

    cloth_samples::TraceWriter trace;
    const double world_zero_us = trace.now_us();
    cloth_world_desc world_desc = cloth_default_world_desc();
    world_desc.worker_count = o.threads;
    cloth_world_id world{};
    if (cloth_world_create(&world_desc, &world) != CLOTH_OK ||
        cloth_world_set_profiling(world, kProfileTasks) != CLOTH_OK) {
        std::fprintf(stderr, "cloth world: %s\n", cloth_get_last_error());
        return 1;
    }
    Clip clip;
    bool teleported = false;
    Pose pose = clip.advance(0.0f, &teleported);
    CharacterBody body;
    Garment cape, skirt;
    cape.stiffness_offset = skirt.stiffness_offset = o.stiffness_offset;
    if (!body.create(world, pose, &error) || !make_cape(world, body.root(), &cape, &error) ||
        !make_skirt(world, body.root(), &skirt, &error)) {
        std::fprintf(stderr, "%s\n", error.c_str());
        return 1;
    }
    if (o.garment_contact > 0.0f) {
        cloth_cloth_contact_desc contact = cloth_default_cloth_contact_desc();
        contact.enabled = 1;
        contact.thickness = o.garment_contact;
        if (cloth_set_cloth_contact(cape.cloth, skirt.cloth, &contact) != CLOTH_OK) {
            std::fprintf(stderr, "cloth_set_cloth_contact: %s\n", cloth_get_last_error());
            return 1;
        }
    }
    if (o.cape_self_collision > 0.0f) {
        cloth_self_collision_desc self = cloth_default_self_collision_desc();
        self.enabled = 1;
        self.thickness = o.cape_self_collision;
        if (cloth_set_self_collision(cape.cloth, &self) != CLOTH_OK) {
            std::fprintf(stderr, "cloth_set_self_collision: %s\n", cloth_get_last_error());
            return 1;
        }
    }
    const Garment* garments[] = {&cape, &skirt};
    // The solver options, for both garments.
    const cloth_solver_kind kind = cloth_samples::solver_kind(o.solving.solver);
    const SolverPlan plan = solver_plan(kind);
    cloth_solver_settings solver = cloth_default_solver_settings();
    solver.kind = kind;
    solver.iterations = o.solving.iterations > 0 ? o.solving.iterations : plan.iterations;
    solver.substeps = o.solving.substeps > 0 ? o.solving.substeps : plan.substeps;
    const cloth_quality_policy policy = cloth_samples::quality_policy(o.solving);
    if (o.solving.quality_policy &&
        cloth_world_set_frame_budget(world, static_cast<float>(o.budget_ms)) != CLOTH_OK) {
        std::fprintf(stderr, "frame budget: %s\n", cloth_get_last_error());
        return 1;
    }
    for (const Garment* g : garments) {
        if (cloth_set_solver(g->cloth, &solver) != CLOTH_OK ||
            (o.solving.quality_policy && cloth_set_quality_policy(g->cloth, &policy) != CLOTH_OK)) {
            std::fprintf(stderr, "%s: solver: %s\n", g->name.c_str(), cloth_get_last_error());
            return 1;
        }
    }
    uint32_t free_particles = 0;
    for (const Garment* g : garments) {
        for (float d : g->max_distance) free_particles += d > 0.0f;
    }
    std::printf(
        "character_cloth: %u joints, %zu body colliders; cape %u and skirt %u particles (%u free, the rest "
        "sewn on at max distance 0), solver %s, iterations %u, substeps %u%s%s%s%s, %u thread(s)\n",
        static_cast<uint32_t>(kJointCount), CharacterBody::parts().size(), cape.count, skirt.count,
        free_particles, o.solving.solver.c_str(), solver.iterations, solver.substeps,
        o.solving.substeps > 0 ? "" : " (", o.solving.substeps > 0 ? "" : plan.why,
        o.solving.substeps > 0 ? "" : ")", o.solving.quality_policy ? ", quality policy on" : "", o.threads);
    // Each garment's worst stretch so far, its skin's beside it, and this
    // frame's kinetic energy relative to the skin over its bound.
    std::printf("%6s %7s %-11s %10s %10s %10s %10s %9s %8s\n", "frame", "time_s", "phase", "cape_str",
                "cape_skin", "skirt_str", "skirt_skin", "max_speed", "energy");

    const int frame_track = trace.track("frame"), cloth_track = trace.track("cloth"),
              check_track = trace.track("checks");
    std::vector<int> worker_tracks;
    std::vector<cloth_task_record> tasks(kProfileTasks);
    std::vector<double> step_ms, stage_ms[kStages];
    // The strain limiter's effort per garment: its passes each frame and
    // the frames it stopped at their cap; the step's time standing idle at
    // the start and standing after the teleport.
    std::vector<double> strain_passes[2], idle_ms, still_ms;
    int capped_frames[2] = {0, 0};
    GarmentChecks checks[2];
    MotionChecks motion(kDt, o.energy_margin_speed);
    std::vector<Moment> moments;
    size_t next_moment = 0;
    int failed_calls = 0, bad_frames = 0, frames_run = 0, jump_frame = -1;
    float worst_speed = 0.0f;
    // The cape and the skirt: the closest two of their particles, and the
    // frames they came within half the contact thickness (1 cm with it off).
    const float garment_gap = 0.5f * (o.garment_contact > 0.0f ? o.garment_contact : 0.02f);
    float closest_garments = INFINITY;
    int garments_touching = 0;
    // The cape against itself: particles at least three self-collision
    // thicknesses apart at rest (beyond its rest neighbours) closer than
    // half of one (1 cm when the cape's self-collision is off).
    const float cape_thickness = o.cape_self_collision > 0.0f ? o.cape_self_collision : 0.01f;
    const float cape_gap = 0.5f * cape_thickness;
    float closest_folds = INFINITY;
    int cape_folds_touching = 0;
    constexpr int kVideoWidth = 640, kVideoHeight = 400, kVideoFps = 30;
    cloth_samples::VideoWriter video;
    if (!o.video.empty() && !video.open(o.video, kVideoWidth, kVideoHeight, kVideoFps, &error)) {
        std::fprintf(stderr, "%s\n", error.c_str());
        return 1;
    }
    const int frames = o.frames > 0 ? o.frames : static_cast<int>(Clip::kDuration / kDt);
    for (int frame = 0; frame < frames; ++frame) {
        const float time = frame * kDt;
        trace.set_frame(frame);
        const double frame_start_us = trace.now_us();
        pose = clip.advance(time, &teleported);
        // The whole skeleton's bodies in one call (a teleport: no sweep),
        // and the skin's joints.
        if (body.move(pose, teleported) != CLOTH_OK) ++failed_calls;
        const std::vector<float> matrices = skinning_matrices(pose);
        for (const Garment* g : garments) {
            if (cloth_set_joint_matrices(g->cloth, matrices.data(), kJointCount,
                                         CLOTH_MATRIX_COLUMN_MAJOR_4X4) != CLOTH_OK)
                ++failed_calls;
        }
        const double start_us = trace.now_us();
        const cloth_result step = cloth_step(world, kDt);
        const double end_us = trace.now_us();
        step_ms.push_back((end_us - start_us) * 1e-3);
        trace.add("cloth_step", cloth_track, start_us, end_us - start_us);
        if (step != CLOTH_OK) {
            ++failed_calls;
            std::fprintf(stderr, "frame %d: cloth_step: %s (%s)\n", frame, cloth_result_name(step),
                         cloth_get_last_error());
        }
        for (int stage = 0; stage < kStages; ++stage) {
            double ms = 0.0;
            uint32_t count = 0;
            if (cloth_world_get_stage_profile(world, static_cast<cloth_stage>(stage), &ms, &count) ==
                    CLOTH_OK &&
                count > 0)
                stage_ms[stage].push_back(ms);
        }
        uint32_t records = 0;
        if (cloth_world_read_task_records(world, tasks.data(), kProfileTasks, &records) == CLOTH_OK) {
            for (uint32_t i = 0; i < records; ++i) {
                const cloth_task_record& task = tasks[i];
                while (worker_tracks.size() <= task.worker)
                    worker_tracks.push_back(
                        trace.track("cloth worker " + std::to_string(worker_tracks.size())));
                trace.add(cloth_stage_name(task.stage), worker_tracks[task.worker],
                          world_zero_us + task.start_us, task.end_us - task.start_us);
            }
        }
        trace.add("frame", frame_track, frame_start_us, end_us - frame_start_us);

        // Checks on the state at the end of the frame (outside its timing).
        const double check_us = trace.now_us();
        bool ok = step == CLOTH_OK;
        float speed = 0.0f;
        for (int k = 0; k < 2; ++k) {
            ok = check_garment(*garments[k], pose, o, &checks[k], &failed_calls) && ok;
            cloth_stats stats{};
            stats.struct_size = sizeof stats;
            cloth_get_stats(garments[k]->cloth, &stats);
            speed = std::max(speed, std::isfinite(stats.max_speed) ? stats.max_speed : INFINITY);
            strain_passes[k].push_back(stats.last_strain_passes);
            capped_frames[k] += stats.last_strain_pass_cap_hit;
        }
        worst_speed = std::max(worst_speed, speed);
        const float gap = closest_between(positions(cape), positions(skirt), 4.0f * garment_gap);
        closest_garments = std::min(closest_garments, gap);
        if (gap < garment_gap) ++garments_touching, ok = false;
        const float fold = closest_within(positions(cape), cape.rest, 3.0f * cape_thickness, 4.0f * cape_gap);
        closest_folds = std::min(closest_folds, fold);
        if (fold < cape_gap) ++cape_folds_touching, ok = false;
        const Phase phase = clip.phase(time);
        if (phase == Phase::kIdle) idle_ms.push_back(step_ms.back());
        if (phase == Phase::kTeleported) still_ms.push_back(step_ms.back());
        ok = motion.observe(pose, phase, frame, teleported, cape, skirt) && ok;
        ok = ok && speed <= o.max_speed;
        bad_frames += !ok;
        ++frames_run;
        trace.add("checks", check_track, check_us, trace.now_us() - check_us);
        if (phase == Phase::kJump && jump_frame < 0) jump_frame = frame;
        if (frame % 60 == 0 || (!ok && bad_frames <= 5)) {
            std::printf("%6d %7.2f %-11s %10.3f %10.3f %10.3f %10.3f %9.2f %8.3f%s\n", frame, time,
                        phase_name(phase), checks[0].worst_strain, checks[0].worst_skin_strain,
                        checks[1].worst_strain, checks[1].worst_skin_strain, speed, motion.energy_ratio(),
                        ok ? "" : "  CHECK FAILED");
        }
        if (next_moment < std::size(kMoments) && time >= kMoments[next_moment].time) {
            moments.push_back({kMoments[next_moment].label, time, pose, positions(cape), positions(skirt)});
            ++next_moment;
        }
        if (video.is_open() && frame % (60 / kVideoFps) == 0) {
            std::vector<uint8_t> rgb;
            const Moment now{"", time, pose, positions(cape), positions(skirt)};
            if (!render_moment(now, cape, skirt, kVideoWidth, kVideoHeight, &rgb, &error) ||
                !video.add(rgb)) {
                std::fprintf(stderr, "video frame %d: %s\n", frame, error.c_str());
                return 1;
            }
        }
    }

    std::printf("\nclip: %d frames (%.1f s)\n", frames_run, frames_run * kDt);
    std::printf("\nframe timings, ms (shared machine: noisy); budget %.2f ms\n", o.budget_ms);
    std::printf("%-20s %9s %9s %9s %9s %9s\n", "stage", "p50", "p95", "p99", "max", "overruns");
    for (int stage = 0; stage < kStages; ++stage) {
        if (stage_ms[stage].empty()) continue;
        const std::string name = std::string("  ") + cloth_stage_name(static_cast<cloth_stage>(stage));
        print_timing_row(name.c_str(), stage_ms[stage], o.budget_ms, 20);
    }
    print_timing_row("cloth step", step_ms, o.budget_ms, 20);
    const double per_particle_us = 1e3 * percentile(step_ms, 0.5) / free_particles;
    std::printf(
        "cost per free particle: %.3f us a frame at p50 (Kim, Chentanez and Mueller 2012: a 1,500-vertex "
        "dress at 0.67 us a vertex on one 2012 core)\n",
        per_particle_us);

    for (int k = 0; k < 2; ++k) {
        std::printf(
            "strain passes of the %s: p50 %.0f, max %.0f a frame; stopped at their cap in %d frames (%.1f "
            "%%)\n",
            garments[k]->name.c_str(), percentile(strain_passes[k], 0.5), percentile(strain_passes[k], 1.0),
            capped_frames[k], 100.0 * capped_frames[k] / std::max(frames_run, 1));
    }
    if (!idle_ms.empty() && !still_ms.empty()) {
        std::printf(
            "standing still after the teleport: cloth step p50 %.3f ms, %.2fx the idle start's %.3f ms\n",
            percentile(still_ms, 0.5), percentile(still_ms, 0.5) / percentile(idle_ms, 0.5),
            percentile(idle_ms, 0.5));
    }

    std::printf("\nchecks over %d frames:\n", frames_run);
    for (int k = 0; k < 2; ++k) {
        const GarmentChecks& c = checks[k];
        std::printf(
            "  %-5s: past its max distance %ld (worst %.2g m), inside its backstop %ld (worst %.2g m), "
            "inside "
            "the body %ld (deepest %.2g m), max stretch %.3f (limit %.3g; its skin's own %.3f)\n",
            garments[k]->name.c_str(), c.past_max_distance, c.worst_max_distance, c.inside_backstop,
            c.worst_backstop, c.inside_body, c.deepest, c.worst_strain, o.max_strain, c.worst_skin_strain);
    }
    std::printf(
        "  the cape and the skirt closer than %.3g m in %d frames (closest %.3g m; contact thickness %.3g "
        "m)\n",
        garment_gap, garments_touching, closest_garments, o.garment_contact);
    std::printf(
        "  the cape with itself (particles %.3g m apart at rest or more) closer than %.3g m in %d frames "
        "(closest %.3g m; self-collision thickness %.3g m)\n",
        3.0f * cape_thickness, cape_gap, cape_folds_touching, closest_folds, o.cape_self_collision);
    std::printf(
        "  max speed %.2f m/s (limit %.3g); cloth calls that failed: %d; frames failing a check: %d\n",
        worst_speed, o.max_speed, failed_calls, bad_frames);
    const bool trails = motion.hem_trails(o.hem_trailing);
    const int worst_energy_frame = motion.worst_energy_frame();
    std::printf(
        "  kinetic energy relative to the skin: at most %.3f of its bound (limit 1; past it in %d frames), "
        "in frame %d (%.2f s, %s): %.3g J against %.3g J (the skin's own peak over the last second %.3g J + "
        "1/2 M (%.3g m/s)^2 %.3g J)\n",
        motion.worst_energy_ratio(), motion.energy_failed_frames(), worst_energy_frame,
        worst_energy_frame * kDt,
        worst_energy_frame >= 0 ? phase_name(clip.phase(worst_energy_frame * kDt)) : "none",
        motion.worst_energy(), motion.worst_bound(), motion.worst_skin_energy(), o.energy_margin_speed,
        motion.margin_energy());
    std::printf(
        "  the cape's hem behind the shoulders in %d of %d running frames (%.1f %%, at least %.0f %% "
        "asked)%s\n",
        motion.hem_behind_frames(), motion.running_frames(),
        100.0 * motion.hem_behind_frames() / std::max(motion.running_frames(), 1), 100.0 * o.hem_trailing,
        trails ? "" : "  CHECK FAILED");
    // Each check's verdict over the whole run, in kCheckNames' order.
    const bool passed[] = {
        failed_calls == 0,
        checks[0].past_max_distance == 0 && checks[1].past_max_distance == 0,
        checks[0].inside_backstop == 0 && checks[1].inside_backstop == 0,
        checks[0].inside_body == 0 && checks[1].inside_body == 0,
        checks[0].worst_strain <= o.max_strain && checks[1].worst_strain <= o.max_strain,
        worst_speed <= o.max_speed,
        garments_touching == 0,
        cape_folds_touching == 0,
        motion.energy_holds(),
        trails,
    };
    static_assert(std::size(passed) == std::size(kCheckNames));
    std::printf("\n");
    int status = 0;
    for (size_t k = 0; k < std::size(kCheckNames); ++k) {
        std::printf("check %s: %s%s\n", kCheckNames[k], passed[k] ? "pass" : "FAIL",
                    required[k] ? "" : " (not required)");
        if (required[k] && !passed[k]) status = 1;
    }

    if (!o.trace.empty()) {
        const int centre = jump_frame >= 0 ? jump_frame : std::max(0, frames_run - 30);
        if (!trace.write_window(o.trace, o.trace_frames, centre)) status = 1;
    }
    if (video.is_open() && !video.close_and_report(o.video, kVideoFps)) status = 1;
    if (!o.png.empty()) {
        if (moments.empty())
            moments.push_back({"last frame", frames_run * kDt, pose, positions(cape), positions(skirt)});
        if (write_moments(o.png, moments, cape, skirt, &error)) {
            cloth_samples::print_written_moments(o.png, moments);
        } else {
            std::fprintf(stderr, "%s\n", error.c_str());
            status = 1;
        }
    }
    cloth_world_destroy(world);
    if (o.require == "all")
        std::printf("%s\n", status == 0 ? "all checks passed" : "CHECKS FAILED");
    else
        std::printf("%s (%s)\n", status == 0 ? "required checks passed" : "REQUIRED CHECKS FAILED",
                    o.require.c_str());
    return status;
}
