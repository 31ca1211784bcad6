// The drone's global EKF (SPEC §4): T_world_odom from UWB ranges and position fixes on top of
// a drifting local EKF.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include <scantling/core/error.hpp>
#include <scantling/localization/global_ekf.hpp>

#include "drone_flight.hpp"

namespace scantling::localization {
namespace {

using testing::Flight;
using testing::FlightSensors;
using testing::FlightTick;
using testing::Trajectory;

const Eigen::Isometry3d kTrueWorldOdom =
    make_isometry(rotation_from_euler_zyx(0.0, 0.0, 0.3), {2.0, 1.0, 0.0});
const Eigen::Vector3d kTagLeverBodyM(0.1, 0.0, 0.05);

GlobalEkfConfig uwb_config() {
    GlobalEkfConfig c;
    // Four anchors around the figure-eight (world frame), at two heights.
    c.uwb_anchors_world_m = {
        {1, {-4.0, -4.0, 0.5}}, {2, {8.0, -3.0, 3.0}}, {3, {8.0, 6.0, 0.5}}, {4, {-4.0, 6.0, 3.0}}};
    c.p_body_uwb_tag_m = kTagLeverBodyM;
    c.uwb_range_sigma_m = 0.05;
    // The local below drifts by a 3 % scale and 5 mrad/s of yaw: beyond its covariance.
    c.translation_random_walk_m_per_sqrt_s = 0.05;
    c.yaw_random_walk_rad_per_sqrt_s = 0.01;
    return c;
}

/// A LiDAR odometry with a 3 % scale error and a yaw bias: the local EKF drifts.
FlightSensors drifting_sensors() {
    FlightSensors s;
    s.increment_scale_error = 0.03;
    s.increment_yaw_bias_rad = 5e-4;
    return s;
}

TEST(GlobalEkf, UwbRangesHoldTheWorldPositionWhileTheLocalDriftsAndRejectOutliers) {
    constexpr double kMaxWorldRmsM = 0.10;
    constexpr double kOutlierProbability = 0.05;
    constexpr double kConvergedAfterS = 2.0;
    LocalEkf local;
    GlobalEkf global(uwb_config(), kTrueWorldOdom);
    Flight flight(Trajectory{}, drifting_sensors(), 21);
    double sum_world = 0.0, sum_local = 0.0;
    int n = 0, outliers = 0, outliers_rejected = 0, inliers = 0, inliers_rejected = 0, k = 0;
    flight.fly(local, 30.0, [&](const FlightTick& tick) {
        global.add_local(local.state());
        if (k++ % 5 == 0) {
            const int id = 1 + (k / 5) % 4;
            const Eigen::Vector3d tag = kTrueWorldOdom * (tick.truth.T_odom_body * kTagLeverBodyM);
            io::UwbRecord r{tick.stamp_s, id, 0.0, true, true};
            r.range_m = (tag - global.config().uwb_anchors_world_m.at(id)).norm() +
                        flight.rng().normal(0.0, 0.05);
            r.line_of_sight = flight.rng().uniform() > kOutlierProbability;
            if (!r.line_of_sight) r.range_m += flight.rng().uniform(0.5, 2.0);
            const bool rejected = global.update_uwb(r).status == UpdateStatus::kRejected;
            (r.line_of_sight ? inliers : outliers)++;
            (r.line_of_sight ? inliers_rejected : outliers_rejected) += rejected ? 1 : 0;
        }
        if (tick.stamp_s < kConvergedAfterS) return;
        const Eigen::Vector3d p_true = (kTrueWorldOdom * tick.truth.T_odom_body).translation();
        sum_world += (global.state().T_odom_body.translation() - p_true).squaredNorm();
        sum_local +=
            (kTrueWorldOdom * local.state().T_odom_body.translation() - p_true).squaredNorm();
        ++n;
    });
    const double world_rms_m = std::sqrt(sum_world / n), local_rms_m = std::sqrt(sum_local / n);
    std::printf(
        "global EKF + UWB: world RMS %.4f m, local RMS %.4f m, outliers %d/%d rejected, "
        "inliers %d/%d rejected\n",
        world_rms_m, local_rms_m, outliers_rejected, outliers, inliers_rejected, inliers);
    EXPECT_LT(world_rms_m, kMaxWorldRmsM);
    EXPECT_GT(local_rms_m, 3.0 * world_rms_m);
    EXPECT_GE(outliers_rejected, 0.9 * outliers);
    EXPECT_LE(inliers_rejected, 0.02 * inliers);
    EXPECT_EQ(global.counters().uwb_rejected,
              static_cast<std::size_t>(outliers_rejected + inliers_rejected));
}

TEST(GlobalEkf, WithoutAbsoluteSourcesKeepsTheInitialTransformAndGrowsItsCovariance) {
    LocalEkf local;
    GlobalEkf global(uwb_config(), kTrueWorldOdom);
    const Eigen::Matrix4d P0 = global.covariance();
    Flight flight(Trajectory{}, drifting_sensors(), 4);
    flight.fly(local, 5.0, [&](const FlightTick&) { global.add_local(local.state()); });
    EXPECT_TRUE(global.T_world_odom().isApprox(kTrueWorldOdom, 1e-12));
    EXPECT_GT(global.covariance()(0, 0), P0(0, 0));
    EXPECT_GT(global.covariance()(3, 3), P0(3, 3));
    const DroneState world = global.state();
    EXPECT_TRUE(world.T_odom_body.isApprox(kTrueWorldOdom * local.state().T_odom_body, 1e-12));
    // The world covariance holds both filters: at least the local tilt and velocity.
    EXPECT_GE(world.covariance(6, 6) + world.covariance(7, 7),
              local.state().covariance(6, 6) + local.state().covariance(7, 7) - 1e-12);
    EXPECT_GT(world.covariance(0, 0), P0(0, 0));
}

TEST(GlobalEkf, PositionFixesCorrectAWrongStartAndGateAnOutlier) {
    GlobalEkfConfig config;
    config.initial_translation_sigma_m = 1.0;
    Eigen::Isometry3d wrong = kTrueWorldOdom;
    wrong.translation().x() += 0.6;
    LocalEkf local;
    GlobalEkf global(config, wrong);
    Flight flight(Trajectory{}, FlightSensors{}, 9);
    int k = 0;
    UpdateResult outlier;
    flight.fly(local, 5.0, [&](const FlightTick& tick) {
        global.add_local(local.state());
        if (k++ % 40 != 0) return;
        PositionFix fix{tick.stamp_s, (kTrueWorldOdom * tick.truth.T_odom_body).translation(),
                        Eigen::Matrix3d::Identity() * 0.05 * 0.05};
        fix.p_world_m += flight.rng().normal3(0.05);
        if (k == 121) fix.p_world_m.x() += 5.0;  // a multipath jump
        const UpdateResult r = global.update_position(fix);
        if (k == 121) outlier = r;
    });
    EXPECT_EQ(outlier.status, UpdateStatus::kRejected);
    const Eigen::Vector3d p_true =
        (kTrueWorldOdom * testing::truth_at(Trajectory{}, 5.0).T_odom_body).translation();
    EXPECT_LT((global.state().T_odom_body.translation() - p_true).norm(), 0.1);
    EXPECT_GE(global.counters().fixes_applied, 2u);
}

TEST(GlobalEkf, RefusesBadInputs) {
    GlobalEkf global(uwb_config(), kTrueWorldOdom);
    EXPECT_EQ(global.update_uwb({0.0, 1, 5.0, true, true}).status, UpdateStatus::kNoLocal);
    DroneState local;
    local.T_odom_body.translation() = Eigen::Vector3d(0, 0, 1.5);
    EXPECT_TRUE(global.add_local(local));
    EXPECT_EQ(global.update_uwb({0.0, 9, 5.0, true, true}).status, UpdateStatus::kUnknownAnchor);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    EXPECT_EQ(global.update_uwb({0.0, 1, nan, false, false}).status, UpdateStatus::kInvalid);
    EXPECT_THROW(global.update_uwb({0.0, 1, nan, true, true}), InputError);
    EXPECT_EQ(global.update_uwb({1.0, 1, 5.0, true, true}).status, UpdateStatus::kNoLocal);
    PositionFix fix;
    fix.covariance(1, 1) = -1.0;
    EXPECT_THROW(global.update_position(fix), InputError);
    local.v_odom_mps.x() = nan;
    EXPECT_THROW(global.add_local(local), InputError);
    local.v_odom_mps.x() = 0.0;
    local.stamp_s = -1.0;
    EXPECT_FALSE(global.add_local(local));
    EXPECT_TRUE(global.state().covariance.allFinite());
}

TEST(GlobalEkf, InvalidConfigNamesTheField) {
    const auto expect_field = [](const GlobalEkfConfig& c, const std::string& field) {
        try {
            GlobalEkf g(c, Eigen::Isometry3d::Identity());
            ADD_FAILURE() << "no ConfigError for " << field;
        } catch (const ConfigError& e) {
            EXPECT_NE(std::string(e.what()).find("global_ekf." + field), std::string::npos)
                << e.what();
        }
    };
    GlobalEkfConfig c;
    c.uwb_range_sigma_m = 0.0;
    expect_field(c, "uwb_range_sigma_m");
    c = {};
    c.max_local_age_s = -1.0;
    expect_field(c, "max_local_age_s");
    c = {};
    c.uwb_anchors_world_m[3] = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
    expect_field(c, "uwb_anchors_world_m[3]");
}

/// A still body (local: at p_odom, or moving at v_odom_mps from it) and UWB ranges from the
/// true world position `p_world_true_m`, every 0.01 s, cycling over the anchors.
struct StillBodyRun {
    Eigen::Vector3d p_odom_m = Eigen::Vector3d(0.0, 0.0, 1.0);
    Eigen::Vector3d v_odom_mps = Eigen::Vector3d::Zero();  ///< the local's (wrong) velocity
    Eigen::Vector3d p_world_true_m = Eigen::Vector3d(0.0, 0.0, 1.0);

