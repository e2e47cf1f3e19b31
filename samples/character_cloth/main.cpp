// character_cloth: a procedurally animated character (17 joints, a body of
// tapered capsules and spheres on them) wearing a cape and a skirt,
// through a clip of idle, walk, run, a sharp turn, a jump with its
// landing, a 360-degree spin and a teleport back to the start. Headless.
// Every frame it checks the garments (each particle within its max
// distance of its skinned position, outside its backstop, not inside the
// body, strain and speed bounded, kinetic energy relative to the skin
// within what the skin's own motion brings; wardrobe_checks.h); at the end
// it prints the budget table and the checks, one line per check with its
// pass or FAIL, and writes a picture of four moments. Exit status 0 only
// when every check held (or every one --require names). The run around
// the scene (options, budget table, trace, video, exit status) is the
// samples' shared harness (samples/common/sample_run.h).
#include <cloth/cloth.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "body.h"
#include "picture.h"
#include "render_png.h"
#include "run_options.h"
#include "sample_run.h"
#include "skeleton.h"
#include "solver_options.h"
#include "step_effort.h"
#include "verdict.h"
#include "wardrobe.h"
#include "wardrobe_checks.h"

using namespace character_cloth;

namespace {

constexpr float kDt = 1.0f / 60.0f;
constexpr uint32_t kProfileTasks = 8192;
constexpr int kVideoWidth = 640, kVideoHeight = 400;

struct Options {
    // --frames (0: the whole clip), --threads, --budget, --png, --video, --trace, --trace-frames
    cloth_samples::RunOptions run;
    // --solver, --iterations, --substeps (0: see solver_plan), --quality-policy, --policy-max-substeps,
    // as vehicle_flag's, for both garments
    cloth_samples::SolverOptions solving;
    float garment_contact = 0.02f;      // m: the cape and the skirt's contact thickness (0: off)
    float stiffness_offset = 0;         // N/m added to both garments' structural stiffness
    float cape_self_collision = 0.01f;  // m: the cape's self-collision thickness (0: off)
    CheckBounds checks;
    std::string require = "all";  // the checks that decide the exit status (WardrobeChecks::names)

