#include <scantling/safety/obstacle_points.hpp>

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include <scantling/core/error.hpp>

#include "detail/prevent_collision_on.hpp"

namespace scantling::safety {
namespace {

// Rounding in the frustum test must never drop a point the sweep scan would keep: gather a
// hair wider (extra points outside the frustum and beyond d_min change nothing).
constexpr double kReachMargin = 1.0 + 1e-9;

}  // namespace

double obstacle_reach_m(const CollisionPreventionConfig& config) {
    const double th = detail::tan_deg(config.half_fov_horizontal_deg);
    const double tv = detail::tan_deg(config.half_fov_vertical_deg);
    const double frustum_corner_m = config.d_att_m * std::sqrt(1.0 + th * th + tv * tv);
    return std::max(frustum_corner_m, config.d_min_m) * kReachMargin;
}

ObstaclePoints gather_obstacle_points(const PointCloud& cloud_body,
                                      const CollisionPreventionConfig& config) {
    config.validate();
    ObstaclePoints obstacles;
    obstacles.reach_m = obstacle_reach_m(config);
    const double reach2 = obstacles.reach_m * obstacles.reach_m;
    // One allocation (a sweep's worth, ~1.5 MB for 64 × 1024) instead of the doublings of a
    // growing vector: in a tight tank most of the sweep is within reach.
    obstacles.points_body.reserve(cloud_body.size());
    for (const Eigen::Vector3d& p : cloud_body.points) {
        const double d2 = p.squaredNorm();
        // The same validity test as the sweep scan: finite and not at the origin.
        if (!std::isfinite(d2) || d2 == 0.0) continue;
        ++obstacles.num_valid_points;
        if (d2 <= reach2) obstacles.points_body.push_back(p);
    }
    return obstacles;
}

CollisionPreventionResult prevent_collision(const Eigen::Vector3d& v_desired_body_mps,
                                            const ObstaclePoints& obstacles,
                                            const CollisionPreventionConfig& config) {
    config.validate();
    const double needed_m = obstacle_reach_m(config);
    if (!(obstacles.reach_m >= needed_m)) {
        throw InputError(fmt::format(
            "prevent_collision: obstacle points gathered within {} m, the config needs {} m "
            "(gather them with the same collision_prevention config)",
            obstacles.reach_m, needed_m));
    }
    return detail::prevent_collision_on(v_desired_body_mps, obstacles.points_body, config,
                                        obstacles.num_valid_points);
}

}  // namespace scantling::safety
