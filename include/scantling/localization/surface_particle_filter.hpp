#pragma once
/// @file
/// The magnetic crawler's localisation, SPEC §6: a particle filter on the surface the crawler
/// drives on, fusing wheel odometry, the gyro's turn rate and UWB ranges (the "PF pose" and its
/// covariance).
///
/// Particle: a pose on the surface, R_world_body with z = the surface normal and x = the
/// heading (the crawler's body frame, sim/crawler_dynamics.hpp), plus its own slip state
/// (longitudinal, lateral and turn-rate slip fractions) and a log-weight.
///
/// Prediction (one per wheel record, over the time since the previous one): the wheels' mean
/// speed over the interval (trapezoid of the two records) is scaled by (1 − s) with s the
/// particle's longitudinal slip, the body also moves sideways by |v| · s_lat, and turns by the
/// gyro's integrated body-z rate (when IMU samples arrived in the interval; else by the wheels'
/// turn rate · (1 + s_yaw), noisier) plus a heading random walk. Then, exactly as the crawler,
/// the position moves along the midpoint heading, is projected onto the surface, and the heading
/// is transported (its normal component removed, renormalised).
/// Why slip states rather than white noise per step: the crawler's slip is correlated over about
/// a second (an Ornstein–Uhlenbeck process with mean slip_mean); white noise per wheel record
/// would average out at 50 Hz and make the cloud far too narrow, and its spread would depend on
/// the wheel rate. Each particle's slip is an OU process with the same mean, σ and correlation
/// time, so the spread grows as the true error does whatever the record rate, and the UWB
/// ranges select the particles whose slip matches the crawler's.
/// Note: slip_mean is what the wheels over-read on average. The scenario simulator's wheel
/// odometry (sim/wheel_odometry.hpp) measures the body's already slipped speed: feed such
/// records with slip_mean = 0.
///
/// UWB (robust likelihood): the tag at p + R · p_body_uwb_tag_m ranges to an anchor; the range
/// error e = range − distance is distributed as (1 − p_nlos − p_out) N(0, σ²) + p_nlos · (a
/// positive excess uniform on [0, nlos_max_excess_m], convolved with N(0, σ²)) + p_out · U(0,
/// uwb_max_range_m) (a gross outlier). A non-line-of-sight range is long, never short, so the
/// mixture lets a long range move the cloud little while a short one still counts. Weights are
/// kept as logarithms and normalised by log-sum-exp; when every likelihood is 0 the weights
/// are reset to uniform (counted). Systematic resampling (one seeded uniform draw) when the
/// effective sample size falls below resample_threshold_fraction · N.
/// The range is applied to the particles at the filter time (the last wheel record): the error
/// is ≤ speed × the stamp difference (3 mm at 0.15 m/s and 50 Hz wheels).
///
/// Estimate: the weighted mean position projected onto the surface, the heading the weighted
/// vector (circular) mean of the particles' headings in that point's tangent plane, the weighted
/// spread of position (about the unprojected weighted mean; ~0 along the normal since every
/// particle is on the surface) and of the yaw deviations from the mean heading, and their cross
/// term, so (tangent position, yaw) has a full 3 × 3 covariance.
///
/// Inputs in stamp order. Contract violations (a non-finite stamp or value in a record flagged
/// valid) throw InputError before anything changes; an invalid record, an unknown anchor or an
/// out-of-order record is refused (a status and a counter) and changes nothing.
///
/// Cost: O(N) per record, one SurfaceProjector::project per particle and wheel record.
/// Thread-safety: not thread-safe; one filter per crawler. Single-threaded by design (500
/// particles are cheap). @note Deterministic: the same config, surface, start, seed and inputs
/// give bit-identical estimates (core/random.hpp).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string_view>
#include <vector>

#include <scantling/core/random.hpp>
#include <scantling/core/surface_projector.hpp>
#include <scantling/io/recording.hpp>
#include <scantling/localization/local_ekf.hpp>

