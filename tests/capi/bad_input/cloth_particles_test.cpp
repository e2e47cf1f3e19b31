// Bad reads, positions, pins and pin targets are rejected and no particle changes.
#include <cstdint>
#include <cstring>
#include <string>

#include "bad_input/fixture.h"

namespace cloth_bad_input {
namespace {

TEST_F(BadInput, ClothFunctionsRejectEachNullPointerAndChangeNothing) {
    const cloth_desc desc = ValidClothDesc();
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_create(a_.world, nullptr, &outs_.cloth));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_create(a_.world, &desc, nullptr));
    const cloth_id c = a_.cloth;
    const uint32_t pinned[] = {0};
    const float xyz[3] = {0.1f, 0.2f, 0.3f};
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_get_particle_count(c, nullptr));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_read_positions(c, nullptr, kFloats));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_read_velocities(c, nullptr, kFloats));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_read_normals(c, nullptr, kFloats));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_set_positions(c, nullptr, xyz, 1));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_set_positions(c, pinned, nullptr, 1));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_set_particle_masses(c, nullptr, xyz, 1));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_set_particle_masses(c, pinned, nullptr, 1));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_read_particle_masses(c, nullptr, kParticles));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_pin(c, nullptr, 1));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_unpin(c, nullptr, 1));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_set_pin_targets(c, nullptr, xyz, 1));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_set_pin_targets(c, pinned, nullptr, 1));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_is_pinned(c, 0, nullptr));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_set_solver(c, nullptr));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_get_solver(c, nullptr));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_set_aero(c, nullptr));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_set_wind(c, nullptr));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_get_stats(c, nullptr));
}

TEST_F(BadInput, ReadWithTooSmallCapacityReturnsInvalidCountAndWritesNothing) {
    for (uint32_t capacity : {0u, 3u, kFloats - 1}) {
        SCOPED_TRACE("capacity " + std::to_string(capacity));
        EXPECT_REJECTED(CLOTH_ERROR_INVALID_COUNT, cloth_read_positions(a_.cloth, outs_.floats, capacity));
        EXPECT_REJECTED(CLOTH_ERROR_INVALID_COUNT, cloth_read_velocities(a_.cloth, outs_.floats, capacity));
        EXPECT_REJECTED(CLOTH_ERROR_INVALID_COUNT, cloth_read_normals(a_.cloth, outs_.floats, capacity));
    }
    for (uint32_t capacity : {0u, kParticles - 1}) {
        SCOPED_TRACE("capacity " + std::to_string(capacity));
        EXPECT_REJECTED(CLOTH_ERROR_INVALID_COUNT,
                        cloth_read_particle_masses(a_.cloth, outs_.floats, capacity));
    }
}

TEST_F(BadInput, SetMassesWithZeroCountOrBadIndexOrAMassNotAboveZeroChangesNoMass) {
    const uint32_t two[] = {20, 21};
    const float masses[2] = {0.01f, 0.02f};
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_COUNT, cloth_set_particle_masses(a_.cloth, two, masses, 0));
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_COUNT,
                    cloth_set_particle_masses(a_.cloth, two, masses, kParticles + 1));
    for (uint32_t bad : {kParticles, UINT32_MAX}) {
        SCOPED_TRACE("index " + std::to_string(bad));
        const uint32_t second_bad[] = {20, bad};
        EXPECT_REJECTED(CLOTH_ERROR_INDEX_OUT_OF_RANGE,
                        cloth_set_particle_masses(a_.cloth, second_bad, masses, 2));
    }
    for (float bad : {0.0f, -0.0f, -1.0f, -1e-30f}) {
        SCOPED_TRACE("mass " + std::to_string(bad));
        const float second_bad[2] = {0.01f, bad};
        EXPECT_REJECTED(CLOTH_ERROR_INVALID_VALUE, cloth_set_particle_masses(a_.cloth, two, second_bad, 2));
    }
}

TEST_F(BadInput, SetPositionsWithZeroCountOrBadIndexOrNonFiniteValueMovesNoParticle) {
    const uint32_t one[] = {20};
    const float xyz[6] = {0.3f, -0.2f, 0.1f, 0.4f, -0.5f, 0.6f};
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_COUNT, cloth_set_positions(a_.cloth, one, xyz, 0));
    for (uint32_t bad : {kParticles, kParticles + 1, UINT32_MAX}) {
        SCOPED_TRACE("index " + std::to_string(bad));
        const uint32_t alone[] = {bad};
        EXPECT_REJECTED(CLOTH_ERROR_INDEX_OUT_OF_RANGE, cloth_set_positions(a_.cloth, alone, xyz, 1));
        // A valid index first: it must not move either.
        const uint32_t second_bad[] = {20, bad};
        EXPECT_REJECTED(CLOTH_ERROR_INDEX_OUT_OF_RANGE, cloth_set_positions(a_.cloth, second_bad, xyz, 2));
    }
    const uint32_t two[] = {20, 21};
    for (int i : {0, 4}) {
        for (float bad : {kNaN, kInf, -kInf}) {
            SCOPED_TRACE("positions[" + std::to_string(i) + "] = " + std::to_string(bad));
            float values[6];
            std::memcpy(values, xyz, sizeof values);
            values[i] = bad;
            EXPECT_REJECTED(CLOTH_ERROR_NOT_FINITE, cloth_set_positions(a_.cloth, two, values, 2));
        }
    }
}

