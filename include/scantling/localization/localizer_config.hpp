#pragma once
/// @file
/// Settings of the Localizer (localizer.hpp): defaults are SPEC §7's values where it gives them;
/// each field's comment says where the others come from. Read from YAML by
/// load_localizer_config; describe_localizer_config prints every key with its value.

#include <string>
#include <string_view>

#include <scantling/localization/attitude_estimator.hpp>
#include <scantling/localization/column_registration.hpp>
#include <scantling/localization/correlative_search.hpp>
#include <scantling/localization/defect_lifting.hpp>
#include <scantling/localization/landmark_correction.hpp>
#include <scantling/localization/localization_map.hpp>
#include <scantling/localization/pose_filter.hpp>
#include <scantling/localization/velocity_odometry.hpp>
#include <scantling/registration/feature_matching.hpp>
#include <scantling/registration/icp.hpp>
#include <scantling/registration/quality.hpp>
#include <scantling/registration/robust_registration.hpp>
#include <scantling/registration/stein_icp.hpp>

namespace scantling::localization {

/// Local registration from the prediction: ICP, Stein-ICP, the structural landmarks seen
/// (art. B: web frame × longitudinal intersections, landmark_correction.hpp), or the column's
/// 3-DoF registration on its detected structure (art. F, column_registration.hpp).
enum class TrackingMethod { kIcp, kStein, kLandmarks, kColumn };
/// How a frame is placed in the map without a prior: correlative search (correlative_search.hpp)
/// or FPFH descriptors with the robust solver (the sources' pipeline; fails in the mock-up).
enum class RelocalizationMethod { kCorrelative, kFpfh };
/// What the VIO's samples give the filter: their pose, or only their body velocity, integrated
/// with the IMU's roll and pitch and the VIO's yaw steps (velocity_odometry.hpp).
enum class OdometryInput { kPose, kVelocity };
std::string_view to_string(RelocalizationMethod method);
std::string_view to_string(TrackingMethod method);
std::string_view to_string(OdometryInput input);
/// "pose" or "velocity"; ConfigError naming `field` otherwise.
OdometryInput odometry_input_from_string(std::string_view name,
                                         std::string_view field = "odometry_input");
TrackingMethod tracking_method_from_string(std::string_view name,
                                           std::string_view field = "tracking.method");

struct TrackingConfig {
    TrackingMethod method = TrackingMethod::kIcp;
    /// Point-to-plane with the front-face search and the clustered covariance (consistent on
    /// tank scans, docs/results.md); the correspondence distance is set per frame (below).
    registration::IcpConfig icp;
    registration::SteinIcpConfig stein;  ///< kStein: seeded at the prediction
    LandmarkCorrectionConfig landmarks;  ///< kLandmarks (needs the structural map)
    ColumnRegistrationConfig column;     ///< kColumn (a distillation column's map)
    /// The correspondence distance: this many predicted position σ plus one voxel, clamped to
    /// [min, max], metres. A tight gate keeps the wrong bay's walls out when the estimate is good.
    double correspondence_sigmas = 3.0;
    double min_correspondence_distance_m = 0.1;
    double max_correspondence_distance_m = 0.5;

