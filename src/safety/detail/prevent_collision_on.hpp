#pragma once
/// @file
/// The one pass of prevent_collision over a span of body-frame points, shared by the sweep
/// and the gathered-obstacle entry points (obstacle_points.hpp), and the frustum's half-angle
/// tangents both need.

#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <optional>
#include <span>

#include <scantling/safety/collision_prevention.hpp>

namespace scantling::safety::detail {

inline double tan_deg(double deg) { return std::tan(deg * std::numbers::pi / 180.0); }

/// `num_valid_points`: the whole sweep's count when `points_body` is a gathered subset
/// (nullopt: count them here).
CollisionPreventionResult prevent_collision_on(const Eigen::Vector3d& v_desired_body_mps,
                                               std::span<const Eigen::Vector3d> points_body,
                                               const CollisionPreventionConfig& config,
                                               std::optional<std::size_t> num_valid_points);

}  // namespace scantling::safety::detail
