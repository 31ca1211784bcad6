// Tracking: a frame registered against the map from the filter's prediction (localizer.hpp).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include <scantling/core/point_cloud.hpp>
#include <scantling/localization/column_registration.hpp>
#include <scantling/localization/localizer.hpp>
#include <scantling/registration/quality.hpp>

namespace scantling::localization {
namespace {

/// Left-twist covariance of Stein particles about the chosen pose.
Matrix6d particle_covariance(const registration::SteinIcpResult& r) {
    Matrix6d C = Matrix6d::Zero();
    const Eigen::Isometry3d inverse = r.T_target_source.inverse();
    for (const Vector6d& particle : r.particles) {
        const Vector6d e = se3_log(registration::isometry_from_pose_params(particle) * inverse);
        C += e * e.transpose();
    }
    return C / static_cast<double>(std::max<std::size_t>(r.particles.size() - 1, 1));
}

struct Registered {
    bool converged = false;
    std::string status;
    Eigen::Isometry3d T_world_sensor = Eigen::Isometry3d::Identity();
    Matrix6d covariance = Matrix6d::Identity();
};

/// ICP or Stein-ICP of `scan` (sensor frame) against the map from `guess` (T_world_sensor).
Registered register_scan(const PointCloud& scan, const MapRegion& map,
                         const Eigen::Isometry3d& guess, double gate_m, const TrackingConfig& tc,
                         std::size_t frame_index) {
    if (tc.method == TrackingMethod::kIcp) {
        registration::IcpConfig icp = tc.icp;
        icp.max_correspondence_distance_m = gate_m;
        const registration::RegistrationResult r =
            registration::align(scan, map.cloud, *map.tree, guess, icp);
        return {r.converged, r.status, r.T_target_source,
                usable_covariance(r.covariance, r.information, 100.0)};
    }
    registration::SteinIcpConfig stein = tc.stein;
    stein.max_correspondence_distance_m = std::max(gate_m, stein.max_correspondence_distance_m);
    stein.seed = tc.stein.seed + frame_index;  // every frame its own particles, reproducibly
    const registration::SteinIcpResult r =
        registration::stein_icp(scan, map.cloud, *map.tree, guess, stein);
    return {r.fitness > 0.0, fmt::format("{} KDE modes", r.num_modes), r.T_target_source,
            particle_covariance(r)};
}

}  // namespace

FrameEvent Localizer::track(const PointCloud& scan, const PointCloud& finite,
                            const QueuedFrame& frame, FrameEvent event) {
    event.mode = LocalizerMode::kTracking;
    event.compartment = compartments_.current();
    const double t = frame.cloud.stamp_s;
    const std::optional<AbsolutePose> predicted = filter_.predict(t);
    const std::optional<Eigen::Matrix3d> R_imu = imu_attitude(t);
    if (!predicted || !R_imu) {
        event.gate = "no_prediction";
        event.reason = "the filter cannot predict the capture time (older than its history)";
        return event;
    }
    const TrackingConfig& tc = config_.tracking;
    if (tc.method == TrackingMethod::kLandmarks) {
        const std::optional<AbsolutePose> pose = landmark_pose(finite, frame, *predicted, event);
        if (!pose) return event;
        return gate_and_fuse(*pose, scan, frame, *R_imu, std::move(event));
    }
    if (tc.method == TrackingMethod::kColumn) {
        const std::optional<AbsolutePose> pose =
            column_pose(finite, frame, *predicted, *R_imu, event);
        if (!pose) return event;
        return gate_and_fuse(*pose, scan, frame, *R_imu, std::move(event));
    }
    const double sigma =
        largest_position_sigma_m(predicted->covariance, predicted->T_world_body.translation());
    const double gate_m =
        std::clamp(tc.correspondence_sigmas * sigma + map_->config().voxel_size_m,
                   tc.min_correspondence_distance_m, tc.max_correspondence_distance_m);
    const Eigen::Isometry3d guess = predicted->T_world_body * frame.T_body_sensor;
    const Registered reg = register_scan(scan, map_->whole(), guess, gate_m, tc, frame.index);
    const Eigen::Isometry3d T_world_body = reg.T_world_sensor * frame.T_body_sensor.inverse();
    event.T_world_body = T_world_body;
    if (!reg.converged) {
        event.gate = "registration";
        event.reason = reg.status;
        reject(event);
        return event;
    }
    return gate_and_fuse({t, T_world_body, reg.covariance}, scan, frame, *R_imu, std::move(event));
}

std::optional<AbsolutePose> Localizer::landmark_pose(const PointCloud& finite,
                                                     const QueuedFrame& frame,
                                                     const AbsolutePose& predicted,
                                                     FrameEvent& event) {
    const io::StructuralMap* structure = map_->structure();
    if (structure == nullptr) {
        event.gate = "no_structure";
        event.reason = "landmark tracking needs the map's metadata (frames, longitudinals)";
        return std::nullopt;
    }
    const LandmarkCorrection c =
        correct_with_landmarks(finite, predicted, frame.T_body_sensor, *structure,
                               compartments_.current(), config_.tracking.landmarks);
    event.landmarks_seen = c.detected.landmarks.size();
    event.landmarks_matched = c.matches.size();
    if (c.ok()) return c.pose;
    event.gate = c.failure;
    event.reason = c.reason;
    // Nothing in view is not a failure of tracking; matches that disagree are.
    if (c.failure == "residual") reject(event);
    return std::nullopt;
}

std::optional<AbsolutePose> Localizer::column_pose(const PointCloud& finite,
                                                   const QueuedFrame& frame,
                                                   const AbsolutePose& predicted,
                                                   const Eigen::Matrix3d& R_world_body_imu,
                                                   FrameEvent& event) {
    const MapRegion& map = map_->whole();
    const ColumnRegistration c =
        register_column(finite, frame.T_body_sensor, R_world_body_imu, predicted, map.cloud,
                        *map.tree, config_.tracking.column, frame.index);
    event.T_world_body = c.T_world_body;
    if (c.ok()) return c.pose;
    event.gate = c.failure;
    event.reason = c.reason;
    // The structure out of view is not a failure of tracking; a poor registration is.
    if (c.failure == "registration") reject(event);
    return std::nullopt;
}

FrameEvent Localizer::gate_and_fuse(const AbsolutePose& measured, const PointCloud& scan,
                                    const QueuedFrame& frame,
                                    const Eigen::Matrix3d& R_world_body_imu, FrameEvent event) {
    event.T_world_body = measured.T_world_body;
    const Eigen::Isometry3d T_world_sensor = measured.T_world_body * frame.T_body_sensor;
    event.overlap =
        registration::overlap_ratio(transformed(scan, T_world_sensor), *map_->whole().tree,
                                    config_.gates.overlap.voxel_size_m, config_.parallel);
    event.gate = common_gates(measured.T_world_body, event.overlap, measured.stamp_s,
                              R_world_body_imu, event.reason);
    if (event.gate.empty()) {
        const std::optional<Innovation> in = filter_.innovation(measured);
        event.mahalanobis_squared = in ? in->mahalanobis_squared : 0.0;
        if (in && in->mahalanobis_squared > config_.gates.mahalanobis_threshold) {
            event.gate = "mahalanobis";
            event.reason = fmt::format("d² = {:.1f} > {:.1f}", in->mahalanobis_squared,
                                       config_.gates.mahalanobis_threshold);
        }
    }
    if (!event.gate.empty()) {
        reject(event);
        return event;
    }
    accept(measured, false);
    event.outcome = FrameOutcome::kRegistered;
    return event;
}

}  // namespace scantling::localization