    void validate(std::string_view prefix = "tracking") const;
};

struct RelocalizationConfig {
    RelocalizationMethod method = RelocalizationMethod::kCorrelative;
    CorrelativeSearchConfig correlative;
    registration::MatchConfig match;  ///< kFpfh: mutual nearest descriptors
    /// The gravity-aligned 4-DoF solver (x, y, z, yaw): roll and pitch come from the IMU, so
    /// wrong matches have two fewer ways to look consistent. β = one voxel (0.05 m).
    registration::RobustRegistrationConfig robust = [] {
        registration::RobustRegistrationConfig c;
        c.rotation = registration::RobustRotation::kYawOnly;
        return c;
    }();
    /// ICP from each candidate; must cover its error (half a search step and 3° of yaw). Ten
    /// iterations bring a right candidate within the polish's gate; wrong ones stop there.
    registration::IcpConfig refine = [] {
        registration::IcpConfig c;
        c.max_correspondence_distance_m = 0.3;
        c.max_iterations = 10;
        return c;
    }();
    /// Voxel of the scan for that first ICP pass, metres, > 0 (~1/10 of the points at 0.2).
    double refine_voxel_m = 0.2;
    /// A second ICP pass from the refined pose with the tracking's tight gate, whose
    /// covariance the filter starts from.
    double polish_correspondence_distance_m = 0.1;
    int normal_neighbors = 30;  ///< normals of the frame, >= 3 (as the map's)
    /// Two candidates more than ambiguity_distance_m (or ambiguity_yaw_rad) apart whose overlaps
    /// differ by less than this are ambiguous, in [0, 1).
    double ambiguity_overlap_margin = 0.05;
    double ambiguity_distance_m = 0.5;
    double ambiguity_yaw_rad = 0.35;
    /// While a prior exists the search box is its position ± this many σ, at least
    /// min_prior_radius_m (metres): the correlative search's step and the VIO's drift.
    double prior_sigmas = 3.0;
    double min_prior_radius_m = 0.5;
    /// Failed re-localisations near the prior or restricted to the current compartment before
    /// every compartment is searched without a prior, >= 1.
    int failures_before_global = 5;

    void validate(std::string_view prefix = "relocalization") const;
};

struct GateConfig {
    registration::AttitudeGateConfig attitude;  ///< 5° roll/pitch against the IMU
    registration::SpeedGateConfig speed;        ///< 0.3 m/s (SPEC §7 motion filter)
    registration::OverlapGateConfig overlap;    ///< >= 75 % within one voxel (SPEC §7)
    /// χ²(6) quantile of the innovation against the prediction, > 0: 22.46 = 99.9 %, so a
    /// consistent filter rejects 1 good registration in 1000.
    double mahalanobis_threshold = 22.458;

    void validate(std::string_view prefix = "gates") const;
};

struct LocalizerConfig {
    LocalizationMapConfig map;  ///< how the map is prepared (used by whoever builds it)
    PoseFilterConfig filter;
    AttitudeEstimatorConfig attitude;
    TrackingConfig tracking;
    RelocalizationConfig relocalization;
    GateConfig gates;
    /// How the camera's defect sightings are lifted into the map (`scantling localize`).
    DefectLiftingConfig defects;
    /// The VIO's pose (default), or its velocity (and yaw steps) with the IMU's roll and pitch:
    /// for a VIO that reports only velocity, or whose position jumps at its resets.
    OdometryInput odometry_input = OdometryInput::kPose;
    VelocityOdometryConfig velocity_odometry;
    /// Shortest time between registration attempts, seconds, >= 0; 0 = every frame. The
    /// sources registered at 0.1 Hz (art. C) to 0.5 Hz (art. E) for lack of speed.
    double registration_period_s = 0.0;
    /// Consecutive rejected tracking frames after which tracking counts as lost, >= 1.
    int max_rejections = 5;
    /// A VIO dropout this long loses tracking (the VIO pose cannot be trusted), seconds, > 0.
    double dropout_relocalization_s = 0.5;
    /// Fewest points of a frame after downsampling to attempt a registration, >= 10.
    std::size_t min_points = 100;
    /// Every due frame is registered globally (no tracking) and, once the filter runs, fused as
    /// an update after the attitude, overlap and speed gates: the sources' pipeline (art. C/D),
    /// for comparison. Off: track from the prediction, re-localise only when lost.
    bool global_every_frame = false;
    /// The compartment a robot without a known pose starts in (-1: unknown, search all).
    int start_compartment = -1;
    ParallelConfig parallel;  ///< threads for every stage (overrides the sub-configs')

    void validate(std::string_view prefix = "localizer") const;
    /// Sets num_threads in every sub-config.
    void set_num_threads(int num_threads);
};

/// Reads a YAML file (every key optional; unknown keys are errors naming file and line) over
/// the defaults, then validates.
LocalizerConfig load_localizer_config(const std::string& path);
/// Every key with its value and documentation, as YAML.
std::string describe_localizer_config(const LocalizerConfig& config);

}  // namespace scantling::localization
