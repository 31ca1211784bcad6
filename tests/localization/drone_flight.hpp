#pragma once
// A synthetic drone flight for the local and global EKF tests: an analytic figure-eight with
// yaw, roll and pitch oscillations, and the sensors a drone carries sampled from it (IMU with
// noise and random-walk biases, LiDAR increments, a down-looking range finder).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <functional>
#include <numbers>

#include <scantling/core/random.hpp>
#include <scantling/core/se3.hpp>
#include <scantling/io/recording.hpp>
#include <scantling/localization/local_ekf.hpp>

namespace scantling::localization::testing {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr double kGravity = 9.81;

/// x = A sin(wt), y = B sin(2wt), z = z₀ + C sin(w_z t); yaw, roll, pitch sinusoids.
struct Trajectory {
    double x_amplitude_m = 3.0;
    double y_amplitude_m = 1.5;
    double period_s = 20.0;
    double height_m = 1.5;  ///< above the floor at odom z = 0
    double z_amplitude_m = 0.3;
    double z_period_s = 15.0;
    double yaw_amplitude_rad = 0.8;
    double yaw_period_s = 12.0;
    double roll_amplitude_rad = 0.05;
    double pitch_amplitude_rad = 0.04;
};

struct TruthSample {
    Eigen::Isometry3d T_odom_body = Eigen::Isometry3d::Identity();
    Eigen::Vector3d v_odom_mps = Eigen::Vector3d::Zero();
    Eigen::Vector3d a_odom_mps2 = Eigen::Vector3d::Zero();
    Eigen::Vector3d omega_body_radps = Eigen::Vector3d::Zero();
};

/// (value, first, second derivative) of a sin(k t + phase).
inline Eigen::Vector3d sine(double a, double k, double t, double phase = 0.0) {
    const double s = std::sin(k * t + phase), c = std::cos(k * t + phase);
    return {a * s, a * k * c, -a * k * k * s};
}

inline TruthSample truth_at(const Trajectory& tr, double t) {
    const double w = kTwoPi / tr.period_s;
    const Eigen::Vector3d x = sine(tr.x_amplitude_m, w, t), y = sine(tr.y_amplitude_m, 2 * w, t),
                          z = sine(tr.z_amplitude_m, kTwoPi / tr.z_period_s, t);
    const Eigen::Vector3d yaw = sine(tr.yaw_amplitude_rad, kTwoPi / tr.yaw_period_s, t),
                          roll = sine(tr.roll_amplitude_rad, kTwoPi / 5.0, t),
                          pitch = sine(tr.pitch_amplitude_rad, kTwoPi / 7.0, t, 1.0);
    TruthSample s;
    const Eigen::Matrix3d R = rotation_from_euler_zyx(roll(0), pitch(0), yaw(0));
    s.T_odom_body = make_isometry(R, Eigen::Vector3d(x(0), y(0), tr.height_m + z(0)));
    s.v_odom_mps = {x(1), y(1), z(1)};
    s.a_odom_mps2 = {x(2), y(2), z(2)};
    const double sp = std::sin(pitch(0)), cp = std::cos(pitch(0));
    const double sr = std::sin(roll(0)), cr = std::cos(roll(0));
    s.omega_body_radps = {roll(1) - yaw(1) * sp, pitch(1) * cr + yaw(1) * cp * sr,
                          -pitch(1) * sr + yaw(1) * cp * cr};
    return s;
}

/// What the sensors produce and how noisy they are (defaults = LocalEkfConfig's models).
struct FlightSensors {
    double imu_rate_hz = 200.0;
    int imu_per_sweep = 20;  ///< 10 Hz LiDAR
    int imu_per_range = 10;  ///< 20 Hz range finder (0 = none)
    double increment_sigma_m = 0.005;
    double increment_sigma_rad = 0.001;
    /// Information along body x for the increments (1/m²); < 0: 1/increment_sigma_m².
    double information_x = -1.0;
    double increment_x_error_sigma_m = 0.0;  ///< error along body x beyond the model (b)
    double increment_scale_error = 0.0;      ///< LiDAR-odometry drift for the global tests
    double increment_yaw_bias_rad = 0.0;
    double range_sigma_m = 0.03;
    /// A box on the floor: ranges between these times are shorter by its height.
    double box_start_s = -1.0, box_end_s = -1.0, box_height_m = 0.0;
};

/// One tick of the flight, after the IMU sample and the measurements at its stamp.
struct FlightTick {
    double stamp_s = 0.0;
    TruthSample truth;
    bool sweep = false;  ///< an increment was fused at this tick
    UpdateResult increment;
    UpdateResult range;
    Eigen::Vector3d p_before_increment_odom = Eigen::Vector3d::Zero();
};

inline Matrix6d increment_information(const FlightSensors& s) {
    Vector6d d;
    const double ix =
        s.information_x < 0.0 ? 1.0 / (s.increment_sigma_m * s.increment_sigma_m) : s.information_x;
    d << ix, Eigen::Vector2d::Constant(1.0 / (s.increment_sigma_m * s.increment_sigma_m)),
        Eigen::Vector3d::Constant(1.0 / (s.increment_sigma_rad * s.increment_sigma_rad));
    return d.asDiagonal();
}

/// Flies `duration_s` with a LocalEkf started from the truth perturbed by its initial
/// covariance; calls `on_tick` after every IMU sample. The filter is returned in `ekf`.
class Flight {
  public:
    Flight(Trajectory trajectory, FlightSensors sensors, std::uint64_t seed)
        : tr_(trajectory), s_(sensors), rng_(seed) {}

