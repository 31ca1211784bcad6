#include "scantling/localization/localizer_config.hpp"

#include <fmt/format.h>

#include <cmath>

#include <scantling/core/error.hpp>
#include <scantling/io/config_schema.hpp>

#include "detail/config_checks.hpp"

namespace scantling::localization {
namespace {

using io::ConfigSchema;
using io::kNonNegative;
using io::kPositive;
using io::kUnitInterval;

ConfigSchema<LikelihoodFieldConfig> likelihood_schema() {
    using C = LikelihoodFieldConfig;
    ConfigSchema<C> s;
    s.field("resolution_m", &C::resolution_m, "cell edge, m", kPositive)
        .field("sigma_m", &C::sigma_m, "score width, m", kPositive)
        .field("margin_m", &C::margin_m, "grid beyond the map, m", kNonNegative)
        .field("max_cells", &C::max_cells, "refuse larger grids", io::Range{.min = 1});
    return s;
}

ConfigSchema<LocalizationMapConfig> map_schema() {
    using C = LocalizationMapConfig;
    ConfigSchema<registration::FpfhConfig> fpfh;
    fpfh.field("radius_m", &registration::FpfhConfig::radius_m, "FPFH neighbourhood, m", kPositive)
        .field("max_neighbors", &registration::FpfhConfig::max_neighbors,
               "most neighbours per point", io::Range{.min = 2});
    ConfigSchema<C> s;
    s.field("voxel_size_m", &C::voxel_size_m, "map and frame voxels, m", kPositive)
        .field("normal_neighbors", &C::normal_neighbors, "k for normals of a map without them",
               io::Range{.min = 3})
        .section("likelihood", &C::likelihood, likelihood_schema(),
                 "likelihood field of the correlative re-localisation")
        .field("compartment_margin_m", &C::compartment_margin_m,
               "a compartment's region: its box grown by this, m", kNonNegative)
        .section("fpfh", &C::fpfh, fpfh, "descriptors for re-localisation");
    return s;
}

ConfigSchema<PoseFilterConfig> filter_schema() {
    using C = PoseFilterConfig;
    ConfigSchema<C> s;
    s.enum_field("kind", &C::kind, {{"ekf", FilterKind::kEkf}, {"ukf", FilterKind::kUkf}},
                 "fusion filter")
        .field("position_random_walk_m_per_sqrt_m", &C::position_random_walk_m_per_sqrt_m,
               "VIO drift per axis, m/sqrt(m)", kNonNegative)
        .field("yaw_random_walk_rad_per_sqrt_m", &C::yaw_random_walk_rad_per_sqrt_m,
               "VIO yaw drift, rad/sqrt(m)", kNonNegative)
        .field("tilt_random_walk_rad_per_sqrt_m", &C::tilt_random_walk_rad_per_sqrt_m,
               "VIO roll/pitch drift, rad/sqrt(m)", kPositive)
        .field("position_random_walk_m_per_sqrt_s", &C::position_random_walk_m_per_sqrt_s,
               "drift without motion, m/sqrt(s)", kNonNegative)
        .field("yaw_random_walk_rad_per_sqrt_s", &C::yaw_random_walk_rad_per_sqrt_s,
               "yaw drift without motion, rad/sqrt(s)", kNonNegative)
        .field("poor_features_drift_gain", &C::poor_features_drift_gain,
               "drift x (1 + gain (1 - feature quality))", kNonNegative)
        .field("position_jitter_m", &C::position_jitter_m, "white noise per VIO pose, m", kPositive)
        .field("attitude_jitter_rad", &C::attitude_jitter_rad, "white noise per VIO attitude, rad",
               kPositive)
        .field("velocity_sigma_mps", &C::velocity_sigma_mps, "VIO velocity noise, m/s",
               kNonNegative)
        .field("dropout_position_random_walk_m_per_sqrt_s",
               &C::dropout_position_random_walk_m_per_sqrt_s, "while the VIO is invalid, m/sqrt(s)",
               kPositive)
        .field("dropout_yaw_random_walk_rad_per_sqrt_s", &C::dropout_yaw_random_walk_rad_per_sqrt_s,
               "while the VIO is invalid, rad/sqrt(s)", kPositive)
        .field("max_odometry_speed_mps", &C::max_odometry_speed_mps,
               "faster VIO steps are jumps, m/s", kPositive)
        .field("jump_position_sigma_m", &C::jump_position_sigma_m, "noise added at a jump, m",
               kPositive)
        .field("jump_yaw_sigma_rad", &C::jump_yaw_sigma_rad, "noise added at a jump, rad",
               kPositive)
        .field("history_s", &C::history_s, "how late a measurement may arrive, s", kPositive)
        .field("ukf_alpha", &C::ukf_alpha, "UKF spread", kPositive)
        .field("ukf_beta", &C::ukf_beta, "UKF prior knowledge (2 = Gaussian)", kNonNegative)
        .field("ukf_kappa", &C::ukf_kappa, "UKF secondary scaling", kNonNegative);
    return s;
}

ConfigSchema<AttitudeEstimatorConfig> attitude_schema() {
    using C = AttitudeEstimatorConfig;
    ConfigSchema<C> s;
    s.field("accel_gain_per_s", &C::accel_gain_per_s, "accelerometer correction rate, 1/s",
            kPositive)
        .field("max_accel_deviation_mps2", &C::max_accel_deviation_mps2,
               "no correction when | |f| - g | exceeds this, m/s^2", kPositive)
        .field("gravity_mps2", &C::gravity_mps2, "m/s^2", kPositive)
        .field("max_gap_s", &C::max_gap_s, "longer gaps restart the filter, s", kPositive)
        .field("history_s", &C::history_s, "s", kPositive);
    return s;
}

ConfigSchema<perception::FrameLandmarkConfig> detector_schema() {
    using C = perception::FrameLandmarkConfig;
    ConfigSchema<perception::PlaneRansacConfig> planes;
    using P = perception::PlaneRansacConfig;
    planes.field("distance_threshold_m", &P::distance_threshold_m, "inlier band, m", kPositive)
        .field("normal_threshold_deg", &P::normal_threshold_deg, "inlier normal agreement, deg",
               io::Range{.min = 0.0, .max = 90.0})
        .field("min_inliers", &P::min_inliers, "smallest plane", io::Range{.min = 3})
        .field("max_planes", &P::max_planes, "", io::Range{.min = 1})
        .field("iterations", &P::iterations, "hypotheses per plane", io::Range{.min = 1})
        .field("seed", &P::seed, "");
    ConfigSchema<C> s;
    s.section("planes", &C::planes, planes, "plane search")
        .field("axis_tolerance_deg", &C::axis_tolerance_deg, "frame / plating classification, deg",
               io::Range{.min = 0.0, .max = 45.0})
        .field("min_stiffener_height_m", &C::min_stiffener_height_m, "m", kPositive)
        .field("max_stiffener_height_m", &C::max_stiffener_height_m, "m", kPositive)
        .field("min_plate_inliers", &C::min_plate_inliers, "smallest plating plane",
               io::Range{.min = 3})
        .field("stiffener_gap_m", &C::stiffener_gap_m, "gap between two stiffeners, m", kPositive)
        .field("min_line_length_m", &C::min_line_length_m, "seen length, m", kPositive)
        .field("min_line_points", &C::min_line_points, "", io::Range{.min = 3})
        .field("height_quantile", &C::height_quantile, "top edge among the heights", kUnitInterval)
        .field("max_gap_to_frame_m", &C::max_gap_to_frame_m, "line end to the frame, m",
               kNonNegative)
        .field("frame_extent_margin_m", &C::frame_extent_margin_m, "m", kNonNegative);
    return s;
}

ConfigSchema<LandmarkCorrectionConfig> landmark_schema() {
    using C = LandmarkCorrectionConfig;
    ConfigSchema<C> s;
    s.section("detector", &C::detector, detector_schema(), "frames, stiffeners, intersections")
        .field("voxel_size_m", &C::voxel_size_m, "frame voxel before detection, m", kPositive)
        .field("association_distance_m", &C::association_distance_m, "match gate, m", kPositive)
        .field("max_residual_m", &C::max_residual_m, "agreement of the consensus, m", kPositive)
        .field("min_landmarks", &C::min_landmarks, "fewest agreeing matches", io::Range{.min = 1})
        .field("position_sigma_m", &C::position_sigma_m, "per landmark, m", kPositive)
        .field("normal_sigma_rad", &C::normal_sigma_rad, "frame normal, rad", kPositive)
        .field("free_rotation_sigma_rad", &C::free_rotation_sigma_rad,
               "about the frame normal, rad", kPositive);
    return s;
}

ConfigSchema<ColumnRegistrationConfig> column_schema() {
    using C = ColumnRegistrationConfig;
    using S = registration::SteinIcpConfig;
    ConfigSchema<perception::ColumnStructureConfig> structure;
    structure
        .field("diameter_m", &perception::ColumnStructureConfig::diameter_m, "column, m", kPositive)
        .field("diameter_tolerance_m", &perception::ColumnStructureConfig::diameter_tolerance_m,
               "diameter check, m", kPositive);
    ConfigSchema<S> stein;
    stein.field("num_particles", &S::num_particles, "K", io::Range{.min = 2})
        .field("iterations", &S::iterations, "T", io::Range{.min = 1})
        .field("refine_iterations", &S::refine_iterations, "Langevin steps", io::Range{.min = 0})
        .field("batch_size", &S::batch_size, "B", io::Range{.min = 1})
        .field("noise_sigma_m", &S::noise_sigma_m, "likelihood sigma, m", kPositive)
        .field("seed", &S::seed, "plus the frame index");
    ConfigSchema<C> s;
    s.section("structure", &C::structure, structure, "detector")
        .field("detection_voxel_m", &C::detection_voxel_m, "0 = every point, m", kNonNegative)
        .field("registration_voxel_m", &C::registration_voxel_m, "m", kPositive)
        .field("downcomer_azimuth_deg", &C::downcomer_azimuth_deg,
               "line of the downcomers through the axis, deg")
        .section("stein", &C::stein, stein, "3-DoF Stein-ICP around the seed")
        .field("max_floor_snap_m", &C::max_floor_snap_m, "z from the map's floor within, m",
               kPositive)
        .field("floor_z_sigma_m", &C::floor_z_sigma_m, "sigma of that z, m", kPositive)
        .field("max_rmse_m", &C::max_rmse_m, "quality gate, m", kPositive)
        .field("min_fitness", &C::min_fitness, "quality gate", kUnitInterval)
        .field("min_position_sigma_m", &C::min_position_sigma_m, "floor, m", kNonNegative)
        .field("min_yaw_sigma_deg", &C::min_yaw_sigma_deg, "floor, deg", kNonNegative)
        .field("free_sigma", &C::free_sigma, "z, roll, pitch (m, rad)", kPositive);
    return s;
}

ConfigSchema<TrackingConfig> tracking_schema() {
    using C = TrackingConfig;
    ConfigSchema<registration::IcpConfig> icp;
    using I = registration::IcpConfig;
    icp.field("max_iterations", &I::max_iterations, "", io::Range{.min = 1})
        .field("covariance_cell_size_m", &I::covariance_cell_size_m,
               "cell of the clustered covariance, m", kPositive)
        .field("map_error_sigma_m", &I::map_error_sigma_m, "map error per cell, m", kNonNegative);
    ConfigSchema<registration::SteinIcpConfig> stein;
    using S = registration::SteinIcpConfig;
    stein.field("num_particles", &S::num_particles, "K", io::Range{.min = 2})
        .field("iterations", &S::iterations, "T", io::Range{.min = 1})
        .field("noise_sigma_m", &S::noise_sigma_m, "likelihood sigma, m", kPositive)
        .field("seed", &S::seed, "plus the frame index");
    ConfigSchema<C> s;
    s.enum_field("method", &C::method,
                 {{"icp", TrackingMethod::kIcp},
                  {"stein", TrackingMethod::kStein},
                  {"landmarks", TrackingMethod::kLandmarks},
                  {"column", TrackingMethod::kColumn}},
                 "local registration, the frame x longitudinal landmarks seen, or the column's "
                 "3-DoF registration (art. F)")
        .section("icp", &C::icp, icp)
        .section("stein", &C::stein, stein)
        .section("landmarks", &C::landmarks, landmark_schema(), "art. B landmark corrections")
        .section("column", &C::column, column_schema(), "art. F 3-DoF column registration")
        .field("correspondence_sigmas", &C::correspondence_sigmas,
               "correspondence distance: this many predicted sigma + a voxel", kPositive)
        .field("min_correspondence_distance_m", &C::min_correspondence_distance_m, "m", kPositive)
        .field("max_correspondence_distance_m", &C::max_correspondence_distance_m, "m", kPositive);
    return s;
}

ConfigSchema<RelocalizationConfig> relocalization_schema() {
    using C = RelocalizationConfig;
    ConfigSchema<registration::RobustRegistrationConfig> robust;
    using R = registration::RobustRegistrationConfig;
    robust.field("noise_bound_m", &R::noise_bound_m, "beta, m", kPositive)
        .field("min_inliers", &R::min_inliers, "", io::Range{.min = 3});
    ConfigSchema<registration::IcpConfig> refine;
    refine
        .field("max_correspondence_distance_m",
               &registration::IcpConfig::max_correspondence_distance_m, "m", kPositive)
        .field("max_iterations", &registration::IcpConfig::max_iterations, "", io::Range{.min = 1});
    ConfigSchema<CorrelativeSearchConfig> correlative;
    using K = CorrelativeSearchConfig;
    correlative.field("translation_step_m", &K::translation_step_m, "position grid, m", kPositive)
        .field("yaw_step_rad", &K::yaw_step_rad, "yaw grid, rad", kPositive)
        .field("scan_voxel_m", &K::scan_voxel_m, "scan thinning voxel, m", kPositive)
        .field("max_scan_points", &K::max_scan_points, "scan points scored", io::Range{.min = 10})
        .field("min_clearance_m", &K::min_clearance_m, "body-to-map distance, m", kNonNegative)
        .field("num_candidates", &K::num_candidates, "poses verified by ICP", io::Range{.min = 1});
    ConfigSchema<C> s;
    s.enum_field("method", &C::method,
                 {{"correlative", RelocalizationMethod::kCorrelative},
                  {"fpfh", RelocalizationMethod::kFpfh}},
                 "global registration")
        .section("correlative", &C::correlative, correlative)
        .section("robust", &C::robust, robust)
        .section("refine", &C::refine, refine)
        .field("refine_voxel_m", &C::refine_voxel_m, "scan voxel of the first ICP pass, m",
               kPositive)
        .field("polish_correspondence_distance_m", &C::polish_correspondence_distance_m,
               "second ICP pass, m", kPositive)
        .field("normal_neighbors", &C::normal_neighbors, "k for the frame's normals",
               io::Range{.min = 3})
        .field("ambiguity_overlap_margin", &C::ambiguity_overlap_margin,
               "candidates elsewhere this close in overlap are ambiguous", kUnitInterval)
        .field("ambiguity_distance_m", &C::ambiguity_distance_m, "m", kPositive)
        .field("ambiguity_yaw_rad", &C::ambiguity_yaw_rad, "rad", kPositive)
        .field("prior_sigmas", &C::prior_sigmas, "search box: prior position +- this many sigma",
               kPositive)
        .field("min_prior_radius_m", &C::min_prior_radius_m, "search box half-width at least, m",
               kPositive)
        .field("failures_before_global", &C::failures_before_global,
               "restricted failures before all compartments are searched", io::Range{.min = 1});
    return s;
}

ConfigSchema<GateConfig> gates_schema() {
    using C = GateConfig;
    ConfigSchema<registration::AttitudeGateConfig> attitude;
    attitude.field("max_difference_rad", &registration::AttitudeGateConfig::max_difference_rad,
                   "roll/pitch against the IMU, rad", kPositive);
    ConfigSchema<registration::SpeedGateConfig> speed;
    speed.field("max_speed_mps", &registration::SpeedGateConfig::max_speed_mps,
                "jump against the VIO, m/s", kPositive);
    ConfigSchema<registration::OverlapGateConfig> overlap;
    overlap
        .field("min_overlap", &registration::OverlapGateConfig::min_overlap, "share",
               io::Range{.min = 0.0, .min_exclusive = true, .max = 1.0})
        .field("voxel_size_m", &registration::OverlapGateConfig::voxel_size_m, "m", kPositive);
    ConfigSchema<C> s;
    s.section("attitude", &C::attitude, attitude)
        .section("speed", &C::speed, speed)
        .section("overlap", &C::overlap, overlap)
        .field("mahalanobis_threshold", &C::mahalanobis_threshold, "chi2(6) quantile", kPositive);
    return s;
}

ConfigSchema<DefectLiftingConfig> defects_schema() {
    using C = DefectLiftingConfig;
    ConfigSchema<C> s;
    s.field("max_frame_offset_s", &C::max_frame_offset_s, "image to depth frame, s", kPositive)
        .field("min_support_radius_px", &C::min_support_radius_px, "px", kPositive)
        .field("min_support_points", &C::min_support_points, "returns on the defect",
               io::Range{.min = 3})
        .field("plane_inlier_m", &C::plane_inlier_m, "m", kPositive)
        .field("range_sigma_m", &C::range_sigma_m, "1 sigma per return, m", kPositive)
        .field("pixel_sigma_px", &C::pixel_sigma_px, "1 sigma of the detection, px", kPositive)
        .field("max_incidence_deg", &C::max_incidence_deg, "deg",
               io::Range{.min = 0.0, .min_exclusive = true, .max = 90.0, .max_exclusive = true})
        .field("local_cloud_radius_m", &C::local_cloud_radius_m, "m", kPositive);
    return s;
}

ConfigSchema<VelocityOdometryConfig> velocity_odometry_schema() {
    ConfigSchema<VelocityOdometryConfig> s;
    using C = VelocityOdometryConfig;
    s.field("max_step_s", &C::max_step_s, "longest step integrated, s", kPositive)
        .field("max_yaw_disagreement_rad", &C::max_yaw_disagreement_rad,
               "VIO yaw step refused when the gyro's differs by more", kPositive)
        .field("tilt_random_walk_rad_per_sqrt_m", &C::tilt_random_walk_rad_per_sqrt_m,
               "IMU tilt: filter tilt random walk at least this", kPositive);
    return s;
}

ConfigSchema<LocalizerConfig> localizer_schema() {
    using C = LocalizerConfig;
    ConfigSchema<ParallelConfig> parallel;
    parallel.field("num_threads", &ParallelConfig::num_threads, "0 = all hardware threads",
                   kNonNegative);
    ConfigSchema<C> s;
    s.section("map", &C::map, map_schema())
        .section("filter", &C::filter, filter_schema())
        .section("attitude", &C::attitude, attitude_schema())
        .section("tracking", &C::tracking, tracking_schema())
        .section("relocalization", &C::relocalization, relocalization_schema())
        .section("gates", &C::gates, gates_schema())
        .section("defects", &C::defects, defects_schema())
        .enum_field("odometry_input", &C::odometry_input,
                    {{"pose", OdometryInput::kPose}, {"velocity", OdometryInput::kVelocity}},
                    "the VIO's pose, or its velocity with the IMU's tilt")
        .section("velocity_odometry", &C::velocity_odometry, velocity_odometry_schema())
        .field("registration_period_s", &C::registration_period_s,
               "shortest time between registrations, s (0 = every frame)", kNonNegative)
        .field("max_rejections", &C::max_rejections, "rejected frames before re-localising",
               io::Range{.min = 1})
        .field("dropout_relocalization_s", &C::dropout_relocalization_s,
               "VIO dropout that loses tracking, s", kPositive)
        .field("min_points", &C::min_points, "fewest frame points to register",
               io::Range{.min = 10})
        .field("global_every_frame", &C::global_every_frame,
               "register every frame globally, no tracking (the sources' pipeline)")
        .field("start_compartment", &C::start_compartment, "-1 = unknown", io::Range{.min = -1})
        .section("parallel", &C::parallel, parallel);
    return s;
}

}  // namespace

std::string_view to_string(TrackingMethod method) {
    switch (method) {
        case TrackingMethod::kIcp:
            return "icp";
        case TrackingMethod::kStein:
            return "stein";
        case TrackingMethod::kLandmarks:
            return "landmarks";
        case TrackingMethod::kColumn:
            return "column";
    }
    return "?";
}

std::string_view to_string(OdometryInput input) {
    return input == OdometryInput::kVelocity ? "velocity" : "pose";
}

OdometryInput odometry_input_from_string(std::string_view name, std::string_view field) {
    if (name == "pose") return OdometryInput::kPose;
    if (name == "velocity") return OdometryInput::kVelocity;
    throw ConfigError(fmt::format("{} = '{}', expected pose or velocity", field, name));
}

TrackingMethod tracking_method_from_string(std::string_view name, std::string_view field) {
    if (name == "icp") return TrackingMethod::kIcp;
    if (name == "stein") return TrackingMethod::kStein;
    if (name == "landmarks") return TrackingMethod::kLandmarks;
    if (name == "column") return TrackingMethod::kColumn;
    throw ConfigError(
        fmt::format("{} = '{}', expected icp, stein, landmarks or column", field, name));
}

void TrackingConfig::validate(std::string_view prefix) const {
    icp.validate(std::string(prefix) + ".icp");
    stein.validate(std::string(prefix) + ".stein");
    landmarks.validate(std::string(prefix) + ".landmarks");
    column.validate(std::string(prefix) + ".column");
    detail::require_positive(correspondence_sigmas, prefix, "correspondence_sigmas");
    detail::require_positive(min_correspondence_distance_m, prefix,
                             "min_correspondence_distance_m");
    detail::require(std::isfinite(max_correspondence_distance_m) &&
                        max_correspondence_distance_m >= min_correspondence_distance_m,
                    prefix, "max_correspondence_distance_m", max_correspondence_distance_m,
                    ">= min_correspondence_distance_m");
}

std::string_view to_string(RelocalizationMethod method) {
    return method == RelocalizationMethod::kCorrelative ? "correlative" : "fpfh";
}

void RelocalizationConfig::validate(std::string_view prefix) const {
    correlative.validate(std::string(prefix) + ".correlative");
    detail::require_positive(refine_voxel_m, prefix, "refine_voxel_m");
    detail::require_positive(polish_correspondence_distance_m, prefix,
                             "polish_correspondence_distance_m");
    match.validate(std::string(prefix) + ".match");
    robust.validate(std::string(prefix) + ".robust");
    refine.validate(std::string(prefix) + ".refine");
    detail::require(normal_neighbors >= 3, prefix, "normal_neighbors", normal_neighbors, ">= 3");
    detail::require(ambiguity_overlap_margin >= 0 && ambiguity_overlap_margin < 1, prefix,
                    "ambiguity_overlap_margin", ambiguity_overlap_margin, "in [0, 1)");
    detail::require_positive(ambiguity_distance_m, prefix, "ambiguity_distance_m");
    detail::require_positive(ambiguity_yaw_rad, prefix, "ambiguity_yaw_rad");
    detail::require_positive(prior_sigmas, prefix, "prior_sigmas");
    detail::require_positive(min_prior_radius_m, prefix, "min_prior_radius_m");
    detail::require(failures_before_global >= 1, prefix, "failures_before_global",
                    failures_before_global, ">= 1");
}

void GateConfig::validate(std::string_view prefix) const {
    attitude.validate(std::string(prefix) + ".attitude");
    speed.validate(std::string(prefix) + ".speed");
    overlap.validate(std::string(prefix) + ".overlap");
    detail::require_positive(mahalanobis_threshold, prefix, "mahalanobis_threshold");
}

void LocalizerConfig::validate(std::string_view prefix) const {
    const std::string p(prefix);
    map.validate(p + ".map");
    filter.validate(p + ".filter");
    attitude.validate(p + ".attitude");
    tracking.validate(p + ".tracking");
    relocalization.validate(p + ".relocalization");
    gates.validate(p + ".gates");
    defects.validate(p + ".defects");
    velocity_odometry.validate(p + ".velocity_odometry");
    parallel.validate(p + ".parallel");
    detail::require_non_negative(registration_period_s, prefix, "registration_period_s");
    detail::require(max_rejections >= 1, prefix, "max_rejections", max_rejections, ">= 1");
    detail::require_positive(dropout_relocalization_s, prefix, "dropout_relocalization_s");
    detail::require(min_points >= 10, prefix, "min_points", static_cast<double>(min_points),
                    ">= 10");
    detail::require(start_compartment >= -1, prefix, "start_compartment", start_compartment,
                    ">= -1");
}

void LocalizerConfig::set_num_threads(int num_threads) {
    parallel.num_threads = num_threads;
    map.parallel.num_threads = num_threads;
    tracking.icp.parallel.num_threads = num_threads;
    tracking.stein.parallel.num_threads = num_threads;
    tracking.column.stein.parallel.num_threads = num_threads;
    relocalization.refine.parallel.num_threads = num_threads;
    relocalization.robust.parallel.num_threads = num_threads;
    relocalization.match.parallel.num_threads = num_threads;
    relocalization.correlative.parallel.num_threads = num_threads;
}

LocalizerConfig load_localizer_config(const std::string& path) {
    LocalizerConfig config = io::load_config(path, localizer_schema());
    config.set_num_threads(config.parallel.num_threads);
    return config;
}

std::string describe_localizer_config(const LocalizerConfig& config) {
    return localizer_schema().describe(config);
}

}  // namespace scantling::localization
