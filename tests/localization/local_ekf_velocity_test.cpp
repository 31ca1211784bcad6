// The local EKF's underwater measurements: a DVL's body-frame velocity over the seabed (with its
// mount's lever arm) and a pressure depth, against analytic ROV motions.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <numbers>
#include <string>

#include <scantling/core/error.hpp>
#include <scantling/core/random.hpp>
#include <scantling/core/se3.hpp>
#include <scantling/localization/local_ekf.hpp>

namespace scantling::localization {
namespace {

constexpr double kGravity = 9.81;
constexpr double kImuRateHz = 200.0;

/// The truth of a rigid body at one instant (odom frame; ω in body axes).
struct Truth {
    Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    Eigen::Vector3d v = Eigen::Vector3d::Zero();
    Eigen::Vector3d a = Eigen::Vector3d::Zero();  ///< odom, gravity excluded
    Eigen::Vector3d omega = Eigen::Vector3d::Zero();
};

/// What the sensor at T_body_sensor measures for a truth (the header's model, written out).
Eigen::Vector3d dvl_truth(const Truth& t, const Eigen::Isometry3d& T_body_sensor) {
    return T_body_sensor.linear().transpose() *
           (t.R.transpose() * t.v + t.omega.cross(T_body_sensor.translation()));
}

io::ImuRecord imu_of(double stamp_s, const Truth& t, const Eigen::Vector3d& accel_bias,
                     const Eigen::Vector3d& gyro_bias, const LocalEkfConfig& c, Rng& rng) {
    const double root_rate = std::sqrt(kImuRateHz);
    const Eigen::Vector3d f = t.R.transpose() * (t.a + Eigen::Vector3d(0, 0, kGravity));
    return {stamp_s,
            f + accel_bias + rng.normal3(c.accel_noise_density_mps2_per_sqrt_hz * root_rate),
            t.omega + gyro_bias + rng.normal3(c.gyro_noise_density_radps_per_sqrt_hz * root_rate)};
}

/// An ROV's IMU: no rotor vibration, so the datasheet densities (local_ekf.hpp's defaults are
/// these ×10 for a multirotor).
LocalEkfConfig rov_config() {
    LocalEkfConfig c;
    c.accel_noise_density_mps2_per_sqrt_hz = 1e-3;
    c.gyro_noise_density_radps_per_sqrt_hz = 7e-5;
    return c;
}

/// Straight run at a constant yaw of 30°: still for 1 s, 0.1 m/s² for 3 s, then 0.3 m/s.
Truth straight_run(double t_s) {
    Truth t;
    t.R = Eigen::AngleAxisd(std::numbers::pi / 6.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    const Eigen::Vector3d forward = t.R.col(0);
    const double accel_s = std::clamp(t_s - 1.0, 0.0, 3.0);
    const double along_m = 0.05 * accel_s * accel_s + 0.3 * std::max(t_s - 4.0, 0.0);
    t.p = Eigen::Vector3d(0, 0, -5.0) + along_m * forward;
    t.v = 0.1 * accel_s * forward;
    t.a = (t_s > 1.0 && t_s < 4.0 ? 0.1 : 0.0) * forward;
    return t;
}

/// Turning on the spot about z at 0.5 rad/s, no translation.
Truth turning(double t_s) {
    Truth t;
    t.R = Eigen::AngleAxisd(0.5 * t_s, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    t.omega = Eigen::Vector3d(0, 0, 0.5);
    return t;
}

struct RunOptions {
    double duration_s = 60.0;
    Eigen::Vector3d accel_bias = Eigen::Vector3d::Zero();
    Eigen::Vector3d gyro_bias = Eigen::Vector3d::Zero();
    double dvl_sigma_mps = 0.005;
    int dvl_every = 20;    ///< IMU samples per DVL sample (10 Hz)
    int depth_every = 40;  ///< 5 Hz; 0 = no depth
    double depth_sigma_m = 0.02;
    double settle_s = 10.0;  ///< the velocity RMS starts here
};

struct RunStats {
    double max_chi2 = 0.0;
    double mean_chi2 = 0.0;
    int dvl_updates = 0;
    int dvl_rejected = 0;
    double velocity_rms_mps = 0.0;  ///< odom velocity error at the IMU rate after settle_s
};

/// Feeds IMU, DVL (mounted by the filter's config) and depth from `truth` into `ekf`.
RunStats run(LocalEkf& ekf, const std::function<Truth(double)>& truth, const RunOptions& o,
             Rng& rng) {
    const LocalEkfConfig& c = ekf.config();
    const int samples = static_cast<int>(o.duration_s * kImuRateHz);
    RunStats stats;
    double chi2_sum = 0.0, velocity_sq = 0.0;
    int velocity_n = 0;
    for (int k = 1; k <= samples; ++k) {
        const double t_s = k / kImuRateHz;
        const Truth x = truth(t_s);
        ekf.add_imu(imu_of(t_s, x, o.accel_bias, o.gyro_bias, c, rng));
        if (k % o.dvl_every == 0) {
            BodyVelocityMeasurement m;
            m.stamp_s = t_s;
            m.v_sensor_mps = dvl_truth(x, c.T_body_velocity_sensor) + rng.normal3(o.dvl_sigma_mps);
            m.covariance_mps2 = Eigen::Matrix3d::Identity() * o.dvl_sigma_mps * o.dvl_sigma_mps;
            const UpdateResult r = ekf.update_body_velocity(m);
            if (r.status != UpdateStatus::kApplied) ++stats.dvl_rejected;
            stats.max_chi2 = std::max(stats.max_chi2, r.mahalanobis_squared);
            chi2_sum += r.mahalanobis_squared;
            ++stats.dvl_updates;
        }
        if (t_s > o.settle_s) {
            velocity_sq += (ekf.state().v_odom_mps - x.v).squaredNorm();
            ++velocity_n;
        }
        if (o.depth_every > 0 && k % o.depth_every == 0)
            ekf.update_depth({t_s, x.p.z() + rng.normal(0.0, o.depth_sigma_m), o.depth_sigma_m});
    }
    stats.mean_chi2 = stats.dvl_updates > 0 ? chi2_sum / stats.dvl_updates : 0.0;
    stats.velocity_rms_mps = velocity_n > 0 ? std::sqrt(velocity_sq / velocity_n) : 0.0;
    return stats;
}

TEST(LocalEkfVelocity, DvlAndDepthHoldAStraightSixtySecondRun) {
    // Measured (seed 11): RMS |dv| 2.9e-3 m/s, at 60 s |dv| 4.1e-3 m/s, |dp| 0.016 m, |dz| 8e-4 m.
    constexpr double kMaxVelocityRmsMps = 0.006;   // over 10 s to 60 s
    constexpr double kMaxVelocityErrorMps = 0.01;  // at 60 s, one sample of that noise
    constexpr double kMaxPositionErrorM = 0.04;
    constexpr double kMaxDepthErrorM = 0.005;
    LocalEkfConfig config = rov_config();
    config.initial_velocity_sigma_mps = 0.5;
    // A DVL and an IMU leave the heading unobservable (the odom velocity and the yaw can turn
    // together unseen), so the yaw holds only as well as the gyro's z bias is known: an ROV's
    // calibrated (FOG-class) gyro. With the default 0.01 rad/s the heading, and with it the odom
    // velocity, wander by tenths of a radian in a minute; the body-frame velocity still holds.
    config.initial_gyro_bias_sigma_radps = 1e-4;
    // Looking down, off the body origin: the mount's rotation is exercised, its lever arm is not
    // (no rotation on a straight run).
    config.T_body_velocity_sensor =
        make_isometry(Eigen::AngleAxisd(std::numbers::pi, Eigen::Vector3d::UnitX()).matrix(),
                      Eigen::Vector3d(0.2, 0.0, -0.3));
    LocalEkf ekf(config);
    const Truth start = straight_run(0.0);
    // The prior velocity is wrong by ~0.25 m/s; the DVL has to correct it.
    ekf.initialize(0.0, make_isometry(start.R, start.p), Eigen::Vector3d(0.2, -0.1, 0.1));
    Rng rng(11);
    RunOptions options;
    options.accel_bias = Eigen::Vector3d(0.02, -0.01, 0.03);
    options.gyro_bias = Eigen::Vector3d(5e-4, -5e-4, 0.0);  // yaw's bias is unobservable here
    const RunStats stats = run(ekf, straight_run, options, rng);
    const Truth end = straight_run(options.duration_s);
    const DroneState s = ekf.state();
    const double velocity_error = (s.v_odom_mps - end.v).norm();
    const double body_velocity_error =
        (s.T_odom_body.linear().transpose() * s.v_odom_mps - end.R.transpose() * end.v).norm();
    const double position_error = (s.T_odom_body.translation() - end.p).norm();
    const double depth_error = std::abs(s.T_odom_body.translation().z() - end.p.z());
    RecordProperty("velocity_error_mps", std::to_string(velocity_error));
    RecordProperty("position_error_m", std::to_string(position_error));
    std::printf(
        "straight run: |dv| = %.5f m/s (body %.5f), |dp| = %.4f m, |dz| = %.4f m, "
        "RMS |dv| %.5f m/s, chi2 mean %.2f max %.2f, rejected %d\n",
        velocity_error, body_velocity_error, position_error, depth_error, stats.velocity_rms_mps,
        stats.mean_chi2, stats.max_chi2, stats.dvl_rejected);
    EXPECT_LT(stats.velocity_rms_mps, kMaxVelocityRmsMps);
    EXPECT_LT(velocity_error, kMaxVelocityErrorMps);
    EXPECT_LT(body_velocity_error, kMaxVelocityErrorMps);
    EXPECT_LT(position_error, kMaxPositionErrorM);
    EXPECT_LT(depth_error, kMaxDepthErrorM);
    EXPECT_LT(stats.mean_chi2, 4.5);  // 3 DoF
    // A 99.9 % gate rejects ~0.6 of 600 consistent samples.
    EXPECT_LE(ekf.counters().velocity_rejected, 3u);
    EXPECT_EQ(ekf.counters().velocity_applied + ekf.counters().velocity_rejected, 600u);
    EXPECT_EQ(ekf.counters().depth_applied, 300u);
    EXPECT_EQ(ekf.counters().depth_rejected, 0u);
}

TEST(LocalEkfVelocity, JacobianMatchesNumericalDerivativeInTheFiltersConvention) {
    constexpr double kTolerance = 1e-6;
    const Eigen::Matrix3d R = rotation_from_euler_zyx(0.4, -0.2, 0.9);
    const Eigen::Vector3d v(0.7, -0.3, 0.2), omega(0.3, -0.5, 0.8);
    const Eigen::Isometry3d T_bs =
        make_isometry(rotation_from_euler_zyx(0.3, 2.8, -0.4), Eigen::Vector3d(0.3, -0.1, -0.2));
    const BodyVelocityPrediction p = predict_body_velocity(R, v, omega, T_bs);
    // Perturbed as LocalEkf::inject does: R ← exp(δθ)·R, v ← v + δv, b_g ← b_g + δb_g.
    const auto h = [&](int block, const Eigen::Vector3d& d) {
        const Eigen::Matrix3d Rd = block == 0 ? Eigen::Matrix3d(so3_exp(d) * R) : R;
        return predict_body_velocity(Rd, block == 1 ? Eigen::Vector3d(v + d) : v,
                                     block == 2 ? Eigen::Vector3d(omega - d) : omega, T_bs)
            .v_sensor_mps;
    };
    const Eigen::Matrix3d* analytic[] = {&p.d_theta, &p.d_velocity, &p.d_gyro_bias};
    const double step = 1e-6;
    for (int block = 0; block < 3; ++block) {
        for (int j = 0; j < 3; ++j) {
            const Eigen::Vector3d d = Eigen::Vector3d::Unit(j) * step;
            const Eigen::Vector3d numeric = (h(block, d) - h(block, -d)) / (2.0 * step);
            EXPECT_LT((numeric - analytic[block]->col(j)).norm(), kTolerance)
                << "block " << block << " column " << j;
        }
    }
    EXPECT_LT((p.v_sensor_mps -
               T_bs.linear().transpose() * (R.transpose() * v + omega.cross(T_bs.translation())))
                  .norm(),
              1e-12);
}

TEST(LocalEkfVelocity, UpdateReducesAYawErrorWhenMovingSideways) {
    // Behaviour of the δθ sign: a filter whose yaw is 0.05 rad off, moving along odom x at
    // 1 m/s, sees the DVL's body velocity rotated; the update must shrink the yaw error.
    LocalEkfConfig config;
    config.initial_yaw_sigma_rad = 0.1;
    config.initial_velocity_sigma_mps = 0.01;
    LocalEkf ekf(config);
    const Eigen::Vector3d v_odom(1.0, 0.0, 0.0);
    ekf.initialize(
        0.0, make_isometry(so3_exp(Eigen::Vector3d(0, 0, 0.05)), Eigen::Vector3d::Zero()), v_odom);
    BodyVelocityMeasurement m;
    m.stamp_s = 0.0;
    m.v_sensor_mps = v_odom;  // the truth's yaw is 0: body velocity = odom velocity
    const UpdateResult r = ekf.update_body_velocity(m);
    ASSERT_EQ(r.status, UpdateStatus::kApplied);
    const double yaw = so3_log(ekf.state().T_odom_body.linear()).z();
    EXPECT_LT(std::abs(yaw), 0.01) << "yaw after the update " << yaw;
}

TEST(LocalEkfVelocity, LeverArmOfATurningBodyIsConsistent) {
    // A DVL at (0.3, 0, −0.2) on a body turning at 0.5 rad/s moves at ω × t = 0.15 m/s while the
    // body stands still. Measured (seed 5): mean χ² 2.7 (3 DoF), RMS |v| 3.2e-3 m/s.
    LocalEkfConfig config = rov_config();
    config.T_body_velocity_sensor = make_isometry(Eigen::Matrix3d::Identity(), {0.3, 0.0, -0.2});
    LocalEkf ekf(config);
    ekf.initialize(0.0, Eigen::Isometry3d::Identity());
    Rng rng(5);
    RunOptions options;
    options.duration_s = 20.0;
    options.depth_every = 0;
    const RunStats stats = run(ekf, turning, options, rng);
    const double speed = ekf.state().v_odom_mps.norm();
    std::printf("lever arm: chi2 mean %.2f max %.2f, rejected %d, |v| = %.5f m/s, RMS %.5f m/s\n",
                stats.mean_chi2, stats.max_chi2, stats.dvl_rejected, speed, stats.velocity_rms_mps);
    EXPECT_LT(stats.mean_chi2, 4.5);  // 3 expected for 3 DoF
    EXPECT_LT(stats.velocity_rms_mps, 0.007);
    EXPECT_LT(speed, 0.01);
    EXPECT_LE(ekf.counters().velocity_rejected, 2u);  // of 200 at a 99.9 % gate
}

TEST(LocalEkfVelocity, IgnoringTheLeverArmIsNotConsistent) {
    // The same motion with the mount left at the body origin: the 0.15 m/s of ω × t cannot be
    // explained, so the check above is able to fail.
    LocalEkfConfig truth_config;
    truth_config.T_body_velocity_sensor =
        make_isometry(Eigen::Matrix3d::Identity(), {0.3, 0.0, -0.2});
    LocalEkf ekf;  // identity mount
    ekf.initialize(0.0, Eigen::Isometry3d::Identity());
    Rng rng(5);
    int rejected_or_biased = 0;
    for (int k = 1; k <= 400; ++k) {
        const double t_s = k / kImuRateHz;
        ekf.add_imu(imu_of(t_s, turning(t_s), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
                           ekf.config(), rng));
        if (k % 20 != 0) continue;
        BodyVelocityMeasurement m;
        m.stamp_s = t_s;
        m.v_sensor_mps = dvl_truth(turning(t_s), truth_config.T_body_velocity_sensor);
        m.covariance_mps2 = Eigen::Matrix3d::Identity() * 0.005 * 0.005;
        if (ekf.update_body_velocity(m).status == UpdateStatus::kRejected) ++rejected_or_biased;
    }
    if (ekf.state().v_odom_mps.norm() > 0.05) ++rejected_or_biased;
    EXPECT_GT(rejected_or_biased, 0);
}

TEST(LocalEkfVelocity, GateRejectsAOneMetrePerSecondOutlier) {
    LocalEkf ekf;
    ekf.initialize(0.0, Eigen::Isometry3d::Identity());
    Rng rng(3);
    RunOptions options;
    options.duration_s = 5.0;
    options.depth_every = 0;
    run(
        ekf, [](double) { return Truth{}; }, options, rng);
    ASSERT_EQ(ekf.counters().velocity_applied, 50u);
    BodyVelocityMeasurement outlier;
    outlier.stamp_s = 5.0;
    outlier.v_sensor_mps = Eigen::Vector3d(1.0, 0.0, 0.0);
    outlier.covariance_mps2 = Eigen::Matrix3d::Identity() * 0.005 * 0.005;
    const UpdateResult r = ekf.update_body_velocity(outlier);
    EXPECT_EQ(r.status, UpdateStatus::kRejected);
    EXPECT_EQ(r.dof, 3);
    EXPECT_GT(r.mahalanobis_squared, ekf.config().velocity_gate_chi2);
    EXPECT_EQ(ekf.counters().velocity_applied, 50u);
    EXPECT_EQ(ekf.counters().velocity_rejected, 1u);
    EXPECT_LT(ekf.state().v_odom_mps.norm(), 0.01);  // the outlier left the state alone
}

void expect_input_error(LocalEkf& ekf, const BodyVelocityMeasurement& m, const std::string& field) {
    try {
        ekf.update_body_velocity(m);
        ADD_FAILURE() << "no InputError for " << field;
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
}

TEST(LocalEkfVelocity, BadInputThrowsInputErrorNamingTheField) {
    LocalEkf ekf;
    ekf.initialize(0.0, Eigen::Isometry3d::Identity());
    const double nan = std::numeric_limits<double>::quiet_NaN();
    BodyVelocityMeasurement m;
    m.v_sensor_mps.x() = nan;
    expect_input_error(ekf, m, "v_sensor_mps");
    m = BodyVelocityMeasurement{};
    m.stamp_s = nan;
    expect_input_error(ekf, m, "stamp_s");
    m = BodyVelocityMeasurement{};
    m.covariance_mps2(1, 1) = nan;
    expect_input_error(ekf, m, "covariance_mps2");
    m = BodyVelocityMeasurement{};
    m.covariance_mps2(1, 1) = -1e-4;  // indefinite
    expect_input_error(ekf, m, "positive definite");
    m = BodyVelocityMeasurement{};
    m.covariance_mps2(0, 1) = 1e-5;  // not symmetric
    expect_input_error(ekf, m, "positive definite");
    EXPECT_THROW(ekf.update_depth({0.0, nan, 0.02}), InputError);
    EXPECT_THROW(ekf.update_depth({0.0, 1.0, 0.0}), InputError);
    EXPECT_EQ(ekf.counters().velocity_applied + ekf.counters().velocity_rejected, 0u);
}

TEST(LocalEkfVelocity, ConfigValidationNamesTheNewFields) {
    const auto expect_config_error = [](const LocalEkfConfig& c, const std::string& field) {
        try {
            c.validate();
            ADD_FAILURE() << "no ConfigError for " << field;
        } catch (const ConfigError& e) {
            EXPECT_NE(std::string(e.what()).find("local_ekf." + field), std::string::npos)
                << e.what();
        }
    };
    LocalEkfConfig c;
    c.velocity_gate_chi2 = 0.0;
    expect_config_error(c, "velocity_gate_chi2");
    c = LocalEkfConfig{};
    c.depth_gate_chi2 = std::numeric_limits<double>::infinity();
    expect_config_error(c, "depth_gate_chi2");
    c = LocalEkfConfig{};
    c.T_body_velocity_sensor.linear() *= 1.1;
    expect_config_error(c, "T_body_velocity_sensor");
}

TEST(LocalEkfDepth, BiasedPriorConvergesAndOutlierIsRejected) {
    // Prior z = 0 with 1 m sigma; the truth is 0.5 m lower. Measured: |z error| ~2e-3 m.
    constexpr double kMaxDepthErrorM = 0.01;
    LocalEkfConfig config;
    config.initial_position_sigma_m = 1.0;
    LocalEkf ekf(config);
    ekf.initialize(0.0, Eigen::Isometry3d::Identity());
    Truth truth;
    truth.p.z() = -0.5;
    Rng rng(9);
    RunOptions options;
    options.duration_s = 10.0;
    const RunStats stats = run(
        ekf, [&](double) { return truth; }, options, rng);
    const double error = std::abs(ekf.state().T_odom_body.translation().z() - truth.p.z());
    std::printf("depth: |dz| = %.5f m after %zu updates (dvl mean chi2 %.2f)\n", error,
                ekf.counters().depth_applied, stats.mean_chi2);
    EXPECT_LT(error, kMaxDepthErrorM);
    EXPECT_EQ(ekf.counters().depth_applied, 50u);
    const UpdateResult r = ekf.update_depth({10.0, truth.p.z() + 5.0, 0.02});
    EXPECT_EQ(r.status, UpdateStatus::kRejected);
    EXPECT_EQ(r.dof, 1);
    EXPECT_EQ(ekf.counters().depth_rejected, 1u);
    EXPECT_LT(std::abs(ekf.state().T_odom_body.translation().z() - truth.p.z()), kMaxDepthErrorM);
}

// With an IMU and a DVL nothing measures heading: a gyro z bias turns the whole estimate. A
// heading at 5 Hz (the ROV's hull line) bounds the yaw and makes the bias observable.
TEST(LocalEkfYaw, AHeadingBoundsTheYawAndEstimatesTheGyroBias) {
    const double bias_radps = 2e-3;  // 7 deg per minute unaided
    const LocalEkfConfig config = rov_config();
    LocalEkf ekf(config);
    ekf.initialize(0.0, Eigen::Isometry3d::Identity());
    Rng rng(4);
    const Truth still;
    for (int k = 1; k <= 120 * 200; ++k) {
        const double t_s = k / kImuRateHz;
        ekf.add_imu(
            imu_of(t_s, still, Eigen::Vector3d::Zero(), {0.0, 0.0, bias_radps}, config, rng));
        if (k % 40 == 0) ekf.update_yaw({t_s, rng.normal() * 0.05, 0.05});
    }
    const DroneState s = ekf.state();
    EXPECT_LT(std::abs(euler_zyx_from_rotation(s.T_odom_body.linear()).z()), 0.02);
    EXPECT_NEAR(s.gyro_bias_radps.z(), bias_radps, 3e-4);
    EXPECT_EQ(ekf.counters().yaw_applied, 600u);
    // A heading 1 rad off is refused by the gate, and a wrapped one is not: π − 0.01 against
    // −π + 0.01 is 0.02 rad apart.
    EXPECT_EQ(ekf.update_yaw({120.0, 1.0, 0.05}).status, UpdateStatus::kRejected);
    LocalEkf turned(config);
    turned.initialize(0.0, Eigen::Isometry3d(Eigen::AngleAxisd(std::numbers::pi - 0.01,
                                                               Eigen::Vector3d::UnitZ())));
    const UpdateResult wrapped = turned.update_yaw({0.0, -std::numbers::pi + 0.01, 0.05});
    EXPECT_EQ(wrapped.status, UpdateStatus::kApplied);
    EXPECT_NEAR(wrapped.mahalanobis_squared, 0.0, 1.0);
}

TEST(LocalEkfYaw, BadInputThrowsInputErrorNamingTheField) {
    LocalEkf ekf;
    ekf.initialize(0.0, Eigen::Isometry3d::Identity());
    const double nan = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(ekf.update_yaw({0.0, nan, 0.05}), InputError);
    EXPECT_THROW(ekf.update_yaw({0.0, 0.0, 0.0}), InputError);
    try {
        ekf.update_yaw({0.0, nan, 0.05});
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("yaw_odom_rad"), std::string::npos);
    }
}

}  // namespace
}  // namespace scantling::localization