TEST_F(BadInput, PinWithOutOfRangeIndexReturnsIndexErrorAndChangesNothing) {
    const uint32_t one[] = {20};
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_COUNT, cloth_pin(a_.cloth, one, 0));
    for (uint32_t bad : {kParticles, UINT32_MAX}) {
        SCOPED_TRACE("index " + std::to_string(bad));
        const uint32_t alone[] = {bad};
        EXPECT_REJECTED(CLOTH_ERROR_INDEX_OUT_OF_RANGE, cloth_pin(a_.cloth, alone, 1));
        const uint32_t second_bad[] = {20, bad};  // 20 is free and must stay free
        EXPECT_REJECTED(CLOTH_ERROR_INDEX_OUT_OF_RANGE, cloth_pin(a_.cloth, second_bad, 2));
    }
}

TEST_F(BadInput, UnpinWithOutOfRangeIndexReturnsIndexErrorAndChangesNothing) {
    const uint32_t one[] = {0};
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_COUNT, cloth_unpin(a_.cloth, one, 0));
    for (uint32_t bad : {kParticles, UINT32_MAX}) {
        SCOPED_TRACE("index " + std::to_string(bad));
        const uint32_t alone[] = {bad};
        EXPECT_REJECTED(CLOTH_ERROR_INDEX_OUT_OF_RANGE, cloth_unpin(a_.cloth, alone, 1));
        const uint32_t second_bad[] = {0, bad};  // 0 is pinned and must stay pinned
        EXPECT_REJECTED(CLOTH_ERROR_INDEX_OUT_OF_RANGE, cloth_unpin(a_.cloth, second_bad, 2));
    }
}

TEST_F(BadInput, SetPinTargetsOnANonPinnedParticleReturnsInvalidValueAndChangesNothing) {
    const float targets[6] = {0.1f, 0.5f, 0.2f, 0.9f, 0.5f, 0.2f};
    const uint32_t free_particle[] = {20};
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_VALUE, cloth_set_pin_targets(a_.cloth, free_particle, targets, 1));
    // Particle 0 is pinned; its target must not be taken either (the twin check sees it).
    const uint32_t pinned_then_free[] = {0, 20};
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_VALUE, cloth_set_pin_targets(a_.cloth, pinned_then_free, targets, 2));
}

TEST_F(BadInput, SetPinTargetsWithZeroCountOrBadIndexOrNonFiniteTargetChangesNothing) {
    const float targets[6] = {0.1f, 0.5f, 0.2f, 0.9f, 0.5f, 0.2f};
    const uint32_t corners[] = {0, kColumns - 1};
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_COUNT, cloth_set_pin_targets(a_.cloth, corners, targets, 0));
    for (uint32_t bad : {kParticles, UINT32_MAX}) {
        SCOPED_TRACE("index " + std::to_string(bad));
        const uint32_t alone[] = {bad};
        EXPECT_REJECTED(CLOTH_ERROR_INDEX_OUT_OF_RANGE, cloth_set_pin_targets(a_.cloth, alone, targets, 1));
        const uint32_t second_bad[] = {0, bad};
        EXPECT_REJECTED(CLOTH_ERROR_INDEX_OUT_OF_RANGE,
                        cloth_set_pin_targets(a_.cloth, second_bad, targets, 2));
    }
    for (int i : {1, 5}) {
        for (float bad : {kNaN, kInf, -kInf}) {
            SCOPED_TRACE("targets[" + std::to_string(i) + "] = " + std::to_string(bad));
            float values[6];
            std::memcpy(values, targets, sizeof values);
            values[i] = bad;
            EXPECT_REJECTED(CLOTH_ERROR_NOT_FINITE, cloth_set_pin_targets(a_.cloth, corners, values, 2));
        }
    }
}

TEST_F(BadInput, IsPinnedWithOutOfRangeIndexReturnsIndexErrorAndWritesNothing) {
    for (uint32_t bad : {kParticles, kParticles + 100, UINT32_MAX}) {
        SCOPED_TRACE("index " + std::to_string(bad));
        EXPECT_REJECTED(CLOTH_ERROR_INDEX_OUT_OF_RANGE, cloth_is_pinned(a_.cloth, bad, OutPinned()));
    }
}

}  // namespace
}  // namespace cloth_bad_input
