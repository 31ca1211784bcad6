#pragma once
/// @file
/// The part of a sweep that can change collision prevention's answer, gathered once per sweep.
///
/// The command loop runs faster than the LiDAR (the drone's commands at 50 Hz, its sweeps at
/// 10 Hz), and each command needs its own frustum, so prevent_collision on the raw sweep scans
/// every point of the sweep five times. Only points within the frustum's reach or within d_min
/// can matter: a point inside the frustum has |p|² = a² + (p·h)² + (p·u)² ≤ d_att² (1 + tan²θ_h
/// + tan²θ_v), and repulsion needs |p| < d_min. Keeping those (in sweep order) and the sweep's
/// count of valid points makes prevent_collision on them return the same result, bit for bit,
/// as on the whole sweep, for every desired velocity (tests/safety/obstacle_points_test.cpp).
/// Measured on `make run`: a few hundred of the sweep's 30,000 points (docs/benchmarks.md).

#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include <scantling/core/point_cloud.hpp>
#include <scantling/safety/collision_prevention.hpp>

namespace scantling::safety {

struct ObstaclePoints {
    std::vector<Eigen::Vector3d> points_body;  ///< finite, not at the origin, |p| ≤ reach_m
    std::size_t num_valid_points = 0;          ///< finite and not at the origin, whole sweep
    double reach_m = 0.0;                      ///< the radius they were gathered within
};

/// The radius beyond which no point can enter `config`'s frustum or repel (validated config).
double obstacle_reach_m(const CollisionPreventionConfig& config);

/// The points of `cloud_body` (body frame) within obstacle_reach_m(config). ConfigError for a
/// bad config.
ObstaclePoints gather_obstacle_points(const PointCloud& cloud_body,
                                      const CollisionPreventionConfig& config = {});

/// prevent_collision on gathered points: the same result as on the sweep they came from.
/// Throws InputError when they were gathered for a shorter reach than `config` needs (another
/// config), as well as prevent_collision's own errors.
CollisionPreventionResult prevent_collision(const Eigen::Vector3d& v_desired_body_mps,
                                            const ObstaclePoints& obstacles,
                                            const CollisionPreventionConfig& config = {});

}  // namespace scantling::safety
