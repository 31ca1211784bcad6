#pragma once
// YAML schemas the mission readers share (mission_scenario.cpp for the drone, and the ROV's,
// the crawler's and the exploring drone's readers), written once.
#include <string>
#include <vector>

#include <filesystem>

#include <scantling/control/config_yaml.hpp>
#include <scantling/io/config_node.hpp>
#include <scantling/io/config_schema.hpp>
#include <scantling/mission/fault_injection.hpp>
#include <scantling/perception/camera_coverage.hpp>
#include <scantling/sim/scenario.hpp>
#include <scantling/sim/scenario_schema.hpp>

namespace scantling::mission::detail {

/// One entry of `faults:` (fault_injection.hpp). Defined in fault_injection.cpp.
const io::ConfigSchema<SensorFault>& fault_schema();

/// The grid and view limits of a camera coverage (perception/camera_coverage.hpp): the drone's
/// `coverage:` figure and the ROV stack's believed coverage. Defined in coverage_spec.cpp.
const io::ConfigSchema<perception::CameraCoverageConfig>& camera_coverage_config_schema();

/// What the table-driven schema reads of a vehicle's mission document (the ROV's, the
/// crawler's, the exploring drone's): the keys they share and the vehicle's stack.
/// `simulation`, `mission`, `operator` and a vehicle's own sections have their own readers.
template <class Stack>
struct VehicleDocument {
    std::string name;
    std::string description;
    sim::PoseSpec start{};
    double linger_s = 1.0;
    Stack stack{};
    std::vector<SensorFault> faults;
};

/// The schema of VehicleDocument<Stack>, with `stack:` read by `stack_schema`.
template <class Stack>
io::ConfigSchema<VehicleDocument<Stack>> vehicle_document_schema(
    const io::ConfigSchema<Stack>& stack_schema) {
    using S = VehicleDocument<Stack>;
    io::ConfigSchema<S> s;
    s.field("name", &S::name, "default: the file's stem")
        .field("description", &S::description)
        .section("start", &S::start, sim::detail::pose_spec_schema(), "start pose, world")
        .field("linger_s", &S::linger_s, "simulated after the end, s", io::kNonNegative)
        .section("stack", &S::stack, stack_schema)
        .list("faults", &S::faults, fault_schema());
    return s;
}

/// Copies what every vehicle's scenario takes from its document into `m`: the name (default:
/// the file's stem), description, the simulation (`root.simulation`), start, linger_s, the
/// stack, the faults and the operator script (`root.operator`, if any).
template <class Scenario, class Stack>
void take_common(Scenario& m, const VehicleDocument<Stack>& document, const io::ConfigNode& root,
                 const io::ConfigNode& simulation, const std::string& name) {
    m.name = document.name.empty() ? std::filesystem::path(name).stem().string() : document.name;
    m.description = document.description;
    m.simulation = sim::scenario_from_node(simulation, "simulation");
    m.start = document.start;
    m.linger_s = document.linger_s;
    m.stack = document.stack;
    m.faults = document.faults;
    if (const io::ConfigNode* script = root.find("operator")) {
        m.operator_script = control::operator_script_from_yaml(*script, "operator").commands();
    }
}

}  // namespace scantling::mission::detail