namespace scantling::localization {

struct SurfaceParticleFilterConfig {
    std::size_t num_particles = 500;         ///< N, >= 1
    double initial_position_sigma_m = 0.05;  ///< per tangent axis, around the start pose
    double initial_yaw_sigma_rad = 0.05;     ///< about the start normal
    /// Longitudinal slip s: the body moves (1 − s) × what the wheels report. Mean, the
    /// stationary 1σ of each particle's slip (covers the slip's variation and the wheel-radius
    /// error) and its correlation time. 0.02 = the simulated crawler's mean slip.
    double slip_mean = 0.02;
    double slip_sigma = 0.05;
    double slip_correlation_time_s = 1.0;
    double lateral_slip_sigma = 0.02;  ///< stationary 1σ of lateral speed / |forward speed|
    /// Stationary 1σ of the relative turn-rate error when turning by the wheels (no gyro):
    /// track slip (the crawler's 0.03) and the differential's noise.
    double wheel_yaw_slip_sigma = 0.1;
    /// Heading random walk, rad per √s: with the gyro (its noise and an uncalibrated bias of a
    /// few mrad/s), and added to the wheel turn when there is no gyro.
    double gyro_yaw_random_walk_rad_per_sqrt_s = 0.01;
    double wheel_yaw_random_walk_rad_per_sqrt_s = 0.05;
    /// IMU mount: the gyro's rate is turned into the body before taking its z (normal) rate.
    Eigen::Matrix3d R_body_imu = Eigen::Matrix3d::Identity();
    /// UWB anchors: id → position in the world, m.
    std::map<int, Eigen::Vector3d> uwb_anchors_world_m;
    Eigen::Vector3d p_body_uwb_tag_m = Eigen::Vector3d::Zero();  ///< tag lever arm, body frame
    double uwb_range_sigma_m = 0.05;     ///< DW1000-class line-of-sight 1σ, > 0
    double nlos_probability = 0.1;       ///< p_nlos: share of long NLOS ranges, [0, 1)
    double nlos_max_excess_m = 3.0;      ///< NLOS excess path uniform on [0, this], > 0
    double outlier_probability = 0.005;  ///< p_out: a reading anywhere in [0, max range], [0, 1)
    double uwb_max_range_m = 50.0;       ///< the outliers' range, > 0
    /// Resample when the effective sample size < this × N, in [0, 1] (0: never, 1: always).
    double resample_threshold_fraction = 0.5;
    /// A wheel interval longer than this is a gap (predicted all the same, counted), s, > 0.
    double max_wheel_gap_s = 0.5;

    /// Throws ConfigError naming the field ("particle_filter.uwb_range_sigma_m = 0, ...").
    void validate(std::string_view prefix = "particle_filter") const;
};

/// One hypothesis of the crawler's pose.
struct SurfaceParticle {
    Eigen::Vector3d p_world_m = Eigen::Vector3d::Zero();         ///< on the surface
    Eigen::Matrix3d R_world_body = Eigen::Matrix3d::Identity();  ///< z = normal, x = heading
    /// (longitudinal, lateral, turn-rate) slip fractions, each an OU process.
    Eigen::Vector3d slip = Eigen::Vector3d::Zero();
    double log_weight = 0.0;  ///< normalised: the weights' log-sum-exp is 0
};

struct SurfaceParticleEstimate {
    double stamp_s = 0.0;  ///< of the last wheel record (0 before the first)
    /// On the surface: z = the normal there, x = the mean heading.
    Eigen::Isometry3d T_world_body = Eigen::Isometry3d::Identity();
    Eigen::Matrix3d position_covariance_m2 = Eigen::Matrix3d::Zero();  ///< world frame
    double yaw_variance_rad2 = 0.0;  ///< of the heading about the normal
    /// Cross-covariance of position (world) and yaw, m·rad.
    Eigen::Vector3d position_yaw_covariance = Eigen::Vector3d::Zero();
    double effective_sample_size = 0.0;  ///< 1 / Σ w², in [1, N]
};

struct SurfaceParticleFilterCounters {
    std::size_t predictions = 0;  ///< wheel intervals predicted
    std::size_t gyro_turns = 0;   ///< of which turned by the gyro
    std::size_t wheel_gaps = 0;   ///< intervals longer than max_wheel_gap_s
    std::size_t wheel_out_of_order = 0;
    std::size_t imu_samples = 0;
    std::size_t imu_out_of_order = 0;
    std::size_t uwb_applied = 0;
    std::size_t uwb_refused = 0;  ///< invalid record, unknown anchor, tag on the anchor
    std::size_t resamples = 0;
    std::size_t weight_resets = 0;  ///< every likelihood was 0: weights made uniform
};

class SurfaceParticleFilter {
  public:
    /// Draws the particles around T_world_body_start projected onto `surface` (not owned, must
    /// outlive the filter). ConfigError on a bad config, InputError on a non-finite start.
    SurfaceParticleFilter(SurfaceParticleFilterConfig config, const SurfaceProjector& surface,
                          const Eigen::Isometry3d& T_world_body_start, std::uint64_t seed);

