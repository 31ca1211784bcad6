#pragma once
/// @file
/// The YAML schema of a scenario (io::ConfigSchema): every key, its type, range and doc.
/// `scantling sim --describe`-style documentation comes from `scenario_schema().describe()`.
///
/// Every key that sizes the run (durations, rates, image sizes, world extents, counts,
/// spacings) has a range bounded by scenario_limits.hpp, so an absurd value is a ParseError
/// naming the file, line, key and bound before anything is built.
///
/// Besides the table-driven checks (unknown keys, wrong types, ranges: ParseError naming file,
/// line and key), `check_scenario_document` enforces what a table cannot: only the section of
/// the selected `type` may appear (`world.storage_tank` next to `type: cylinder` is an error),
/// sensor keys must apply to the sensor's type, a preset must belong to the type, and a moving
/// obstacle's size key must match its shape (`radius_m` for a sphere, `half_extents_m` for a box).
///
/// Thread-safety: the schema is built once (function-local static) and immutable.

#include <string>
#include <utility>
#include <vector>

#include <scantling/io/config_node.hpp>
#include <scantling/io/config_schema.hpp>
#include <scantling/sim/scenario.hpp>
#include <scantling/sim/scenario_limits.hpp>

namespace scantling::sim {

/// The schema of the whole scenario document.
const io::ConfigSchema<Scenario>& scenario_schema();

/// Type-dependent checks of a parsed document (see the file comment). Throws ParseError
/// "<file>: line L: key 'sensors[1].columns': does not apply to type 'imu' ...".
void check_scenario_document(const io::ConfigNode& root);

/// A scenario from a parsed document or sub-document (a mission's `simulation:`), with both
/// checks above; key paths in messages start with `prefix` ("simulation.dt_s"). Not validated
/// as a whole (Scenario::validate); `name` and `base_directory` are left to the caller.
Scenario scenario_from_node(const io::ConfigNode& node, const std::string& prefix = "");

namespace detail {

/// [0, max]: a size where 0 means the model's default, or a non-negative bounded value.
constexpr io::Range up_to(double max) { return io::Range{.min = 0.0, .max = max}; }
/// (0, max]: a length, radius or rate bounded by scenario_limits.hpp.
constexpr io::Range positive_up_to(double max) {
    return io::Range{.min = 0.0, .min_exclusive = true, .max = max};
}
/// [min, max]: a count or a spacing with a floor.
constexpr io::Range between(double min, double max) { return io::Range{.min = min, .max = max}; }
/// A world extent (length, width, height, radius, diameter, margin): (0, kMaxWorldExtent_m].
inline constexpr io::Range kExtent = positive_up_to(limits::kMaxWorldExtent_m);
/// A spacing of repeated structure: [kMinStructureSpacing_m, kMaxWorldExtent_m].
inline constexpr io::Range kSpacing =
    between(limits::kMinStructureSpacing_m, limits::kMaxWorldExtent_m);
/// A coordinate: [-kMaxCoordinate_m, kMaxCoordinate_m] (every element of a vector).
inline constexpr io::Range kCoordinate =
    between(-limits::kMaxCoordinate_m, limits::kMaxCoordinate_m);

const io::ConfigSchema<WorldSpec>& world_spec_schema();
/// `world.ship_hull.appendages` (scenario_schema_appendages.cpp).
io::ConfigSchema<HullAppendagesConfig> hull_appendages_schema();
const io::ConfigSchema<VehicleSpec>& vehicle_spec_schema();
const io::ConfigSchema<SensorSpec>& sensor_spec_schema();
const io::ConfigSchema<PoseSpec>& pose_spec_schema();
/// Every sensor type with its YAML name (`type:` of a sensor; a mission's `faults[].sensor`).
const std::vector<std::pair<std::string, SensorType>>& sensor_type_choices();
const io::ConfigSchema<MovingObstacle>& moving_obstacle_schema();
/// ParseError for a size key of the other shape ("moving_obstacles[0].half_extents_m: does not
/// apply to shape 'sphere'").
void check_moving_obstacle(const io::ConfigNode& item, const std::string& path);
/// `world.plate.holes[i]` and `world.obstacles[i]` (scenario_schema_surface_obstacles.cpp).
io::ConfigSchema<PlateHoleConfig> plate_hole_schema();
const io::ConfigSchema<SurfaceObstacleConfig>& surface_obstacle_schema();
/// ParseError for a missing `kind`, a missing required key of the kind, or a key of another kind
/// ("world.obstacles[0].size_m: does not apply to kind 'bolt'").
void check_surface_obstacle(const io::ConfigNode& item, const std::string& path);
}  // namespace detail

}  // namespace scantling::sim
