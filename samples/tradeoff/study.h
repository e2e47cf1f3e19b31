// The study's subcommands (main.cpp lists them).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "scenes.h"

namespace tradeoff {

struct ProbeOptions {
    std::string scene = "falling_flat";
    uint32_t resolution = 64;
    float stiffness = 1000.0f;
    std::string solver = "default";
    uint32_t iterations = 1;
    uint32_t substeps = 1;
    float strain_limit = 0;
    float dt = 1.0f / 60.0f;
    uint32_t frames = 300;
};

struct MatrixOptions {
    uint32_t frames = 600;
    bool still_air = false;  // air, drag and (the scenes' default) spring damping off
    std::vector<uint32_t> resolutions = {32, 64, 128};
    std::string csv;
};

struct ParetoOptions {
    // Scene names (cloth_samples::scene_name); empty: every scene.
    std::vector<std::string> scenes;
    uint32_t resolution = 64;
    float seconds = 1.0f;
    float stiffness = 1000.0f;
    std::string csv;
    bool default_only = false;  // only the DEFAULT at 1/60 s against the reference
};

struct StabilityOptions {
    std::string csv;
    uint32_t frames = 120;
};

struct BulletOptions {
    uint32_t frames = 600;
    std::vector<uint32_t> resolutions = {32, 64};
    std::string csv;
};

bool parse_scene(const std::string& name, cloth_samples::SceneKind& out);
bool parse_solver(const std::string& name, cloth_solver_kind& out);

int run_probe(const ProbeOptions& options);
int run_default_matrix(const MatrixOptions& options);
int run_pareto(const ParetoOptions& options);
int run_stability(const StabilityOptions& options);
int run_bullet(const BulletOptions& options);

}  // namespace tradeoff