    void fly(GlobalEkf& global, double duration_s) const {
        DroneState local;
        local.covariance = 1e-4 * Matrix9d::Identity();
        const auto& anchors = global.config().uwb_anchors_world_m;
        for (int k = 0; k * 0.01 < duration_s; ++k) {
            local.stamp_s = k * 0.01;
            local.T_odom_body.translation() = p_odom_m + v_odom_mps * local.stamp_s;
            local.v_odom_mps = v_odom_mps;
            global.add_local(local);
            const int id = 1 + k % 4;
            const double range_m = (p_world_true_m - anchors.at(id)).norm();
            global.update_uwb({local.stamp_s, id, range_m, true, true});
        }
    }
};

GlobalEkfConfig still_config() {
    GlobalEkfConfig c = uwb_config();
    c.p_body_uwb_tag_m.setZero();
    return c;
}

TEST(GlobalEkf, ReacquiresWhenEveryAnchorDisagreesWithItsOwnConfidentEstimate) {
    // The filter believes the body at (0, 0, 1) with 5 cm of σ; it is truly 3 m away: every
    // range fails the gate. After the window (50 ranges) the covariance re-opens.
    StillBodyRun run;
    run.p_world_true_m = Eigen::Vector3d(3.0, 0.0, 1.0);
    GlobalEkf global(still_config(), Eigen::Isometry3d::Identity());
    run.fly(global, 3.0);
    EXPECT_GE(global.counters().uwb_reacquisitions, 1u);
    EXPECT_LT((global.state().T_odom_body.translation() - run.p_world_true_m).norm(), 0.05);
    // Without re-acquisition the gate keeps the ranges out until the drift velocity's random
    // walk has grown the covariance enough: still 0.95 m off after 3 s.
    GlobalEkfConfig never = still_config();
    never.uwb_reacquire_window = 0;
    GlobalEkf locked(never, Eigen::Isometry3d::Identity());
    run.fly(locked, 3.0);
    EXPECT_EQ(locked.counters().uwb_reacquisitions, 0u);
    EXPECT_GT((locked.state().T_odom_body.translation() - run.p_world_true_m).norm(), 0.5);
}

TEST(GlobalEkf, EstimatesTheLocalFiltersVelocityErrorAsTheDriftVelocity) {
    // The local filter believes it moves at 0.3 m/s along x (an unobserved velocity error);
    // the body is still. UWB sees it still: the world output's velocity goes to zero.
    StillBodyRun run;
    run.v_odom_mps = Eigen::Vector3d(0.3, 0.0, 0.0);
    GlobalEkf global(still_config(), Eigen::Isometry3d::Identity());
    run.fly(global, 20.0);
    const DroneState world = global.state();
    EXPECT_LT(world.v_odom_mps.norm(), 0.05);
    EXPECT_NEAR(global.drift_velocity_mps().x(), -0.3, 0.05);
    EXPECT_LT((world.T_odom_body.translation() - run.p_world_true_m).norm(), 0.05);
    // Without the drift velocity the output keeps the local's 0.3 m/s.
    GlobalEkfConfig fixed = still_config();
    fixed.drift_velocity_random_walk_mps_per_sqrt_s = 0.0;
    GlobalEkf without(fixed, Eigen::Isometry3d::Identity());
    run.fly(without, 20.0);
    EXPECT_NEAR(without.state().v_odom_mps.x(), 0.3, 0.01);
}

}  // namespace
}  // namespace scantling::localization
