#pragma once
// Scenario checks that a key range cannot express (scenario_world_size.cpp,
// scenario_schema_obstacles.cpp).

#include <string_view>
#include <vector>

#include <scantling/sim/scenario.hpp>

namespace scantling::sim::detail {

/// Throws ConfigError naming the keys whose product sizes the world mesh (storage-tank
/// courses x segments, Moebius segments, urban facade windows) when it exceeds
/// limits::kMaxWorldElements, more than limits::kMaxSurfaceObstacles obstacles and plate holes,
/// and a plate stiffener spacing that is neither 0 nor at least
/// limits::kMinStructureSpacing_m. Call after the world's own validate().
void check_world_size(const WorldSpec& spec, std::string_view prefix);

/// Throws ConfigError for more than limits::kMaxMovingObstacles obstacles (each is tested
/// against every ray), more than limits::kMaxWaypoints waypoints in one, or an invalid or
/// repeated obstacle (MovingObstacles::validate, items named "<list_key>[i]").
void check_moving_obstacles(const std::vector<MovingObstacle>& obstacles,
                            std::string_view list_key);

}  // namespace scantling::sim::detail
