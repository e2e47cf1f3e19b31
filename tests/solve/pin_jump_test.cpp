// A cloth whose attachment jumps far for one frame, and a flag in gusty
// wind: what the strain limit keeps when its constraints cannot all hold
// or the step stirs the cloth hard, tried through the C API as a host
// would, beside an untouched twin cloth in the same world.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "cloth/cloth.h"
#include "pinned_cloth.h"
#include "run_scene.h"

namespace {

struct JumpCase {
    cloth_solver_kind kind;
    uint32_t iterations;
    bool library_defaults;  // else like-for-like: no spring damping, no air, no sleep
    bool set_positions;     // else cloth_set_pin_targets
    bool whole_edge;        // else the two top corners
    float z_noise;          // out-of-plane offsets of the rest shape, m
};

// Two 32x32 cloths of 1 kg over 1 m x 1 m, hanging from their pins, every
// spring kind 1e3 N/m but bend 1e2 (like-for-like) or the library's
// defaults; the first's particle 0 is moved 10 m in x for one frame.
class JumpScene {
  public:
    static constexpr uint32_t kSide = 32;
    static constexpr uint32_t kCount = kSide * kSide;

    explicit JumpScene(const JumpCase& c) : case_(c) {
        cloth_world_desc world_desc = cloth_default_world_desc();
        EXPECT_EQ(cloth_world_create(&world_desc, &world_), CLOTH_OK);
        cloth_grid_desc grid = cloth_default_grid_desc();
        cloth_fabric_id fabric{};
        EXPECT_EQ(cloth_fabric_create_grid(world_, &grid, &fabric), CLOTH_OK);
        std::vector<float> rest(3 * kCount);
        uint32_t seed = 12345;
        for (uint32_t i = 0; i < kCount; ++i) {
            seed = seed * 1664525u + 1013904223u;
            rest[3 * i] = float(i % kSide) / (kSide - 1);
            rest[3 * i + 1] = -float(i / kSide) / (kSide - 1);
            rest[3 * i + 2] = c.z_noise * (float(seed >> 8) / float(1u << 24) - 0.5f);
        }
        cloth_desc desc = cloth_default_desc();
        desc.fabric = fabric;
        desc.particle_mass = 1.0f / kCount;
        desc.initial_positions = rest.data();
        if (!c.library_defaults) {
            desc.structural = {1e3f, 0.0f};
            desc.shear = {1e3f, 0.0f};
            desc.bend = {1e2f, 0.0f};
            desc.aero.air_density = 0.0f;
            desc.aero.linear_drag = 0.0f;
        }
        desc.solver.kind = c.kind;
        desc.solver.iterations = c.iterations;
        desc.solver.cg_tolerance = 1e-2f;  // the reference solver, kept affordable for a test
        for (cloth_id* cloth : {&jumped_, &twin_}) {
            EXPECT_EQ(cloth_create(world_, &desc, cloth), CLOTH_OK);
            if (c.kind != CLOTH_SOLVER_DEFAULT) {  // the default's own limit for every kind
                cloth_strain_limit limit = cloth_default_strain_limit();
                limit.max_strain = 0.08f;
                EXPECT_EQ(cloth_set_strain_limit(*cloth, &limit), CLOTH_OK);
            }
            if (!c.library_defaults) {
                cloth_sleep_params sleep = cloth_default_sleep_params();
                sleep.enabled = false;
                EXPECT_EQ(cloth_set_sleep(*cloth, &sleep), CLOTH_OK);
            }
            std::vector<uint32_t> pins{0, kSide - 1};
            if (c.whole_edge) {
                pins.clear();
                for (uint32_t p = 0; p < kSide; ++p) pins.push_back(p);
            }
            EXPECT_EQ(cloth_pin(*cloth, pins.data(), static_cast<uint32_t>(pins.size())), CLOTH_OK);
        }
    }
    ~JumpScene() { cloth_world_destroy(world_); }

