// Bad skins, joint matrices, skinned positions, max distances and backstops
// are rejected with their own code and a message naming the argument, and
// change nothing: both worlds' main cloths get the same valid skin first, so
// the twin check at the end catches a skin, a matrix, a max distance or a
// backstop that a failed call half set.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "bad_input/fixture.h"

namespace cloth_bad_input {
namespace {

constexpr uint32_t kJoints = 2;

class SkinBadInput : public BadInput {
  protected:
    void SetUp() override {
        BadInput::SetUp();
        joints_.assign(2 * kParticles, 0u);
        weights_.assign(2 * kParticles, 0.5f);
        for (uint32_t v = 0; v < kParticles; ++v) joints_[2 * v + 1] = 1;
        identity_.assign(16 * kJoints, 0.0f);
        for (uint32_t j = 0; j < kJoints; ++j) {
            for (int d = 0; d < 4; ++d) identity_[16 * j + 5 * d] = 1.0f;
        }
        for (const Scene* s : {&a_, &b_}) {
            const cloth_skin_desc desc = Valid();
            ASSERT_EQ(cloth_set_skin(s->cloth, &desc), CLOTH_OK);
            ASSERT_EQ(
                cloth_set_joint_matrices(s->cloth, identity_.data(), kJoints, CLOTH_MATRIX_COLUMN_MAJOR_4X4),
                CLOTH_OK);
            const std::vector<float> reach(kParticles, 0.2f);
            ASSERT_EQ(cloth_set_max_distances(s->cloth, reach.data(), kParticles), CLOTH_OK);
        }
    }
    cloth_skin_desc Valid() const {
        cloth_skin_desc d = cloth_default_skin_desc();
        d.particle_count = kParticles;
        d.joint_count = kJoints;
        d.influences = 2;
        d.joints = joints_.data();
        d.weights = weights_.data();
        return d;
    }
    // The last error of a call made again on this thread.
    static std::string MessageOf(cloth_result result) {
        EXPECT_NE(result, CLOTH_OK);
        return cloth_get_last_error();
    }

    std::vector<uint32_t> joints_;
    std::vector<float> weights_, identity_;
};

TEST_F(SkinBadInput, ASkinWithABadJointWeightOrCountIsRejectedAndNamesTheArgument) {
    const cloth_id c = a_.cloth;
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_set_skin(c, nullptr));
    for (const auto& broken : BrokenDescs(Valid())) {
        SCOPED_TRACE(broken.first);
        EXPECT_REJECTED(CLOTH_ERROR_INVALID_DESC, cloth_set_skin(c, &broken.second));
    }
    cloth_skin_desc d = Valid();
    d.particle_count = kParticles + 1;  // skin data for a fabric of another particle count
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_COUNT, cloth_set_skin(c, &d));
    EXPECT_NE(MessageOf(cloth_set_skin(c, &d)).find("particle_count"), std::string::npos);
    d = Valid();
    d.joint_count = 0;
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_COUNT, cloth_set_skin(c, &d));
    d = Valid();
    d.influences = 5;
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_COUNT, cloth_set_skin(c, &d));
    d = Valid();
    d.joints = nullptr;
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_set_skin(c, &d));
    d = Valid();
    d.weights = nullptr;  // two influences need weights
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_set_skin(c, &d));

    std::vector<uint32_t> joints = joints_;
    joints[7] = kJoints;  // a joint index past the joint count
    d = Valid();
    d.joints = joints.data();
    EXPECT_REJECTED(CLOTH_ERROR_INDEX_OUT_OF_RANGE, cloth_set_skin(c, &d));
    EXPECT_NE(MessageOf(cloth_set_skin(c, &d)).find("joints[7]"), std::string::npos);

    std::vector<float> weights = weights_;
    weights[6] = 0.502f;  // vertex 3's weights sum to 1.002
    d = Valid();
    d.weights = weights.data();
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_VALUE, cloth_set_skin(c, &d));
    EXPECT_NE(MessageOf(cloth_set_skin(c, &d)).find("weights of vertex 3"), std::string::npos);
    weights = weights_;
    weights[4] = kNaN;
    EXPECT_REJECTED(CLOTH_ERROR_NOT_FINITE, cloth_set_skin(c, &d));
    weights = weights_;
    weights[4] = -0.5f;
    weights[5] = 1.5f;
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_VALUE, cloth_set_skin(c, &d));
}

