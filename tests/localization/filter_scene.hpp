#pragma once
// A drifting VIO and noisy absolute poses drawn from exactly the models PoseFilter assumes, so
// the filter's estimate can be checked against the truth (error, NEES).
#include <Eigen/Geometry>
#include <cmath>
#include <vector>

#include <scantling/core/random.hpp>
#include <scantling/core/se3.hpp>
#include <scantling/io/recording.hpp>
#include <scantling/localization/pose_filter.hpp>

namespace scantling::localization::test {

struct FilterScene {
    std::vector<Eigen::Isometry3d> truth;  ///< T_world_body per VIO sample
    std::vector<io::VioRecord> vio;
    std::vector<AbsolutePose> measurements;  ///< at `measurement_rate_hz`, between VIO samples
};

inline Vector6d draw(const Matrix6d& covariance, Rng& rng) {
    const Eigen::LLT<Matrix6d> llt(covariance);
    Vector6d z;
    for (int k = 0; k < 6; ++k) z[k] = rng.normal();
    return llt.matrixL() * z;
}

/// A 60 s flight at ~0.3 m/s (a lap with height changes) sampled at 30 Hz.
inline Eigen::Isometry3d true_pose(double t) {
    const double yaw = 0.05 * t;
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = rotation_from_euler_zyx(0.02 * std::sin(0.3 * t), 0.02 * std::cos(0.2 * t), yaw);
    T.translation() = Eigen::Vector3d(1.0 + 6.0 * std::sin(yaw), 1.5 - 6.0 * std::cos(yaw) + 6.0,
                                      0.9 + 0.3 * std::sin(0.1 * t));
    return T;
}

inline FilterScene make_filter_scene(const PoseFilterConfig& config, std::uint64_t seed,
                                     double duration_s = 60.0, double measurement_rate_hz = 1.0) {
    Rng rng(seed);
    FilterScene scene;
    Eigen::Isometry3d E = Eigen::Isometry3d::Identity();  // T_world_odom, drifting
    E.translation() = Eigen::Vector3d(0.3, -0.2, 0.1);
    const double dt = 1.0 / 30.0;
    double next_measurement = 0.5 / measurement_rate_hz;
    Matrix6d R = Matrix6d::Zero();
    R.diagonal() << 4e-4, 4e-4, 4e-4, 1e-4, 1e-4, 4e-4;  // 2 cm, 0.6°, 1.1° yaw
    for (int k = 0; k * dt <= duration_s; ++k) {
        const double t = k * dt;
        const Eigen::Isometry3d B = true_pose(t);
        if (k > 0) {
            const double d = (B.translation() - scene.truth.back().translation()).norm();
            Vector6d n;
            for (int i = 0; i < 3; ++i) {
                n[i] = rng.normal() *
                       std::sqrt(std::pow(config.position_random_walk_m_per_sqrt_m, 2) * d +
                                 std::pow(config.position_random_walk_m_per_sqrt_s, 2) * dt);
            }
            n[3] = rng.normal() * config.tilt_random_walk_rad_per_sqrt_m * std::sqrt(d);
            n[4] = rng.normal() * config.tilt_random_walk_rad_per_sqrt_m * std::sqrt(d);
            n[5] =
                rng.normal() * std::sqrt(std::pow(config.yaw_random_walk_rad_per_sqrt_m, 2) * d +
                                         std::pow(config.yaw_random_walk_rad_per_sqrt_s, 2) * dt);
            Vector6d xi;
            xi.head<3>() = n.head<3>() + B.translation().cross(n.tail<3>());
            xi.tail<3>() = n.tail<3>();
            E = se3_exp(xi) * E;
        }
        io::VioRecord v;
        v.stamp_s = t;
        v.valid = true;
        v.T_odom_body = E.inverse() * B;
        for (int i = 0; i < 3; ++i)
            v.T_odom_body.translation()[i] += config.position_jitter_m * rng.normal();
        const Eigen::Vector3d dtheta(config.attitude_jitter_rad * rng.normal(),
                                     config.attitude_jitter_rad * rng.normal(),
                                     config.attitude_jitter_rad * rng.normal());
        v.T_odom_body.linear() = so3_exp(dtheta) * v.T_odom_body.linear();
        v.feature_quality = 1.0;
        scene.truth.push_back(B);
        scene.vio.push_back(v);
        if (t + dt > next_measurement && t <= next_measurement) {
            const Eigen::Isometry3d Bm = true_pose(next_measurement);
            scene.measurements.push_back({next_measurement, se3_exp(draw(R, rng)) * Bm, R});
            next_measurement += 1.0 / measurement_rate_hz;
        }
    }
    return scene;
}

}  // namespace scantling::localization::test
