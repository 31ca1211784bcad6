#include <scantling/core/error.hpp>
#include <scantling/core/random.hpp>
#include <scantling/core/se3.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

namespace scantling {
namespace {

constexpr double kPi = std::numbers::pi;
// exp/log round trips are a handful of flops from exact: a few ulps of 1.
constexpr double kRoundTripTol = 1e-12;
// Central differences with step h have error O(h²) + O(eps/h); h = 1e-6 gives ~1e-9.
constexpr double kNumericStep = 1e-6;
constexpr double kJacobianTol = 1e-8;

double max_abs_diff(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
    return (a - b).cwiseAbs().maxCoeff();
}

double pose_diff(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
    return max_abs_diff(a.matrix(), b.matrix());
}

std::vector<Eigen::Vector3d> test_rotation_vectors() {
    return {Eigen::Vector3d(0.3, -0.2, 0.5),
            Eigen::Vector3d(1e-9, -2e-9, 5e-10),
            Eigen::Vector3d(0.0, 0.0, 0.0),
            Eigen::Vector3d(0.004, 0.003, -0.002),
            Eigen::Vector3d(2.0, 1.0, -1.5).normalized() * 3.0,
            Eigen::Vector3d(0.1, 0.7, -0.7).normalized() * (kPi - 1e-7)};
}

TEST(Se3, HatIsCrossProductAndVeeInvertsIt) {
    const Eigen::Vector3d a(1.0, -2.0, 3.0);
    const Eigen::Vector3d b(-0.5, 4.0, 0.25);
    EXPECT_LT((hat(a) * b - a.cross(b)).norm(), 1e-15);
    EXPECT_EQ(vee(hat(a)), a);
}

TEST(Se3, So3ExpLogRoundTripIncludingTinyAndNearPiAngles) {
    for (const Eigen::Vector3d& omega : test_rotation_vectors()) {
        const Eigen::Matrix3d R = so3_exp(omega);
        EXPECT_LT(max_abs_diff(R * R.transpose(), Eigen::Matrix3d::Identity()), kRoundTripTol);
        EXPECT_NEAR(R.determinant(), 1.0, kRoundTripTol);
        EXPECT_LT((so3_log(R) - omega).norm(), kRoundTripTol) << omega.transpose();
    }
}

TEST(Se3, So3ExpMatchesEigenAngleAxis) {
    const Eigen::Vector3d axis = Eigen::Vector3d(0.2, -0.9, 0.4).normalized();
    const Eigen::Matrix3d expected = Eigen::AngleAxisd(1.3, axis).toRotationMatrix();
    EXPECT_LT(max_abs_diff(so3_exp(1.3 * axis), expected), 1e-15);
}

TEST(Se3, So3LogOfTinyRotationKeepsFullRelativePrecision) {
    const Eigen::Vector3d omega(3e-12, -1e-12, 2e-12);
    EXPECT_LT((so3_log(so3_exp(omega)) - omega).norm(), 1e-26);
}

TEST(Se3, So3LogAtExactlyPiReturnsAnglePiAboutTheAxis) {
    const Eigen::Vector3d axis = Eigen::Vector3d(1.0, 2.0, -2.0) / 3.0;
    const Eigen::Vector3d omega = so3_log(Eigen::AngleAxisd(kPi, axis).toRotationMatrix());
    EXPECT_NEAR(omega.norm(), kPi, kRoundTripTol);
    EXPECT_NEAR(std::abs(omega.normalized().dot(axis)), 1.0, kRoundTripTol);
}

TEST(Se3, So3LogNearPiKeepsTheRotationSense) {
    // θ = π - 1e-6 and 2π - θ about the opposite axis are different rotations; the sign of
    // the axis must be read from the antisymmetric part.
    const Eigen::Vector3d axis = Eigen::Vector3d(0.3, -0.4, 0.5).normalized();
    const Eigen::Vector3d omega = (kPi - 1e-6) * axis;
    EXPECT_LT((so3_log(so3_exp(omega)) - omega).norm(), 1e-9);
    EXPECT_LT((so3_log(so3_exp(-omega)) + omega).norm(), 1e-9);
}

TEST(Se3, So3LeftJacobianMatchesNumericalDerivative) {
    for (const Eigen::Vector3d& omega : test_rotation_vectors()) {
        const Eigen::Matrix3d R_inv = so3_exp(omega).transpose();
        Eigen::Matrix3d numeric;
        for (int k = 0; k < 3; ++k) {
            const Eigen::Vector3d d = kNumericStep * Eigen::Vector3d::Unit(k);
            // exp(ω + d) exp(ω)⁻¹ = exp(J_l d): differentiate log of the left perturbation.
            numeric.col(k) =
                (so3_log(so3_exp(omega + d) * R_inv) - so3_log(so3_exp(omega - d) * R_inv)) /
                (2.0 * kNumericStep);
        }
        EXPECT_LT(max_abs_diff(so3_left_jacobian(omega), numeric), kJacobianTol)
            << omega.transpose();
    }
}

TEST(Se3, So3RightJacobianMatchesNumericalDerivative) {
    for (const Eigen::Vector3d& omega : test_rotation_vectors()) {
        const Eigen::Matrix3d R_inv = so3_exp(omega).transpose();
        Eigen::Matrix3d numeric;
        for (int k = 0; k < 3; ++k) {
            const Eigen::Vector3d d = kNumericStep * Eigen::Vector3d::Unit(k);
            numeric.col(k) =
                (so3_log(R_inv * so3_exp(omega + d)) - so3_log(R_inv * so3_exp(omega - d))) /
                (2.0 * kNumericStep);
        }
        EXPECT_LT(max_abs_diff(so3_right_jacobian(omega), numeric), kJacobianTol)
            << omega.transpose();
    }
}

TEST(Se3, So3JacobianInversesAreInverses) {
    for (const Eigen::Vector3d& omega : test_rotation_vectors()) {
        EXPECT_LT(max_abs_diff(so3_left_jacobian(omega) * so3_left_jacobian_inverse(omega),
                               Eigen::Matrix3d::Identity()),
                  kRoundTripTol);
        EXPECT_LT(max_abs_diff(so3_right_jacobian(omega) * so3_right_jacobian_inverse(omega),
                               Eigen::Matrix3d::Identity()),
                  kRoundTripTol);
    }
}

TEST(Se3, So3JacobianCoefficientsAreContinuousAtTheSeriesSwitch) {
    // The Taylor branch is used below 1e-2 rad; both sides must agree to rounding.
    const Eigen::Vector3d axis = Eigen::Vector3d(1.0, 2.0, 3.0).normalized();
    const Eigen::Vector3d below = (1e-2 - 1e-12) * axis;
    const Eigen::Vector3d above = (1e-2 + 1e-12) * axis;
    EXPECT_LT(max_abs_diff(so3_left_jacobian(below), so3_left_jacobian(above)), 1e-11);
    EXPECT_LT(max_abs_diff(so3_left_jacobian_inverse(below), so3_left_jacobian_inverse(above)),
              1e-11);
    EXPECT_LT(max_abs_diff(so3_exp(below), so3_exp(above)), 1e-11);
}

TEST(Se3, Se3ExpLogRoundTrip) {
    for (const Eigen::Vector3d& omega : test_rotation_vectors()) {
        Vector6d xi;
        xi << 1.5, -0.3, 2.0, omega;
        EXPECT_LT((se3_log(se3_exp(xi)) - xi).norm(), 1e-10) << xi.transpose();
    }
}

TEST(Se3, Se3ExpOfPureTranslationIsTranslation) {
    Vector6d xi;
    xi << 1.0, 2.0, 3.0, 0.0, 0.0, 0.0;
    const Eigen::Isometry3d T = se3_exp(xi);
    EXPECT_EQ(T.translation(), Eigen::Vector3d(1.0, 2.0, 3.0));
    EXPECT_EQ(T.linear(), Eigen::Matrix3d::Identity());
}

TEST(Se3, AdjointConjugatesTwists) {
    Vector6d xi_b;
    xi_b << 0.4, -0.1, 0.3, 0.2, 0.5, -0.3;
    Vector6d pose;
    pose << 2.0, -1.0, 0.5, 0.3, -1.2, 0.8;
    const Eigen::Isometry3d T_a_b = se3_exp(pose);
    const Eigen::Isometry3d lhs = T_a_b * se3_exp(xi_b) * T_a_b.inverse();
    EXPECT_LT(pose_diff(lhs, se3_exp(se3_adjoint(T_a_b) * xi_b)), kRoundTripTol);
}

TEST(Se3, InterpolateHitsEndpointsAndMidpoint) {
    const Eigen::Isometry3d T_w_a = make_isometry(so3_exp({0.0, 0.0, 0.2}), {0.0, 0.0, 0.0});
    const Eigen::Isometry3d T_w_b = make_isometry(so3_exp({0.0, 0.0, 1.0}), {2.0, 4.0, -2.0});
    EXPECT_LT(pose_diff(interpolate(T_w_a, T_w_b, 0.0), T_w_a), kRoundTripTol);
    EXPECT_LT(pose_diff(interpolate(T_w_a, T_w_b, 1.0), T_w_b), kRoundTripTol);
    const Eigen::Isometry3d mid = interpolate(T_w_a, T_w_b, 0.5);
    EXPECT_LT((mid.translation() - Eigen::Vector3d(1.0, 2.0, -1.0)).norm(), kRoundTripTol);
    EXPECT_LT(max_abs_diff(mid.linear(), so3_exp({0.0, 0.0, 0.6})), kRoundTripTol);
    const Eigen::Isometry3d beyond = interpolate(T_w_a, T_w_b, 1.5);
    EXPECT_LT(max_abs_diff(beyond.linear(), so3_exp({0.0, 0.0, 1.4})), kRoundTripTol);
}

TEST(Se3, GeodesicInterpolationHitsEndpointsAndComposesHalves) {
    Vector6d xi;
    xi << 1.0, -2.0, 0.5, 0.4, 0.2, -0.9;
    const Eigen::Isometry3d T_w_a = make_isometry(so3_exp({0.1, 0.2, 0.3}), {1.0, 1.0, 1.0});
    const Eigen::Isometry3d T_w_b = T_w_a * se3_exp(xi);
    EXPECT_LT(pose_diff(interpolate_geodesic(T_w_a, T_w_b, 1.0), T_w_b), 1e-10);
    const Eigen::Isometry3d mid = interpolate_geodesic(T_w_a, T_w_b, 0.5);
    EXPECT_LT(pose_diff(mid * se3_exp(0.5 * xi), T_w_b), 1e-10);
}

TEST(Se3, EulerZyxRoundTrip) {
    const Eigen::Vector3d rpy(0.3, -0.7, 2.5);
    const Eigen::Matrix3d R = rotation_from_euler_zyx(rpy.x(), rpy.y(), rpy.z());
    const Eigen::Matrix3d expected = (Eigen::AngleAxisd(2.5, Eigen::Vector3d::UnitZ()) *
                                      Eigen::AngleAxisd(-0.7, Eigen::Vector3d::UnitY()) *
                                      Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()))
                                         .toRotationMatrix();
    EXPECT_LT(max_abs_diff(R, expected), 1e-15);
    EXPECT_LT((euler_zyx_from_rotation(R) - rpy).norm(), kRoundTripTol);
}

TEST(Se3, EulerZyxAtGimbalLockSetsRollToZeroAndKeepsTheRotation) {
    for (const double pitch : {kPi / 2.0, -kPi / 2.0}) {
        const Eigen::Matrix3d R = rotation_from_euler_zyx(0.4, pitch, 1.1);
        const Eigen::Vector3d rpy = euler_zyx_from_rotation(R);
        EXPECT_EQ(rpy.x(), 0.0);
        EXPECT_NEAR(rpy.y(), pitch, 1e-8);
        // Only yaw - roll (pitch +π/2) or yaw + roll (pitch -π/2) is observable.
        EXPECT_NEAR(rpy.z(), pitch > 0.0 ? 1.1 - 0.4 : 1.1 + 0.4, kRoundTripTol);
        EXPECT_LT(max_abs_diff(rotation_from_euler_zyx(rpy.x(), rpy.y(), rpy.z()), R), 1e-8);
    }
}

TEST(Se3, EulerZyxNearGimbalLockReproducesTheRotation) {
    const Eigen::Matrix3d R = rotation_from_euler_zyx(0.4, kPi / 2.0 - 1e-9, 1.1);
    const Eigen::Vector3d rpy = euler_zyx_from_rotation(R);
    EXPECT_LT(max_abs_diff(rotation_from_euler_zyx(rpy.x(), rpy.y(), rpy.z()), R), 1e-12);
}

TEST(Se3, AverageOfNoisyRotationsRecoversTheTrueRotation) {
    Rng rng(7);
    const Eigen::Matrix3d R_true = so3_exp({0.5, -1.0, 2.0});
    constexpr double kNoiseSigmaRad = 0.05;
    constexpr int kSamples = 400;
    std::vector<Eigen::Matrix3d> samples;
    for (int i = 0; i < kSamples; ++i)
        samples.push_back(R_true * so3_exp(rng.normal3(kNoiseSigmaRad)));
    // Standard error of the mean per axis = σ/√400 = 0.0025 rad; the 3-axis error norm stays
    // below 5 standard errors with probability > 0.9999 (χ² with 3 degrees of freedom).
    constexpr double kMeanTolRad = 5.0 * kNoiseSigmaRad / 20.0;
    EXPECT_LT(rotation_angle_rad(R_true.transpose() * average_rotations(samples)), kMeanTolRad);
}

TEST(Se3, WeightedAverageOfTwoRotationsIsTheGeodesicPoint) {
    const std::vector<Eigen::Matrix3d> rotations{so3_exp({0.0, 0.0, 0.0}),
                                                 so3_exp({0.0, 0.0, 1.2})};
    const std::vector<double> weights{1.0, 3.0};
    // Geodesic mean of two points weighted 1:3 lies 3/4 of the way along the arc.
    EXPECT_LT(max_abs_diff(average_rotations(rotations, weights), so3_exp({0.0, 0.0, 0.9})), 1e-12);
}

TEST(Se3, AverageRotationsRejectsBadInput) {
    const std::vector<Eigen::Matrix3d> none;
    EXPECT_THROW(average_rotations(none), InputError);
    const std::vector<Eigen::Matrix3d> two{Eigen::Matrix3d::Identity(),
                                           Eigen::Matrix3d::Identity()};
    const std::vector<double> one_weight{1.0};
    EXPECT_THROW(average_rotations(two, one_weight), InputError);
    const std::vector<double> negative{1.0, -0.5};
    EXPECT_THROW(average_rotations(two, negative), InputError);
    const std::vector<double> zeros{0.0, 0.0};
    EXPECT_THROW(average_rotations(two, zeros), InputError);
    const std::vector<double> nan{1.0, std::nan("")};
    EXPECT_THROW(average_rotations(two, nan), InputError);
}

TEST(Se3, OrthonormalizeReturnsNearestRotation) {
    const Eigen::Matrix3d R = so3_exp({0.3, 0.2, -0.1});
    const Eigen::Matrix3d noisy = R + 1e-3 * Eigen::Matrix3d::Ones();
    const Eigen::Matrix3d fixed = orthonormalize(noisy);
    EXPECT_LT(max_abs_diff(fixed * fixed.transpose(), Eigen::Matrix3d::Identity()), 1e-14);
    EXPECT_NEAR(fixed.determinant(), 1.0, 1e-14);
    EXPECT_LT(rotation_angle_rad(R.transpose() * fixed), 2e-3);
    // A reflection is mapped to a proper rotation.
    EXPECT_NEAR(orthonormalize(-Eigen::Matrix3d::Identity()).determinant(), 1.0, 1e-14);
}

TEST(Se3, PoseErrorReportsDistanceAndAngle) {
    const Eigen::Isometry3d T_w_a = make_isometry(so3_exp({0.0, 0.2, 0.0}), {1.0, 0.0, 0.0});
    const Eigen::Isometry3d T_w_b = make_isometry(so3_exp({0.0, -0.1, 0.0}), {1.0, 3.0, 4.0});
    const PoseError error = pose_error(T_w_a, T_w_b);
    EXPECT_NEAR(error.translation_m, 5.0, 1e-15);
    EXPECT_NEAR(error.rotation_rad, 0.3, 1e-15);
    EXPECT_NEAR(rotation_angle_rad(so3_exp({0.0, 0.0, kPi})), kPi, 1e-15);
}

}  // namespace
}  // namespace scantling