TEST_F(SkinBadInput, JointMatricesAndSkinnedPositionsAreCheckedBeforeTheSkinChanges) {
    const cloth_id c = a_.cloth;
    std::vector<float> m = identity_;
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER,
                    cloth_set_joint_matrices(c, nullptr, kJoints, CLOTH_MATRIX_COLUMN_MAJOR_4X4));
    // A matrix array shorter than the joint count.
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_COUNT,
                    cloth_set_joint_matrices(c, m.data(), kJoints - 1, CLOTH_MATRIX_COLUMN_MAJOR_4X4));
    EXPECT_NE(
        MessageOf(cloth_set_joint_matrices(c, m.data(), 1, CLOTH_MATRIX_ROW_MAJOR_3X4)).find("matrix_count"),
        std::string::npos);
    m[16 + 12] = kInf;  // joint 1's translation
    EXPECT_REJECTED(CLOTH_ERROR_NOT_FINITE,
                    cloth_set_joint_matrices(c, m.data(), kJoints, CLOTH_MATRIX_COLUMN_MAJOR_4X4));
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_VALUE, cloth_set_joint_matrices(c, identity_.data(), kJoints,
                                                                        static_cast<cloth_matrix_layout>(7)));
    // The second cloth has no skin.
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_VALUE, cloth_set_joint_matrices(a_.other, identity_.data(), kJoints,
                                                                        CLOTH_MATRIX_COLUMN_MAJOR_4X4));

    std::vector<float> x(kFloats, 0.0f), n(kFloats, 0.0f);
    for (uint32_t v = 0; v < kParticles; ++v) n[3 * v + 2] = 1.0f;
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_COUNT,
                    cloth_set_skinned_positions(c, x.data(), n.data(), kParticles - 1));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_set_skinned_positions(c, nullptr, n.data(), kParticles));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_set_skinned_positions(c, x.data(), nullptr, kParticles));
    x[5] = kNaN;
    EXPECT_REJECTED(CLOTH_ERROR_NOT_FINITE, cloth_set_skinned_positions(c, x.data(), n.data(), kParticles));
    x[5] = 0.0f;
    n[3 * 9 + 2] = 0.0f;  // a zero normal
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_VALUE,
                    cloth_set_skinned_positions(c, x.data(), n.data(), kParticles));
    EXPECT_NE(
        MessageOf(cloth_set_skinned_positions(c, x.data(), n.data(), kParticles)).find("normals_xyz[9]"),
        std::string::npos);
    float out[kFloats];
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_COUNT, cloth_read_skinned_positions(c, out, nullptr, kFloats - 1));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_read_skinned_positions(c, nullptr, nullptr, kFloats));
}

TEST_F(SkinBadInput, MaxDistancesAndBackstopsRejectNaNNegativeAndARadiusOfZero) {
    const cloth_id c = a_.cloth;
    std::vector<float> reach(kParticles, 0.1f);
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_set_max_distances(c, nullptr, kParticles));
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_COUNT, cloth_set_max_distances(c, reach.data(), kParticles - 1));
    reach[11] = kNaN;
    EXPECT_REJECTED(CLOTH_ERROR_NOT_FINITE, cloth_set_max_distances(c, reach.data(), kParticles));
    EXPECT_NE(MessageOf(cloth_set_max_distances(c, reach.data(), kParticles)).find("distances[11]"),
              std::string::npos);
    reach[11] = -0.1f;
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_VALUE, cloth_set_max_distances(c, reach.data(), kParticles));
    reach[11] = 0.1f;
    // The second cloth has no skin.
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_VALUE, cloth_set_max_distances(a_.other, reach.data(), kParticles));

    std::vector<float> distance(kParticles, 0.05f), radius(kParticles, 0.04f);
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_set_backstops(c, nullptr, radius.data(), kParticles));
    EXPECT_REJECTED(CLOTH_ERROR_NULL_POINTER, cloth_set_backstops(c, distance.data(), nullptr, kParticles));
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_COUNT,
                    cloth_set_backstops(c, distance.data(), radius.data(), kParticles + 1));
    radius[20] = 0.0f;  // a radius of 0 with a positive distance
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_VALUE,
                    cloth_set_backstops(c, distance.data(), radius.data(), kParticles));
    EXPECT_NE(MessageOf(cloth_set_backstops(c, distance.data(), radius.data(), kParticles)).find("radii[20]"),
              std::string::npos);
    radius[20] = kInf;
    EXPECT_REJECTED(CLOTH_ERROR_NOT_FINITE,
                    cloth_set_backstops(c, distance.data(), radius.data(), kParticles));
    radius[20] = 0.04f;
    distance[3] = -1.0f;
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_VALUE,
                    cloth_set_backstops(c, distance.data(), radius.data(), kParticles));
}

