#include <scantling/core/error.hpp>
#include <scantling/core/se3.hpp>
#include <scantling/core/trajectory_metrics.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

namespace scantling {
namespace {

constexpr double kPi = std::numbers::pi;
// Sums of a few thousand double terms: far below any printed digit.
constexpr double kExactTol = 1e-9;

using Trajectory = std::vector<Eigen::Isometry3d>;

Eigen::Isometry3d pose(double x, double y, double z, double yaw_rad = 0.0) {
    return make_isometry(rotation_from_euler_zyx(0.0, 0.0, yaw_rad), Eigen::Vector3d(x, y, z));
}

/// A drive along x at `step_m` per frame, with a gentle weave in y and z so that the path is
/// not degenerate for the alignment.
Trajectory drive(int num_frames, double step_m) {
    Trajectory poses;
    for (int i = 0; i < num_frames; ++i) {
        const double s = step_m * i;
        poses.push_back(pose(s, 20.0 * std::sin(s / 150.0), 2.0 * std::sin(s / 90.0)));
    }
    return poses;
}

/// `num_frames` poses 1 m apart along x (exact integers, so distances are exact).
Trajectory straight_line(int num_frames) {
    Trajectory poses;
    for (int i = 0; i < num_frames; ++i) poses.push_back(pose(i, 0, 0));
    return poses;
}

/// Relative motions of `gt` with every translation scaled by `scale`: a pure scale drift.
Trajectory scaled_motion(const Trajectory& gt, double scale) {
    Trajectory est{gt.front()};
    for (std::size_t i = 1; i < gt.size(); ++i) {
        Eigen::Isometry3d delta = gt[i - 1].inverse() * gt[i];
        delta.translation() *= scale;
        est.push_back(est.back() * delta);
    }
    return est;
}

TEST(TrajectoryMetrics, IdenticalTrajectoriesHaveZeroError) {
    const Trajectory gt = drive(1200, 1.0);
    const TrajectoryMetrics m = evaluate_trajectory(gt, gt);
    EXPECT_GT(m.kitti.num_segments, 0u);
    EXPECT_LT(m.kitti.rte_percent, kExactTol);
    // acos near 1 turns rounding of the trace (~1e-16) into ~1e-8 rad: still far below 1e-6.
    EXPECT_LT(m.kitti.rre_deg_per_100m, 1e-6);
    EXPECT_LT(m.ate.rmse_m, kExactTol);
    EXPECT_LT(m.rpe.trans_rmse_m, kExactTol);
    EXPECT_LT(m.rpe.rot_mean_deg, 1e-5);
    EXPECT_EQ(m.num_poses, 1200u);
}

TEST(TrajectoryMetrics, ConstantScaleDriftOfOnePercentGivesOnePercentRte) {
    const Trajectory gt = straight_line(1001);
    const Trajectory est = scaled_motion(gt, 1.01);
    const KittiMetrics m = kitti_metrics(gt, est);
    // A segment of nominal length L spans L + 1 frames (see the counting rule below), so its
    // end is 0.01 (L + 1) m off: t_err / len = 1 % × (L + 1) / L.
    ASSERT_EQ(m.per_length.size(), 8u);
    EXPECT_EQ(m.per_length.front().length_m, 100.0);
    EXPECT_EQ(m.per_length.back().length_m, 800.0);
    std::size_t sum = 0;
    for (const KittiLengthErrors& l : m.per_length) {
        sum += l.num_segments;
        EXPECT_NEAR(l.rte_percent, (l.length_m + 1.0) / l.length_m, kExactTol) << l.length_m;
        EXPECT_LT(l.rre_deg_per_100m, kExactTol);
    }
    EXPECT_EQ(sum, m.num_segments);
    EXPECT_GT(m.rte_percent, 1.0);
    EXPECT_LT(m.rte_percent, 1.01);
}

TEST(TrajectoryMetrics, SegmentsFollowTheDevkitCountingRule) {
    // 1001 frames 1 m apart along a line: a segment of length L starting at frame f ends at the
    // first frame strictly more than L further, f + L + 1, which must exist (<= 1000). Starts
    // every 10 frames: f = 0, 10, ..., f <= 999 - L.
    const Trajectory gt = straight_line(1001);
    const KittiMetrics m = kitti_metrics(gt, gt);
    ASSERT_EQ(m.per_length.size(), 8u);
    for (const KittiLengthErrors& l : m.per_length) {
        const auto expected = static_cast<std::size_t>((999 - l.length_m) / 10) + 1;
        EXPECT_EQ(l.num_segments, expected) << l.length_m;
    }
}

TEST(TrajectoryMetrics, PureYawDriftGivesExpectedRre) {
    // Straight drive along x, 1 m a frame; the estimate turns by kYawRate each metre but moves
    // as the truth in its own frame. A segment of nominal length L spans L + 1 frames, so its
    // heading error is kYawRate (L + 1) and r_err / len = kYawRate (L + 1) / L.
    constexpr double kYawRateRadPerM = 1e-5;
    const Trajectory gt = straight_line(1001);
    Trajectory est;
    Eigen::Isometry3d T_est = Eigen::Isometry3d::Identity();
    for (std::size_t i = 0; i < gt.size(); ++i) {
        est.push_back(T_est);
        T_est = T_est * pose(1.0, 0, 0, kYawRateRadPerM);
    }
    const KittiMetrics m = kitti_metrics(gt, est);
    const double deg_per_100m = kYawRateRadPerM * 180.0 / kPi * 100.0;
    double weighted_sum = 0.0;
    for (const KittiLengthErrors& l : m.per_length) {
        const double expected = deg_per_100m * (l.length_m + 1.0) / l.length_m;
        // acos of 1 − θ²/2 in double keeps ~8 digits at θ ~ 1e-3 rad.
        EXPECT_NEAR(l.rre_deg_per_100m, expected, 1e-6 * expected) << l.length_m;
        weighted_sum += expected * static_cast<double>(l.num_segments);
    }
    EXPECT_NEAR(m.rre_deg_per_100m, weighted_sum / static_cast<double>(m.num_segments),
                1e-6 * deg_per_100m);
    // The heading error bends the path sideways, so the translation is off too.
    EXPECT_GT(m.rte_percent, 0.0);
}

TEST(TrajectoryMetrics, ShortPathHasNoKittiSegmentsButAteAndRpe) {
    const Trajectory gt = drive(60, 1.0);
    Trajectory est = gt;
    for (Eigen::Isometry3d& T : est) T.translation().y() += 0.5;  // constant offset
    const TrajectoryMetrics m = evaluate_trajectory(gt, est);
    EXPECT_EQ(m.kitti.num_segments, 0u);
    EXPECT_TRUE(std::isnan(m.kitti.rte_percent));
    EXPECT_TRUE(m.kitti.per_length.empty());
    EXPECT_LT(m.ate.rmse_m, 1e-9);  // removed by the alignment
    EXPECT_GT(m.rpe.num_pairs, 40u);
    EXPECT_LT(m.rpe.trans_rmse_m, 1e-9);  // relative motions are exact
}

TEST(TrajectoryMetrics, AteOfAConstantPositionErrorIsItsMagnitude) {
    // Each true position is estimated twice, 0.3 m above and 0.3 m below: the offsets cancel in
    // the cross-covariance, so the best alignment is the identity and every error is 0.3 m.
    Trajectory gt, est;
    for (int i = 0; i < 100; ++i) {
        for (const double dz : {0.3, -0.3}) {
            gt.push_back(pose(i, 10.0 * std::sin(i / 30.0), 0));
            est.push_back(pose(i, 10.0 * std::sin(i / 30.0), dz));
        }
    }
    const AteResult ate = absolute_trajectory_error(gt, est);
    EXPECT_LT((ate.T_gt_est.matrix() - Eigen::Matrix4d::Identity()).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_NEAR(ate.rmse_m, 0.3, 1e-12);
    EXPECT_NEAR(ate.mean_m, 0.3, 1e-12);
    EXPECT_NEAR(ate.median_m, 0.3, 1e-12);
    EXPECT_NEAR(ate.max_m, 0.3, 1e-12);
    EXPECT_EQ(ate.errors_m.size(), 200u);
    const double path_m = cumulative_distances_m(gt).back();
    EXPECT_NEAR(ate.percent_of_path, 100.0 * 0.3 / path_m, 1e-12);
}

TEST(TrajectoryMetrics, AteOfAStraightPathDoesNotThrow) {
    Trajectory gt, est;
    for (int i = 0; i < 20; ++i) {
        gt.push_back(pose(i, 0, 0));
        est.push_back(pose(0, i * 1.0, 5.0));  // the same line elsewhere, turned by 90°
    }
    EXPECT_LT(absolute_trajectory_error(gt, est).rmse_m, 1e-9);
}

TEST(TrajectoryMetrics, RpeMeasuresTheErrorOverTenMetres) {
    // The estimate's steps are 2 % too long: over 10 m (10 frames) the error is 0.2 m.
    const Trajectory gt = straight_line(101);
    const Trajectory est = scaled_motion(gt, 1.02);
    const RpeResult rpe = relative_pose_error(gt, est);
    EXPECT_EQ(rpe.num_pairs, 91u);  // i = 0..90 reach i + 10
    EXPECT_NEAR(rpe.trans_rmse_m, 0.2, 1e-9);
    EXPECT_NEAR(rpe.trans_mean_m, 0.2, 1e-9);
    EXPECT_EQ(rpe.rot_mean_deg, 0.0);
}

TEST(TrajectoryMetrics, RejectsBadInputNamingTheProblem) {
    const Trajectory gt = drive(10, 1.0);
    Trajectory shorter(gt.begin(), gt.end() - 1);
    EXPECT_THROW(evaluate_trajectory(gt, shorter), InputError);
    EXPECT_THROW(evaluate_trajectory(Trajectory{}, Trajectory{}), InputError);
    EXPECT_THROW(evaluate_trajectory(Trajectory{gt[0]}, Trajectory{gt[0]}), InputError);
    Trajectory bad = gt;
    bad[3].translation().x() = std::nan("");
    try {
        kitti_metrics(gt, bad);
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("estimated pose 3 is not finite"), std::string::npos)
            << e.what();
    }
    TrajectoryMetricsConfig config;
    config.kitti.frame_step = 0;
    EXPECT_THROW(evaluate_trajectory(gt, gt, config), ConfigError);
    config = {};
    config.rpe.delta_m = -1.0;
    EXPECT_THROW(evaluate_trajectory(gt, gt, config), ConfigError);
    KittiMetricConfig kitti;
    kitti.segment_lengths_m = {100, 0};
    EXPECT_THROW(kitti.validate(), ConfigError);
}

TEST(Umeyama, RecoversAKnownRigidTransform) {
    const Eigen::Isometry3d T_gt_est =
        make_isometry(so3_exp(Eigen::Vector3d(0.3, -0.5, 1.2)), Eigen::Vector3d(4, -2, 7));
    std::vector<Eigen::Vector3d> est, gt;
    for (int i = 0; i < 30; ++i) {
        est.emplace_back(std::sin(i), 0.1 * i, std::cos(0.5 * i));
        gt.push_back(T_gt_est * est.back());
    }
    const Eigen::Isometry3d T = align_umeyama(est, gt);
    EXPECT_LT((T.matrix() - T_gt_est.matrix()).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(Umeyama, PlanarPointsGiveARotationNotAReflection) {
    const Eigen::Isometry3d T_gt_est =
        make_isometry(so3_exp(Eigen::Vector3d(0.0, 0.0, 2.5)), Eigen::Vector3d(1, 2, 0));
    std::vector<Eigen::Vector3d> est{{0, 0, 0}, {1, 0, 0}, {0, 2, 0}, {3, 1, 0}};
    std::vector<Eigen::Vector3d> gt;
    for (const auto& p : est) gt.push_back(T_gt_est * p);
    const Eigen::Isometry3d T = align_umeyama(est, gt);
    EXPECT_NEAR(T.linear().determinant(), 1.0, 1e-12);
    EXPECT_LT((T.matrix() - T_gt_est.matrix()).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(Umeyama, RejectsDegenerateInput) {
    const std::vector<Eigen::Vector3d> two{{0, 0, 0}, {1, 0, 0}};
    EXPECT_THROW(align_umeyama(two, two), InputError);
    const std::vector<Eigen::Vector3d> line{{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {5, 5, 5}};
    EXPECT_THROW(align_umeyama(line, line), InputError);
    const std::vector<Eigen::Vector3d> same(5, Eigen::Vector3d(1, 2, 3));
    EXPECT_THROW(align_umeyama(same, same), InputError);
    const std::vector<Eigen::Vector3d> tri{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    EXPECT_THROW(align_umeyama(tri, line), InputError);  // sizes differ
    std::vector<Eigen::Vector3d> nan = tri;
    nan[1].y() = std::nan("");
    EXPECT_THROW(align_umeyama(nan, tri), InputError);
}

TEST(Association, MatchesOffsetStampsAndInterpolatesTheGroundTruth) {
    // Ground truth at 100 Hz turning at a constant rate; estimates at 10 Hz offset by 4 ms.
    std::vector<double> gt_stamps, est_stamps;
    Trajectory gt, est;
    auto truth_at = [](double t) { return pose(3.0 * t, std::sin(t), 0.1 * t, 0.4 * t); };
    for (int i = 0; i <= 1000; ++i) {
        gt_stamps.push_back(0.01 * i);
        gt.push_back(truth_at(0.01 * i));
    }
    for (int i = 0; i < 100; ++i) {
        est_stamps.push_back(0.1 * i + 0.004);
        est.push_back(truth_at(est_stamps.back()));
    }
    est_stamps.push_back(50.0);  // far beyond the ground truth: unmatched
    est.push_back(truth_at(50.0));
    const AssociatedTrajectories a = associate_by_time(gt_stamps, gt, est_stamps, est);
    ASSERT_EQ(a.est.size(), 100u);
    EXPECT_EQ(a.num_unmatched, 1u);
    // Interpolation is exact for yaw (slerp) and linear motion, close for the sine in y.
    double worst_m = 0.0;
    for (std::size_t i = 0; i < a.est.size(); ++i) {
        worst_m = std::max(worst_m, (a.gt[i].translation() - a.est[i].translation()).norm());
        EXPECT_NEAR(rotation_angle_rad(a.gt[i].linear().transpose() * a.est[i].linear()), 0.0,
                    1e-9);
    }
    // Linear interpolation of sin t over 10 ms is off by at most (0.01 s)² / 8 = 1.25e-5 m;
    // nearest-pose matching would be 4 ms × 3 m/s = 12 mm off.
    EXPECT_LT(worst_m, 1.3e-5);

    AssociationConfig nearest;
    nearest.interpolate_gt = false;
    const AssociatedTrajectories b = associate_by_time(gt_stamps, gt, est_stamps, est, nearest);
    EXPECT_NEAR((b.gt[5].translation() - b.est[5].translation()).x(), -0.012, 1e-9);

    AssociationConfig strict;
    strict.max_time_difference_s = 0.001;
    EXPECT_THROW(associate_by_time(gt_stamps, gt, est_stamps, est, strict), InputError);
    std::vector<double> unsorted = est_stamps;
    std::swap(unsorted[2], unsorted[3]);
    EXPECT_THROW(associate_by_time(gt_stamps, gt, unsorted, est), InputError);
}

// ---- SiMpLE's published KITTI figures (the devkit's per-sequence mean) ----

std::string kitti_poses_dir() { return std::string(SCANTLING_SHARED_DATA_DIR) + "/kitti-poses"; }

// A minimal reader (core may not use io): 12 numbers a line, row-major 3×4.
Trajectory read_poses(const std::string& path) {
    std::ifstream in(path);
    Trajectory poses;
    Eigen::Matrix<double, 3, 4, Eigen::RowMajor> m;
    while (true) {
        for (int k = 0; k < 12; ++k) {
            if (!(in >> m.data()[k])) return poses;
        }
        Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
        T.matrix().topRows<3>() = m;
        poses.push_back(T);
    }
}

void expect_simple_figure(const std::string& sequence, double published_percent) {
    const std::string gt_path = kitti_poses_dir() + "/groundtruth/" + sequence + ".txt";
    const std::string est_path = kitti_poses_dir() + "/simple-estimates/" + sequence + ".txt";
    if (!std::filesystem::exists(gt_path) || !std::filesystem::exists(est_path)) {
        GTEST_SKIP() << "shared data not found: " << gt_path << " (set SCANTLING_SHARED_DATA_DIR)";
    }
    const Trajectory gt = read_poses(gt_path), est = read_poses(est_path);
    const KittiMetrics m = kitti_metrics(gt, est);
    // SiMpLE's README prints 4 decimals: agreement means rounding to the same figure.
    EXPECT_NEAR(m.rte_percent, published_percent, 0.5e-4) << "sequence " << sequence;
}

TEST(KittiMetricOnSimple, ReproducesThePublishedFigureOnSequence05) {
    expect_simple_figure("05", 0.3372);
}

TEST(KittiMetricOnSimple, ReproducesThePublishedFigureOnSequence00) {
    expect_simple_figure("00", 0.6667);
}

TEST(KittiMetricOnSimple, ReproducesThePublishedFiguresOnTheOtherSequences) {
    // The same column of SiMpLE's README table (Ubuntu 20.04.5), from the same estimates.
    const std::vector<std::pair<std::string, double>> published = {
        {"01", 0.7749}, {"02", 0.6263}, {"03", 0.7369}, {"04", 0.4067}, {"06", 0.2613},
        {"07", 0.4706}, {"08", 0.8236}, {"09", 0.5684}, {"10", 0.6454}};
    for (const auto& [sequence, percent] : published) expect_simple_figure(sequence, percent);
}

}  // namespace
}  // namespace scantling
