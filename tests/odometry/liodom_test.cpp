#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <scantling/core/error.hpp>
#include <scantling/core/se3.hpp>
#include <scantling/odometry/liodom.hpp>

#include "synthetic_scene.hpp"

namespace scantling::odometry {
namespace {

constexpr double kPeriodS = 0.1;

/// The sensor drives along the hall's aisle at 1.5 m/s with a gentle weave and yaw.
Eigen::Isometry3d true_pose(std::size_t i) {
    const double t = kPeriodS * static_cast<double>(i);
    const Eigen::Vector3d p(-15.0 + 1.5 * t, 0.4 * std::sin(0.5 * t), 1.8 + 0.05 * std::sin(t));
    return make_isometry(rotation_from_euler_zyx(0.01 * std::sin(t), 0.0, 0.15 * std::sin(0.4 * t)),
                         p);
}

class SyntheticRun : public ::testing::Test {
  protected:
    static constexpr std::size_t kSweeps = 60;
    static void SetUpTestSuite() {
        const test::Scene scene = test::hall_scene();
        Rng rng(42);
        sweeps_ = new std::vector<PointCloud>();
        for (std::size_t i = 0; i < kSweeps; ++i) {
            PointCloud sweep = test::scan(scene, true_pose(i), test::SweepSpec{}, rng);
            sweep.stamp_s = kPeriodS * static_cast<double>(i);
            sweeps_->push_back(std::move(sweep));
        }
    }
    static void TearDownTestSuite() {
        delete sweeps_;
        sweeps_ = nullptr;
    }
    static LiodomConfig config(int threads) {
        // The hall is street-sized: the automotive preset, with the range gate of a drone.
        LiodomConfig c = liodom_preset("kitti");
        c.features.min_range_m = 0.5;
        c.parallel.num_threads = threads;
        c.registration.parallel.num_threads = threads;
        return c;
    }
    static std::vector<FrameReport> run(const LiodomConfig& c, const SweepReader& reader) {
        return run_odometry(kSweeps, reader, c, {}, true_pose(0));
    }
    static SweepReader reader() {
        return [](std::size_t i) { return (*sweeps_)[i]; };
    }
    static std::vector<PointCloud>* sweeps_;
};
std::vector<PointCloud>* SyntheticRun::sweeps_ = nullptr;

TEST_F(SyntheticRun, FollowsTheTrueTrajectory) {
    const auto reports = run(config(1), reader());
    ASSERT_EQ(reports.size(), kSweeps);
    EXPECT_EQ(reports.front().status, FrameStatus::kFirst);
    double path = 0.0;
    for (std::size_t i = 1; i < kSweeps; ++i) {
        path += (true_pose(i).translation() - true_pose(i - 1).translation()).norm();
        EXPECT_EQ(reports[i].status, FrameStatus::kOk) << i << ": " << reports[i].message;
        EXPECT_GT(reports[i].num_correspondences, 100U);
    }
    const PoseError end = pose_error(reports.back().T_odom_sensor, true_pose(kSweeps - 1));
    // ~8.9 m driven. This analytic hall (pillars and crates, 64 rings over 40°) checks the
    // pipeline, not the accuracy claims (those are measured on the simulator's worlds,
    // docs/results.md): measured 0.09 m and 0.65° at the end, a lost track would be metres off.
    EXPECT_LT(end.translation_m, 0.02 * path);
    EXPECT_LT(end.rotation_rad, 1.0 * M_PI / 180.0);
}

TEST_F(SyntheticRun, PipelinedRunEqualsTheSequentialOne) {
    const auto a = run(config(1), reader());
    const auto b = run(config(2), reader());
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        EXPECT_TRUE(a[i].T_odom_sensor.matrix() == b[i].T_odom_sensor.matrix()) << i;
        EXPECT_EQ(a[i].num_correspondences, b[i].num_correspondences);
    }
}

TEST_F(SyntheticRun, BadSweepsAreReportedAndCarriedByTheMotionModel) {
    // Sweep 20 empty, 21 all NaN, 22 unreadable; a 1 s gap before sweep 40.
    const double nan = std::numeric_limits<double>::quiet_NaN();
    SweepReader bad = [&](std::size_t i) -> PointCloud {
        PointCloud s = (*sweeps_)[i];
        if (i == 20) {
            PointCloud empty;
            empty.stamp_s = s.stamp_s;
            return empty;
        }
        if (i == 21) {
            for (auto& p : s.points) p = Eigen::Vector3d(nan, nan, nan);
            return s;
        }
        if (i == 22) throw FileError("sweep_22.pcd", "cannot open");
        return s;
    };
    const auto reports = run(config(2), bad);
    ASSERT_EQ(reports.size(), kSweeps);
    EXPECT_EQ(reports[20].status, FrameStatus::kNoEdges);
    EXPECT_EQ(reports[21].status, FrameStatus::kNoEdges);
    EXPECT_EQ(reports[22].status, FrameStatus::kUnreadable);
    EXPECT_NE(reports[22].message.find("sweep_22.pcd"), std::string::npos);
    // The carried poses follow the motion model (within the 0.3 s of constant velocity).
    for (std::size_t i : {20U, 21U, 22U}) {
        EXPECT_LT(pose_error(reports[i].T_odom_sensor, true_pose(i)).translation_m, 0.05) << i;
    }
    // It recovers: the end is as good as without the bad sweeps.
    EXPECT_EQ(reports[23].status, FrameStatus::kOk);
    EXPECT_LT(pose_error(reports.back().T_odom_sensor, true_pose(kSweeps - 1)).translation_m, 0.15);
}

TEST_F(SyntheticRun, ATimeJumpIsFlagged) {
    SweepReader jumpy = [&](std::size_t i) {
        PointCloud s = (*sweeps_)[i];
        if (i >= 40) s.stamp_s += 1.0;
        return s;
    };
    const auto reports = run(config(1), jumpy);
    EXPECT_TRUE(reports[40].time_gap);
    EXPECT_FALSE(reports[39].time_gap);
    EXPECT_FALSE(reports[41].time_gap);
    EXPECT_NE(reports[40].message.find("time gap"), std::string::npos);
    // Registration still finds the pose (the sensor moved only one period).
    EXPECT_EQ(reports[40].status, FrameStatus::kOk);
    EXPECT_LT(pose_error(reports[40].T_odom_sensor, true_pose(40)).translation_m, 0.12);
}

TEST(LiodomConfig, PresetsLoadAndDiffer) {
    const auto names = liodom_preset_names();
    ASSERT_EQ(names.size(), 3U);
    for (const auto& n : names) EXPECT_NO_THROW(liodom_preset(n).validate()) << n;
    EXPECT_GT(liodom_preset("kitti").features.max_range_m,
              liodom_preset("confined").features.max_range_m);
    EXPECT_THROW(liodom_preset("velodyne"), ConfigError);
    const std::string yaml = describe_liodom_config(liodom_preset("confined"));
    EXPECT_NE(yaml.find("max_range_m"), std::string::npos);
    EXPECT_NE(yaml.find("cell_size_xy_m"), std::string::npos);
}

TEST(LiodomConfig, InvalidValuesNameTheField) {
    LiodomConfig c;
    c.max_time_gap_s = 0.0;
    try {
        c.validate();
        FAIL();
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("odometry.max_time_gap_s"), std::string::npos);
    }
}

}  // namespace
}  // namespace scantling::odometry
