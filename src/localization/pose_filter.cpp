#include "scantling/localization/pose_filter.hpp"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include <scantling/core/error.hpp>

#include "detail/config_checks.hpp"
#include "detail/pose_filter_math.hpp"

namespace scantling::localization {
namespace {

bool finite_pose(const AbsolutePose& pose) {
    return std::isfinite(pose.stamp_s) && pose.T_world_body.matrix().allFinite() &&
           pose.covariance.allFinite();
}

bool positive_definite(const Matrix6d& m) {
    const Matrix6d sym = 0.5 * (m + m.transpose());
    Eigen::LLT<Matrix6d> llt(sym);
    return llt.info() == Eigen::Success;
}

}  // namespace

std::string_view to_string(FilterKind kind) { return kind == FilterKind::kEkf ? "ekf" : "ukf"; }

FilterKind filter_kind_from_string(std::string_view name, std::string_view field) {
    if (name == "ekf") return FilterKind::kEkf;
    if (name == "ukf") return FilterKind::kUkf;
    throw ConfigError(fmt::format("{} = '{}', expected ekf or ukf", field, name));
}

std::string_view to_string(OdometryStatus status) {
    switch (status) {
        case OdometryStatus::kOk:
            return "ok";
        case OdometryStatus::kFirst:
            return "first";
        case OdometryStatus::kDropout:
            return "dropout";
        case OdometryStatus::kJump:
            return "jump";
        case OdometryStatus::kOutOfOrder:
            return "out_of_order";
    }
    return "?";
}

std::string_view to_string(MeasurementStatus status) {
    switch (status) {
        case MeasurementStatus::kApplied:
            return "applied";
        case MeasurementStatus::kPending:
            return "pending";
        case MeasurementStatus::kTooOld:
            return "too_old";
        case MeasurementStatus::kNotInitialized:
            return "not_initialized";
        case MeasurementStatus::kInvalid:
            return "invalid";
    }
    return "?";
}

void PoseFilterConfig::validate(std::string_view prefix) const {
    const std::pair<double, std::string_view> non_negative[] = {
        {position_random_walk_m_per_sqrt_m, "position_random_walk_m_per_sqrt_m"},
        {yaw_random_walk_rad_per_sqrt_m, "yaw_random_walk_rad_per_sqrt_m"},
        {position_random_walk_m_per_sqrt_s, "position_random_walk_m_per_sqrt_s"},
        {yaw_random_walk_rad_per_sqrt_s, "yaw_random_walk_rad_per_sqrt_s"},
        {poor_features_drift_gain, "poor_features_drift_gain"},
        {velocity_sigma_mps, "velocity_sigma_mps"},
        {ukf_beta, "ukf_beta"},
        {ukf_kappa, "ukf_kappa"}};
    for (const auto& [value, field] : non_negative)
        detail::require_non_negative(value, prefix, field);
    const std::pair<double, std::string_view> positive[] = {
        {tilt_random_walk_rad_per_sqrt_m, "tilt_random_walk_rad_per_sqrt_m"},
        {position_jitter_m, "position_jitter_m"},
        {attitude_jitter_rad, "attitude_jitter_rad"},
        {dropout_position_random_walk_m_per_sqrt_s, "dropout_position_random_walk_m_per_sqrt_s"},
        {dropout_yaw_random_walk_rad_per_sqrt_s, "dropout_yaw_random_walk_rad_per_sqrt_s"},
        {max_odometry_speed_mps, "max_odometry_speed_mps"},
        {jump_position_sigma_m, "jump_position_sigma_m"},
        {jump_yaw_sigma_rad, "jump_yaw_sigma_rad"},
        {history_s, "history_s"},
        {ukf_alpha, "ukf_alpha"}};
    for (const auto& [value, field] : positive) detail::require_positive(value, prefix, field);
}

PoseFilter::PoseFilter(PoseFilterConfig config) : config_(std::move(config)) { config_.validate(); }

OdometryStatus PoseFilter::add_odometry(const io::VioRecord& sample) {
    const bool finite = std::isfinite(sample.stamp_s) && sample.T_odom_body.matrix().allFinite() &&
                        sample.v_body_mps.allFinite();
    if (!finite) {
        throw InputError(fmt::format("VIO sample at {} s is not finite", sample.stamp_s));
    }
    if (!history_.empty() && sample.stamp_s <= history_.back().vio.stamp_s) {
        return OdometryStatus::kOutOfOrder;
    }
    Entry entry;
    entry.vio = sample;
    entry.status = history_.empty() ? OdometryStatus::kFirst
                                    : detail::classify_step(history_.back().vio, sample,
                                                            config_.max_odometry_speed_mps);
    history_.push_back(std::move(entry));
    apply_entry(history_.size() - 1);
    apply_pending();
    prune();
    return history_.back().status;
}

std::optional<std::size_t> PoseFilter::entry_at(double stamp_s) const {
    if (history_.empty() || stamp_s < history_.front().vio.stamp_s) return std::nullopt;
    const auto it = std::upper_bound(history_.begin(), history_.end(), stamp_s,
                                     [](double t, const Entry& e) { return t < e.vio.stamp_s; });
    return static_cast<std::size_t>(it - history_.begin()) - 1;
}

Eigen::Isometry3d PoseFilter::odometry_pose(std::size_t i, double stamp_s) const {
    const Entry& a = history_[i];
    if (i + 1 >= history_.size() || stamp_s <= a.vio.stamp_s) return a.vio.T_odom_body;
    const Entry& b = history_[i + 1];
    const double s = (stamp_s - a.vio.stamp_s) / (b.vio.stamp_s - a.vio.stamp_s);
    return interpolate(a.vio.T_odom_body, b.vio.T_odom_body, std::clamp(s, 0.0, 1.0));
}

std::optional<Eigen::Isometry3d> PoseFilter::odometry_at(double stamp_s) const {
    const auto i = entry_at(stamp_s);
    if (!i) return std::nullopt;
    return odometry_pose(*i, stamp_s);
}

Matrix6d PoseFilter::jitter_covariance(const Eigen::Isometry3d& T_world_body) const {
    Vector6d d;
    d.head<3>().setConstant(config_.position_jitter_m * config_.position_jitter_m);
    d.tail<3>().setConstant(config_.attitude_jitter_rad * config_.attitude_jitter_rad);
    return twist_covariance(d.asDiagonal(), T_world_body.translation());
}

PoseFilter::Estimate PoseFilter::predict_step(const Estimate& previous, const Entry& from,
                                              const Entry& to) const {
    Estimate next = previous;
    if (to.status == OdometryStatus::kJump) {
        // Hold the body pose across the jump: E' · V_to = E · V_from.
        next.T_world_odom =
            previous.T_world_odom * from.vio.T_odom_body * to.vio.T_odom_body.inverse();
    }
    const Eigen::Vector3d c = (next.T_world_odom * to.vio.T_odom_body).translation();
    next.covariance += detail::process_noise(config_, from.vio, to.vio, to.status, c);
    return next;
}

void PoseFilter::apply_entry(std::size_t i) {
    Entry& e = history_[i];
    if (i > 0) {
        const Entry& previous = history_[i - 1];
        e.prior = previous.posterior ? std::optional(predict_step(*previous.posterior, previous, e))
                                     : std::nullopt;
    }
    std::optional<Estimate> current = e.prior;
    if (e.initialization) {
        const Eigen::Isometry3d V = odometry_pose(i, e.initialization->stamp_s);
        current = Estimate{
            e.initialization->T_world_body * V.inverse(),
            e.initialization->covariance + jitter_covariance(e.initialization->T_world_body)};
    }
    if (current) {
        for (const AbsolutePose& m : e.measurements) {
            current = measurement_update(*current, odometry_pose(i, m.stamp_s), m);
        }
    }
    e.posterior = current;
}

void PoseFilter::replay_from(std::size_t i) {
    for (std::size_t j = i; j < history_.size(); ++j) apply_entry(j);
}

MeasurementStatus PoseFilter::insert(std::size_t i, const AbsolutePose& pose, bool initialization) {
    Entry& e = history_[i];
    if (initialization) {
        e.initialization = pose;
        std::erase_if(e.measurements,
                      [&](const AbsolutePose& m) { return m.stamp_s < pose.stamp_s; });
    } else {
        if (e.initialization && pose.stamp_s < e.initialization->stamp_s) {
            return MeasurementStatus::kTooOld;  // captured before a restart
        }
        if (!e.posterior && !e.initialization) return MeasurementStatus::kNotInitialized;
        const auto at =
            std::upper_bound(e.measurements.begin(), e.measurements.end(), pose.stamp_s,
                             [](double t, const AbsolutePose& m) { return t < m.stamp_s; });
        e.measurements.insert(at, pose);
    }
    replay_from(i);
    return MeasurementStatus::kApplied;
}

MeasurementStatus PoseFilter::initialize(const AbsolutePose& pose) {
    if (!finite_pose(pose) || !positive_definite(pose.covariance))
        return MeasurementStatus::kInvalid;
    if (history_.empty() || pose.stamp_s > history_.back().vio.stamp_s) {
        pending_.emplace_back(pose, true);
        return MeasurementStatus::kPending;
    }
    const auto i = entry_at(pose.stamp_s);
    if (!i) return MeasurementStatus::kTooOld;
    return insert(*i, pose, true);
}

MeasurementStatus PoseFilter::update(const AbsolutePose& pose) {
    if (!finite_pose(pose) || !positive_definite(pose.covariance))
        return MeasurementStatus::kInvalid;
    if (history_.empty() || pose.stamp_s > history_.back().vio.stamp_s) {
        pending_.emplace_back(pose, false);
        return MeasurementStatus::kPending;
    }
    const auto i = entry_at(pose.stamp_s);
    if (!i) return MeasurementStatus::kTooOld;
    return insert(*i, pose, false);
}

void PoseFilter::apply_pending() {
    const double last = history_.back().vio.stamp_s;
    std::vector<std::pair<AbsolutePose, bool>> waiting;
    for (const auto& [pose, init] : pending_) {
        if (pose.stamp_s > last) {
            waiting.emplace_back(pose, init);
            continue;
        }
        const auto i = entry_at(pose.stamp_s);
        if (i) insert(*i, pose, init);
    }
    pending_ = std::move(waiting);
}

void PoseFilter::prune() {
    const double oldest = history_.back().vio.stamp_s - config_.history_s;
    while (history_.size() > 2 && history_[1].vio.stamp_s < oldest) history_.pop_front();
}

bool PoseFilter::initialized() const {
    return !history_.empty() && history_.back().posterior.has_value();
}

std::optional<FusedState> PoseFilter::state() const {
    if (!initialized()) return std::nullopt;
    const Entry& e = history_.back();
    FusedState s;
    s.stamp_s = e.vio.stamp_s;
    s.T_world_body = e.posterior->T_world_odom * e.vio.T_odom_body;
    s.v_world_mps = s.T_world_body.linear() * e.vio.v_body_mps;
    s.covariance = position_attitude_covariance(
        e.posterior->covariance + jitter_covariance(s.T_world_body), s.T_world_body.translation());
    s.velocity_covariance =
        Eigen::Matrix3d::Identity() * config_.velocity_sigma_mps * config_.velocity_sigma_mps;
    return s;
}

std::optional<AbsolutePose> PoseFilter::predict(double stamp_s) const {
    std::optional<std::size_t> i = entry_at(stamp_s);
    if (!i || !history_[*i].posterior) return std::nullopt;
    const Estimate& e = *history_[*i].posterior;
    AbsolutePose p;
    p.stamp_s = stamp_s;
    p.T_world_body = e.T_world_odom * odometry_pose(*i, stamp_s);
    p.covariance = e.covariance + jitter_covariance(p.T_world_body);
    return p;
}

std::optional<Innovation> PoseFilter::innovation(const AbsolutePose& pose) const {
    if (!finite_pose(pose) || history_.empty() || pose.stamp_s > history_.back().vio.stamp_s) {
        return std::nullopt;
    }
    const auto i = entry_at(pose.stamp_s);
    if (!i || !history_[*i].posterior) return std::nullopt;
    return innovation_of(*history_[*i].posterior, odometry_pose(*i, pose.stamp_s), pose);
}

Innovation PoseFilter::innovation_of(const Estimate& prior, const Eigen::Isometry3d& T_odom_body,
                                     const AbsolutePose& pose) const {
    const Eigen::Isometry3d B = prior.T_world_odom * T_odom_body;
    const Matrix6d R = pose.covariance + jitter_covariance(B);
    return config_.kind == FilterKind::kEkf
               ? detail::ekf_innovation(prior.covariance, R, B, pose.T_world_body)
               : detail::ukf_innovation(prior.covariance, R, B, pose.T_world_body, config_)
                     .innovation;
}

PoseFilter::Estimate PoseFilter::measurement_update(const Estimate& prior,
                                                    const Eigen::Isometry3d& T_odom_body,
                                                    const AbsolutePose& pose) const {
    const Eigen::Isometry3d B = prior.T_world_odom * T_odom_body;
    const Matrix6d R = pose.covariance + jitter_covariance(B);
    const detail::Correction c =
        config_.kind == FilterKind::kEkf
            ? detail::ekf_correction(prior.covariance, R, B, pose.T_world_body)
            : detail::ukf_correction(prior.covariance, R, B, pose.T_world_body, config_);
    Estimate posterior;
    posterior.T_world_odom = se3_exp(c.delta) * prior.T_world_odom;
    posterior.covariance = c.covariance;
    return posterior;
}

Matrix6d position_attitude_covariance(const Matrix6d& twist_covariance,
                                      const Eigen::Vector3d& p_world_body) {
    Matrix6d M = Matrix6d::Identity();
    M.topRightCorner<3, 3>() = -hat(p_world_body);  // δp = ρ + ω × p
    return M * twist_covariance * M.transpose();
}

Matrix6d twist_covariance(const Matrix6d& position_attitude_covariance,
                          const Eigen::Vector3d& p_world_body) {
    Matrix6d N = Matrix6d::Identity();
    N.topRightCorner<3, 3>() = hat(p_world_body);  // ρ = δp − ω × p
    return N * position_attitude_covariance * N.transpose();
}

double largest_position_sigma_m(const Matrix6d& twist_covariance,
                                const Eigen::Vector3d& p_world_body) {
    const Eigen::Matrix3d P =
        position_attitude_covariance(twist_covariance, p_world_body).topLeftCorner<3, 3>();
    const double largest =
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(P).eigenvalues().maxCoeff();
    return std::sqrt(std::max(largest, 0.0));
}

Vector6d position_attitude_error(const Eigen::Isometry3d& T_world_body_true,
                                 const Eigen::Isometry3d& T_world_body_estimate) {
    Vector6d e;
    e.head<3>() = T_world_body_true.translation() - T_world_body_estimate.translation();
    e.tail<3>() = so3_log(T_world_body_true.linear() * T_world_body_estimate.linear().transpose());
    return e;
}

}  // namespace scantling::localization