    void fly(LocalEkf& ekf, double duration_s,
             const std::function<void(const FlightTick&)>& on_tick) {
        start(ekf);
        const int n = static_cast<int>(std::lround(duration_s * s_.imu_rate_hz));
        for (int k = 0; k <= n; ++k) on_tick(step(ekf, k));
    }

    Rng& rng() { return rng_; }

  private:
    void start(LocalEkf& ekf) {
        const LocalEkfConfig& c = ekf.config();
        const TruthSample t0 = truth_at(tr_, 0.0);
        accel_bias_ = rng_.normal3(c.initial_accel_bias_sigma_mps2);
        gyro_bias_ = rng_.normal3(c.initial_gyro_bias_sigma_radps);
        const Eigen::Vector3d tilt(rng_.normal(0.0, c.initial_tilt_sigma_rad),
                                   rng_.normal(0.0, c.initial_tilt_sigma_rad), 0.0);
        Eigen::Isometry3d T = t0.T_odom_body;
        T.linear() = so3_exp(tilt) * T.linear();
        ekf.initialize(0.0, T, t0.v_odom_mps + rng_.normal3(c.initial_velocity_sigma_mps));
    }

    io::ImuRecord imu_sample(const LocalEkfConfig& c, const TruthSample& t, double stamp_s) {
        const double dt = 1.0 / s_.imu_rate_hz, root_rate = std::sqrt(s_.imu_rate_hz);
        accel_bias_ += rng_.normal3(c.accel_bias_random_walk_mps3_per_sqrt_hz * std::sqrt(dt));
        gyro_bias_ += rng_.normal3(c.gyro_bias_random_walk_radps2_per_sqrt_hz * std::sqrt(dt));
        const Eigen::Matrix3d& R = t.T_odom_body.linear();
        io::ImuRecord r;
        r.stamp_s = stamp_s;
        r.specific_force_mps2 = R.transpose() * (t.a_odom_mps2 + Eigen::Vector3d(0, 0, kGravity)) +
                                accel_bias_ +
                                rng_.normal3(c.accel_noise_density_mps2_per_sqrt_hz * root_rate);
        r.angular_rate_radps = t.omega_body_radps + gyro_bias_ +
                               rng_.normal3(c.gyro_noise_density_radps_per_sqrt_hz * root_rate);
        return r;
    }

    PoseIncrement increment(const TruthSample& t, double stamp_s) {
        PoseIncrement inc;
        inc.start_stamp_s = sweep_start_s_;
        inc.end_stamp_s = stamp_s;
        inc.information = increment_information(s_);
        Eigen::Isometry3d h = sweep_start_.inverse() * t.T_odom_body;
        h.translation() *= 1.0 + s_.increment_scale_error;
        Vector6d eps;
        const double x_sigma_m =
            s_.information_x == 0.0 ? s_.increment_x_error_sigma_m : s_.increment_sigma_m;
        eps << rng_.normal() * x_sigma_m, rng_.normal(0.0, s_.increment_sigma_m),
            rng_.normal(0.0, s_.increment_sigma_m), rng_.normal3(s_.increment_sigma_rad);
        eps(5) += s_.increment_yaw_bias_rad;
        inc.T_body0_body1 = se3_exp(-eps) * h;  // the true increment is exp(ε) · z
        return inc;
    }

    io::RangeRecord range(const TruthSample& t, double stamp_s) {
        const Eigen::Vector3d ray = t.T_odom_body.linear() * -Eigen::Vector3d::UnitZ();
        double height_m = t.T_odom_body.translation().z();
        if (stamp_s >= s_.box_start_s && stamp_s < s_.box_end_s) height_m -= s_.box_height_m;
        return io::RangeRecord{stamp_s, true,
                               height_m / -ray.z() + rng_.normal(0.0, s_.range_sigma_m)};
    }

    FlightTick step(LocalEkf& ekf, int k) {
        FlightTick tick;
        tick.stamp_s = k / s_.imu_rate_hz;
        tick.truth = truth_at(tr_, tick.stamp_s);
        ekf.add_imu(imu_sample(ekf.config(), tick.truth, tick.stamp_s));
        if (s_.imu_per_range > 0 && k % s_.imu_per_range == 0)
            tick.range = ekf.update_range(range(tick.truth, tick.stamp_s));
        if (k % s_.imu_per_sweep == 0) {
            if (k == 0) {
                ekf.clone_pose(tick.stamp_s);
            } else {
                tick.sweep = true;
                tick.p_before_increment_odom = ekf.state().T_odom_body.translation();
                tick.increment = ekf.update_increment(increment(tick.truth, tick.stamp_s));
            }
            sweep_start_ = tick.truth.T_odom_body;
            sweep_start_s_ = tick.stamp_s;
        }
        return tick;
    }

    Trajectory tr_;
    FlightSensors s_;
    Rng rng_;
    Eigen::Vector3d accel_bias_ = Eigen::Vector3d::Zero();
    Eigen::Vector3d gyro_bias_ = Eigen::Vector3d::Zero();
    Eigen::Isometry3d sweep_start_ = Eigen::Isometry3d::Identity();
    double sweep_start_s_ = 0.0;
};

}  // namespace scantling::localization::testing
