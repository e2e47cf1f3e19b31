// cloth_create rejects bad descriptions and values with their codes and changes nothing.
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "bad_input/fixture.h"

namespace cloth_bad_input {
namespace {

struct DescCase {
    std::string what;
    std::function<void(cloth_desc&)> change;
    cloth_result expected;
};

void AddSpringCases(std::vector<DescCase>& cases) {
    using P = cloth_spring_params cloth_desc::*;
    const std::pair<const char*, P> kinds[] = {
        {"structural", &cloth_desc::structural}, {"shear", &cloth_desc::shear}, {"bend", &cloth_desc::bend}};
    for (const auto& [name, member] : kinds) {
        const std::string n = name;
        const P m = member;
        cases.push_back({n + ".stiffness = -1", [m](cloth_desc& d) { (d.*m).stiffness = -1.0f; },
                         CLOTH_ERROR_INVALID_VALUE});
        cases.push_back({n + ".damping = -0.5", [m](cloth_desc& d) { (d.*m).damping = -0.5f; },
                         CLOTH_ERROR_INVALID_VALUE});
        cases.push_back({n + ".stiffness = NaN", [m](cloth_desc& d) { (d.*m).stiffness = kNaN; },
                         CLOTH_ERROR_NOT_FINITE});
        cases.push_back({n + ".stiffness = inf", [m](cloth_desc& d) { (d.*m).stiffness = kInf; },
                         CLOTH_ERROR_NOT_FINITE});
        cases.push_back(
            {n + ".damping = inf", [m](cloth_desc& d) { (d.*m).damping = kInf; }, CLOTH_ERROR_NOT_FINITE});
        cases.push_back(
            {n + ".damping = NaN", [m](cloth_desc& d) { (d.*m).damping = kNaN; }, CLOTH_ERROR_NOT_FINITE});
    }
}

TEST_F(BadInput, CreateClothWithADescNotFromDefaultOrAWrongSizeReturnsInvalidDesc) {
    for (const auto& broken : BrokenDescs(ValidClothDesc())) {
        SCOPED_TRACE(broken.first);
        const cloth_desc& desc = broken.second;
        EXPECT_REJECTED(CLOTH_ERROR_INVALID_DESC, cloth_create(a_.world, &desc, &outs_.cloth));
    }
    // The nested solver settings carry their own struct_size.
    for (uint32_t size :
         {0u, uint32_t(sizeof(cloth_solver_settings) - 1), uint32_t(sizeof(cloth_solver_settings) + 1)}) {
        SCOPED_TRACE("desc.solver.struct_size " + std::to_string(size));
        cloth_desc desc = ValidClothDesc();
        desc.solver.struct_size = size;
        EXPECT_REJECTED(CLOTH_ERROR_INVALID_DESC, cloth_create(a_.world, &desc, &outs_.cloth));
    }
}

TEST_F(BadInput, CreateClothWithNonPositiveOrNonFiniteAreaDensityIsRejected) {
    const std::pair<float, cloth_result> cases[] = {
        {0.0f, CLOTH_ERROR_INVALID_VALUE},  {-0.0f, CLOTH_ERROR_INVALID_VALUE},
        {-0.2f, CLOTH_ERROR_INVALID_VALUE}, {kNaN, CLOTH_ERROR_NOT_FINITE},
        {kInf, CLOTH_ERROR_NOT_FINITE},     {-kInf, CLOTH_ERROR_NOT_FINITE},
    };
    for (const auto& [density, expected] : cases) {
        SCOPED_TRACE("area_density = " + std::to_string(density));
        cloth_desc desc = ValidClothDesc();
        desc.area_density = density;
        EXPECT_REJECTED(expected, cloth_create(a_.world, &desc, &outs_.cloth));
    }
}

TEST_F(BadInput, CreateClothWithNegativeOrNonFiniteParticleMassIsRejected) {
    const std::pair<float, cloth_result> cases[] = {
        {-0.01f, CLOTH_ERROR_INVALID_VALUE},
        {-kInf, CLOTH_ERROR_NOT_FINITE},
        {kNaN, CLOTH_ERROR_NOT_FINITE},
        {kInf, CLOTH_ERROR_NOT_FINITE},
    };
    for (const auto& [mass, expected] : cases) {
        SCOPED_TRACE("particle_mass = " + std::to_string(mass));
        cloth_desc desc = ValidClothDesc();
        desc.particle_mass = mass;
        EXPECT_REJECTED(expected, cloth_create(a_.world, &desc, &outs_.cloth));
    }
}

TEST_F(BadInput, CreateClothWithANonFiniteInitialPositionReturnsNotFinite) {
    std::vector<float> start(kFloats);
    ASSERT_EQ(cloth_read_positions(a_.cloth, start.data(), kFloats), CLOTH_OK);
    for (uint32_t i : {0u, kFloats / 2 + 1, kFloats - 1}) {
        for (float bad : {kNaN, kInf, -kInf}) {
            SCOPED_TRACE("initial_positions[" + std::to_string(i) + "] = " + std::to_string(bad));
            std::vector<float> positions = start;
            positions[i] = bad;
            cloth_desc desc = ValidClothDesc();
            desc.initial_positions = positions.data();
            EXPECT_REJECTED(CLOTH_ERROR_NOT_FINITE, cloth_create(a_.world, &desc, &outs_.cloth));
        }
    }
}

TEST_F(BadInput, CreateClothWithNegativeOrNonFiniteSpringParamsIsRejected) {
    std::vector<DescCase> cases;
    AddSpringCases(cases);
    for (const DescCase& c : cases) {
        SCOPED_TRACE(c.what);
        cloth_desc desc = ValidClothDesc();
        c.change(desc);
        EXPECT_REJECTED(c.expected, cloth_create(a_.world, &desc, &outs_.cloth));
    }
}

TEST_F(BadInput, CreateClothWithOutOfRangeSolverSettingsIsRejected) {
    for (const auto& [what, change, expected] : BadSolver()) {
        SCOPED_TRACE("desc.solver: " + what);
        cloth_desc desc = ValidClothDesc();
        change(desc.solver);
        EXPECT_REJECTED(expected, cloth_create(a_.world, &desc, &outs_.cloth));
    }
}

TEST_F(BadInput, CreateClothWithOutOfRangeAeroParamsIsRejected) {
    for (const auto& [what, change, expected] : BadAero()) {
        SCOPED_TRACE("desc.aero: " + what);
        cloth_desc desc = ValidClothDesc();
        change(desc.aero);
        EXPECT_REJECTED(expected, cloth_create(a_.world, &desc, &outs_.cloth));
    }
}

TEST_F(BadInput, CreatingMoreClothsThanMaxClothsReturnsCapacity) {
    check_twin_ = false;
    const cloth_desc desc = ValidClothDesc();
    cloth_id third{};
    ASSERT_EQ(cloth_create(a_.world, &desc, &third), CLOTH_OK) << "the fixture leaves one slot free";
    EXPECT_REJECTED(CLOTH_ERROR_CAPACITY, cloth_create(a_.world, &desc, &outs_.cloth));
}

TEST_F(BadInput, CreateClothWhenTheAllocatorFailsReturnsOutOfMemoryLeaksNothingAndTheWorldStillWorks) {
    check_twin_ = false;
    const cloth_desc desc = ValidClothDesc();
    int failures = 0;
    bool created = false;
    cloth_id cloth{};
    for (long n = 0; n < 10000 && !created; ++n) {
        a_.host.fail_after(n);
        SCOPED_TRACE("allocator fails after " + std::to_string(n) + " allocations");
        const size_t live_before = a_.host.live_bytes();
        const size_t calls_before = a_.host.allocations();
        const ClothState before = ReadState(a_.cloth);
        cloth_id out = cloth_id{0xA5A5, 0xA5A5, 0xA5A5, 0xA5A5};
        const cloth_test::CallOutcome o =
            cloth_test::call_on_fresh_thread([&] { return cloth_create(a_.world, &desc, &out); });
        a_.host.fail_after(-1);
        if (o.result == CLOTH_OK) {
            created = true;
            cloth = out;
            EXPECT_EQ(a_.host.allocations() - calls_before, static_cast<size_t>(n))
                << "cloth_create succeeded after a NULL from the allocator";
            break;
        }
        ++failures;
        ++cloth_test::bad_inputs();
        EXPECT_EQ(o.result, CLOTH_ERROR_OUT_OF_MEMORY) << result_name(o.result);
        EXPECT_NE(o.error_after, "");
        EXPECT_EQ(a_.host.live_bytes(), live_before) << "memory leaked by a failed cloth_create";
        EXPECT_TRUE(out == (cloth_id{0xA5A5, 0xA5A5, 0xA5A5, 0xA5A5})) << "out_cloth written on failure";
        EXPECT_TRUE(SameState(before, ReadState(a_.cloth)));
        ASSERT_FALSE(HasFailure()) << "stopping at the first failing allocation count";
    }
    EXPECT_GE(failures, 1) << "cloth_create never used the world's allocator";
    ASSERT_TRUE(created);
    // The world still works: it steps, and the new cloth is a full cloth.
    EXPECT_EQ(cloth_step(a_.world, kFrame), CLOTH_OK) << cloth_get_last_error();
    const ClothState s = ReadState(cloth);
    EXPECT_EQ(s.count, kParticles);
    EXPECT_TRUE(AllFinite(s.positions));
    EXPECT_EQ(cloth_destroy(cloth), CLOTH_OK);
}

}  // namespace
}  // namespace cloth_bad_input
