#include "scantling/localization/velocity_odometry.hpp"

#include <cmath>
#include <numbers>

#include <scantling/core/se3.hpp>

#include "detail/config_checks.hpp"

namespace scantling::localization {
namespace {

/// Heading of the body's x axis about world z (the ZYX yaw), radians.
double yaw_of(const Eigen::Matrix3d& R) { return euler_zyx_from_rotation(R).z(); }

}  // namespace

void VelocityOdometryConfig::validate(std::string_view prefix) const {
    detail::require_positive(max_step_s, prefix, "max_step_s");
    detail::require_positive(tilt_random_walk_rad_per_sqrt_m, prefix,
                             "tilt_random_walk_rad_per_sqrt_m");
    detail::require_positive(max_yaw_disagreement_rad, prefix, "max_yaw_disagreement_rad");
}

VelocityOdometry::VelocityOdometry(VelocityOdometryConfig config) : config_(config) {
    config_.validate();
}

double VelocityOdometry::yaw_step(const io::VioRecord& sample, double imu_yaw_rad) const {
    if (!previous_ || !previous_->imu_yaw_rad) return 0.0;
    const double imu_step =
        std::remainder(imu_yaw_rad - *previous_->imu_yaw_rad, 2.0 * std::numbers::pi);
    if (!sample.valid || !previous_->vio_yaw_rad) return imu_step;
    const double vio_step = std::remainder(
        yaw_of(sample.T_odom_body.linear()) - *previous_->vio_yaw_rad, 2.0 * std::numbers::pi);
    return std::abs(vio_step - imu_step) <= config_.max_yaw_disagreement_rad ? vio_step : imu_step;
}

io::VioRecord VelocityOdometry::integrate(const io::VioRecord& sample,
                                          const std::optional<Eigen::Matrix3d>& R_world_body) {
    if (previous_ && !(sample.stamp_s > previous_->stamp_s)) return held(sample);
    const bool valid = sample.valid && R_world_body.has_value() && sample.v_body_mps.allFinite();
    Previous now{.stamp_s = sample.stamp_s,
                 .v_odom_mps = {},
                 .valid = valid,
                 .vio_yaw_rad = {},
                 .imu_yaw_rad = {}};
    if (R_world_body) {
        const Eigen::Vector3d rpy_imu = euler_zyx_from_rotation(*R_world_body);
        yaw_odom_rad_ =
            yaw_odom_rad_ ? *yaw_odom_rad_ + yaw_step(sample, rpy_imu.z()) : rpy_imu.z();
        // The IMU's tilt under the integrated heading.
        R_odom_body_ = rotation_from_euler_zyx(rpy_imu.x(), rpy_imu.y(), *yaw_odom_rad_);
        now.imu_yaw_rad = rpy_imu.z();
    }
    if (sample.valid) now.vio_yaw_rad = yaw_of(sample.T_odom_body.linear());
    if (valid) {
        now.v_odom_mps = R_odom_body_ * sample.v_body_mps;
        if (previous_ && previous_->valid) {
            const double dt_s = sample.stamp_s - previous_->stamp_s;
            if (dt_s <= config_.max_step_s) {
                p_odom_m_ += 0.5 * (previous_->v_odom_mps + now.v_odom_mps) * dt_s;
            }
        }
    }
    previous_ = now;
    io::VioRecord out = held(sample);
    out.valid = valid;
    if (!sample.v_body_mps.allFinite()) out.v_body_mps.setZero();  // the filter needs finite
    return out;
}

io::VioRecord VelocityOdometry::held(const io::VioRecord& sample) const {
    io::VioRecord out = sample;
    out.T_odom_body.linear() = R_odom_body_;
    out.T_odom_body.translation() = p_odom_m_;
    return out;
}

}  // namespace scantling::localization