// A skin setter that allocates (a new skin, the first host-skinned
// positions, max distances that pin particles) and meets an allocator
// returning NULL at any of its allocations reports CLOTH_ERROR_OUT_OF_MEMORY
// and changes nothing: the cloths' state, the world's memory and the
// skinned positions read back are as before, and the twin check at the end
// finds the skin the same as the twin's after the same calls succeed.
TEST_F(SkinBadInput, ASkinSetterWhoseAllocationFailsReturnsOutOfMemoryAndChangesNothing) {
    std::vector<uint32_t> joints(kParticles, 1u);
    cloth_skin_desc rebind = cloth_default_skin_desc();
    rebind.particle_count = kParticles;
    rebind.joint_count = kJoints;
    rebind.joints = joints.data();
    std::vector<float> x(kFloats, 0.5f), n(kFloats, 0.0f), reach(kParticles, 0.3f);
    for (uint32_t v = 0; v < kParticles; ++v) n[3 * v + 2] = 1.0f;
    reach[0] = reach[kColumns - 1] = 0.0f;  // pins two free particles
    struct Setter {
        const char* name;
        std::function<cloth_result(cloth_id)> call;
    };
    const Setter setters[] = {
        {"cloth_set_skin", [&](cloth_id c) { return cloth_set_skin(c, &rebind); }},
        {"cloth_set_skinned_positions",
         [&](cloth_id c) { return cloth_set_skinned_positions(c, x.data(), n.data(), kParticles); }},
        {"cloth_set_max_distances",
         [&](cloth_id c) { return cloth_set_max_distances(c, reach.data(), kParticles); }},
    };
    for (const Setter& setter : setters) {
        SCOPED_TRACE(setter.name);
        // A step skins both cloths, so that there are skinned positions to compare.
        ASSERT_EQ(cloth_step(a_.world, kFrame), CLOTH_OK) << cloth_get_last_error();
        ASSERT_EQ(cloth_step(b_.world, kFrame), CLOTH_OK) << cloth_get_last_error();
        int failures = 0;
        bool done = false;
        for (long allowed = 0; allowed < 100 && !done; ++allowed) {
            SCOPED_TRACE("allocator fails after " + std::to_string(allowed) + " allocations");
            std::vector<float> skinned_before(kFloats), skinned_after(kFloats);
            ASSERT_EQ(cloth_read_skinned_positions(a_.cloth, skinned_before.data(), nullptr, kFloats),
                      CLOTH_OK);
            const cloth_test::Unchanged unchanged(watch_);
            a_.host.fail_after(allowed);
            const cloth_result r = setter.call(a_.cloth);
            a_.host.fail_after(-1);
            if (r == CLOTH_OK) {
                done = true;
                break;
            }
            ++failures;
            ++cloth_test::bad_inputs();
            EXPECT_EQ(r, CLOTH_ERROR_OUT_OF_MEMORY) << cloth_get_last_error();
            EXPECT_EQ(unchanged.what_changed(), "");
            ASSERT_EQ(cloth_read_skinned_positions(a_.cloth, skinned_after.data(), nullptr, kFloats),
                      CLOTH_OK);
            EXPECT_EQ(skinned_before, skinned_after) << "the skin changed";
            ASSERT_FALSE(HasFailure()) << "stopping at the first failing allocation count";
        }
        EXPECT_GE(failures, 1) << setter.name << " never used the world's allocator";
        ASSERT_TRUE(done);
        ASSERT_EQ(setter.call(b_.cloth), CLOTH_OK) << "the twin takes the same call";
    }
}

}  // namespace
}  // namespace cloth_bad_input
