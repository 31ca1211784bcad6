#include <gtest/gtest.h>

#include <string>

#include <scantling/core/error.hpp>
#include <scantling/core/se3.hpp>
#include <scantling/registration/constrained_icp.hpp>

#include "scenes.hpp"

namespace scantling::registration {
namespace {

using test::make_pose;
using test::sample_room_corner;

// The SPEC's stopping rule (steps below 0.01 m and 0.01 rad) ends the iteration early, but the
// Gauss-Newton step that passes it lands within ~0.1 mm here (3 mm noise, 8000 points); the
// bounds leave room for that coarse stop.
constexpr double kTolM = 0.002;
constexpr double kTolRad = 0.001;

struct Clouds {
    PointCloud target;
    PointCloud source;
};

/// The room corner seen from two stops related by `truth` (T_target_source).
Clouds clouds_for(const Eigen::Isometry3d& truth) {
    return {sample_room_corner(20000, 21, 0.003),
            transformed(sample_room_corner(8000, 22, 0.003), truth.inverse())};
}

TEST(ConstrainedIcpTest, RecoversPlanarCorrectionWithinCapsAndKeepsZRollPitchExactlyZero) {
    const Eigen::Isometry3d truth = make_pose(0.0, 0.0, 0.03, Eigen::Vector3d(0.12, -0.15, 0.0));
    const Clouds c = clouds_for(truth);
    const RegistrationResult r = align_constrained(c.source, c.target, {});
    EXPECT_TRUE(r.converged) << r.status;
    EXPECT_EQ(r.status, "converged");
    EXPECT_LE(r.iterations, 25);
    const PoseError e = pose_error(r.T_target_source, truth);
    EXPECT_LT(e.translation_m, kTolM);
    EXPECT_LT(e.rotation_rad, kTolRad);
    const Eigen::Matrix4d M = r.T_target_source.matrix();
    EXPECT_EQ(M(2, 3), 0.0);  // z
    EXPECT_EQ(M(2, 0), 0.0);  // roll and pitch: the z row and column are exactly e_z
    EXPECT_EQ(M(2, 1), 0.0);
    EXPECT_EQ(M(0, 2), 0.0);
    EXPECT_EQ(M(1, 2), 0.0);
    EXPECT_EQ(M(2, 2), 1.0);
    ASSERT_TRUE(r.covariance.has_value());
    EXPECT_EQ(r.covariance->row(2).norm(), 0.0);  // fixed directions carry no variance
}

TEST(ConstrainedIcpTest, RotationBeyondCapFallsBackToPriorAndSaysSo) {
    const Clouds c = clouds_for(make_pose(0.0, 0.0, 0.1, Eigen::Vector3d(0.05, 0.0, 0.0)));
    const RegistrationResult r = align_constrained(c.source, c.target, {});
    EXPECT_FALSE(r.converged);
    EXPECT_EQ(r.status.rfind("cap_hit: rotation", 0), 0u) << r.status;
    EXPECT_TRUE(r.T_target_source.matrix() == Eigen::Matrix4d::Identity());
}

TEST(ConstrainedIcpTest, TranslationBeyondCapFallsBackToPriorAndSaysSo) {
    const Clouds c = clouds_for(make_pose(0.0, 0.0, 0.0, Eigen::Vector3d(0.45, 0.0, 0.0)));
    const Eigen::Isometry3d prior = make_pose(0.0, 0.0, 0.01, Eigen::Vector3d(0.0, 0.02, 0.0));
    const RegistrationResult r = align_constrained(c.source, c.target, {}, prior);
    EXPECT_FALSE(r.converged);
    EXPECT_EQ(r.status.rfind("cap_hit: translation", 0), 0u) << r.status;
    EXPECT_TRUE(r.T_target_source.matrix() == prior.matrix());
}

TEST(ConstrainedIcpTest, SixDofModeAlsoHonoursTheCaps) {
    const Eigen::Isometry3d truth = make_pose(0.01, -0.01, 0.02, Eigen::Vector3d(0.1, 0.05, 0.03));
    const Clouds c = clouds_for(truth);
    ConstrainedIcpConfig config;
    config.planar = false;
    const RegistrationResult r = align_constrained(c.source, c.target, config);
    EXPECT_TRUE(r.converged) << r.status;
    const PoseError e = pose_error(r.T_target_source, truth);
    EXPECT_LT(e.translation_m, kTolM);
    EXPECT_LT(e.rotation_rad, kTolRad);
}

TEST(ConstrainedIcpTest, OneAndTwoThreadsGiveBitIdenticalResults) {
    const Clouds c = clouds_for(make_pose(0.0, 0.0, 0.02, Eigen::Vector3d(0.1, 0.1, 0.0)));
    ConstrainedIcpConfig config;
    config.max_points = 5000;  // exercises the seeded thinning too
    config.parallel.num_threads = 1;
    const RegistrationResult one = align_constrained(c.source, c.target, config);
    config.parallel.num_threads = 2;
    const RegistrationResult two = align_constrained(c.source, c.target, config);
    EXPECT_TRUE(one.T_target_source.matrix() == two.T_target_source.matrix());
    EXPECT_EQ(one.num_inliers, two.num_inliers);
}

TEST(ConstrainedIcpTest, EmptyCloudsAndBadConfigThrow) {
    const Clouds c = clouds_for(Eigen::Isometry3d::Identity());
    EXPECT_THROW(align_constrained(PointCloud{}, c.target, {}), InputError);
    EXPECT_THROW(align_constrained(c.source, PointCloud{}, {}), InputError);
    ConstrainedIcpConfig config;
    config.max_rotation_rad = 0.0;
    EXPECT_THROW(align_constrained(c.source, c.target, config), ConfigError);
    config = {};
    config.voxel_size_m = -0.01;
    EXPECT_THROW(config.validate(), ConfigError);
}

TEST(CorrectedMapPoseTest, AppliesLocalisationMotionThenCorrection) {
    const Eigen::Isometry3d P_prev = make_pose(0.0, 0.0, 0.5, Eigen::Vector3d(2.0, 1.0, 0.0));
    const Eigen::Isometry3d P_cprev = make_pose(0.0, 0.0, 0.45, Eigen::Vector3d(2.1, 0.9, 0.0));
    const Eigen::Isometry3d P_cnew = make_pose(0.0, 0.0, 0.65, Eigen::Vector3d(3.0, 1.4, 0.0));
    const Eigen::Isometry3d C = make_pose(0.0, 0.0, -0.01, Eigen::Vector3d(0.02, -0.03, 0.0));
    const Eigen::Isometry3d P_new = corrected_map_pose(P_prev, P_cprev, P_cnew, C);
    // The corrected motion since the previous stop is the localisation's motion then C.
    const Eigen::Isometry3d motion = P_prev.inverse() * P_new;
    const Eigen::Isometry3d expected = P_cprev.inverse() * P_cnew * C;
    EXPECT_TRUE(motion.matrix().isApprox(expected.matrix(), 1e-12));
    // No drift and no correction: the map pose is the localisation pose.
    const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
    EXPECT_TRUE(
        corrected_map_pose(P_cprev, P_cprev, P_cnew, I).matrix().isApprox(P_cnew.matrix(), 1e-12));
}

}  // namespace
}  // namespace scantling::registration
