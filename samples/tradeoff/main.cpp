// tradeoff: the speed/accuracy study of the solver settings (docs/accuracy.md,
// docs/stability.md). Subcommands:
//   probe      one scene, one setting: a line of figures
//   default    the point-2 matrix with the default settings (pass/fail per scene)
//   pareto     every solver setting against a converged reference (CSV)
//   stability  stable/unstable per solver over stiffness, step, mass, resolution (CSV)
//   bullet     the same scenes in Bullet's btSoftBody, side by side (CSV)
// Figures are wall-clock medians on whatever machine runs it.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <map>
#include <string>

#include "run_scene.h"
#include "study.h"

using namespace tradeoff;

int main(int argc, char** argv) {
    CLI::App app{"Speed/accuracy study of the cloth solvers"};
    app.require_subcommand(1);

    ProbeOptions probe;
    CLI::App* probe_cmd = app.add_subcommand("probe", "run one scene with one setting");
    probe_cmd->add_option("--scene", probe.scene, "hanging, falling_flat, flag_in_wind, draped_sphere");
    probe_cmd->add_option("--resolution", probe.resolution);
    probe_cmd->add_option("--stiffness", probe.stiffness);
    probe_cmd->add_option("--solver", probe.solver, "default, jacobi, pcg, chebyshev, cg, explicit");
    probe_cmd->add_option("--iterations", probe.iterations);
    probe_cmd->add_option("--substeps", probe.substeps);
    probe_cmd->add_option("--strain-limit", probe.strain_limit);
    probe_cmd->add_option("--dt", probe.dt);
    probe_cmd->add_option("--frames", probe.frames);

    MatrixOptions matrix;
    CLI::App* default_cmd = app.add_subcommand("default", "point-2 matrix with default settings");
    default_cmd->add_option("--frames", matrix.frames);
    default_cmd->add_option("--resolutions", matrix.resolutions)->delimiter(',');
    default_cmd->add_option("--csv", matrix.csv);
    default_cmd->add_flag(
        "--still-air", matrix.still_air,
        "no air, drag or lift (springs and gravity only; the scenes' springs are undamped)");

    ParetoOptions pareto;
    CLI::App* pareto_cmd = app.add_subcommand("pareto", "every setting against a converged reference");
    pareto_cmd->add_option("--resolution", pareto.resolution);
    pareto_cmd->add_option("--seconds", pareto.seconds, "simulated time per run");
    pareto_cmd->add_option("--stiffness", pareto.stiffness);
    pareto_cmd->add_option("--csv", pareto.csv);
    pareto_cmd->add_flag("--default-only", pareto.default_only,
                         "only the DEFAULT at 1/60 s against the reference");
    pareto_cmd->add_option(
        "--scenes", pareto.scenes,
        "scenes to run: hanging, falling_flat, flag_in_wind, draped_sphere (default: all)");

    StabilityOptions stability;
    CLI::App* stability_cmd = app.add_subcommand("stability", "stability map");
    stability_cmd->add_option("--csv", stability.csv);
    stability_cmd->add_option("--frames", stability.frames);

    BulletOptions bullet;
    CLI::App* bullet_cmd = app.add_subcommand("bullet", "side by side with btSoftBody");
    bullet_cmd->add_option("--frames", bullet.frames);
    bullet_cmd->add_option("--resolutions", bullet.resolutions)->delimiter(',');
    bullet_cmd->add_option("--csv", bullet.csv);

    CLI11_PARSE(app, argc, argv);
    if (*probe_cmd) return run_probe(probe);
    if (*default_cmd) return run_default_matrix(matrix);
    if (*pareto_cmd) return run_pareto(pareto);
    if (*stability_cmd) return run_stability(stability);
    if (*bullet_cmd) return run_bullet(bullet);
    return 1;
}
