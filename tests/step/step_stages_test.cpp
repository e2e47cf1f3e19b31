// The staged step: running a frame's stages through any task system, with
// the groups split into any ranges and run in any order on any worker,
// gives the same bits as running them serially.
#include <gtest/gtest.h>

#include <cstring>

#include "collide/self_collision.h"
#include "jobs/task_system.h"
#include "test_support.h"

namespace cloth {
namespace {

using cloth::testing::make_grid;
using cloth::testing::make_mesh_from_grid;
using cloth::testing::perturb;

const Vec3 kGravity(0.0f, -9.81f, 0.0f);

// Runs every item as its own range, last item first, each on a different
// worker: the most hostile legal schedule a single thread can produce.
class ReversedSingleItems final : public TaskSystem {
  public:
    uint32_t worker_count() const override { return 7; }
    void parallel_for(uint32_t count, uint32_t, RangeTask task, void* context) override {
        for (uint32_t i = count; i-- > 0;) task(i, i + 1, i % 7, context);
        ++calls;
    }
    uint32_t calls = 0;
};

struct Case {
    const char* name;
    bool mesh;
    cloth_solver_kind kind;
    uint32_t iterations, substeps;
    bool air;
    int frames;
    float stiffness = 300.0f;
    float damping = 0.2f;
};

std::vector<float> run(const Case& c, TaskSystem* tasks) {
    // 40 x 30 = 1200 particles: five groups, the last one partial.
    auto fabric = c.mesh ? make_mesh_from_grid(40, 30) : make_grid(40, 30);
    SolverSettings solver;
    solver.kind = c.kind;
    solver.iterations = c.iterations;
    solver.substeps = c.substeps;
    AeroParams air;
    air.wind = Vec3(6.0f, 0.0f, 2.0f);
    if (!c.air) air.air_density = 0;
    ClothInstance cloth(cloth::testing::heap(), fabric,
                        cloth::testing::uniform_material(c.stiffness, c.damping, 0.2f), solver, air);
    cloth.pin(0);
    cloth.pin(39);
    cloth.pin(700);  // inside a middle group
    perturb(cloth, 0.01f);
    for (int frame = 0; frame < c.frames; ++frame) {
        cloth.set_pin_target(39, Vec3(1.0f + 0.01f * frame, 0.0f, 0.0f));
        const Status status = cloth.step(1.0f / 60.0f, kGravity, tasks);
        EXPECT_TRUE(status.ok()) << c.name << ": " << status.message;
    }
    std::vector<float> out;
    for (const Vec3Soa* a : {&cloth.positions(), &cloth.velocities()}) {
        for (uint32_t i = 0; i < cloth.particle_count(); ++i)
            out.insert(out.end(), {a->x[i], a->y[i], a->z[i]});
    }
    return out;
}

TEST(StepStages, AnyScheduleOfTheGroupsGivesTheSerialBits) {
    const Case cases[] = {
        {"grid jacobi k=1", false, CLOTH_SOLVER_JACOBI, 1, 1, true, 20},
        {"grid jacobi k=4 substeps 3", false, CLOTH_SOLVER_JACOBI, 4, 3, true, 20},
        {"grid jacobi still air", false, CLOTH_SOLVER_JACOBI, 2, 1, false, 20},
        {"mesh jacobi k=3", true, CLOTH_SOLVER_JACOBI, 3, 2, true, 20},
        {"grid cg", false, CLOTH_SOLVER_CG, 1, 1, true, 2},
        {"grid pcg k=8 substeps 2", false, CLOTH_SOLVER_PCG, 8, 2, true, 20},
        {"mesh pcg k=6", true, CLOTH_SOLVER_PCG, 6, 1, true, 10},
        {"grid chebyshev k=6 substeps 4", false, CLOTH_SOLVER_CHEBYSHEV, 6, 4, true, 10, 20.0f, 0.05f},
        {"grid default (pcg, strain limit)", false, CLOTH_SOLVER_DEFAULT, 1, 1, true, 10, 3000.0f},
        // Explicit Euler needs small steps to stay finite at this stiffness.
        {"grid explicit", false, CLOTH_SOLVER_EXPLICIT, 1, 64, true, 5, 20.0f, 0.001f},
    };
    for (const Case& c : cases) {
        const std::vector<float> serial = run(c, nullptr);
        ReversedSingleItems hostile;
        const std::vector<float> scheduled = run(c, &hostile);
        ASSERT_EQ(serial.size(), scheduled.size());
        EXPECT_EQ(std::memcmp(serial.data(), scheduled.data(), serial.size() * sizeof(float)), 0) << c.name;
        EXPECT_GT(hostile.calls, 0u) << c.name;
    }
}

TEST(StepStages, EveryParticleStageHasOneTaskPerGroupOfAtMostGroupSizeParticles) {
    auto fabric = make_grid(40, 30);
    ClothInstance cloth(cloth::testing::heap(), fabric, Material{}, SolverSettings{}, AeroParams{});
    EXPECT_EQ(cloth.group_count(), (1200u + ClothInstance::kGroupSize - 1) / ClothInstance::kGroupSize);
    cloth.begin_frame_alone(1.0f / 60.0f, kGravity, BudgetBounds{});
    uint32_t stages = 0;
    while (!cloth.frame_done()) {
        cloth.prepare_stage();
        EXPECT_EQ(cloth.task_count(), cloth.group_count()) << stage_name(cloth.stage());
        for (uint32_t t = 0; t < cloth.task_count(); ++t) cloth.run_task(t, 0);
        cloth.finish_stage();
        ++stages;
    }
    EXPECT_TRUE(cloth.end_frame().ok());
    // Air, forces, assembly, one sweep, integration.
    EXPECT_EQ(stages, 5u);
}

// The stage of every round of one frame, consecutive repeats (a solver's
// iterations, strain-limit rounds, projection passes) folded into one.
std::vector<Stage> stage_sequence(ClothInstance& cloth) {
    std::vector<Stage> seen;
    cloth.begin_frame_alone(1.0f / 60.0f, kGravity, BudgetBounds{});
    while (!cloth.frame_done()) {
        cloth.prepare_stage();
        if (seen.empty() || seen.back() != cloth.stage()) seen.push_back(cloth.stage());
        for (uint32_t t = 0; t < cloth.task_count(); ++t) cloth.run_task(t, 0);
        cloth.finish_stage();
    }
    EXPECT_TRUE(cloth.end_frame().ok());
    return seen;
}

// The order frame_plan.cpp writes down, with every optional stage on: air,
// a staged solver, self-collision, and a strain limit whose pass is
// followed by a projection of the self-collision's contacts and, after the
// last, the self-collision's response, over two substeps (the calm cloth
// needs one pass).
TEST(StepStages, AFrameRunsThePlannedStagesInThePlannedOrderEverySubstep) {
    auto fabric = make_grid(40, 30);
    SolverSettings solver;
    solver.kind = CLOTH_SOLVER_PCG;
    solver.iterations = 4;
    solver.substeps = 2;
    solver.strain_limit.max_strain = 0.05f;
    ClothInstance cloth(cloth::testing::heap(), fabric, Material{}, solver, AeroParams{});
    cloth.pin(0);
    SelfCollisionSettings self;
    self.thickness = 0.5f * mean_rest_edge(*fabric);
    cloth.set_self_collision(&self);
    const std::vector<Stage> substep = {
        Stage::kAir,         Stage::kForces,        Stage::kAssemble,    Stage::kIterativeSolve,
        Stage::kIntegrate,   Stage::kSelfCollision, Stage::kSelfSort,    Stage::kSelfContacts,
        Stage::kSelfProject, Stage::kStrainLimit,   Stage::kSelfProject, Stage::kSelfRespond};
    std::vector<Stage> expected = substep;
    expected.insert(expected.end(), substep.begin(), substep.end());
    const std::vector<Stage> seen = stage_sequence(cloth);
    ASSERT_EQ(seen.size(), expected.size());
    for (size_t i = 0; i < seen.size(); ++i) {
        EXPECT_EQ(seen[i], expected[i])
            << i << ": " << stage_name(seen[i]) << " where the plan has " << stage_name(expected[i]);
    }
}

// A feature that is off adds no stage; the explicit baseline replaces the
// assembly, the solve and the implicit integration.
TEST(StepStages, StagesThatAreOffAreNotRun) {
    auto fabric = make_grid(40, 30);
    SolverSettings solver;
    solver.kind = CLOTH_SOLVER_EXPLICIT;
    AeroParams still;
    still.air_density = 0;
    ClothInstance cloth(cloth::testing::heap(), fabric, Material{}, solver, still);
    const std::vector<Stage> seen = stage_sequence(cloth);
    ASSERT_EQ(seen.size(), 2u);
    EXPECT_EQ(seen[0], Stage::kForces);
    EXPECT_EQ(seen[1], Stage::kExplicit);
}

}  // namespace
}  // namespace cloth
