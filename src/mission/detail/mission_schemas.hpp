#pragma once
// YAML schemas both mission readers use (mission_scenario.cpp for the drone, rov_mission_scenario
// .cpp for the ROV), written once.
#include <scantling/io/config_schema.hpp>
#include <scantling/mission/fault_injection.hpp>
#include <scantling/perception/camera_coverage.hpp>

namespace scantling::mission::detail {

/// One entry of `faults:` (fault_injection.hpp). Defined in fault_injection.cpp.
const io::ConfigSchema<SensorFault>& fault_schema();

/// The grid and view limits of a camera coverage (perception/camera_coverage.hpp): the drone's
/// `coverage:` figure and the ROV stack's believed coverage. Defined in coverage_spec.cpp.
const io::ConfigSchema<perception::CameraCoverageConfig>& camera_coverage_config_schema();

}  // namespace scantling::mission::detail
