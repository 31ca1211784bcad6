#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include <scantling/core/error.hpp>
#include <scantling/core/se3.hpp>
#include <scantling/registration/icp.hpp>

#include "scenes.hpp"

namespace scantling::registration {
namespace {

using test::make_pose;
using test::sample_clutter;
using test::sample_plane;
using test::sample_room_corner;

constexpr double kNoiseM = 0.005;  // range noise of a good LiDAR / depth camera
// Point-to-plane and GICP pin every direction by thousands of planar residuals with 5 mm
// noise: the error of the mean is far below 1 mm and 0.05°; the bound leaves margin for the
// sampling difference between the two clouds (different points on the same surfaces).
constexpr double kPlaneTolM = 0.002;
constexpr double kPlaneTolRad = 0.001;
// Point-to-point matches different samples of a surface (spacing ~4 cm): it converges slowly
// along the surfaces (~50 iterations here) and keeps a bias of a fraction of a millimetre.
constexpr double kPointTolM = 0.003;
constexpr double kPointTolRad = 0.001;

/// ~15° and ~0.5 m from identity, about the scene centre.
Eigen::Isometry3d truth() { return make_pose(0.1, -0.12, 0.2, Eigen::Vector3d(0.3, -0.25, 0.3)); }

struct Scene {
    PointCloud target = sample_room_corner(30000, 1, kNoiseM);
    PointCloud source = transformed(sample_room_corner(8000, 2, kNoiseM), truth().inverse());
};

const Scene& scene() {
    static const Scene s;
    return s;
}

IcpConfig config_for(IcpMethod method) {
    IcpConfig c;
    c.method = method;
    c.max_correspondence_distance_m = 1.5;
    c.max_iterations = 60;
    c.translation_tolerance_m = 1e-5;
    c.rotation_tolerance_rad = 1e-5;
    return c;
}

void expect_near_truth(const RegistrationResult& r, double tol_m, double tol_rad) {
    const PoseError e = pose_error(r.T_target_source, truth());
    EXPECT_TRUE(r.converged) << r.status;
    EXPECT_LT(e.translation_m, tol_m);
    EXPECT_LT(e.rotation_rad, tol_rad);
}

TEST(IcpTest, PointToPlaneRecoversKnownPoseFromFifteenDegrees) {
    const RegistrationResult r =
        align(scene().source, scene().target, Eigen::Isometry3d::Identity(),
              config_for(IcpMethod::kPointToPlane));
    expect_near_truth(r, kPlaneTolM, kPlaneTolRad);
    EXPECT_EQ(r.status, "converged");
    EXPECT_GT(r.fitness, 0.95);
    EXPECT_LT(r.rmse_m, 0.1);
}

TEST(IcpTest, GicpRecoversKnownPoseFromFifteenDegrees) {
    const RegistrationResult r =
        align(scene().source, scene().target, Eigen::Isometry3d::Identity(),
              config_for(IcpMethod::kGeneralized));
    expect_near_truth(r, kPlaneTolM, kPlaneTolRad);
}

TEST(IcpTest, PointToPointRecoversKnownPoseFromFifteenDegrees) {
    IcpConfig c = config_for(IcpMethod::kPointToPoint);
    c.max_iterations = 200;  // slow along surfaces: many small steps
    const RegistrationResult r =
        align(scene().source, scene().target, Eigen::Isometry3d::Identity(), c);
    expect_near_truth(r, kPointTolM, kPointTolRad);
}

TEST(IcpTest, PrebuiltTreeGivesTheSameResult) {
    const IcpConfig c = config_for(IcpMethod::kPointToPlane);
    const KdTree tree(scene().target.points);
    const RegistrationResult a =
        align(scene().source, scene().target, Eigen::Isometry3d::Identity(), c);
    const RegistrationResult b =
        align(scene().source, scene().target, tree, Eigen::Isometry3d::Identity(), c);
    EXPECT_TRUE(a.T_target_source.matrix() == b.T_target_source.matrix());
}

/// The scene's source with 30 % of its points replaced by clutter: n_out / (n + n_out) = 0.3.
PointCloud source_with_outliers() {
    PointCloud source = scene().source;
    const PointCloud clutter = sample_clutter(source.size() * 3 / 7, 3);
    append(source, transformed(clutter, truth().inverse()));
    return source;
}

// Outliers that happen to lie near a surface pass any kernel and bias the pose a little; the
// measured error is 1–10 mm and < 0.03°, against 18 cm and 0.4° without a kernel.
constexpr double kOutlierTolM = 0.015;
constexpr double kOutlierTolRad = 0.002;

TEST(IcpTest, ThirtyPercentOutliersBiasPlainLeastSquares) {
    IcpConfig c = config_for(IcpMethod::kPointToPlane);
    c.max_correspondence_distance_m = 1.0;
    const RegistrationResult r =
        align(source_with_outliers(), scene().target, Eigen::Isometry3d::Identity(), c);
    EXPECT_GT(pose_error(r.T_target_source, truth()).translation_m, 0.1);
}

struct KernelCase {
    RobustKernel kernel;
    /// Redescending kernels (Geman-McClure, Tukey) ignore every residual far beyond the scale,
    /// so from 15° away they need a scale near the initial misalignment of the surfaces (10 cm
    /// here; 5 cm stalls); Huber never ignores outliers, so a small scale limits their pull.
    double scale_m;
};

class RobustKernelIcpTest : public ::testing::TestWithParam<KernelCase> {};

TEST_P(RobustKernelIcpTest, ToleratesThirtyPercentOutlierPoints) {
    IcpConfig c = config_for(IcpMethod::kPointToPlane);
    c.max_correspondence_distance_m = 1.0;
    c.kernel = GetParam().kernel;
    c.kernel_scale_m = GetParam().scale_m;
    const RegistrationResult r =
        align(source_with_outliers(), scene().target, Eigen::Isometry3d::Identity(), c);
    expect_near_truth(r, kOutlierTolM, kOutlierTolRad);
}

INSTANTIATE_TEST_SUITE_P(Kernels, RobustKernelIcpTest,
                         ::testing::Values(KernelCase{RobustKernel::kHuber, 0.02},
                                           KernelCase{RobustKernel::kCauchy, 0.05},
                                           KernelCase{RobustKernel::kGemanMcClure, 0.1},
                                           KernelCase{RobustKernel::kTukey, 0.1}),
                         [](const auto& param_info) {
                             return std::string(to_string(param_info.param.kernel));
                         });

TEST(IcpTest, GicpWithCauchyKernelToleratesThirtyPercentOutlierPoints) {
    IcpConfig c = config_for(IcpMethod::kGeneralized);
    c.max_correspondence_distance_m = 1.0;
    c.kernel = RobustKernel::kCauchy;
    const RegistrationResult r =
        align(source_with_outliers(), scene().target, Eigen::Isometry3d::Identity(), c);
    expect_near_truth(r, kOutlierTolM, kOutlierTolRad);
}

class ThreadsIcpTest : public ::testing::TestWithParam<IcpMethod> {};

TEST_P(ThreadsIcpTest, OneAndTwoThreadsGiveBitIdenticalResults) {
    IcpConfig c = config_for(GetParam());
    c.max_iterations = 10;
    c.kernel = RobustKernel::kCauchy;
    c.parallel.num_threads = 1;
    const RegistrationResult one =
        align(scene().source, scene().target, Eigen::Isometry3d::Identity(), c);
    c.parallel.num_threads = 2;
    const RegistrationResult two =
        align(scene().source, scene().target, Eigen::Isometry3d::Identity(), c);
    EXPECT_TRUE(one.T_target_source.matrix() == two.T_target_source.matrix());
    EXPECT_TRUE(one.information == two.information);
    EXPECT_EQ(one.rmse_m, two.rmse_m);
    EXPECT_EQ(one.num_inliers, two.num_inliers);
}

INSTANTIATE_TEST_SUITE_P(Methods, ThreadsIcpTest,
                         ::testing::Values(IcpMethod::kPointToPoint, IcpMethod::kPointToPlane,
                                           IcpMethod::kGeneralized),
                         [](const auto& param_info) {
                             return std::string(to_string(param_info.param));
                         });

class PlaneDegeneracyTest : public ::testing::TestWithParam<IcpMethod> {};

TEST_P(PlaneDegeneracyTest, SinglePlaneReportsExactlyItsThreeFreeDirections) {
    const PointCloud target = sample_plane(4000, 4, 2.0);
    const PointCloud source = sample_plane(2000, 5, 2.0);
    const RegistrationResult r =
        align(source, target, Eigen::Isometry3d::Identity(), config_for(GetParam()));
    ASSERT_EQ(r.degeneracy.weak_directions.size(), 3u);
    EXPECT_TRUE(r.degeneracy.degenerate);
    EXPECT_FALSE(r.covariance.has_value());
    // x, y translation and yaw are free; z, roll and pitch (indices 2, 3, 4) are held. GICP
    // keeps an in-plane weight of epsilon = 1e-3 of the normal one: below the 1e-2 threshold.
    for (const Vector6d& v : r.degeneracy.weak_directions) {
        EXPECT_LT(v.segment<3>(2).norm(), 1e-6) << v.transpose();
    }
    EXPECT_GT(r.degeneracy.eigenvalues(3), 0.1);
}

INSTANTIATE_TEST_SUITE_P(Methods, PlaneDegeneracyTest,
                         ::testing::Values(IcpMethod::kPointToPlane, IcpMethod::kGeneralized),
                         [](const auto& param_info) {
                             return std::string(to_string(param_info.param));
                         });

TEST(IcpTest, RoomCornerIsWellConstrainedAndHasACovariance) {
    const RegistrationResult r =
        align(scene().source, scene().target, Eigen::Isometry3d::Identity(),
              config_for(IcpMethod::kPointToPlane));
    EXPECT_FALSE(r.degeneracy.degenerate);
    ASSERT_TRUE(r.covariance.has_value());
    const Matrix6d product = *r.covariance * r.information;
    EXPECT_TRUE(product.isApprox(Matrix6d::Identity(), 1e-6));
    // 8000 residuals of 5 mm noise: the translation sigma is a fraction of a millimetre.
    EXPECT_LT(std::sqrt(r.covariance->diagonal().head<3>().maxCoeff()), 0.001);
    EXPECT_GT(r.covariance->diagonal().minCoeff(), 0.0);
}

TEST(IcpTest, CloudsFarApartReportTooFewCorrespondencesInsteadOfConverging) {
    const Eigen::Isometry3d far = make_pose(0, 0, 0, Eigen::Vector3d(100.0, 0.0, 0.0));
    const RegistrationResult r =
        align(scene().source, scene().target, far, config_for(IcpMethod::kPointToPlane));
    EXPECT_FALSE(r.converged);
    EXPECT_EQ(r.status.rfind("too_few_correspondences", 0), 0u) << r.status;
    EXPECT_EQ(r.num_inliers, 0u);
    EXPECT_EQ(r.iterations, 0);
    EXPECT_TRUE(r.T_target_source.matrix() == far.matrix());
}

TEST(IcpTest, MaxIterationsIsReportedAsNotConverged) {
    IcpConfig c = config_for(IcpMethod::kPointToPoint);
    c.max_iterations = 2;
    const RegistrationResult r =
        align(scene().source, scene().target, Eigen::Isometry3d::Identity(), c);
    EXPECT_FALSE(r.converged);
    EXPECT_EQ(r.status, "max_iterations");
    EXPECT_EQ(r.iterations, 2);
}

TEST(IcpTest, EmptyOrNonFiniteInputThrowsInputError) {
    const PointCloud empty;
    const IcpConfig c;
    const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
    EXPECT_THROW(align(empty, scene().target, I, c), InputError);
    EXPECT_THROW(align(scene().source, empty, I, c), InputError);
    PointCloud bad = scene().source;
    bad.points[7].x() = std::nan("");
    EXPECT_THROW(align(bad, scene().target, I, c), InputError);
    Eigen::Isometry3d nan_pose = I;
    nan_pose(0, 3) = std::nan("");
    EXPECT_THROW(align(scene().source, scene().target, nan_pose, c), InputError);
    const KdTree wrong_tree(scene().source.points);
    EXPECT_THROW(align(scene().source, scene().target, wrong_tree, I, c), InputError);
    IcpConfig back_faces = c;  // needs target normals to tell the faces apart
    back_faces.back_faces = BackFaces::kReject;
    EXPECT_THROW(align(scene().source, scene().target, I, back_faces), InputError);
}

TEST(IcpTest, BadConfigThrowsConfigErrorNamingTheField) {
    IcpConfig c;
    c.max_correspondence_distance_m = -1.0;
    try {
        c.validate();
        FAIL() << "expected ConfigError";
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("icp.max_correspondence_distance_m = -1"),
                  std::string::npos)
            << e.what();
    }
    c = IcpConfig{};
    c.min_correspondences = 3;
    EXPECT_THROW(c.validate(), ConfigError);
    c = IcpConfig{};
    c.degeneracy_threshold = 1.0;
    EXPECT_THROW(c.validate(), ConfigError);
    c = IcpConfig{};
    c.covariance_cell_size_m = 0.0;
    EXPECT_THROW(c.validate(), ConfigError);
}

TEST(IcpTest, MethodNamesRoundTrip) {
    for (IcpMethod m :
         {IcpMethod::kPointToPoint, IcpMethod::kPointToPlane, IcpMethod::kGeneralized}) {
        EXPECT_EQ(icp_method_from_string(to_string(m)), m);
    }
    EXPECT_THROW(icp_method_from_string("ndt"), ConfigError);
    for (IcpCovariance m : {IcpCovariance::kHessian, IcpCovariance::kClusteredSandwich}) {
        EXPECT_EQ(icp_covariance_from_string(to_string(m)), m);
    }
    EXPECT_THROW(icp_covariance_from_string("censi"), ConfigError);
}

}  // namespace
}  // namespace scantling::registration
