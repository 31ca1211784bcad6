#include <scantling/core/error.hpp>
#include <scantling/sim/lawnmower_trajectory.hpp>

#include "detail/sensor_checks.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

namespace scantling::sim {
namespace {

// An extent that is a multiple of the spacing up to rounding must not get an extra slice.
constexpr double kSliceCountSlack = 1e-9;
// Below this horizontal length the wall normal is vertical (floor/ceiling): use yaw_rad.
constexpr double kVerticalNormal = 1e-6;

int slice_count(double extent_m, double spacing_m) {
    return static_cast<int>(std::ceil(extent_m / spacing_m - kSliceCountSlack)) + 1;
}

double heading_of(const LawnmowerTrajectoryConfig& c) {
    const Eigen::Vector3d towards_wall = -c.T_world_wall.linear().col(2);
    if (!c.face_wall || towards_wall.head<2>().norm() < kVerticalNormal) return c.yaw_rad;
    return std::atan2(towards_wall.y(), towards_wall.x());
}

double across_extent_m(const LawnmowerTrajectoryConfig& c) {
    return c.slices == SliceDirection::kHorizontal ? c.height_m : c.width_m;
}

/// Corners (u along the slice from 0 to `along_m`, w across it from 0) in flying order.
std::vector<Eigen::Vector2d> slice_corners(double along_m, double across_m, int n) {
    std::vector<Eigen::Vector2d> corners;
    for (int j = 0; j < n; ++j) {
        const double w = across_m * j / (n - 1);
        const bool forward = j % 2 == 0;
        corners.emplace_back(forward ? 0.0 : along_m, w);
        corners.emplace_back(forward ? along_m : 0.0, w);
    }
    return corners;
}

/// Wall-frame point of corner (u, w): horizontal slices run along x and step down from the
/// top; vertical slices step along x and first run down from the top (when start_at_top).
Eigen::Vector3d wall_point(const LawnmowerTrajectoryConfig& c, const Eigen::Vector2d& uw) {
    const bool horizontal = c.slices == SliceDirection::kHorizontal;
    const double v = horizontal ? uw.y() : uw.x();
    const double y = c.start_at_top ? c.height_m - v : v;
    return {horizontal ? uw.x() : uw.y(), y, c.standoff_m};
}

WaypointTrajectoryConfig path_config(const LawnmowerTrajectoryConfig& c, int n) {
    const double across = across_extent_m(c);
    const double along = c.slices == SliceDirection::kHorizontal ? c.width_m : c.height_m;
    WaypointTrajectoryConfig path;
    path.max_speed_mps = c.max_speed_mps;
    path.max_accel_mps2 = c.max_accel_mps2;
    path.shape = c.shape;
    const double yaw = heading_of(c);
    for (const Eigen::Vector2d& uw : slice_corners(along, across, n)) {
        path.waypoints.push_back({c.T_world_wall * wall_point(c, uw), yaw, 0.0});
    }
    return path;
}

}  // namespace

void LawnmowerTrajectoryConfig::validate(std::string_view prefix) const {
    const Eigen::Matrix3d R = T_world_wall.linear();
    if (!T_world_wall.matrix().allFinite() ||
        (R.transpose() * R - Eigen::Matrix3d::Identity()).norm() > 1e-6 || R.determinant() < 0) {
        throw ConfigError(fmt::format("{}.T_world_wall is not a rigid transform", prefix));
    }
    detail::require_positive(prefix, "width_m", width_m);
    detail::require_positive(prefix, "height_m", height_m);
    detail::require_non_negative(prefix, "standoff_m", standoff_m);
    detail::require_positive(prefix, "slice_spacing_m", slice_spacing_m);
    detail::require(std::isfinite(yaw_rad), prefix, "yaw_rad", yaw_rad, "finite");
    detail::require_positive(prefix, "max_speed_mps", max_speed_mps);
    detail::require_positive(prefix, "max_accel_mps2", max_accel_mps2);
    const double extent = slices == SliceDirection::kHorizontal ? height_m : width_m;
    detail::require(extent / slice_spacing_m <= 1e5, prefix, "slice_spacing_m", slice_spacing_m,
                    fmt::format(">= extent / 1e5 = {} (at most 1e5 slices)", extent / 1e5));
}

double footprint_slice_spacing_m(double fov_rad, double standoff_m, double overlap) {
    if (!(fov_rad > 0.0 && fov_rad < std::numbers::pi) || !(standoff_m > 0.0) ||
        !std::isfinite(standoff_m) || !(overlap >= 0.0 && overlap < 1.0)) {
        throw InputError(fmt::format(
            "footprint_slice_spacing_m: fov_rad = {}, standoff_m = {}, overlap = {}, expected "
            "fov in (0, pi), standoff > 0, overlap in [0, 1)",
            fov_rad, standoff_m, overlap));
    }
    return 2.0 * standoff_m * std::tan(0.5 * fov_rad) * (1.0 - overlap);
}

LawnmowerTrajectory::LawnmowerTrajectory(const LawnmowerTrajectoryConfig& config)
    : config_((config.validate(), config)),
      num_slices_(slice_count(across_extent_m(config_), config_.slice_spacing_m)),
      step_m_(across_extent_m(config_) / (num_slices_ - 1)),
      path_(path_config(config_, num_slices_)) {}

}  // namespace scantling::sim