    cloth_result step() { return cloth_step(world_, 1.0f / 60.0f); }
    // Moves particle 0 of the first cloth to (x, y, z) as the case says.
    void move_pin(const float* to) {
        const uint32_t pin = 0;
        if (case_.set_positions) {
            ASSERT_EQ(cloth_set_positions(jumped_, &pin, to, 1), CLOTH_OK);
        } else {
            ASSERT_EQ(cloth_set_pin_targets(jumped_, &pin, to, 1), CLOTH_OK);
        }
    }
    std::vector<float> positions(cloth_id cloth) const {
        std::vector<float> x(3 * kCount);
        EXPECT_EQ(cloth_read_positions(cloth, x.data(), static_cast<uint32_t>(x.size())), CLOTH_OK);
        return x;
    }
    cloth_stats stats() const { return cloth::testing::stats_of(jumped_); }
    // The farthest any particle of the jumped cloth is from its twin's
    // (infinity if a coordinate is not finite).
    float distance_to_twin() const {
        const std::vector<float> a = positions(jumped_), b = positions(twin_);
        float worst = 0.0f;
        for (uint32_t i = 0; i < kCount; ++i) {
            const float dx = a[3 * i] - b[3 * i], dy = a[3 * i + 1] - b[3 * i + 1],
                        dz = a[3 * i + 2] - b[3 * i + 2];
            const float d = std::sqrt(dx * dx + dy * dy + dz * dz);
            worst = std::isfinite(d) ? std::max(worst, d) : INFINITY;
        }
        return worst;
    }

    cloth_id jumped() const { return jumped_; }

