#include "scantling/localization/attitude_estimator.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include <scantling/core/error.hpp>
#include <scantling/core/se3.hpp>

#include "detail/config_checks.hpp"

namespace scantling::localization {

void AttitudeEstimatorConfig::validate(std::string_view prefix) const {
    const std::pair<double, std::string_view> positive[] = {
        {accel_gain_per_s, "accel_gain_per_s"},
        {max_accel_deviation_mps2, "max_accel_deviation_mps2"},
        {gravity_mps2, "gravity_mps2"},
        {max_gap_s, "max_gap_s"},
        {history_s, "history_s"}};
    for (const auto& [value, field] : positive) detail::require_positive(value, prefix, field);
}

std::string_view to_string(ImuStatus status) {
    switch (status) {
        case ImuStatus::kOk:
            return "ok";
        case ImuStatus::kFirst:
            return "first";
        case ImuStatus::kGapRestart:
            return "gap_restart";
        case ImuStatus::kOutOfOrder:
            return "out_of_order";
        case ImuStatus::kInvalid:
            return "invalid";
    }
    return "?";
}

AttitudeEstimator::AttitudeEstimator(AttitudeEstimatorConfig config) : config_(config) {
    config_.validate();
}

Eigen::Quaterniond AttitudeEstimator::from_accelerometer(const Eigen::Vector3d& f) const {
    // At rest the specific force points up: the body's view of the world z axis.
    return Eigen::Quaterniond::FromTwoVectors(f.normalized(), Eigen::Vector3d::UnitZ());
}

ImuStatus AttitudeEstimator::add(const io::ImuRecord& s) {
    if (!std::isfinite(s.stamp_s) || !s.specific_force_mps2.allFinite() ||
        !s.angular_rate_radps.allFinite() || s.specific_force_mps2.norm() < 1e-6) {
        return ImuStatus::kInvalid;
    }
    if (!history_.empty() && s.stamp_s <= history_.back().stamp_s) return ImuStatus::kOutOfOrder;
    ImuStatus status = ImuStatus::kOk;
    Eigen::Quaterniond q;
    if (history_.empty() || s.stamp_s - history_.back().stamp_s > config_.max_gap_s) {
        status = history_.empty() ? ImuStatus::kFirst : ImuStatus::kGapRestart;
        q = from_accelerometer(s.specific_force_mps2);
    } else {
        const double dt = s.stamp_s - history_.back().stamp_s;
        q = history_.back().q_world_body;
        Eigen::Vector3d omega = s.angular_rate_radps;
        const Eigen::Vector3d& f = s.specific_force_mps2;
        if (std::abs(f.norm() - config_.gravity_mps2) < config_.max_accel_deviation_mps2) {
            const Eigen::Vector3d up_est = q.conjugate() * Eigen::Vector3d::UnitZ();
            omega += config_.accel_gain_per_s * f.normalized().cross(up_est);
        }
        q = (q * Eigen::Quaterniond(so3_exp(omega * dt))).normalized();
    }
    history_.push_back({s.stamp_s, q});
    while (history_.size() > 2 && history_.front().stamp_s < s.stamp_s - config_.history_s) {
        history_.pop_front();
    }
    return status;
}

std::optional<Eigen::Matrix3d> AttitudeEstimator::attitude_at(double stamp_s) const {
    if (history_.empty() || stamp_s < history_.front().stamp_s) return std::nullopt;
    const auto it = std::upper_bound(history_.begin(), history_.end(), stamp_s,
                                     [](double t, const Sample& x) { return t < x.stamp_s; });
    return (it - 1)->q_world_body.toRotationMatrix();
}

}  // namespace scantling::localization
