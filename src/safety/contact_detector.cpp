// Out-of-view contact detection from the IMU (contact_detector.hpp; SPEC §5, issue 14 item 6).
#include <scantling/safety/contact_detector.hpp>

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>

namespace scantling::safety {
namespace {

void require_finite(const Eigen::Vector3d& v, std::string_view field) {
    if (!v.allFinite()) {
        throw InputError(fmt::format("contact_detector: {} = ({}, {}, {}), expected finite", field,
                                     v.x(), v.y(), v.z()));
    }
}

/// Checks the sample's contract and returns R_world_body (normalised).
Eigen::Matrix3d checked_rotation(const io::ImuRecord& imu, const Eigen::Quaterniond& q_world_body,
                                 const Eigen::Vector3d& a_expected_world_mps2) {
    if (!std::isfinite(imu.stamp_s)) {
        throw InputError(
            fmt::format("contact_detector: imu.stamp_s = {}, expected finite", imu.stamp_s));
    }
    require_finite(imu.specific_force_mps2, "imu.specific_force_mps2");
    require_finite(imu.angular_rate_radps, "imu.angular_rate_radps");
    require_finite(a_expected_world_mps2, "a_expected_world_mps2");
    const double norm = q_world_body.norm();
    if (!q_world_body.coeffs().allFinite() || norm < 1e-6) {
        throw InputError(fmt::format(
            "contact_detector: q_world_body norm = {}, expected a finite non-zero quaternion",
            norm));
    }
    return q_world_body.normalized().toRotationMatrix();
}

}  // namespace

void ContactDetectorConfig::validate(std::string_view prefix) const {
    using namespace config_checks;
    require_positive(threshold_mps2, prefix, "threshold_mps2");
    require_count_at_least(min_samples_above, 1, prefix, "min_samples_above");
    require_non_negative(refractory_s, prefix, "refractory_s");
    require_positive(baseline_time_constant_s, prefix, "baseline_time_constant_s");
    require_positive(max_spike_duration_s, prefix, "max_spike_duration_s");
    require_positive(gravity_mps2, prefix, "gravity_mps2");
    require_positive(back_off_speed_mps, prefix, "back_off_speed_mps");
    require_positive(back_off_duration_s, prefix, "back_off_duration_s");
}

ContactDetector::ContactDetector(const ContactDetectorConfig& config) : config_(config) {
    config_.validate();
}

std::optional<Contact> ContactDetector::add(const io::ImuRecord& imu,
                                            const Eigen::Quaterniond& q_world_body,
                                            const Eigen::Vector3d& a_expected_world_mps2) {
    const Eigen::Matrix3d R_world_body = checked_rotation(imu, q_world_body, a_expected_world_mps2);
    if (started_ && imu.stamp_s <= last_stamp_s_) {
        ++num_out_of_order_;
        return std::nullopt;
    }
    const Eigen::Vector3d g_world(0.0, 0.0, -config_.gravity_mps2);
    const Eigen::Vector3d raw =
        R_world_body * imu.specific_force_mps2 + g_world - a_expected_world_mps2;
    const double dt_s = started_ ? imu.stamp_s - last_stamp_s_ : 0.0;
    last_stamp_s_ = imu.stamp_s;
    if (!started_) {
        started_ = true;
        start_s_ = imu.stamp_s;
    }
    residual_ =
        baseline_samples_ > 0.0 ? Eigen::Vector3d(raw - baseline_) : Eigen::Vector3d::Zero();
    if (residual_.norm() > config_.threshold_mps2) return on_above(raw, imu.stamp_s);
    run_samples_ = 0;
    update_baseline(raw, dt_s);
    return std::nullopt;
}

void ContactDetector::update_baseline(const Eigen::Vector3d& raw, double dt_s) {
    // 1/n weights while warming up (the plain mean of what came so far), then an exponential
    // mean with time constant τ that follows the stamps (an IMU gap weighs the new sample more).
    const double alpha_exp = 1.0 - std::exp(-dt_s / config_.baseline_time_constant_s);
    const double alpha = std::max(1.0 / (baseline_samples_ + 1.0), alpha_exp);
    baseline_ += alpha * (raw - baseline_);
    baseline_samples_ += 1.0;
}

std::optional<Contact> ContactDetector::on_above(const Eigen::Vector3d& raw, double stamp_s) {
    if (run_samples_ == 0) {
        run_start_s_ = stamp_s;
        run_sum_.setZero();
        run_peak_mps2_ = 0.0;
    }
    ++run_samples_;
    run_sum_ += residual_;
    run_peak_mps2_ = std::max(run_peak_mps2_, residual_.norm());
    if (stamp_s - run_start_s_ > config_.max_spike_duration_s) {
        // Too long for an impact: an offset stepped. Restart the mean from here.
        baseline_ = raw;
        baseline_samples_ = 1.0;
        run_samples_ = 0;
        ++num_baseline_restarts_;
        return std::nullopt;
    }
    if (run_samples_ != config_.min_samples_above || !may_report(stamp_s)) return std::nullopt;
    last_contact_ = make_contact(stamp_s);
    ++num_contacts_;
    return last_contact_;
}

bool ContactDetector::may_report(double stamp_s) const {
    const bool warmed_up = stamp_s - start_s_ >= config_.baseline_time_constant_s;
    const bool refractory =
        last_contact_.has_value() && stamp_s - last_contact_->stamp_s < config_.refractory_s;
    return warmed_up && !refractory;
}

Contact ContactDetector::make_contact(double stamp_s) const {
    Contact contact;
    contact.stamp_s = stamp_s;
    // Every sample of the run has |residual| > threshold > 0; their sum can only vanish if the
    // push reversed within the run, in which case the latest sample's direction stands.
    const Eigen::Vector3d sum = run_sum_.norm() > 0.0 ? run_sum_ : residual_;
    contact.impulse_direction_world = sum.normalized();
    contact.peak_residual_mps2 = run_peak_mps2_;
    contact.back_off_velocity_world_mps =
        config_.back_off_speed_mps * contact.impulse_direction_world;
    contact.back_off_until_s = stamp_s + config_.back_off_duration_s;
    return contact;
}

bool ContactDetector::backing_off(double t_s) const {
    return last_contact_.has_value() && t_s >= last_contact_->stamp_s &&
           t_s < last_contact_->back_off_until_s;
}

Eigen::Vector3d ContactDetector::back_off_velocity(double t_s) const {
    return backing_off(t_s) ? last_contact_->back_off_velocity_world_mps : Eigen::Vector3d::Zero();
}

}  // namespace scantling::safety