  private:
    JumpCase case_;
    cloth_world_id world_{};
    cloth_id jumped_{}, twin_{};
};

// What a jump and return did: the frames after the pin's return until the
// stretch is back within the promise (limit 0.08 + 0.02), or -1; the
// energy the jump's step added; and the distance to the twin and the
// promise's stat and kinetic energy 60 frames after the return.
struct JumpOutcome {
    int back_within = -1;
    double jump_energy = 0;
    float distance_after_60 = 0;
    double kinetic_after_60 = 0;
    uint8_t unmet_after_60 = 1;
};

double total_energy(const cloth_stats& s) { return s.kinetic_energy + s.gravity_energy + s.elastic_energy; }

// Settles, jumps particle 0 by 10 m for one frame and back, and checks
// what must hold on the way. The stats say whether the step met the
// strain limit's promise: the settled cloth does, the jump's step cannot
// and says so.
JumpOutcome jump_and_return(const JumpCase& c) {
    JumpScene scene(c);
    JumpOutcome out;
    for (int f = 0; f < 60; ++f) EXPECT_EQ(scene.step(), CLOTH_OK);
    // The explicit step is past its stability bound at 1e3 N/m and 1/60 s
    // (omega dt = 17): it does not settle within the promise.
    if (c.kind != CLOTH_SOLVER_EXPLICIT) {
        EXPECT_EQ(scene.stats().strain_limit_unmet, 0) << "settled, kind " << c.kind;
    }
    const double settled_energy = total_energy(scene.stats());
    const std::vector<float> start = scene.positions(scene.jumped());
    const float moved[] = {start[0] + 10.0f, start[1], start[2]};
    scene.move_pin(moved);
    EXPECT_EQ(scene.step(), CLOTH_OK) << "the jump";
    const cloth_stats jump = scene.stats();
    out.jump_energy = total_energy(jump) - settled_energy;
    EXPECT_EQ(jump.strain_limit_unmet, 1) << "the jump";
    EXPECT_GT(jump.strain_limit_excess, 1.0f) << "the jump";
    scene.move_pin(start.data());
    for (int f = 1; f <= 60; ++f) {
        EXPECT_EQ(scene.step(), CLOTH_OK) << "frame " << f << " after the return";
        const cloth_stats s = scene.stats();
        EXPECT_TRUE(std::isfinite(s.kinetic_energy) && std::isfinite(s.elastic_energy)) << "frame " << f;
        EXPECT_EQ(s.strain_limit_unmet, s.strain_limit_excess > 0.02f ? 1 : 0) << "frame " << f;
        if (out.back_within < 0 && s.max_strain <= 0.10f) out.back_within = f;
    }
    out.distance_after_60 = scene.distance_to_twin();
    out.unmet_after_60 = scene.stats().strain_limit_unmet;
    out.kinetic_after_60 = scene.stats().kinetic_energy;
    return out;
}

const JumpCase kKinds[] = {
    {CLOTH_SOLVER_DEFAULT, 1, false, false, false, 0.0f},
    {CLOTH_SOLVER_JACOBI, 1, false, false, false, 0.0f},
    {CLOTH_SOLVER_CG, 1, false, false, false, 0.0f},
    {CLOTH_SOLVER_EXPLICIT, 1, false, false, false, 0.0f},
    {CLOTH_SOLVER_PCG, 16, false, false, false, 0.0f},
    {CLOTH_SOLVER_CHEBYSHEV, 16, false, false, false, 0.0f},
    {CLOTH_SOLVER_DEFAULT, 1, true, true, true, 0.0f},
    {CLOTH_SOLVER_PCG, 16, true, true, true, 0.0f},
};

// The strain-limit passes once amplified an alternating pattern wherever
// every spring of a particle was far past the limit: this jump took the
// default to 1e6 m within the frame and left it 1.3e5 m from its twin for
// good, every step returning CLOTH_OK. Now every kind stays finite and
// hangs from its pins: no particle farther from its twin than the two
// cloths can be apart while both hang within the limit from the same pins
// (2.2 m for a 1 m cloth; the jumped cloth may come back folded over,
// which is as far from the twin as a cloth can be). It comes to rest
// there: 60 frames after the return its kinetic energy is under 1 J of
// the 1e5 J the jump put in (docs/accuracy.md: creased or turned over,
// not swinging). The explicit step, past its stability bound here, never
// settles.
TEST(PinJump, OnePinMovedTenMetresForOneFrameLeavesEveryKindFiniteAndRestingFromItsPins) {
    for (const JumpCase& c : kKinds) {
        const JumpOutcome out = jump_and_return(c);
        EXPECT_LT(out.distance_after_60, 2.5f) << "kind " << c.kind << (c.whole_edge ? ", whole edge" : "");
        if (c.kind != CLOTH_SOLVER_EXPLICIT) {
            EXPECT_LT(out.kinetic_after_60, 1.0) << "kind " << c.kind << (c.whole_edge ? ", whole edge" : "");
        }
    }
}

// The pins ask for more stretch than any limit gives: the 8 % limit held
// everywhere gathered it in the springs beside the moved pin, whose
// strain cable (100 times the spring) then held 4e6-1.3e7 J. The limit
// now gives way for the step to what the pins ask, and the jump adds no
// more energy than the fabric's own springs stretched between the pins
// hold (1.4e5-3e5 J here), for every kind, two pins or a pinned edge.
TEST(PinJump, TheJumpsStepAddsNoMoreEnergyThanTheFabricsSpringsBetweenThePinsHold) {
    for (const JumpCase& c : kKinds) {
        const JumpOutcome out = jump_and_return(c);
        EXPECT_LT(out.jump_energy, 1e6) << "kind " << c.kind << (c.whole_edge ? ", whole edge" : "");
        EXPECT_GT(out.jump_energy, 1e3) << "kind " << c.kind << ": the jump stretched the cloth";
    }
}

// A cloth a millimetre out of plane, as any cloth that has moved is: after
// the pin comes back, the strain limit's promise holds again within 30
// frames, with either call, two pins or a pinned edge, like-for-like or
// with the library's damping and air. (An exactly flat cloth can fold
// only within its plane, and such a fold holds springs past the limit:
// docs/accuracy.md.)
TEST(PinJump, ACurvedClothIsBackWithinTheLimitsPromiseWithinThirtyFramesOfThePinsReturn) {
    for (bool library_defaults : {false, true}) {
        for (bool set_positions : {false, true}) {
            for (bool whole_edge : {false, true}) {
                const JumpCase c{CLOTH_SOLVER_DEFAULT, 1, library_defaults, set_positions, whole_edge, 1e-3f};
                const JumpOutcome out = jump_and_return(c);
                EXPECT_GE(out.back_within, 1) << library_defaults << set_positions << whole_edge;
                EXPECT_LE(out.back_within, 30) << library_defaults << set_positions << whole_edge;
                EXPECT_EQ(out.unmet_after_60, 0) << library_defaults << set_positions << whole_edge;
                EXPECT_LT(out.distance_after_60, 2.5f);
                EXPECT_LT(out.kinetic_after_60, 1.0) << library_defaults << set_positions << whole_edge;
            }
        }
    }
}

// A 128x128 flag with its left column pinned in a cross breeze, undamped,
// the default solver on two workers: its structural springs once
// stretched within the promise but were left compressed by 12 % at frame
// 99 and 24 % at frame 371, where the passes pulled stretched springs in
// against their neighbours. Every step's row and column springs now stay
// within 0.10 of their rest length either way over the frames of the
// first spikes.
TEST(StrainLimitPromise, AWindyFlagOf128By128HoldsItsSpringsWithinTheLimitStretchedOrCompressed) {
    constexpr uint32_t side = 128;
    cloth_world_desc world_desc = cloth_default_world_desc();
    world_desc.worker_count = 2;
    cloth_world_id world{};
    ASSERT_EQ(cloth_world_create(&world_desc, &world), CLOTH_OK);
    cloth_grid_desc grid = cloth_default_grid_desc();
    grid.columns = grid.rows = side;
    grid.origin[0] = -0.5f;
    grid.origin[1] = 1.0f;
    cloth_fabric_id fabric{};
    ASSERT_EQ(cloth_fabric_create_grid(world, &grid, &fabric), CLOTH_OK);
    cloth_desc desc = cloth_default_desc();
    desc.fabric = fabric;
    desc.particle_mass = 1.0f / float(side * side - side);
    desc.structural = desc.shear = desc.bend = {1e3f, 0.0f};
    cloth_id flag{};
    ASSERT_EQ(cloth_create(world, &desc, &flag), CLOTH_OK);
    std::vector<uint32_t> column;
    for (uint32_t r = 0; r < side; ++r) column.push_back(r * side);
    ASSERT_EQ(cloth_pin(flag, column.data(), side), CLOTH_OK);
    cloth_sleep_params sleep = cloth_default_sleep_params();
    sleep.enabled = false;
    ASSERT_EQ(cloth_set_sleep(flag, &sleep), CLOTH_OK);
    const float wind[] = {10.0f, 0.0f, 1.0f};
    ASSERT_EQ(cloth_set_wind(flag, wind), CLOTH_OK);
    std::vector<float> x(3 * side * side);
    float worst = 0.0f;
    for (int f = 0; f < 110; ++f) {
        ASSERT_EQ(cloth_step(world, 1.0f / 60.0f), CLOTH_OK) << "frame " << f;
        ASSERT_EQ(cloth_read_positions(flag, x.data(), static_cast<uint32_t>(x.size())), CLOTH_OK);
        const float strain = static_cast<float>(tradeoff::grid_abs_strain(x, side));
        EXPECT_LE(strain, 0.10f) << "frame " << f;
        worst = std::max(worst, strain);
    }
    EXPECT_GT(worst, 0.05f) << "the flag is stretched: the limit is at work";
    cloth_world_destroy(world);
}

}  // namespace
