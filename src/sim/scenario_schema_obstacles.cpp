// Moving obstacles in a scenario (moving_obstacles.hpp): the schema of the section
// (scenario_schema.hpp) and the checks no key range expresses (detail/scenario_checks.hpp).
#include <scantling/sim/scenario_schema.hpp>

#include <fmt/format.h>

#include <string>
#include <utility>
#include <vector>

#include <scantling/core/error.hpp>

#include "detail/scenario_checks.hpp"

namespace scantling::sim::detail {
namespace {

using io::ConfigSchema;

const std::vector<std::pair<std::string, ObstacleShape>> kObstacleShapes{
    {"sphere", ObstacleShape::kSphere}, {"box", ObstacleShape::kBox}};

ConfigSchema<ObstacleWaypoint> obstacle_waypoint_schema() {
    ConfigSchema<ObstacleWaypoint> s;
    s.field("t_s", &ObstacleWaypoint::t_s, "simulated time; strictly increasing",
            up_to(limits::kMaxDuration_s))
        .field("xyz", &ObstacleWaypoint::xyz, "centre, world frame, m", kCoordinate);
    return s;
}

}  // namespace

const ConfigSchema<MovingObstacle>& moving_obstacle_schema() {
    static const ConfigSchema<MovingObstacle> schema = [] {
        using O = MovingObstacle;
        ConfigSchema<O> s;
        s.field("name", &O::name, "unique among the obstacles")
            .enum_field("shape", &O::shape, kObstacleShapes)
            .field("radius_m", &O::radius_m, "sphere", kExtent)
            .field("half_extents_m", &O::half_extents_m, "box: along world x, y, z", kExtent)
            .list("waypoints", &O::waypoints, obstacle_waypoint_schema(),
                  "centre path, linear in time; held before the first and after the last");
        return s;
    }();
    return schema;
}

void check_moving_obstacle(const io::ConfigNode& item, const std::string& path) {
    if (!item.is_map()) return;  // the schema reports it
    const io::ConfigNode* shape = item.find("shape");
    const std::string name = shape != nullptr && shape->is_scalar() ? shape->scalar : "sphere";
    const std::vector<std::pair<std::string, std::string>> size_keys{{"radius_m", "sphere"},
                                                                     {"half_extents_m", "box"}};
    for (const auto& [key, owner] : size_keys) {
        const io::ConfigNode* value = item.find(key);
        if (value != nullptr && owner != name && (name == "sphere" || name == "box")) {
            io::detail::fail(*value, io::detail::join_key(path, key),
                             "applies to shape '" + owner + "', but shape is '" + name + "'");
        }
    }
}

void check_moving_obstacles(const std::vector<MovingObstacle>& obstacles,
                            std::string_view list_key) {
    if (obstacles.size() > limits::kMaxMovingObstacles) {
        throw ConfigError(fmt::format("{} has {} obstacles, expected at most {}", list_key,
                                      obstacles.size(), limits::kMaxMovingObstacles));
    }
    for (std::size_t i = 0; i < obstacles.size(); ++i) {
        if (obstacles[i].waypoints.size() > limits::kMaxWaypoints) {
            throw ConfigError(fmt::format("{}[{}].waypoints has {} waypoints, expected at most {}",
                                          list_key, i, obstacles[i].waypoints.size(),
                                          limits::kMaxWaypoints));
        }
    }
    MovingObstacles::validate(obstacles, list_key);
}

}  // namespace scantling::sim::detail
