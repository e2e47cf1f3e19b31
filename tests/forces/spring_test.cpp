// The spring force and its Jacobian (paper eqs. 11-12) against central
// finite differences, and the signs that make W positive definite.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <limits>
#include <ostream>
#include <string>

#include "forces/springs.h"

namespace cloth {
namespace {

// Central differences of f_i with respect to x_j (double-step in float).
Mat3 numeric_dfi_dxj(const Vec3& xi, const Vec3& xj, float rest, float k, bool wrt_j) {
    Mat3 out;
    const float eps = 1e-3f;
    for (int c = 0; c < 3; ++c) {
        Vec3 plus_i = xi, minus_i = xi, plus_j = xj, minus_j = xj;
        (wrt_j ? plus_j : plus_i)[c] += eps;
        (wrt_j ? minus_j : minus_i)[c] -= eps;
        const Vec3 fp = spring_force_and_jacobian(plus_i, plus_j, rest, k, false).force;
        const Vec3 fm = spring_force_and_jacobian(minus_i, minus_j, rest, k, false).force;
        out.col(c) = (fp - fm) / (2 * eps);
    }
    return out;
}

struct Case {
    const char* name;
    float length_ratio;  // current length / rest length
};

// How GoogleTest prints a case (in failures and in --gtest_list_tests,
// which gtest_discover_tests reads): its name and ratio, not the struct's
// bytes, whose name pointer differs from build to build.
void PrintTo(const Case& c, std::ostream* out) { *out << c.name << " (" << c.length_ratio << " x rest)"; }

class SpringJacobian : public ::testing::TestWithParam<Case> {};

TEST_P(SpringJacobian, ExactJacobianMatchesFiniteDifferencesAndDiagonalBlockIsItsNegative) {
    const float rest = 0.5f, k = 100.0f;
    const Vec3 direction = Vec3(0.3f, -0.8f, 0.5f).normalized();
    const Vec3 xi(0.1f, 0.2f, -0.3f);
    const Vec3 xj = xi + direction * (rest * GetParam().length_ratio);

    const SpringEval eval = spring_force_and_jacobian(xi, xj, rest, k, /*compression_safe=*/false);
    const Mat3 analytic = eval.jacobian.to_matrix();
    const Mat3 off_diagonal = numeric_dfi_dxj(xi, xj, rest, k, true);
    const Mat3 diagonal = numeric_dfi_dxj(xi, xj, rest, k, false);
    const float scale = k;
    EXPECT_LT((analytic - off_diagonal).norm(), 2e-3f * scale) << "df_i/dx_j = J_ij";
    EXPECT_LT((analytic + diagonal).norm(), 2e-3f * scale) << "df_i/dx_i = -J_ij";
    // The force pulls i towards j when stretched, pushes it away when compressed.
    const float along = eval.force.dot(direction);
    if (GetParam().length_ratio > 1) {
        EXPECT_GT(along, 0.0f);
    } else {
        EXPECT_LT(along, 0.0f);
    }
    EXPECT_NEAR(along, k * rest * (GetParam().length_ratio - 1), 1e-3f * k);
}

INSTANTIATE_TEST_SUITE_P(StretchedAndCompressed, SpringJacobian,
                         ::testing::Values(Case{"stretched", 1.3f}, Case{"slightly_stretched", 1.01f},
                                           Case{"compressed", 0.7f}, Case{"strongly_compressed", 0.3f}),
                         [](const auto& info) { return std::string(info.param.name); });

// The step's kernel: its f~ is the spring force plus the damping force plus
// h J rv, with J the finite-difference derivative of the force.
TEST(SpringJacobian, ViscousRightHandSideIsForcePlusDampingPlusHJTimesRelativeVelocity) {
    const float rest = 0.4f, k = 300.0f, c = 0.7f, h = 1.0f / 60.0f;
    const Vec3 xi(0.0f, 0.1f, 0.0f), xj(0.3f, 0.5f, -0.2f);  // stretched
    const Vec3 rv(0.4f, -1.1f, 0.6f);
    const Vec3 d = xj - xi, u = d.normalized();
    const Mat3 jacobian = numeric_dfi_dxj(xi, xj, rest, k, true);
    const Vec3 expected = u * (k * (d.norm() - rest)) + u * (c * u.dot(rv)) + h * jacobian * rv;
    const SpringTerm t =
        spring_term(d.x(), d.y(), d.z(), rv.x(), rv.y(), rv.z(), rest, k, c, h, SpringModel::make(true));
    EXPECT_LT((Vec3(t.fx, t.fy, t.fz) - expected).norm(), 2e-3f * expected.norm());
    // A_s = h^2 J + h c u u^T.
    const Mat3 block = Sym3{t.bxx, t.bxy, t.bxz, t.byy, t.byz, t.bzz}.to_matrix();
    const Mat3 expected_block = h * h * jacobian + h * c * u * u.transpose();
    EXPECT_LT((block - expected_block).norm(), 2e-3f * expected_block.norm());
}

// The strain cable (springs.h): past cable_stretch * l0 the force gains
// cable_factor * k times the excess over that length, and the block the
// kernel returns (h = 1, c = 0, rv = 0: J itself) is the derivative of
// that force; short of it the cable does nothing.
TEST(SpringJacobian, StrainCablePullsOnlyPastItsLengthAndItsJacobianIsTheForcesDerivative) {
    const float rest = 0.25f, k = 40.0f;
    SpringModel model = SpringModel::make(true);
    model.cable_stretch = 1.08f;
    model.cable_factor = 100.0f;
    const Vec3 u = Vec3(-0.2f, 0.9f, 0.4f).normalized();
    auto force = [&](const Vec3& d) {
        const SpringTerm t = spring_term(d.x(), d.y(), d.z(), 0, 0, 0, rest, k, 0.0f, 1.0f, model);
        return Vec3(t.fx, t.fy, t.fz);
    };
    for (float ratio : {1.05f, 1.12f}) {
        SCOPED_TRACE("length / rest = " + std::to_string(ratio));
        const Vec3 d = u * (rest * ratio);
        const float cable = ratio > model.cable_stretch ? k * model.cable_factor : 0.0f;
        const float expected = k * rest * (ratio - 1) + cable * rest * (ratio - model.cable_stretch);
        EXPECT_NEAR(force(d).dot(u), expected, 1e-4f * expected);
        // df_i/dx_j by central differences of the kernel's force.
        Mat3 numeric;
        const float eps = 1e-4f;
        for (int c = 0; c < 3; ++c) {
            Vec3 plus = d, minus = d;
            plus[c] += eps;
            minus[c] -= eps;
            numeric.col(c) = (force(plus) - force(minus)) / (2 * eps);
        }
        const SpringTerm t = spring_term(d.x(), d.y(), d.z(), 0, 0, 0, rest, k, 0.0f, 1.0f, model);
        const Mat3 block = Sym3{t.bxx, t.bxy, t.bxz, t.byy, t.byz, t.bzz}.to_matrix();
        EXPECT_LT((block - numeric).norm(), 2e-3f * (k + cable)) << block << "\n" << numeric;
    }
}

// cable_approach (springs.h): within it short of cable_stretch * l0 the
// cable pulls nothing, but its stiffness is in the block along the spring,
// so a substep starting there sees the kink it is heading for; short of
// the band, and past cable_stretch, the term is the one without it.
TEST(SpringJacobian, ANearCableIsInTheJacobianButPullsNothing) {
    const float rest = 0.25f, k = 40.0f;
    SpringModel plain = SpringModel::make(true);
    plain.cable_stretch = 1.08f;
    plain.cable_factor = 100.0f;
    SpringModel approaching = plain;
    approaching.cable_approach = 0.01f;
    const Vec3 u = Vec3(-0.2f, 0.9f, 0.4f).normalized();
    auto term = [&](float ratio, const SpringModel& model) {
        const Vec3 d = u * (rest * ratio);
        return spring_term(d.x(), d.y(), d.z(), 0, 0, 0, rest, k, 0.0f, 1.0f, model);
    };
    auto along = [&](const SpringTerm& t) {
        return u.dot(Sym3{t.bxx, t.bxy, t.bxz, t.byy, t.byz, t.bzz}.to_matrix() * u);
    };
    auto force = [&](const SpringTerm& t) { return Vec3(t.fx, t.fy, t.fz).dot(u); };
    const SpringTerm near = term(1.075f, approaching), near_plain = term(1.075f, plain);
    EXPECT_EQ(force(near), force(near_plain)) << "the near cable pulls nothing";
    EXPECT_NEAR(along(near), k + k * plain.cable_factor * 1.08f / 1.075f, 1e-3f * k * plain.cable_factor)
        << "but its stiffness is in the block";
    EXPECT_NEAR(along(near_plain), k, 1e-4f * k);
    for (float ratio : {1.05f, 1.12f}) {
        SCOPED_TRACE("length / rest = " + std::to_string(ratio));
        const SpringTerm a = term(ratio, approaching), b = term(ratio, plain);
        const float x[] = {a.fx, a.fy, a.fz, a.bxx, a.bxy, a.bxz, a.byy, a.byz, a.bzz};
        const float y[] = {b.fx, b.fy, b.fz, b.bxx, b.bxy, b.bxz, b.byy, b.byz, b.bzz};
        for (int c = 0; c < 9; ++c) EXPECT_EQ(x[c], y[c]) << "component " << c;
    }
}

TEST(SpringJacobian, ASlackCableAddsExactlyNothingEvenWithAnEnormousStrainLimit) {
    // The C API accepts any finite max_strain: up to FLT_MAX, the cable's rest
    // length overflows to inf. A slack cable must still add exact zeros (not
    // 0 * inf = NaN), on compressed, stretched and coincident springs alike.
    const float rest = 0.25f, k = 1000.0f;
    SpringModel cable = SpringModel::make(true);
    cable.cable_stretch = 1.0f + std::numeric_limits<float>::max();
    cable.cable_factor = 100.0f;
    for (float ratio : {0.0f, 1e-12f, 0.5f, 1.5f, 1e6f}) {
        SCOPED_TRACE("length / rest = " + std::to_string(ratio));
        const float dx = rest * ratio * 0.6f, dy = rest * ratio * 0.8f;
        const SpringTerm with = spring_term<true>(dx, dy, 0, 0.5f, -1, 2, rest, k, 1.0f, 0.01f, cable);
        const SpringTerm without =
            spring_term<false>(dx, dy, 0, 0.5f, -1, 2, rest, k, 1.0f, 0.01f, SpringModel::make(true));
        const float a[] = {with.fx,  with.fy,  with.fz,  with.bxx, with.bxy,
                           with.bxz, with.byy, with.byz, with.bzz};
        const float b[] = {without.fx,  without.fy,  without.fz,  without.bxx, without.bxy,
                           without.bxz, without.byy, without.byz, without.bzz};
        for (int c = 0; c < 9; ++c) EXPECT_EQ(a[c], b[c]) << "component " << c;
    }
}

TEST(SpringJacobian, CoincidentEndsExertNoForceEvenWithTheExactJacobian) {
    const SpringTerm t =
        spring_term(0, 0, 0, 1.0f, 2.0f, 3.0f, 0.5f, 1000.0f, 1.0f, 0.1f, SpringModel::make(false));
    for (float value : {t.fx, t.fy, t.fz, t.bxx, t.bxy, t.bxz, t.byy, t.byz, t.bzz}) EXPECT_EQ(value, 0.0f);
}

float min_eigenvalue(const Mat3& m) {
    Eigen::SelfAdjointEigenSolver<Mat3> solver(m);
    return solver.eigenvalues().minCoeff();
}

TEST(SpringJacobian, CompressedExactJacobianIsIndefinite) {
    const Vec3 xi = Vec3::Zero(), xj(0.5f, 0.0f, 0.0f);  // rest 1: compressed to half
    const SpringEval exact = spring_force_and_jacobian(xi, xj, 1.0f, 10.0f, false);
    EXPECT_LT(min_eigenvalue(exact.jacobian.to_matrix()), 0.0f) << "(1 - l0/L) < 0 on the transverse axes";
}

TEST(SpringJacobian, CompressionSafeJacobianIsPositiveSemidefiniteAndAlongTheSpring) {
    const Vec3 xi = Vec3::Zero(), xj(0.0f, 0.4f, 0.3f);  // length 0.5, rest 1
    const float k = 10.0f;
    const SpringEval safe = spring_force_and_jacobian(xi, xj, 1.0f, k, true);
    const Vec3 u = (xj - xi).normalized();
    EXPECT_LT((safe.jacobian.to_matrix() - k * u * u.transpose()).norm(), 1e-5f) << "eq. 12: k d d^T / L^2";
    EXPECT_GE(min_eigenvalue(safe.jacobian.to_matrix()), -1e-5f);
    // Stretched springs are untouched by the option.
    const Vec3 far(0.0f, 1.6f, 1.2f);
    EXPECT_LT((spring_force_and_jacobian(xi, far, 1.0f, k, true).jacobian.to_matrix() -
               spring_force_and_jacobian(xi, far, 1.0f, k, false).jacobian.to_matrix())
                  .norm(),
              1e-6f);
}

TEST(SpringJacobian, DiagonalBlockOfWIsPositiveDefiniteAndAtLeastTheMass) {
    // W_ii = m I + h^2 sum_j J_ij: with compression-safe blocks every
    // eigenvalue is >= m, so W_ii^-1 exists and shrinks the step.
    const float m = 0.01f, h = 1.0f / 60.0f;
    Sym3 w = Sym3::identity(m);
    const Vec3 xi = Vec3::Zero();
    const Vec3 neighbours[] = {{0.9f, 0, 0}, {0, 1.2f, 0}, {0.5f, 0.5f, 0.1f}, {-0.3f, 0, 0.2f}};
    for (const Vec3& xj : neighbours)
        w += spring_force_and_jacobian(xi, xj, 1.0f, 1000.0f, true).jacobian * (h * h);
    EXPECT_GE(min_eigenvalue(w.to_matrix()), m * (1 - 1e-4f));
    const Mat3 product = w.to_matrix() * w.inverse().to_matrix();
    EXPECT_LT((product - Mat3::Identity()).norm(), 1e-4f);
}

}  // namespace
}  // namespace cloth
