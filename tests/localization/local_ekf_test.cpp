// The drone's local EKF (SPEC §4): IMU prediction, LiDAR increments by stochastic cloning,
// range finder and barometer, against an analytic figure-eight.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <scantling/core/error.hpp>
#include <scantling/localization/local_ekf.hpp>

#include "drone_flight.hpp"

namespace scantling::localization {
namespace {

using testing::Flight;
using testing::FlightSensors;
using testing::FlightTick;
using testing::Trajectory;
using testing::TruthSample;

/// Relative error of the numerical derivative (central differences, step 1e-6).
constexpr double kJacobianTolerance = 1e-6;

Eigen::Isometry3d perturbed(const Eigen::Isometry3d& T, const Vector6d& d) {
    return make_isometry(so3_exp(d.tail<3>()) * T.linear(), T.translation() + d.head<3>());
}

Eigen::Isometry3d some_pose(double a) {
    return make_isometry(rotation_from_euler_zyx(0.1 * a, -0.2, 0.7 * a), {a, 2.0 - a, 1.5});
}

TEST(LocalEkfJacobians, IncrementJacobianMatchesNumericalDerivative) {
    const Eigen::Isometry3d T0 = some_pose(0.3), T1 = some_pose(1.1);
    const Eigen::Matrix<double, 6, 12> J = increment_jacobian(T0, T1);
    const Eigen::Isometry3d h = T0.inverse() * T1;
    const double step = 1e-6;
    for (int j = 0; j < 12; ++j) {
        Vector6d d = Vector6d::Zero();
        d(j % 6) = step;
        const auto at = [&](double sign) {
            const Eigen::Isometry3d a = j < 6 ? T0 : perturbed(T0, sign * d);
            const Eigen::Isometry3d b = j < 6 ? perturbed(T1, sign * d) : T1;
            return se3_log((a.inverse() * b) * h.inverse());
        };
        const Vector6d numeric = (at(1.0) - at(-1.0)) / (2.0 * step);
        EXPECT_LT((numeric - J.col(j)).norm(), kJacobianTolerance) << "column " << j;
    }
}

TEST(LocalEkfJacobians, RangeJacobianMatchesNumericalDerivative) {
    Eigen::Isometry3d T_body_sensor{Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX())};
    T_body_sensor.translation() = Eigen::Vector3d(0.1, -0.05, -0.08);
    const Eigen::Isometry3d T =
        make_isometry(rotation_from_euler_zyx(0.2, -0.15, 1.0), {1, 2, 1.7});
    const RangePrediction p = predict_range(T, T_body_sensor, 0.2);
    const double step = 1e-6;
    for (int j = 0; j < 6; ++j) {
        Vector6d d = Vector6d::Zero();
        d(j) = step;
        const double numeric = (predict_range(perturbed(T, d), T_body_sensor, 0.2).range_m -
                                predict_range(perturbed(T, -d), T_body_sensor, 0.2).range_m) /
                               (2.0 * step);
        EXPECT_NEAR(numeric, p.jacobian(j), kJacobianTolerance) << "column " << j;
    }
}

TEST(LocalEkf, ImuIncrementsAndHeightTrackASixtySecondFigureEight) {
    // 0.005 m and 1 mrad per 10 Hz sweep random-walk to ~0.1 m over 60 s (LiODOM is ~1 % of
    // the distance); the IMU and the height hold the rest.
    constexpr double kMaxPositionRmsM = 0.15;
    constexpr double kMaxHeightRmsM = 0.02;  // range finder, 0.03 m per sample at 20 Hz
    LocalEkf ekf;
    Flight flight(Trajectory{}, FlightSensors{}, 7);
    double sum_sq = 0.0, sum_sq_z = 0.0;
    int n = 0;
    flight.fly(ekf, 60.0, [&](const FlightTick& tick) {
        const Eigen::Vector3d e =
            ekf.state().T_odom_body.translation() - tick.truth.T_odom_body.translation();
        sum_sq += e.squaredNorm();
        sum_sq_z += e.z() * e.z();
        ++n;
    });
    const double rms_m = std::sqrt(sum_sq / n), rms_z_m = std::sqrt(sum_sq_z / n);
    RecordProperty("position_rms_m", std::to_string(rms_m));
    std::printf("local EKF 60 s: position RMS %.4f m, height RMS %.4f m\n", rms_m, rms_z_m);
    EXPECT_LT(rms_m, kMaxPositionRmsM);
    EXPECT_LT(rms_z_m, kMaxHeightRmsM);
    EXPECT_EQ(ekf.counters().increments_applied, 600u);
    EXPECT_LT(ekf.counters().ranges_rejected, 10u);  // 99.9 % gate: ~1 in 1000 of 1200
    EXPECT_EQ(ekf.counters().imu_gaps, 0u);
}

/// The x estimates of a corridor flight along x whose increments carry no information along
/// body x but an error of `x_error_sigma_m` there; the filter is returned in `ekf`.
std::vector<double> corridor_flight(LocalEkf& ekf, double x_error_sigma_m) {
    Trajectory corridor;  // yaw, roll and pitch held at 0: body x is odom x
    corridor.yaw_amplitude_rad = corridor.roll_amplitude_rad = corridor.pitch_amplitude_rad = 0.0;
    FlightSensors sensors;
    sensors.information_x = 0.0;
    sensors.increment_x_error_sigma_m = x_error_sigma_m;
    Flight flight(corridor, sensors, 11);
    std::vector<double> x_m;
    flight.fly(ekf, 10.0, [&](const FlightTick& tick) {
        if (tick.sweep) {
            EXPECT_EQ(tick.increment.status, UpdateStatus::kApplied);
            EXPECT_EQ(tick.increment.dof, 5);
        }
        x_m.push_back(ekf.state().T_odom_body.translation().x() -
                      tick.truth.T_odom_body.translation().x());
    });
    return x_m;
}

TEST(LocalEkf, DegenerateIncrementsLeaveTheNullDirectionToTheImu) {
    // The same flight twice, the increments' x wrong by 0.5 m (1σ) per sweep in one of them:
    // a null direction that carried any weight would drag x by decimetres per sweep. What
    // remains is se3_log's coupling of the x error into the other axes (|ω × t| / 2 ≈ 0.3 mm).
    constexpr double kMaxDifferenceM = 0.05;  // a tenth of one sweep's 0.5 m x error
    LocalEkf clean, wrong;
    const std::vector<double> error_clean_m = corridor_flight(clean, 0.0);
    const std::vector<double> error_wrong_m = corridor_flight(wrong, 0.5);
    double max_difference_m = 0.0;
    for (std::size_t i = 0; i < error_clean_m.size(); ++i)
        max_difference_m =
            std::max(max_difference_m, std::abs(error_clean_m[i] - error_wrong_m[i]));
    // Along x only the IMU's double integral remains: σx grows, y and z stay tight (y: the
    // increments' 5 mm per sweep random walk, 0.05 m after 100 sweeps; z: the range finder).
    const Matrix9d P = wrong.state().covariance;
    const double sx = std::sqrt(P(0, 0)), sy = std::sqrt(P(1, 1)), sz = std::sqrt(P(2, 2));
    std::printf(
        "degenerate x: sigma x %.3f, y %.4f, z %.4f m, error x %.3f m, max difference "
        "%.2e m\n",
        sx, sy, sz, error_wrong_m.back(), max_difference_m);
    EXPECT_LT(max_difference_m, kMaxDifferenceM);
    EXPECT_GT(sx, 1.0);
    EXPECT_GT(sx, 10.0 * sy);
    EXPECT_LT(sy, 0.1);
    EXPECT_LT(sz, 0.02);
    EXPECT_LT(std::abs(error_wrong_m.back()), 3.0 * sx);
}

/// Band of the mean of N χ²(k)/N values at 95 % (Wilson–Hilferty).
std::pair<double, double> nees_band(int dof, int runs) {
    const double n = static_cast<double>(dof * runs), z = 1.959964;
    const auto quantile = [&](double zz) {
        return n * std::pow(1.0 - 2.0 / (9.0 * n) + zz * std::sqrt(2.0 / (9.0 * n)), 3) / runs;
    };
    return {quantile(-z), quantile(z)};
}

TEST(LocalEkf, PositionNeesLiesInItsChiSquareBandOverThirtySeeds) {
    constexpr int kSeeds = 30;
    constexpr double kDurationS = 6.0;  // 30 × 6 s: fast enough for ASan
    double nees_sum = 0.0;
    for (int seed = 0; seed < kSeeds; ++seed) {
        LocalEkf ekf;
        Flight flight(Trajectory{}, FlightSensors{}, 1000 + seed);
        TruthSample last;
        flight.fly(ekf, kDurationS, [&](const FlightTick& tick) { last = tick.truth; });
        const DroneState s = ekf.state();
        const Eigen::Vector3d e = s.T_odom_body.translation() - last.T_odom_body.translation();
        nees_sum += e.dot(s.covariance.topLeftCorner<3, 3>().ldlt().solve(e));
    }
    const double mean_nees = nees_sum / kSeeds;
    const auto [low, high] = nees_band(3, kSeeds);
    std::printf("local EKF position NEES over %d seeds: %.3f, band [%.3f, %.3f]\n", kSeeds,
                mean_nees, low, high);
    EXPECT_GT(mean_nees, low);
    EXPECT_LT(mean_nees, high);
}

TEST(LocalEkf, RangeOverABoxIsGatedAndTheHeightHolds) {
    // A 0.4 m box under the drone for 2 s: the range drops by 0.4 m, 13 σ.
    constexpr double kMaxHeightErrorM = 0.05;
    FlightSensors sensors;
    sensors.box_start_s = 4.0;
    sensors.box_end_s = 6.0;
    sensors.box_height_m = 0.4;
    LocalEkf ekf;
    Flight flight(Trajectory{}, sensors, 3);
    int rejected_on_box = 0;
    double max_error_m = 0.0;
    flight.fly(ekf, 8.0, [&](const FlightTick& tick) {
        const bool on_box = tick.stamp_s >= 4.0 && tick.stamp_s < 6.0;
        if (on_box && tick.range.status == UpdateStatus::kRejected) ++rejected_on_box;
        max_error_m = std::max(max_error_m, std::abs(ekf.state().T_odom_body.translation().z() -
                                                     tick.truth.T_odom_body.translation().z()));
    });
    EXPECT_EQ(rejected_on_box, 40);  // every range over the box
    EXPECT_GE(ekf.counters().ranges_rejected, 40u);
    EXPECT_LT(max_error_m, kMaxHeightErrorM);
}

TEST(LocalEkf, BarometerBiasIsEstimatedAndAltitudeTracked) {
    // No range finder: the barometer (offset 120 m, σ 0.3 m) and increments hold the height.
    FlightSensors sensors;
    sensors.imu_per_range = 0;
    LocalEkf ekf;
    Flight flight(Trajectory{}, sensors, 5);
    int k = 0;
    flight.fly(ekf, 10.0, [&](const FlightTick& tick) {
        if (k++ % 10 != 0) return;
        const double z = tick.truth.T_odom_body.translation().z();
        const auto r =
            ekf.update_barometer({tick.stamp_s, 120.0 + z + flight.rng().normal(0, 0.3), 0.3});
        EXPECT_NE(r.status, UpdateStatus::kTooOld);
    });
    const double z_error = ekf.state().T_odom_body.translation().z() -
                           testing::truth_at(Trajectory{}, 10.0).T_odom_body.translation().z();
    EXPECT_LT(std::abs(z_error), 0.1);
    EXPECT_GT(ekf.counters().barometer_applied, 150u);
}

TEST(LocalEkf, ImuGapIsPredictedAcrossWithGrowingCovarianceAndReported) {
    LocalEkf ekf;
    ekf.initialize(0.0, Eigen::Isometry3d::Identity());
    const Eigen::Vector3d f(0, 0, 9.81);
    EXPECT_EQ(ekf.add_imu({0.005, f, Eigen::Vector3d::Zero()}), ImuPredictionStatus::kFirst);
    EXPECT_EQ(ekf.add_imu({0.010, f, Eigen::Vector3d::Zero()}), ImuPredictionStatus::kOk);
    const double var_before = ekf.state().covariance(6, 6);
    EXPECT_EQ(ekf.add_imu({0.310, f, Eigen::Vector3d::Zero()}), ImuPredictionStatus::kGap);
    EXPECT_EQ(ekf.counters().imu_gaps, 1u);
    EXPECT_NEAR(ekf.stamp_s(), 0.310, 1e-12);
    // 0.3 s of the gap's 2 m/s² random walk: at least 1.2 (m/s)² more velocity variance.
    EXPECT_GT(ekf.state().covariance(6, 6) - var_before, 1.1);
    EXPECT_TRUE(ekf.state().T_odom_body.matrix().allFinite());
}

TEST(LocalEkf, RefusesBadInputsWithoutCorruptingTheState) {
    LocalEkf ekf;
    EXPECT_EQ(ekf.add_imu({0.0, {0, 0, 9.81}, Eigen::Vector3d::Zero()}),
              ImuPredictionStatus::kNotInitialized);
    EXPECT_EQ(ekf.update_range({0.0, true, 1.0}).status, UpdateStatus::kNotInitialized);
    ekf.initialize(0.0, Eigen::Isometry3d::Identity());
    const double nan = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(ekf.add_imu({0.01, {nan, 0, 9.81}, Eigen::Vector3d::Zero()}), InputError);
    EXPECT_EQ(ekf.add_imu({0.02, {0, 0, 9.81}, Eigen::Vector3d::Zero()}),
              ImuPredictionStatus::kFirst);
    EXPECT_EQ(ekf.add_imu({0.01, {0, 0, 9.81}, Eigen::Vector3d::Zero()}),
              ImuPredictionStatus::kOutOfOrder);
    EXPECT_EQ(ekf.add_imu({0.02, {0, 0, 9.81}, Eigen::Vector3d::Zero()}),
              ImuPredictionStatus::kOutOfOrder);
    EXPECT_EQ(ekf.counters().imu_out_of_order, 2u);
    EXPECT_THROW(ekf.update_range({0.02, true, nan}), InputError);
    EXPECT_EQ(ekf.update_range({0.02, false, nan}).status, UpdateStatus::kInvalid);
    EXPECT_EQ(ekf.update_range({0.02, true, 20.0}).status, UpdateStatus::kInvalid);
    EXPECT_EQ(ekf.update_range({-1.0, true, 1.0}).status, UpdateStatus::kTooOld);
    EXPECT_THROW(ekf.update_barometer({0.02, 1.0, 0.0}), InputError);
    PoseIncrement inc;
    inc.start_stamp_s = 0.0;
    inc.end_stamp_s = 0.02;
    EXPECT_EQ(ekf.update_increment(inc).status, UpdateStatus::kNoClone);
    ekf.clone_pose(0.02);
    inc.start_stamp_s = 0.02;
    inc.end_stamp_s = 0.03;
    EXPECT_EQ(ekf.update_increment(inc).status, UpdateStatus::kNoInformation);
    inc.information(0, 0) = nan;
    EXPECT_THROW(ekf.update_increment(inc), InputError);
    EXPECT_TRUE(ekf.state().covariance.allFinite());
    EXPECT_TRUE(ekf.state().T_odom_body.matrix().allFinite());
}

void expect_config_error(const LocalEkfConfig& config, const std::string& field) {
    try {
        LocalEkf ekf(config);
        ADD_FAILURE() << "no ConfigError for " << field;
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("local_ekf." + field), std::string::npos) << e.what();
    }
}

TEST(LocalEkf, InvalidConfigNamesTheField) {
    LocalEkfConfig c;
    c.max_imu_gap_s = 0.0;
    expect_config_error(c, "max_imu_gap_s");
    c = {};
    c.range_sigma_m = -0.1;
    expect_config_error(c, "range_sigma_m");
    c = {};
    c.max_range_m = c.min_range_m;
    expect_config_error(c, "max_range_m");
    c = {};
    c.information_relative_threshold = 1.0;
    expect_config_error(c, "information_relative_threshold");
    c = {};
    c.gyro_noise_density_radps_per_sqrt_hz = std::numeric_limits<double>::quiet_NaN();
    expect_config_error(c, "gyro_noise_density_radps_per_sqrt_hz");
    c = {};
    c.T_body_imu.linear() *= 2.0;
    expect_config_error(c, "T_body_imu");
}

}  // namespace
}  // namespace scantling::localization
