// bullet: the point-2 scenes in Bullet's btSoftBody (the cloth of
// btSoftBodyHelpers::CreatePatch with diagonal links plus bending links,
// 1 kg, the same particle grid, pins, gravity, wind, 1/60 s frames) next to
// this library's default settings, in one process. Bullet's links take a
// stiffness fraction (kLST in [0, 1]) and position iterations rather than
// N/m, so it runs at its stiffest link setting with its default and larger
// position-iteration counts; the comparison is time per step at equal or
// lower strain, strain measured the same way for both (structural grid
// neighbours, (L - l0) / l0).
#include <BulletSoftBody/btSoftBodyHelpers.h>
#include <BulletSoftBody/btSoftBodyRigidBodyCollisionConfiguration.h>
#include <BulletSoftBody/btSoftRigidDynamicsWorld.h>
#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>

#include "run_scene.h"
#include "study.h"

namespace tradeoff {

using cloth_samples::SceneConfig;
using cloth_samples::SceneKind;

namespace {

struct BulletRun {
    bool ok = true;
    double ms_per_frame = 0, max_strain = 0, mean_strain = 0;
};

// Structural strain over the grid's horizontal and vertical neighbours.
void grid_strain(const btSoftBody& body, uint32_t n, double& max_strain, double& mean_strain) {
    const double rest = 1.0 / (n - 1);
    double worst = -1e300, sum = 0;
    uint32_t count = 0;
    auto visit = [&](uint32_t a, uint32_t b) {
        const double strain = (body.m_nodes[int(a)].m_x - body.m_nodes[int(b)].m_x).length() / rest - 1.0;
        worst = std::max(worst, strain);
        sum += std::fabs(strain);
        ++count;
    };
    for (uint32_t row = 0; row < n; ++row) {
        for (uint32_t col = 0; col < n; ++col) {
            if (col + 1 < n) visit(row * n + col, row * n + col + 1);
            if (row + 1 < n) visit(row * n + col, (row + 1) * n + col);
        }
    }
    max_strain = worst;
    mean_strain = sum / count;
}

BulletRun run_bullet_scene(SceneKind kind, uint32_t n, int position_iterations, uint32_t frames) {
    btSoftBodyRigidBodyCollisionConfiguration configuration;
    btCollisionDispatcher dispatcher(&configuration);
    btDbvtBroadphase broadphase;
    btSequentialImpulseConstraintSolver solver;
    btSoftRigidDynamicsWorld world(&dispatcher, &broadphase, &solver, &configuration);
    const btVector3 gravity(0, -9.81f, 0);
    world.setGravity(gravity);
    btSoftBodyWorldInfo& info = world.getWorldInfo();
    info.m_gravity = gravity;
    info.air_density = 1.2f;
    info.m_sparsesdf.Initialize();

    // Same corners as scenes.cpp: particle (row, col) at origin + col u + row v.
    const btVector3 origin(0, 1.5f, 0), u(1, 0, 0),
        v = kind == SceneKind::kFallingFlat ? btVector3(0, 0, 1) : btVector3(0, -1, 0);
    btSoftBody* body = btSoftBodyHelpers::CreatePatch(info, origin, origin + u, origin + v, origin + u + v,
                                                      int(n), int(n), 0, true);
    body->m_materials[0]->m_kLST = 1.0f;
    body->generateBendingConstraints(2, body->m_materials[0]);
    body->setTotalMass(1.0f);
    body->m_cfg.piterations = position_iterations;
    body->m_cfg.aeromodel = btSoftBody::eAeroModel::V_TwoSidedLiftDrag;
    body->m_cfg.kDG = 1.0f;
    body->m_cfg.kLF = 0.5f;
    if (kind == SceneKind::kFlagInWind) {
        for (uint32_t row = 0; row < n; ++row) body->setMass(int(row * n), 0);
        body->setWindVelocity(btVector3(10.0f, 0, 1.0f));
    } else {
        body->setMass(0, 0);
        body->setMass(int(n - 1), 0);
    }
    world.addSoftBody(body);

    BulletRun out;
    std::vector<double> ms;
    for (uint32_t f = 0; f < frames; ++f) {
        const auto start = std::chrono::steady_clock::now();
        world.stepSimulation(1.0f / 60.0f, 1, 1.0f / 60.0f);
        ms.push_back(
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
        double max_strain, mean_strain;
        grid_strain(*body, n, max_strain, mean_strain);
        if (!std::isfinite(max_strain)) {
            out.ok = false;
            break;
        }
        out.max_strain = std::max(out.max_strain, max_strain);
        out.mean_strain = std::max(out.mean_strain, mean_strain);
    }
    std::nth_element(ms.begin(), ms.begin() + ms.size() / 2, ms.end());
    out.ms_per_frame = ms[ms.size() / 2];
    world.removeSoftBody(body);
    delete body;
    return out;
}

}  // namespace

int run_bullet(const BulletOptions& o) {
    std::FILE* csv = o.csv.empty() ? nullptr : std::fopen(o.csv.c_str(), "w");
    if (csv) {
        std::fprintf(csv,
                     "scene,resolution,stiffness,ours_ms,ours_max_strain,ours_mean_strain,bullet_piterations,"
                     "bullet_ms,bullet_max_strain,bullet_mean_strain,time_ratio,max_strain_ratio\n");
    }
    std::printf(
        "| scene | res | k (ours) | ours ms/step | ours max / mean strain | Bullet piterations | Bullet "
        "ms/step | Bullet max / mean strain | time ours/Bullet | max strain ours/Bullet |\n");
    std::printf("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
    for (uint32_t n : o.resolutions) {
        for (SceneKind kind : {SceneKind::kHanging, SceneKind::kFallingFlat, SceneKind::kFlagInWind}) {
            for (float k : {1e3f, 1e4f}) {
                SceneConfig config;
                config.kind = kind;
                config.resolution = n;
                config.stiffness = k;
                const RunResult ours = run_scene(config, 1.0f / 60.0f, o.frames);
                for (int piterations : {1, 4, 16}) {
                    const BulletRun theirs = run_bullet_scene(kind, n, piterations, o.frames);
                    const double time_ratio = ours.ms_per_frame / theirs.ms_per_frame;
                    const double strain_ratio = ours.max_strain / theirs.max_strain;
                    std::printf("| %s | %u | %g | %.3f | %.3f / %.4f | %d | %.3f | %s | %.2f | %.3g |\n",
                                cloth_samples::scene_name(kind), n, double(k), ours.ms_per_frame,
                                ours.max_strain, ours.mean_strain, piterations, theirs.ms_per_frame,
                                theirs.ok ? (std::to_string(theirs.max_strain).substr(0, 6) + " / " +
                                             std::to_string(theirs.mean_strain).substr(0, 6))
                                                .c_str()
                                          : "non-finite",
                                time_ratio, strain_ratio);
                    std::fflush(stdout);
                    if (csv) {
                        std::fprintf(csv, "%s,%u,%g,%.4f,%.5f,%.5f,%d,%.4f,%.5f,%.5f,%.4f,%.4g\n",
                                     cloth_samples::scene_name(kind), n, double(k), ours.ms_per_frame,
                                     ours.max_strain, ours.mean_strain, piterations, theirs.ms_per_frame,
                                     theirs.max_strain, theirs.mean_strain, time_ratio, strain_ratio);
                    }
                }
            }
        }
    }
    if (csv) std::fclose(csv);
    return 0;
}

}  // namespace tradeoff