    Options() { run.png = "character_cloth.png"; }
};

void add_options(CLI::App& app, Options* o, const cloth_samples::Verdict& verdict) {
    cloth_samples::add_run_options(
        app, &o->run,
        {"the whole clip", "picture of four moments of the clip", "the second around the jump"});
    cloth_samples::add_solver_options(app, &o->solving);
    cloth_samples::add_quality_policy_options(app, &o->solving, "the garments'");
    CheckBounds& c = o->checks;
    app.add_option("--max-strain", c.max_strain, "check: bound on the garments' max stretch");
    app.add_option("--max-speed", c.max_speed, "check: bound on the garments' max particle speed, m/s");
    app.add_option("--energy-margin-speed", c.energy_margin_speed,
                   "check: the garments' free particles' kinetic energy relative to the skin stays within "
                   "the skin's own peak over the last second plus 1/2 M v^2 with this v, m/s (M: the "
                   "garments' mass)")
        ->check(CLI::NonNegativeNumber);
    app.add_option("--hem-trailing", c.hem_trailing,
                   "check: fraction of running frames with the cape's hem behind the shoulders");
    app.add_option("--stiffness-offset", o->stiffness_offset,
                   "N/m added to both garments' structural stiffness (1000 N/m): the clip's figures are "
                   "chaotic, and a few hundredths of a N/m show how far they move");
    app.add_option("--garment-contact", o->garment_contact,
                   "contact thickness between the cape and the skirt, m (0: off; the check asks for half "
                   "of it between any two of their particles)")
        ->check(CLI::NonNegativeNumber);
    app.add_option("--cape-self-collision", o->cape_self_collision,
                   "self-collision thickness of the cape, which the spin folds onto itself, m (0: off)")
        ->check(CLI::NonNegativeNumber);
    app.add_option("--tolerance", c.tolerance,
                   "check: how far past a max distance, into a backstop or into the body, m");
    verdict.add_require_option(app, &o->require);
}

// Iterations and substeps per solver kind when --iterations or --substeps
// is 0: vehicle_flag's for the same kinds (docs/vehicle_flag.md), at the
// same 60 Hz and structural stiffness (1000 N/m), not tuned for the
// garments. The default picks its own; the explicit kind needs the light
// spring damping vehicle_flag gives it, which the garments do not have.
cloth_samples::SolverPlan solver_plan(cloth_solver_kind kind) {
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

// The garments' contact with each other and the cape's with itself, at
// the thicknesses asked (0: off); false with a message.
bool set_collisions(const Options& o, const Garment& cape, const Garment& skirt, std::string* error) {
    if (o.garment_contact > 0.0f) {
        cloth_cloth_contact_desc contact = cloth_default_cloth_contact_desc();
        contact.enabled = 1;
        contact.thickness = o.garment_contact;
        if (cloth_set_cloth_contact(cape.cloth, skirt.cloth, &contact) != CLOTH_OK) {
            *error = std::string("cloth_set_cloth_contact: ") + cloth_get_last_error();
            return false;
        }
    }
    if (o.cape_self_collision > 0.0f) {
        cloth_self_collision_desc self = cloth_default_self_collision_desc();
        self.enabled = 1;
        self.thickness = o.cape_self_collision;
        if (cloth_set_self_collision(cape.cloth, &self) != CLOTH_OK) {
            *error = std::string("cloth_set_self_collision: ") + cloth_get_last_error();
            return false;
        }
    }
    return true;
}

// The same solver settings for every garment; false with a message.
bool set_solver(const cloth_solver_settings& solver, const Garment* const (&garments)[2],
                std::string* error) {
    for (const Garment* g : garments) {
        if (cloth_set_solver(g->cloth, &solver) != CLOTH_OK) {
            *error = g->name + ": solver: " + cloth_get_last_error();
            return false;
        }
    }
    return true;
}

// One moment of the run, drawn after the fact.
struct Moment {
    std::string label;
    float time = 0;
    Pose pose;
    std::vector<float> cape, skirt;
};

std::vector<float> positions(const Garment& g) {
    std::vector<float> x(3 * g.count);
    cloth_read_positions(g.cloth, x.data(), 3 * g.count);
    return x;
}

Moment capture(const char* label, float time, const Pose& pose, const Garment& cape, const Garment& skirt) {
    return {label, time, pose, positions(cape), positions(skirt)};
}

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
    cloth_samples::Verdict verdict(WardrobeChecks::names());
    add_options(app, &o, verdict);
    CLI11_PARSE(app, argc, argv);
    if (!verdict.require(o.require)) return 2;

    cloth_samples::SampleRun run(o.run, kProfileTasks);
    cloth_world_desc world_desc = cloth_default_world_desc();
    world_desc.worker_count = o.run.threads;
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
    const Garment* const garments[] = {&cape, &skirt};
    // The solver options, for both garments.
    const cloth_samples::SolverPlan plan = solver_plan(cloth_samples::solver_kind(o.solving.solver));
    const cloth_solver_settings solver = cloth_samples::solver_settings(o.solving, plan);
    std::string error;
    if (!body.create(world, pose, &error) || !make_cape(world, body.root(), &cape, &error) ||
        !make_skirt(world, body.root(), &skirt, &error) || !set_collisions(o, cape, skirt, &error) ||
        !set_solver(solver, garments, &error)) {
        std::fprintf(stderr, "%s\n", error.c_str());
        return 1;
    }
    const cloth_id cloths[] = {cape.cloth, skirt.cloth};
    if (!cloth_samples::apply_quality_policy(o.solving, world, o.run.budget_ms, cloths, 2)) return 1;
    uint32_t free_particles = 0;
    for (const Garment* g : garments) {
        for (float d : g->max_distance) free_particles += d > 0.0f;
    }
    std::printf(
        "character_cloth: %u joints, %zu body colliders; cape %u and skirt %u particles (%u free, the rest "
        "sewn on at max distance 0), solver %s, iterations %u, substeps %u%s%s, %u thread(s)\n",
        static_cast<uint32_t>(kJointCount), CharacterBody::parts().size(), cape.count, skirt.count,
        free_particles, o.solving.solver.c_str(), solver.iterations, solver.substeps,
        cloth_samples::plan_note(o.solving, plan).c_str(),
        o.solving.quality_policy ? ", quality policy on" : "", o.run.threads);
    WardrobeChecks::print_head();

    // The budget table's rows and the trace's tracks, in their order.
    cloth_samples::FrameTimer& timer = run.timer();
    run.profile().add_stage_rows(&run.table());
    const auto cloth_part = timer.part("cloth step", "cloth_step", "cloth");
    const auto checks_part = timer.part(nullptr, "checks", "checks");
    WardrobeChecks checks(o.checks, cape, skirt, o.garment_contact, o.cape_self_collision, kDt);
    StepEffort effort(cape, skirt);
    cloth_samples::Picture<Moment> picture(o.run.png);
    const auto draw = [&](const Moment& m, int width, int height, std::vector<uint8_t>* rgb,
                          std::string* error) {
        return render_moment(m, cape, skirt, width, height, rgb, error);
    };
    int failed_calls = 0, frames_run = 0, jump_frame = -1;
    if (!run.open_video(kVideoWidth, kVideoHeight)) return 1;
    const int clip_frames = static_cast<int>(Clip::kDuration / kDt);
    for (int frame = 0; run.more_frames(frame, frame >= clip_frames); ++frame) {
        const float time = frame * kDt;
        run.begin_frame(frame);
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
        const cloth_result step = timer.time(cloth_part, [&] { return cloth_step(world, kDt); });
        if (step != CLOTH_OK) {
            ++failed_calls;
            std::fprintf(stderr, "frame %d: cloth_step: %s (%s)\n", frame, cloth_result_name(step),
                         cloth_get_last_error());
        }
        run.profile().record(world);
        run.end_frame();

        // Checks on the state at the end of the frame (outside its timing).
        const double checks_start_us = timer.now_us();
        const Phase phase = clip.phase(time);
        const bool ok = checks.observe(pose, phase, frame, teleported, step == CLOTH_OK, &failed_calls);
        effort.observe(phase, cloth_part.row->back());
        ++frames_run;
        timer.end_part(checks_part, checks_start_us);
        if (phase == Phase::kJump && jump_frame < 0) jump_frame = frame;
        if (frame % 60 == 0 || (!ok && checks.bad_frames() <= 5)) checks.print_frame(frame, time, phase, ok);
        if (const MomentPlan* m = picture.due(kMoments, [&](const MomentPlan& p) { return time >= p.time; }))
            picture.add(capture(m->label, time, pose, cape, skirt));
        if (run.video().due(frame)) {
            const Moment now = capture("", time, pose, cape, skirt);
            const auto draw_now = [&](int width, int height, auto* rgb, auto* error) {
                return draw(now, width, height, rgb, error);
            };
            if (!run.video().add(draw_now, "frame " + std::to_string(frame))) return 1;
        }
    }

    std::printf("\nclip: %d frames (%.1f s)\n", frames_run, frames_run * kDt);
    run.print_timings("frame timings", "stage", 20);
    effort.print(*cloth_part.row, free_particles, frames_run);
    checks.print(frames_run, failed_calls, clip);
    checks.set_verdicts(failed_calls, &verdict);
    verdict.print_checks();

    if (!run.write_trace(jump_frame >= 0 ? jump_frame : std::max(0, frames_run - 30))) verdict.fail_output();
    if (!run.video().finish()) verdict.fail_output();
    const auto last_frame = [&] { return capture("last frame", frames_run * kDt, pose, cape, skirt); };
    if (!picture.finish_panels(last_frame, 480, 400, draw)) verdict.fail_output();
    cloth_world_destroy(world);
    return verdict.finish();
}
