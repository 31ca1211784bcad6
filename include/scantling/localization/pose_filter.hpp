#pragma once
/// @file
/// Fusion of a drifting odometry (VIO) with absolute pose measurements (registrations against
/// the map), SPEC §7: an EKF or a UKF (FilterKind), both over the same state and models.
///
/// State: the drift of the odometry, E = T_world_odom, so that the fused body pose is
/// T_world_body = E · T_odom_body(VIO). A VIO is gravity-aligned and drifts slowly with the
/// distance travelled, so E is a random walk driven by that distance: translation per axis
/// (position_random_walk), yaw about the body's current position (a yaw error rotates every
/// later displacement, so it acts about where the body is, not about the world origin) and a
/// small tilt. Its error is a left twist ξ = (ρ, ω) in the world frame (core/se3.hpp order and
/// the convention of registration/result.hpp): E_true = exp(ξ) · E. Because
/// exp(ξ) · E · T_odom_body = exp(ξ) · T_world_body, a measured body pose observes ξ directly.
///
/// Why this state and not (p, R, v) driven by VIO increments: the VIO's per-sample jitter is
/// white, not a random walk. Differencing consecutive VIO poses would accumulate it as drift
/// (2σ² per sample, ~0.15 m after 100 s at 30 Hz for σ = 2 mm) and make the covariance wrong;
/// here it enters once, as noise on each output and each measurement.
///
/// The EKF linearises the composition exp(n) · exp(ξ) of measurement noise n and state error;
/// the UKF propagates sigma points of (ξ, n) through it exactly (augmented, 12-D). They agree
/// when both are small and differ when the state is uncertain in rotation (after a global
/// re-localisation).
///
/// Delayed measurements: a registration finishes after its frame was captured. Every VIO sample
/// adds a history entry (the prediction to it and the measurements applied there). A measurement
/// is applied at the last entry at or before its capture time, with the VIO pose interpolated
/// to that time, and every later entry is replayed; so a late measurement gives exactly the
/// estimate an on-time one gives. A measurement newer than the last VIO sample waits for the
/// VIO to pass its stamp; one older than the history (history_s) is refused.
///
/// Odometry faults: an invalid VIO sample (dropout) adds time-based noise instead of
/// distance-based; a jump (speed above max_odometry_speed_mps) is absorbed into E so that the
/// body pose holds, with jump noise added. Both are reported (OdometryStatus).
///
/// Thread-safety: not thread-safe; one filter per estimator. Deterministic.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <deque>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <scantling/core/se3.hpp>
#include <scantling/io/recording.hpp>

namespace scantling::localization {

enum class FilterKind { kEkf, kUkf };
std::string_view to_string(FilterKind kind);
/// "ekf" or "ukf"; ConfigError naming `field` otherwise.
FilterKind filter_kind_from_string(std::string_view name, std::string_view field = "filter.kind");

/// An absolute pose of the body in the map (world) frame, e.g. a registration.
struct AbsolutePose {
    double stamp_s = 0.0;  ///< capture time of the data it came from
    Eigen::Isometry3d T_world_body = Eigen::Isometry3d::Identity();
    /// Left twist (ρ, ω) in the world frame about its origin: the true pose is
    /// exp(ε) · T_world_body with ε ~ N(0, covariance) (registration/result.hpp).
    Matrix6d covariance = Matrix6d::Identity();
};

/// The fused estimate at one VIO sample.
struct FusedState {
    double stamp_s = 0.0;
    Eigen::Isometry3d T_world_body = Eigen::Isometry3d::Identity();
    Eigen::Vector3d v_world_mps = Eigen::Vector3d::Zero();
    /// Covariance of (δp, δθ) at the body: p_true = p + δp, R_true = exp(δθ) · R, both in the
    /// world frame, metres and radians (position_attitude_covariance of the twist covariance).
    Matrix6d covariance = Matrix6d::Zero();
    Eigen::Matrix3d velocity_covariance = Eigen::Matrix3d::Zero();  ///< of v_world_mps
};

/// What the last VIO sample did to the prediction.
enum class OdometryStatus { kOk, kFirst, kDropout, kJump, kOutOfOrder };
std::string_view to_string(OdometryStatus status);

struct PoseFilterConfig {
    FilterKind kind = FilterKind::kEkf;
    /// Random walk of the odometry's drift per axis, m per √m travelled. 0.02: a T265-class
    /// VIO drifts ~1 % of the distance (the simulator's default).
    double position_random_walk_m_per_sqrt_m = 0.02;
    double yaw_random_walk_rad_per_sqrt_m = 0.003;  ///< ≈ 0.17° after 1 m
    /// Roll and pitch barely drift (the VIO sees gravity); > 0 keeps the covariance regular.
    double tilt_random_walk_rad_per_sqrt_m = 3e-4;
    /// Drift while hovering (per √s), so the covariance grows slowly without motion too.
    double position_random_walk_m_per_sqrt_s = 1e-3;
    double yaw_random_walk_rad_per_sqrt_s = 1e-4;
    /// The VIO's feature quality q in [0, 1] scales the distance random walks by
    /// 1 + gain · (1 − q) (a VIO reports its tracking confidence; 4 = the simulator's default).
    double poor_features_drift_gain = 4.0;
    /// White noise of each VIO pose (not accumulated): per axis, metres and radians.
    double position_jitter_m = 0.002;
    double attitude_jitter_rad = 0.002;
    double velocity_sigma_mps = 0.01;  ///< white noise of the VIO's body velocity, per axis
    /// While the VIO is invalid its pose is not trusted: random walk per √s.
    double dropout_position_random_walk_m_per_sqrt_s = 0.1;
    double dropout_yaw_random_walk_rad_per_sqrt_s = 0.02;
    /// A VIO step faster than this is a jump (relocalised or reset VIO), m/s, > 0.
    double max_odometry_speed_mps = 3.0;
    /// Noise added at a jump (the motion across it is unknown), per axis, m and rad.
    double jump_position_sigma_m = 0.3;
    double jump_yaw_sigma_rad = 0.1;
    /// How far back measurements may be applied, seconds, > 0 (the slowest registration).
    double history_s = 10.0;
    /// UKF spread (scaled unscented transform): α, β, κ over the 12-D augmented state.
    double ukf_alpha = 1.0;
    double ukf_beta = 2.0;
    double ukf_kappa = 0.0;

