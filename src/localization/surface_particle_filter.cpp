// The crawler's particle filter on its surface: wheels, gyro, UWB (surface_particle_filter.hpp).
#include "scantling/localization/surface_particle_filter.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

#include <fmt/format.h>

#include <scantling/core/error.hpp>

#include "detail/config_checks.hpp"

namespace scantling::localization {

using Eigen::Matrix3d;
using Eigen::Vector3d;

namespace {

constexpr double kMinusInfinity = -std::numeric_limits<double>::infinity();

Matrix3d yaw_rotation(double angle_rad) {
    return Eigen::AngleAxisd(angle_rad, Vector3d::UnitZ()).toRotationMatrix();
}

double log_sum_exp(double a, double b) {
    const double m = std::max(a, b);
    if (m == kMinusInfinity) return kMinusInfinity;
    return m + std::log(std::exp(a - m) + std::exp(b - m));
}

/// log of the uniform excess on [0, L] convolved with N(0, σ²): (Φ(e/σ) − Φ((e − L)/σ)) / L.
double log_nlos_density(double error_m, double sigma_m, double max_excess_m) {
    const double a = error_m / (sigma_m * std::numbers::sqrt2);
    const double b = (error_m - max_excess_m) / (sigma_m * std::numbers::sqrt2);
    const double mass = 0.5 * (std::erfc(-a) - std::erfc(-b));
    return mass > 0.0 ? std::log(mass / max_excess_m) : kMinusInfinity;
}

/// One exact step of an Ornstein–Uhlenbeck process with stationary N(mean, sigma²).
double ou_step(double x, double mean, double sigma, double decay, double standard_normal) {
    return mean + decay * (x - mean) + sigma * std::sqrt(1.0 - decay * decay) * standard_normal;
}

Vector3d weighted_mean_position(const std::vector<SurfaceParticle>& particles) {
    Vector3d mean_m = Vector3d::Zero();
    for (const SurfaceParticle& particle : particles)
        mean_m += std::exp(particle.log_weight) * particle.p_world_m;
    return mean_m;
}

/// The circular mean: the weighted mean of the unit headings in the tangent plane of `normal`.
Vector3d mean_heading(const std::vector<SurfaceParticle>& particles, const Vector3d& normal) {
    Vector3d heading = Vector3d::Zero();
    for (const SurfaceParticle& particle : particles) {
        const Vector3d x = particle.R_world_body.col(0);
        heading += std::exp(particle.log_weight) * (x - normal * normal.dot(x)).normalized();
    }
    return heading;
}

/// Each particle's heading angle from the mean heading (R_mean's x) about the mean normal.
std::vector<double> yaw_deviations(const std::vector<SurfaceParticle>& particles,
                                   const Matrix3d& R_mean) {
    std::vector<double> yaw_rad(particles.size());
    for (std::size_t i = 0; i < particles.size(); ++i) {
        const Vector3d x = particles[i].R_world_body.col(0);
        yaw_rad[i] = std::atan2(x.dot(R_mean.col(1)), x.dot(R_mean.col(0)));
    }
    return yaw_rad;
}

void require_finite(bool ok, std::string_view what, double stamp_s) {
    if (!ok)
        throw InputError(fmt::format("particle_filter: {} at {} s is not finite", what, stamp_s));
}

}  // namespace

void SurfaceParticleFilterConfig::validate(std::string_view prefix) const {
    detail::require_count_at_least(num_particles, 1, prefix, "num_particles");
    detail::require_non_negative(initial_position_sigma_m, prefix, "initial_position_sigma_m");
    detail::require_non_negative(initial_yaw_sigma_rad, prefix, "initial_yaw_sigma_rad");
    detail::require(std::isfinite(slip_mean) && slip_mean > -1.0 && slip_mean < 1.0, prefix,
                    "slip_mean", slip_mean, "in (-1, 1)");
    detail::require_non_negative(slip_sigma, prefix, "slip_sigma");
    detail::require_positive(slip_correlation_time_s, prefix, "slip_correlation_time_s");
    detail::require_non_negative(lateral_slip_sigma, prefix, "lateral_slip_sigma");
    detail::require_non_negative(wheel_yaw_slip_sigma, prefix, "wheel_yaw_slip_sigma");
    detail::require_non_negative(gyro_yaw_random_walk_rad_per_sqrt_s, prefix,
                                 "gyro_yaw_random_walk_rad_per_sqrt_s");
    detail::require_non_negative(wheel_yaw_random_walk_rad_per_sqrt_s, prefix,
                                 "wheel_yaw_random_walk_rad_per_sqrt_s");
    const bool rotation = R_body_imu.allFinite() &&
                          (R_body_imu.transpose() * R_body_imu).isIdentity(1e-6) &&
                          R_body_imu.determinant() > 0.0;
    detail::require(rotation, prefix, "R_body_imu", R_body_imu.determinant(), "a rotation");
    for (const auto& [id, p_world_m] : uwb_anchors_world_m) {
        detail::require(p_world_m.allFinite(), prefix, fmt::format("uwb_anchors_world_m[{}]", id),
                        p_world_m.norm(), "finite");
    }
    detail::require(p_body_uwb_tag_m.allFinite(), prefix, "p_body_uwb_tag_m",
                    p_body_uwb_tag_m.norm(), "finite");
    detail::require_positive(uwb_range_sigma_m, prefix, "uwb_range_sigma_m");
    detail::require(nlos_probability >= 0.0 && nlos_probability < 1.0, prefix, "nlos_probability",
                    nlos_probability, "in [0, 1)");
    detail::require_positive(nlos_max_excess_m, prefix, "nlos_max_excess_m");
    detail::require(outlier_probability >= 0.0 && outlier_probability + nlos_probability < 1.0,
                    prefix, "outlier_probability", outlier_probability,
                    ">= 0 with outlier_probability + nlos_probability < 1");
    detail::require_positive(uwb_max_range_m, prefix, "uwb_max_range_m");
    detail::require(resample_threshold_fraction >= 0.0 && resample_threshold_fraction <= 1.0,
                    prefix, "resample_threshold_fraction", resample_threshold_fraction,
                    "in [0, 1]");
    detail::require_positive(max_wheel_gap_s, prefix, "max_wheel_gap_s");
}

double uwb_range_log_likelihood(double error_m, const SurfaceParticleFilterConfig& c) {
    const double sigma = c.uwb_range_sigma_m;
    const double z = error_m / sigma;
    const double log_los = std::log1p(-c.nlos_probability - c.outlier_probability) - 0.5 * z * z -
                           std::log(sigma * std::sqrt(2.0 * std::numbers::pi));
    const double log_nlos =
        c.nlos_probability > 0.0
            ? std::log(c.nlos_probability) + log_nlos_density(error_m, sigma, c.nlos_max_excess_m)
            : kMinusInfinity;
    const double log_outlier = c.outlier_probability > 0.0
                                   ? std::log(c.outlier_probability / c.uwb_max_range_m)
                                   : kMinusInfinity;
    return log_sum_exp(log_sum_exp(log_los, log_nlos), log_outlier);
}

SurfaceParticleFilter::SurfaceParticleFilter(SurfaceParticleFilterConfig config,
                                             const SurfaceProjector& surface,
                                             const Eigen::Isometry3d& T_world_body_start,
                                             std::uint64_t seed)
    : config_(std::move(config)), surface_(&surface), rng_(seed) {
    config_.validate();
    if (!T_world_body_start.matrix().allFinite())
        throw InputError("particle_filter: the start pose is not finite");
    initialize_particles(T_world_body_start);
}

Eigen::Isometry3d SurfaceParticleFilter::settle(const Vector3d& p_world,
                                                const Vector3d& heading_world) const {
    const SurfacePoint s = surface_->project(p_world);
    const Vector3d& z = s.normal;
    Vector3d x = heading_world - z * z.dot(heading_world);
    if (x.norm() < 1e-9) x = z.unitOrthogonal();  // heading along the normal: any tangent
    x.normalize();
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() << x, z.cross(x), z;
    T.translation() = s.point;
    return T;
}

void SurfaceParticleFilter::initialize_particles(const Eigen::Isometry3d& T_world_body_start) {
    const Eigen::Isometry3d T0 =
        settle(T_world_body_start.translation(), T_world_body_start.linear().col(0));
    const SurfaceParticleFilterConfig& c = config_;
    const double log_uniform = -std::log(static_cast<double>(c.num_particles));
    particles_.resize(c.num_particles);
    for (SurfaceParticle& particle : particles_) {
        const double dx = rng_.normal(0.0, c.initial_position_sigma_m);
        const double dy = rng_.normal(0.0, c.initial_position_sigma_m);
        const double dyaw = rng_.normal(0.0, c.initial_yaw_sigma_rad);
        const Eigen::Isometry3d T =
            settle(T0 * Vector3d(dx, dy, 0.0), T0.linear() * yaw_rotation(dyaw).col(0));
        particle.p_world_m = T.translation();
        particle.R_world_body = T.linear();
        // Start from the slip's stationary distribution: the crawler's slip is unknown.
        particle.slip =
            Vector3d(rng_.normal(c.slip_mean, c.slip_sigma), rng_.normal(0.0, c.lateral_slip_sigma),
                     rng_.normal(0.0, c.wheel_yaw_slip_sigma));
        particle.log_weight = log_uniform;
    }
}

ImuPredictionStatus SurfaceParticleFilter::add_imu(const io::ImuRecord& sample) {
    require_finite(std::isfinite(sample.stamp_s) && sample.angular_rate_radps.allFinite(),
                   "IMU sample", sample.stamp_s);
    if (last_imu_stamp_s_ && sample.stamp_s <= *last_imu_stamp_s_) {
        ++counters_.imu_out_of_order;
        return ImuPredictionStatus::kOutOfOrder;
    }
    const double rate_radps = (config_.R_body_imu * sample.angular_rate_radps).z();
    // The sample's rate is its mean over the interval ending at its stamp (sim/imu.hpp).
    if (gyro_stamp_s_ && sample.stamp_s > *gyro_stamp_s_)
        gyro_turn_rad_ += rate_radps * (sample.stamp_s - *gyro_stamp_s_);
    gyro_stamp_s_ = std::max(gyro_stamp_s_.value_or(sample.stamp_s), sample.stamp_s);
    const ImuPredictionStatus status =
        last_imu_stamp_s_ ? ImuPredictionStatus::kOk : ImuPredictionStatus::kFirst;
    last_imu_stamp_s_ = sample.stamp_s;
    held_rate_radps_ = rate_radps;
    imu_in_interval_ = true;
    ++counters_.imu_samples;
    return status;
}

std::optional<double> SurfaceParticleFilter::take_gyro_turn(double stamp_s) {
    std::optional<double> turn_rad;
    if (imu_in_interval_) {
        // Hold the last rate up to the wheel stamp; a sample past it was integrated already and
        // its excess (< one IMU period) moves into this interval instead of the next.
        if (gyro_stamp_s_ && *gyro_stamp_s_ < stamp_s)
            gyro_turn_rad_ += held_rate_radps_ * (stamp_s - *gyro_stamp_s_);
        turn_rad = gyro_turn_rad_;
    }
    gyro_turn_rad_ = 0.0;
    gyro_stamp_s_ = std::max(gyro_stamp_s_.value_or(stamp_s), stamp_s);
    imu_in_interval_ = false;
    return turn_rad;
}

ImuPredictionStatus SurfaceParticleFilter::add_wheel_odometry(
    const io::WheelOdometryRecord& wheel) {
    require_finite(std::isfinite(wheel.stamp_s) && std::isfinite(wheel.forward_speed_mps) &&
                       std::isfinite(wheel.yaw_rate_radps),
                   "wheel odometry", wheel.stamp_s);
    if (last_wheel_ && wheel.stamp_s <= last_wheel_->stamp_s) {
        ++counters_.wheel_out_of_order;
        return ImuPredictionStatus::kOutOfOrder;
    }
    ImuPredictionStatus status = ImuPredictionStatus::kFirst;
    if (!last_wheel_) {
        take_gyro_turn(wheel.stamp_s);  // turns before the start belong to no interval
    } else {
        const double dt_s = wheel.stamp_s - last_wheel_->stamp_s;
        status = ImuPredictionStatus::kOk;
        if (dt_s > config_.max_wheel_gap_s) {
            status = ImuPredictionStatus::kGap;
            ++counters_.wheel_gaps;
        }
        predict(wheel, dt_s);
    }
    last_wheel_ = wheel;
    stamp_s_ = wheel.stamp_s;
    return status;
}

void SurfaceParticleFilter::predict(const io::WheelOdometryRecord& wheel, double dt_s) {
    const double distance_m =
        0.5 * (last_wheel_->forward_speed_mps + wheel.forward_speed_mps) * dt_s;
    const double wheel_turn_rad = 0.5 * (last_wheel_->yaw_rate_radps + wheel.yaw_rate_radps) * dt_s;
    const std::optional<double> gyro_turn_rad = take_gyro_turn(wheel.stamp_s);
    for (SurfaceParticle& particle : particles_)
        move_particle(particle, distance_m, gyro_turn_rad, wheel_turn_rad, dt_s);
    ++counters_.predictions;
    if (gyro_turn_rad) ++counters_.gyro_turns;
}

void SurfaceParticleFilter::move_particle(SurfaceParticle& particle, double distance_m,
                                          const std::optional<double>& gyro_turn_rad,
                                          double wheel_turn_rad, double dt_s) {
    const SurfaceParticleFilterConfig& c = config_;
    const double decay = std::exp(-dt_s / c.slip_correlation_time_s);
    // Always four draws per particle, whichever turn is used: the stream stays aligned.
    Vector3d& slip = particle.slip;
    slip.x() = ou_step(slip.x(), c.slip_mean, c.slip_sigma, decay, rng_.normal());
    slip.y() = ou_step(slip.y(), 0.0, c.lateral_slip_sigma, decay, rng_.normal());
    slip.z() = ou_step(slip.z(), 0.0, c.wheel_yaw_slip_sigma, decay, rng_.normal());
    const double walk = rng_.normal() * std::sqrt(dt_s);
    const double turn_rad =
        gyro_turn_rad
            ? *gyro_turn_rad + c.gyro_yaw_random_walk_rad_per_sqrt_s * walk
            : wheel_turn_rad * (1.0 + slip.z()) + c.wheel_yaw_random_walk_rad_per_sqrt_s * walk;
    // As the crawler: move along the midpoint heading, project, transport the turned heading.
    const Matrix3d& R = particle.R_world_body;
    const Vector3d step_body(distance_m * (1.0 - slip.x()), std::abs(distance_m) * slip.y(), 0.0);
    const Vector3d move_world = R * (yaw_rotation(0.5 * turn_rad) * step_body);
    const Eigen::Isometry3d T =
        settle(particle.p_world_m + move_world, R * yaw_rotation(turn_rad).col(0));
    particle.p_world_m = T.translation();
    particle.R_world_body = T.linear();
}

UpdateResult SurfaceParticleFilter::update_uwb(const io::UwbRecord& range) {
    if (!range.valid) {
        ++counters_.uwb_refused;
        return UpdateResult{UpdateStatus::kInvalid, 0.0, 0};
    }
    require_finite(std::isfinite(range.stamp_s) && std::isfinite(range.range_m), "UWB range",
                   range.stamp_s);
    const auto anchor = config_.uwb_anchors_world_m.find(range.anchor_id);
    if (anchor == config_.uwb_anchors_world_m.end()) {
        ++counters_.uwb_refused;
        return UpdateResult{UpdateStatus::kUnknownAnchor, 0.0, 0};
    }
    const SurfaceParticleEstimate before = estimate();
    const double predicted_m =
        (before.T_world_body * config_.p_body_uwb_tag_m - anchor->second).norm();
    std::vector<double> log_likelihoods(particles_.size());
    for (std::size_t i = 0; i < particles_.size(); ++i) {
        const SurfaceParticle& particle = particles_[i];
        const Vector3d tag_world =
            particle.p_world_m + particle.R_world_body * config_.p_body_uwb_tag_m;
        const double error_m = range.range_m - (tag_world - anchor->second).norm();
        log_likelihoods[i] = uwb_range_log_likelihood(error_m, config_);
    }
    if (!reweight(log_likelihoods)) ++counters_.weight_resets;
    resample_if_degenerate();
    ++counters_.uwb_applied;
    const double z = (range.range_m - predicted_m) / config_.uwb_range_sigma_m;
    return UpdateResult{UpdateStatus::kApplied, z * z, 1};
}

bool SurfaceParticleFilter::reweight(const std::vector<double>& log_likelihoods) {
    double max_log = kMinusInfinity;
    for (std::size_t i = 0; i < particles_.size(); ++i)
        max_log = std::max(max_log, particles_[i].log_weight + log_likelihoods[i]);
    // Every likelihood 0: the range says nothing usable (impossible while outlier_probability
    // > 0, whose floor is finite).
    if (!std::isfinite(max_log)) return reset_weights();
    double sum = 0.0;
    for (std::size_t i = 0; i < particles_.size(); ++i)
        sum += std::exp(particles_[i].log_weight + log_likelihoods[i] - max_log);
    const double log_normaliser = max_log + std::log(sum);
    if (!std::isfinite(log_normaliser)) return reset_weights();
    for (std::size_t i = 0; i < particles_.size(); ++i)
        particles_[i].log_weight += log_likelihoods[i] - log_normaliser;
    return true;
}

bool SurfaceParticleFilter::reset_weights() {
    const double log_uniform = -std::log(static_cast<double>(particles_.size()));
    for (SurfaceParticle& particle : particles_) particle.log_weight = log_uniform;
    return false;
}

double SurfaceParticleFilter::effective_sample_size() const {
    double sum_w2 = 0.0;
    for (const SurfaceParticle& particle : particles_)
        sum_w2 += std::exp(2.0 * particle.log_weight);
    return 1.0 / sum_w2;
}

void SurfaceParticleFilter::resample_if_degenerate() {
    const double n = static_cast<double>(particles_.size());
    if (effective_sample_size() >= config_.resample_threshold_fraction * n) return;
    // Systematic: N evenly spaced pointers with one random offset (low variance, O(N)).
    std::vector<SurfaceParticle> drawn;
    drawn.reserve(particles_.size());
    const double offset = rng_.uniform();
    double cumulative = std::exp(particles_.front().log_weight);
    std::size_t i = 0;
    for (std::size_t k = 0; k < particles_.size(); ++k) {
        const double pointer = (offset + static_cast<double>(k)) / n;
        while (pointer > cumulative && i + 1 < particles_.size())
            cumulative += std::exp(particles_[++i].log_weight);
        drawn.push_back(particles_[i]);
        drawn.back().log_weight = -std::log(n);
    }
    particles_ = std::move(drawn);
    ++counters_.resamples;
}

SurfaceParticleEstimate SurfaceParticleFilter::estimate() const {
    const Vector3d mean_m = weighted_mean_position(particles_);
    SurfaceParticleEstimate e;
    e.stamp_s = stamp_s();
    e.T_world_body = settle(mean_m, mean_heading(particles_, surface_->project(mean_m).normal));
    const std::vector<double> yaw_rad = yaw_deviations(particles_, e.T_world_body.linear());
    // The vector mean of the headings is not exactly the deviations' mean: spread about theirs.
    double mean_yaw_rad = 0.0;
    for (std::size_t i = 0; i < particles_.size(); ++i)
        mean_yaw_rad += std::exp(particles_[i].log_weight) * yaw_rad[i];
    for (std::size_t i = 0; i < particles_.size(); ++i) {
        const double w = std::exp(particles_[i].log_weight);
        const Vector3d dp = particles_[i].p_world_m - mean_m;
        const double dyaw = yaw_rad[i] - mean_yaw_rad;
        e.position_covariance_m2 += w * dp * dp.transpose();
        e.position_yaw_covariance += w * dyaw * dp;
        e.yaw_variance_rad2 += w * dyaw * dyaw;
    }
    e.effective_sample_size = effective_sample_size();
    return e;
}

}  // namespace scantling::localization