    /// Integrates the body-z rate since the previous sample (the sample's rate held over the
    /// interval ending at its stamp). InputError when not finite; an older stamp: kOutOfOrder.
    ImuPredictionStatus add_imu(const io::ImuRecord& sample);

    /// Predicts every particle to the record's stamp. The first record sets the filter time
    /// (kFirst, no motion; gyro turns before it are dropped). InputError when not finite; a
    /// stamp at or before the previous one: kOutOfOrder, ignored.
    ImuPredictionStatus add_wheel_odometry(const io::WheelOdometryRecord& wheel);

    /// Weights the particles by the range's robust likelihood, resamples when degenerate.
    /// kInvalid for a record flagged invalid, kUnknownAnchor for an id not in the config;
    /// InputError for a valid record with a non-finite stamp or range (as GlobalEkf). The
    /// result's χ² is the estimate's normalised squared range residual (1 DoF).
    UpdateResult update_uwb(const io::UwbRecord& range);

    /// O(N): the weighted mean pose, its covariance and the effective sample size.
    SurfaceParticleEstimate estimate() const;

    double stamp_s() const { return stamp_s_.value_or(0.0); }
    const std::vector<SurfaceParticle>& particles() const { return particles_; }
    const SurfaceParticleFilterCounters& counters() const { return counters_; }
    const SurfaceParticleFilterConfig& config() const { return config_; }

  private:
    void initialize_particles(const Eigen::Isometry3d& T_world_body_start);
    /// The heading change over the interval ending at `stamp_s`; nullopt without IMU samples.
    std::optional<double> take_gyro_turn(double stamp_s);
    void predict(const io::WheelOdometryRecord& wheel, double dt_s);
    void move_particle(SurfaceParticle& particle, double distance_m,
                       const std::optional<double>& gyro_turn_rad, double wheel_turn_rad,
                       double dt_s);
    /// Adds the log-likelihoods and normalises (log-sum-exp); false when all were −∞.
    bool reweight(const std::vector<double>& log_likelihoods);
    /// Uniform weights; returns false (reweight's "all were −∞").
    bool reset_weights();
    void resample_if_degenerate();
    double effective_sample_size() const;
    /// Onto the surface with body z = normal and x = `heading` transported (the crawler's).
    Eigen::Isometry3d settle(const Eigen::Vector3d& p_world,
                             const Eigen::Vector3d& heading_world) const;

    SurfaceParticleFilterConfig config_;
    const SurfaceProjector* surface_;
    Rng rng_;
    std::vector<SurfaceParticle> particles_;
    std::optional<io::WheelOdometryRecord> last_wheel_;
    std::optional<double> stamp_s_;
    // Gyro integration: the body-z turn since the last prediction, integrated up to gyro_stamp_s_.
    double gyro_turn_rad_ = 0.0;
    std::optional<double> gyro_stamp_s_;
    std::optional<double> last_imu_stamp_s_;
    double held_rate_radps_ = 0.0;
    bool imu_in_interval_ = false;
    SurfaceParticleFilterCounters counters_;
};

/// The robust log-likelihood of a UWB range error e = measured − predicted (the file comment's
/// mixture). Finite for finite e when the Gaussian share 1 − p_nlos − p_out is > 0.
double uwb_range_log_likelihood(double error_m, const SurfaceParticleFilterConfig& config);

}  // namespace scantling::localization
