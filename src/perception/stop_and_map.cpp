// The crawler's stop-and-map (stop_and_map.hpp).
#include <scantling/perception/stop_and_map.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>

namespace scantling::perception {
namespace {

bool finite(const Eigen::Isometry3d& T) { return T.matrix().allFinite(); }

/// The points labelled positive or negative: what constrains the motion in the surface's plane
/// (see the file comment).
PointCloud obstacle_points(const SurfaceObstacles& detection) {
    PointCloud out;
    for (std::size_t i = 0; i < detection.labels.size(); ++i) {
        const SurfaceLabel l = detection.labels[i];
        if (l == SurfaceLabel::kPositive || l == SurfaceLabel::kNegative) {
            out.points.push_back(detection.points.points[i]);
        }
    }
    return out;
}

}  // namespace

void StopAndMapConfig::validate(std::string_view prefix) const {
    obstacles.validate(std::string(prefix) + ".obstacles");
    icp.validate(std::string(prefix) + ".icp");
    config_checks::require(max_points > 0, prefix, "max_points", max_points, "> 0");
    config_checks::require(min_icp_points >= 6, prefix, "min_icp_points", min_icp_points, ">= 6");
    config_checks::require(lidar_fov_rad > 0.0 && lidar_fov_rad <= std::numbers::pi, prefix,
                           "lidar_fov_rad", lidar_fov_rad, "in (0, pi]");
    config_checks::require_non_negative(fov_margin_rad, prefix, "fov_margin_rad");
    config_checks::require_positive(expected_range_m, prefix, "expected_range_m");
}

std::vector<MappedObstacle> map_obstacles(const SurfaceObstacles& detection,
                                          const Eigen::Isometry3d& T_world_body) {
    std::vector<MappedObstacle> out;
    out.reserve(detection.clusters.size());
    for (const ObstacleCluster& c : detection.clusters) {
        const Eigen::Vector3d p_body(c.centroid_xy_m.x(), c.centroid_xy_m.y(),
                                     detection.surface.height_m(c.centroid_xy_m));
        out.push_back({.label = c.label,
                       .centroid_world_m = T_world_body * p_body,
                       .min_body_xy_m = c.min_xy_m,
                       .max_body_xy_m = c.max_xy_m,
                       .num_cells = c.num_cells});
    }
    return out;
}

StopMapper::StopMapper(const StopAndMapConfig& config, const Eigen::Isometry3d& T_body_lidar)
    : config_((config.validate(), config)), T_body_lidar_(T_body_lidar) {
    if (!finite(T_body_lidar_)) throw InputError("stop and map: the LiDAR mount is not finite");
}

void StopMapper::begin(double t_s, const Eigen::Isometry3d& T_world_body_localisation) {
    if (open_) throw InputError("stop and map: a stop is already open");
    if (!std::isfinite(t_s) || !finite(T_world_body_localisation)) {
        throw InputError("stop and map: the stop's time or localisation pose is not finite");
    }
    open_.emplace(Open{.begin_s = t_s,
                       .T_world_body = T_world_body_localisation,
                       .cloud_body = {},
                       .num_frames = 0});
}

void StopMapper::add_frame(const PointCloud& frame_lidar) {
    if (!open_) return;
    PointCloud& cloud = open_->cloud_body;
    const std::size_t room = config_.max_points - std::min(config_.max_points, cloud.size());
    const std::size_t n = std::min(room, frame_lidar.size());
    cloud.points.reserve(cloud.size() + n);
    // The robot stands still: every frame is in the same body frame (positions only, as the
    // detection and the ICP read them).
    for (std::size_t i = 0; i < n; ++i)
        cloud.points.push_back(T_body_lidar_ * frame_lidar.points[i]);
    ++open_->num_frames;
}

void StopMapper::correct(StopMap& stop) const {
    stop.T_world_body_map = stop.T_world_body_localisation;
    if (!previous_) {
        stop.icp_status = "first stop";
        return;
    }
    // The localisation's motion since the previous stop, carried onto the previous map pose.
    const Eigen::Isometry3d C_none = Eigen::Isometry3d::Identity();
    stop.T_world_body_map = registration::corrected_map_pose(
        previous_->T_world_body_map, previous_->T_world_body_localisation,
        stop.T_world_body_localisation, C_none);
    if (!config_.correct_pose) {
        stop.icp_status = "off";
        return;
    }
    // The new stop's obstacle points against the whole previous cloud, whose normals are then
    // estimated with the surface around each obstacle (see the file comment).
    const PointCloud source = obstacle_points(stop.detection);
    // The previous stop's cloud in the robot frame the localisation predicts now.
    const PointCloud target =
        transformed(previous_->cloud_body, stop.T_world_body_localisation.inverse() *
                                               previous_->T_world_body_localisation);
    if (source.size() < config_.min_icp_points || target.size() < config_.min_icp_points) {
        stop.icp_status = fmt::format("too few obstacle points: {} and {} < min_icp_points = {}",
                                      source.size(), target.size(), config_.min_icp_points);
        return;
    }
    const registration::RegistrationResult r =
        registration::align_constrained(source, target, config_.icp);
    stop.icp_status = r.status;
    if (!r.converged) return;
    if (r.degeneracy.degenerate) {
        stop.icp_status =
            fmt::format("degenerate: {} weak direction(s)", r.degeneracy.weak_directions.size());
        return;
    }
    stop.icp_applied = true;
    stop.T_world_body_map = registration::corrected_map_pose(
        previous_->T_world_body_map, previous_->T_world_body_localisation,
        stop.T_world_body_localisation, r.T_target_source);
}

StopMap StopMapper::finish(double t_s) {
    if (!open_) throw InputError("stop and map: no stop is open");
    Open open = std::move(*open_);
    open_.reset();
    StopMap stop;
    stop.index = stops_++;
    stop.begin_s = open.begin_s;
    stop.end_s = t_s;
    stop.num_frames = open.num_frames;
    stop.T_world_body_localisation = open.T_world_body;
    std::optional<ExpectedView> view;
    if (config_.missing_returns_are_negative) {
        view = ExpectedView{.T_body_sensor = T_body_lidar_,
                            .half_fov_rad = 0.5 * config_.lidar_fov_rad,
                            .margin_rad = config_.fov_margin_rad,
                            .max_range_m = config_.expected_range_m};
    }
    stop.detection = detect_surface_obstacles(open.cloud_body, config_.obstacles, view);
    correct(stop);
    stop.obstacles = map_obstacles(stop.detection, stop.T_world_body_map);
    previous_ = Previous{.cloud_body = stop.detection.points,
                         .T_world_body_localisation = stop.T_world_body_localisation,
                         .T_world_body_map = stop.T_world_body_map};
    stop.cloud_body = std::move(open.cloud_body);
    return stop;
}

std::optional<Eigen::Isometry3d> StopMapper::last_map_pose() const {
    if (!previous_) return std::nullopt;
    return previous_->T_world_body_map;
}

}  // namespace scantling::perception
