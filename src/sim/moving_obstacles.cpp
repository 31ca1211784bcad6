// Moving obstacles (moving_obstacles.hpp): validation, motion and the queries of the set.
#include <scantling/sim/moving_obstacles.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include <scantling/core/error.hpp>
#include <scantling/sim/ray_caster.hpp>

#include "detail/obstacle_geometry.hpp"

namespace scantling::sim {
namespace {

constexpr double kUnitNormTolerance = 1e-6;  ///< as RayCaster's

[[noreturn]] void refuse(std::string_view prefix, std::string_view field, std::string_view value,
                         std::string_view expected) {
    throw ConfigError(fmt::format("{}.{} = {}, expected {}", prefix, field, value, expected));
}

void check_size(const MovingObstacle& o, std::string_view prefix) {
    if (o.shape == ObstacleShape::kSphere) {
        if (!(std::isfinite(o.radius_m) && o.radius_m > 0.0)) {
            refuse(prefix, "radius_m", fmt::format("{}", o.radius_m), "finite > 0");
        }
        return;
    }
    if (!(o.half_extents_m.allFinite() && o.half_extents_m.minCoeff() > 0.0)) {
        refuse(prefix, "half_extents_m",
               fmt::format("[{}, {}, {}]", o.half_extents_m.x(), o.half_extents_m.y(),
                           o.half_extents_m.z()),
               "each finite > 0");
    }
}

void check_waypoints(const std::vector<ObstacleWaypoint>& waypoints, std::string_view prefix) {
    if (waypoints.empty()) {
        throw ConfigError(fmt::format("{}.waypoints is empty, expected at least one", prefix));
    }
    for (std::size_t i = 0; i < waypoints.size(); ++i) {
        const std::string item = fmt::format("{}.waypoints[{}]", prefix, i);
        const ObstacleWaypoint& w = waypoints[i];
        if (!std::isfinite(w.t_s)) refuse(item, "t_s", fmt::format("{}", w.t_s), "finite");
        if (!w.xyz.allFinite()) throw ConfigError(item + ".xyz is not finite");
        if (i > 0 && !(w.t_s > waypoints[i - 1].t_s)) {
            refuse(item, "t_s", fmt::format("{}", w.t_s),
                   fmt::format("> {} (the previous waypoint's: times strictly increase)",
                               waypoints[i - 1].t_s));
        }
    }
}

/// InputError unless `t_s` is finite and the obstacle `name` has a waypoint (formatted only on
/// failure: this runs for every obstacle at every sensor firing).
void check_query(double t_s, const MovingObstacle& o) {
    if (!std::isfinite(t_s)) {
        throw InputError(
            fmt::format("moving obstacle '{}': t_s = {}, expected finite", o.name, t_s));
    }
    if (o.waypoints.empty()) {
        throw InputError(fmt::format("moving obstacle '{}' has no waypoints", o.name));
    }
}

/// Index of the first waypoint later than t_s (0: before all, size: at or after the last).
std::size_t segment_end(const std::vector<ObstacleWaypoint>& waypoints, double t_s) {
    const auto it = std::upper_bound(waypoints.begin(), waypoints.end(), t_s,
                                     [](double t, const ObstacleWaypoint& w) { return t < w.t_s; });
    return static_cast<std::size_t>(it - waypoints.begin());
}

void check_ray(const Eigen::Vector3d& origin, const Eigen::Vector3d& unit_direction,
               double min_range_m, double max_range_m) {
    if (!origin.allFinite()) throw InputError("moving obstacles: ray origin is not finite");
    const double norm = unit_direction.norm();
    if (!(std::abs(norm - 1.0) <= kUnitNormTolerance)) {
        throw InputError(fmt::format("moving obstacles: |direction| = {}, expected 1", norm));
    }
    if (!(min_range_m >= 0.0 && std::isfinite(min_range_m) && max_range_m > min_range_m)) {
        throw InputError(fmt::format(
            "moving obstacles: ranges [{}, {}], expected 0 <= min_range_m < max_range_m",
            min_range_m, max_range_m));
    }
}

}  // namespace

void MovingObstacle::validate(std::string_view prefix) const {
    if (name.empty()) throw ConfigError(fmt::format("{}.name is empty, expected a name", prefix));
    check_size(*this, prefix);
    check_waypoints(waypoints, prefix);
}

Eigen::Vector3d MovingObstacle::position_at(double t_s) const {
    check_query(t_s, *this);
    const std::size_t end = segment_end(waypoints, t_s);
    if (end == 0) return waypoints.front().xyz;
    if (end == waypoints.size()) return waypoints.back().xyz;
    const ObstacleWaypoint& a = waypoints[end - 1];
    const ObstacleWaypoint& b = waypoints[end];
    return a.xyz + (t_s - a.t_s) / (b.t_s - a.t_s) * (b.xyz - a.xyz);
}

Eigen::Vector3d MovingObstacle::velocity_at(double t_s) const {
    check_query(t_s, *this);
    const std::size_t end = segment_end(waypoints, t_s);
    if (end == 0 || end == waypoints.size()) return Eigen::Vector3d::Zero();
    const ObstacleWaypoint& a = waypoints[end - 1];
    const ObstacleWaypoint& b = waypoints[end];
    return (b.xyz - a.xyz) / (b.t_s - a.t_s);
}

double MovingObstacle::distance_m(const Eigen::Vector3d& p_world, double t_s) const {
    if (!p_world.allFinite()) throw InputError("moving obstacle distance: point is not finite");
    const Eigen::Vector3d centre = position_at(t_s);
    return shape == ObstacleShape::kSphere
               ? detail::sphere_distance_m(centre, radius_m, p_world)
               : detail::box_distance_m(centre, half_extents_m, p_world);
}

MovingObstacles::MovingObstacles(std::vector<MovingObstacle> obstacles)
    : obstacles_(std::move(obstacles)) {
    validate(obstacles_);
}

void MovingObstacles::validate(std::span<const MovingObstacle> obstacles,
                               std::string_view list_key) {
    std::set<std::string_view> names;
    for (std::size_t i = 0; i < obstacles.size(); ++i) {
        const std::string prefix = fmt::format("{}[{}]", list_key, i);
        obstacles[i].validate(prefix);
        if (!names.insert(obstacles[i].name).second) {
            refuse(prefix, "name", "'" + obstacles[i].name + "'", "unique among the obstacles");
        }
    }
}

std::optional<std::size_t> MovingObstacles::find(std::string_view name) const {
    for (std::size_t i = 0; i < obstacles_.size(); ++i) {
        if (obstacles_[i].name == name) return i;
    }
    return std::nullopt;
}

std::vector<Eigen::Vector3d> MovingObstacles::centres_at(double t_s) const {
    std::vector<Eigen::Vector3d> centres;
    centres.reserve(obstacles_.size());
    for (const MovingObstacle& o : obstacles_) centres.push_back(o.position_at(t_s));
    return centres;
}

std::optional<ObstacleHit> MovingObstacles::intersect(const Eigen::Vector3d& origin,
                                                      const Eigen::Vector3d& unit_direction,
                                                      double min_range_m, double max_range_m,
                                                      double t_s) const {
    check_ray(origin, unit_direction, min_range_m, max_range_m);
    return intersect_at(centres_at(t_s), origin, unit_direction, min_range_m, max_range_m);
}

std::optional<ObstacleHit> MovingObstacles::intersect_at(
    std::span<const Eigen::Vector3d> centres_world, const Eigen::Vector3d& origin,
    const Eigen::Vector3d& unit_direction, double min_range_m, double max_range_m) const {
    std::optional<ObstacleHit> nearest;
    for (std::size_t i = 0; i < obstacles_.size(); ++i) {
        const MovingObstacle& o = obstacles_[i];
        const double limit_m = nearest ? nearest->range_m : max_range_m;
        const std::optional<detail::ShapeHit> hit =
            o.shape == ObstacleShape::kSphere
                ? detail::intersect_sphere(centres_world[i], o.radius_m, origin, unit_direction,
                                           min_range_m, limit_m)
                : detail::intersect_box(centres_world[i], o.half_extents_m, origin, unit_direction,
                                        min_range_m, limit_m);
        // Strictly nearer only: ties go to the lowest index.
        if (hit && (!nearest || hit->range_m < nearest->range_m)) {
            nearest =
                ObstacleHit{hit->range_m, origin + hit->range_m * unit_direction, hit->normal, i};
        }
    }
    return nearest;
}

bool MovingObstacles::occluded(const Eigen::Vector3d& from, const Eigen::Vector3d& to,
                               double t_s) const {
    if (!from.allFinite() || !to.allFinite()) {
        throw InputError("moving obstacles: line-of-sight end point is not finite");
    }
    if (!std::isfinite(t_s)) {
        throw InputError(fmt::format("moving obstacles: t_s = {}, expected finite", t_s));
    }
    constexpr double kMargin_m = RayCaster::kLineOfSightMargin_m;
    const double length_m = (to - from).norm();
    if (empty() || length_m < 2.0 * kMargin_m) return false;
    return intersect_at(centres_at(t_s), from, (to - from) / length_m, kMargin_m,
                        length_m - kMargin_m)
        .has_value();
}

double MovingObstacles::distance_m(const Eigen::Vector3d& p_world, double t_s) const {
    double nearest_m = std::numeric_limits<double>::infinity();
    for (const MovingObstacle& o : obstacles_)
        nearest_m = std::min(nearest_m, o.distance_m(p_world, t_s));
    return nearest_m;
}

}  // namespace scantling::sim
