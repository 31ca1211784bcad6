// Relative motions in the trajectory metrics: rotations as printed in pose files (rounded, so
// not quite orthonormal) give no error of their own, and a trajectory against itself gives
// exactly 0 in every metric.
#include <scantling/core/error.hpp>
#include <scantling/core/se3.hpp>
#include <scantling/core/trajectory_metrics.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace scantling {
namespace {

using Trajectory = std::vector<Eigen::Isometry3d>;

/// Rounding of the rotations to the 6 decimals of a "%f" pose file moves each rotation by
/// ~1e-6 rad; over a 100 m segment that is ~1e-6 rad / 100 m = 6e-5 deg/100 m at most.
constexpr double kRoundingRreDegPer100m = 1e-4;

/// A winding 3-D drive, 2 m a frame, turning in yaw, pitch and roll.
Trajectory winding_drive(int num_frames) {
    Trajectory poses;
    for (int i = 0; i < num_frames; ++i) {
        const double s = 2.0 * i;
        const Eigen::Matrix3d R = rotation_from_euler_zyx(0.05 * std::sin(s / 70.0),
                                                          0.08 * std::sin(s / 110.0), 0.004 * s);
        poses.push_back(make_isometry(
            R, Eigen::Vector3d(s, 20.0 * std::sin(s / 150.0), 2.0 * std::sin(s / 90.0))));
    }
    return poses;
}

/// `poses` as a KITTI file written with "%.6f" would hold them: every entry rounded to 6
/// decimals, so RᵀR − I is ~1e-6, not ~1e-16.
Trajectory rounded_to_six_decimals(Trajectory poses) {
    for (Eigen::Isometry3d& T : poses) {
        T.matrix().topRows<3>() =
            T.matrix().topRows<3>().unaryExpr([](double v) { return std::round(v * 1e6) / 1e6; });
    }
    return poses;
}

/// The estimate turns by `yaw_rate_rad_per_frame` more than the truth every frame.
Trajectory with_yaw_drift(const Trajectory& gt, double yaw_rate_rad_per_frame) {
    Trajectory est{gt.front()};
    const Eigen::Isometry3d drift = make_isometry(
        rotation_from_euler_zyx(0.0, 0.0, yaw_rate_rad_per_frame), Eigen::Vector3d::Zero());
    for (std::size_t i = 1; i < gt.size(); ++i) {
        est.push_back(est.back() * drift * (gt[i - 1].inverse() * gt[i]));
    }
    return est;
}

TEST(RelativePose, TrajectoryWithRoundedRotationsAgainstItselfGivesExactZeros) {
    const Trajectory poses = rounded_to_six_decimals(winding_drive(400));
    ASSERT_GT((poses[7].linear().transpose() * poses[7].linear() - Eigen::Matrix3d::Identity())
                  .cwiseAbs()
                  .maxCoeff(),
              1e-8)
        << "the test needs rotations that are not orthonormal to rounding";
    const TrajectoryMetrics m = evaluate_trajectory(poses, poses);
    ASSERT_GT(m.kitti.num_segments, 0u);
    EXPECT_EQ(m.kitti.rte_percent, 0.0);
    EXPECT_EQ(m.kitti.rre_deg_per_100m, 0.0);
    for (const KittiLengthErrors& l : m.kitti.per_length) {
        EXPECT_EQ(l.rte_percent, 0.0) << l.length_m;
        EXPECT_EQ(l.rre_deg_per_100m, 0.0) << l.length_m;
    }
    EXPECT_EQ(m.ate.rmse_m, 0.0);
    EXPECT_EQ(m.ate.max_m, 0.0);
    EXPECT_EQ(m.ate.median_m, 0.0);
    EXPECT_EQ(m.ate.percent_of_path, 0.0);
    ASSERT_GT(m.rpe.num_pairs, 0u);
    EXPECT_EQ(m.rpe.trans_rmse_m, 0.0);
    EXPECT_EQ(m.rpe.rot_mean_deg, 0.0);
}

TEST(RelativePose, ExactRotationsAgainstThemselvesGiveExactZerosToo) {
    const Trajectory poses = winding_drive(400);
    const TrajectoryMetrics m = evaluate_trajectory(poses, poses);
    EXPECT_EQ(m.kitti.rre_deg_per_100m, 0.0);
    EXPECT_EQ(m.rpe.rot_mean_deg, 0.0);
    EXPECT_EQ(m.ate.rmse_m, 0.0);
}

TEST(RelativePose, RoundedRotationsDoNotChangeTheRotationError) {
    // 1e-5 rad a frame of heading drift: ~2.9e-2 deg/100 m. Rounding both trajectories as a
    // pose file does must not add the ~1e-3 rad (square root of 1e-6) a transpose gives.
    const Trajectory gt = winding_drive(400);
    const Trajectory est = with_yaw_drift(gt, 1e-5);
    const KittiMetrics exact = kitti_metrics(gt, est);
    const KittiMetrics rounded =
        kitti_metrics(rounded_to_six_decimals(gt), rounded_to_six_decimals(est));
    ASSERT_GT(exact.num_segments, 0u);
    EXPECT_NEAR(rounded.rre_deg_per_100m, exact.rre_deg_per_100m, kRoundingRreDegPer100m);
    const RpeResult rpe_exact = relative_pose_error(gt, est);
    const RpeResult rpe_rounded =
        relative_pose_error(rounded_to_six_decimals(gt), rounded_to_six_decimals(est));
    // RPE over 10 m (5 frames): 5e-5 rad = 2.9e-3 deg; rounding may move it by ~1e-6 rad.
    EXPECT_NEAR(rpe_rounded.rot_mean_deg, rpe_exact.rot_mean_deg, 1e-4);
}

TEST(RelativePose, AMatrixThatIsNoRotationIsRefusedNamingThePose) {
    Trajectory est = winding_drive(50);
    est[17].linear() *= 1.01;  // a scale, not rounding
    try {
        evaluate_trajectory(winding_drive(50), est);
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("estimated pose 17 has no rotation"),
                  std::string::npos)
            << e.what();
    }
    Trajectory mirrored = winding_drive(50);
    mirrored[3].linear().col(2) *= -1.0;  // det = −1
    EXPECT_THROW(relative_pose_error(mirrored, winding_drive(50)), InputError);
}

TEST(RelativePose, UmeyamaOfIdenticalPointsIsExactlyTheIdentity) {
    std::vector<Eigen::Vector3d> points;
    for (const Eigen::Isometry3d& T : winding_drive(100)) points.push_back(T.translation());
    const Eigen::Isometry3d T = align_umeyama(points, points);
    EXPECT_EQ(T.matrix(), Eigen::Matrix4d::Identity()) << T.matrix();
}

}  // namespace
}  // namespace scantling
