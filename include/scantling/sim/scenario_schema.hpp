#pragma once
/// @file
/// The YAML schema of a scenario (io::ConfigSchema): every key, its type, range and doc.
/// `scantling sim --describe`-style documentation comes from `scenario_schema().describe()`.
///
/// Besides the table-driven checks (unknown keys, wrong types, ranges: ParseError naming file,
/// line and key), `check_scenario_document` enforces what a table cannot: only the section of
/// the selected `type` may appear (`world.storage_tank` next to `type: cylinder` is an error),
/// sensor keys must apply to the sensor's type, and a preset must belong to the type.
///
/// Thread-safety: the schema is built once (function-local static) and immutable.

#include <scantling/io/config_node.hpp>
#include <scantling/io/config_schema.hpp>
#include <scantling/sim/scenario.hpp>

namespace scantling::sim {

/// The schema of the whole scenario document.
const io::ConfigSchema<Scenario>& scenario_schema();

/// Type-dependent checks of a parsed document (see the file comment). Throws ParseError
/// "<file>: line L: key 'sensors[1].columns': does not apply to type 'imu' ...".
void check_scenario_document(const io::ConfigNode& root);

namespace detail {
const io::ConfigSchema<WorldSpec>& world_spec_schema();
const io::ConfigSchema<VehicleSpec>& vehicle_spec_schema();
const io::ConfigSchema<SensorSpec>& sensor_spec_schema();
const io::ConfigSchema<PoseSpec>& pose_spec_schema();
}  // namespace detail

}  // namespace scantling::sim