    /// Throws ConfigError naming the field ("filter.history_s = 0, expected > 0").
    void validate(std::string_view prefix = "filter") const;
};

/// Innovation of a measurement against the prediction at its capture time.
struct Innovation {
    Vector6d residual = Vector6d::Zero();    ///< left twist from prediction to measurement
    Matrix6d covariance = Matrix6d::Zero();  ///< S = prediction + measurement + jitter
    double mahalanobis_squared = 0.0;
};

/// Why a measurement was not applied (empty when it was).
enum class MeasurementStatus { kApplied, kPending, kTooOld, kNotInitialized, kInvalid };
std::string_view to_string(MeasurementStatus status);

class PoseFilter {
  public:
    /// Validates the config (ConfigError).
    explicit PoseFilter(PoseFilterConfig config = {});

    /// Adds a VIO sample (time order; an older or equal stamp is refused: kOutOfOrder, the
    /// sample is ignored). Applies the measurements that were waiting for it.
    OdometryStatus add_odometry(const io::VioRecord& sample);

    /// Starts (or restarts, after a re-localisation) the estimate from an absolute pose: E is set
    /// so that the body is at `pose` at its stamp, covariance = pose + jitter. Later entries are
    /// replayed. kPending when the VIO has not reached the stamp yet (applied when it has).
    MeasurementStatus initialize(const AbsolutePose& pose);

    /// Innovation of `pose` against the state at its capture time (nullopt when it cannot be
    /// evaluated yet: not initialised, too old, or newer than the last VIO sample).
    std::optional<Innovation> innovation(const AbsolutePose& pose) const;

    /// Applies `pose` at its capture time (see the file comment).
    MeasurementStatus update(const AbsolutePose& pose);

    bool initialized() const;
    /// The state at the last VIO sample (nullopt before initialisation or any VIO).
    std::optional<FusedState> state() const;
    /// The predicted body pose at `stamp_s` (interpolated between VIO samples; at the last one
    /// when later), with its twist covariance; nullopt when not initialised or too old.
    std::optional<AbsolutePose> predict(double stamp_s) const;
    /// The VIO pose interpolated at `stamp_s` (nullopt outside the history).
    std::optional<Eigen::Isometry3d> odometry_at(double stamp_s) const;
    const PoseFilterConfig& config() const { return config_; }

  private:
    struct Estimate {
        Eigen::Isometry3d T_world_odom = Eigen::Isometry3d::Identity();
        Matrix6d covariance = Matrix6d::Zero();  ///< of the left twist of T_world_odom
    };
    struct Entry {
        io::VioRecord vio;
        OdometryStatus status = OdometryStatus::kOk;
        std::optional<Estimate> prior;               ///< after the prediction to this sample
        std::optional<Estimate> posterior;           ///< after the measurements applied here
        std::optional<AbsolutePose> initialization;  ///< a (re)start applied here
        std::vector<AbsolutePose> measurements;      ///< applied here, in stamp order
    };

    /// Index of the last entry with stamp <= t (nullopt when t is before the history).
    std::optional<std::size_t> entry_at(double stamp_s) const;
    Eigen::Isometry3d odometry_pose(std::size_t i, double stamp_s) const;
    /// Recomputes entries from i on (their priors from i − 1's posterior).
    void replay_from(std::size_t i);
    void apply_entry(std::size_t i);
    Estimate predict_step(const Estimate& previous, const Entry& from, const Entry& to) const;
    Estimate measurement_update(const Estimate& prior, const Eigen::Isometry3d& T_odom_body,
                                const AbsolutePose& pose) const;
    Innovation innovation_of(const Estimate& prior, const Eigen::Isometry3d& T_odom_body,
                             const AbsolutePose& pose) const;
    Matrix6d jitter_covariance(const Eigen::Isometry3d& T_world_body) const;
    MeasurementStatus insert(std::size_t i, const AbsolutePose& pose, bool initialization);
    void apply_pending();
    void prune();

    PoseFilterConfig config_;
    std::deque<Entry> history_;
    std::vector<std::pair<AbsolutePose, bool>> pending_;  ///< (pose, is initialisation)
};

/// (δp, δθ) covariance at the body from the left-twist covariance of T_world_body.
Matrix6d position_attitude_covariance(const Matrix6d& twist_covariance,
                                      const Eigen::Vector3d& p_world_body);
/// The inverse map: left-twist covariance from a (δp, δθ) covariance at p_world_body.
Matrix6d twist_covariance(const Matrix6d& position_attitude_covariance,
                          const Eigen::Vector3d& p_world_body);
/// Largest position standard deviation of a left-twist covariance at p_world_body, metres.
double largest_position_sigma_m(const Matrix6d& twist_covariance,
                                const Eigen::Vector3d& p_world_body);
/// (δp, δθ) of the estimate against the truth, as FusedState::covariance defines them.
Vector6d position_attitude_error(const Eigen::Isometry3d& T_world_body_true,
                                 const Eigen::Isometry3d& T_world_body_estimate);

}  // namespace scantling::localization
