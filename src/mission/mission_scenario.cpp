// Mission scenario files (mission_scenario.hpp).
#include <scantling/mission/mission_scenario.hpp>

#include <filesystem>
#include <string>

#include <scantling/control/config_yaml.hpp>
#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>
#include <scantling/io/config_node.hpp>
#include <scantling/io/config_schema.hpp>
#include <scantling/planning/config_yaml.hpp>
#include <scantling/safety/config_yaml.hpp>
#include <scantling/sim/scenario_schema.hpp>

namespace scantling::mission {
namespace {

/// A recorded point of the scenario (`recorded_points:`), for `mission: {type: goto}`.
struct RecordedPointSpec {
    std::string name;
    Eigen::Vector3d position_m = Eigen::Vector3d::Zero();
};

/// What the table-driven schema reads; `simulation`, `mission`, `operator` and
/// `recorded_points` are read by their own readers.
struct MissionDocument {
    std::string name;
    std::string description;
    sim::PoseSpec start{};
    double floor_height_m = 0.0;
    double linger_s = 1.0;
    DroneStackConfig stack{};
    std::vector<RecordedPointSpec> recorded_points;
};

const io::ConfigSchema<DroneStackConfig>& stack_schema() {
    using S = DroneStackConfig;
    static const io::ConfigSchema<S> schema = [] {
        io::ConfigSchema<S> s;
        s.field("odometry_sigma_m", &S::odometry_sigma_m,
                "point-to-line noise scaling LiODOM's information, m", io::kPositive)
            .field("barometer_sigma_m", &S::barometer_sigma_m, "barometer 1σ, m", io::kPositive)
            .field("collision_prevention", &S::collision_prevention, "SPEC §3 on the sweep")
            .section("collision", &S::collision, safety::collision_prevention_schema())
            .field("height_keeping", &S::height_keeping, "floor and ceiling clearance")
            .section("height", &S::height, safety::height_keeping_schema())
            .field("max_sweep_age_s", &S::max_sweep_age_s, "older: no safety data, s",
                   io::kPositive)
            .field("max_position_sigma_m", &S::max_position_sigma_m,
                   "larger horizontal σ: estimate invalid, hover, m", io::kPositive)
            .section("manager", &S::manager, control::mission_manager_schema());
        return s;
    }();
    return schema;
}

const io::ConfigSchema<RecordedPointSpec>& recorded_point_schema() {
    using S = RecordedPointSpec;
    static const io::ConfigSchema<S> schema = [] {
        io::ConfigSchema<S> s;
        s.field("name", &S::name, "name the goto mission uses")
            .field("position_m", &S::position_m, "world frame, m");
        return s;
    }();
    return schema;
}

const io::ConfigSchema<MissionDocument>& document_schema() {
    using S = MissionDocument;
    static const io::ConfigSchema<S> schema = [] {
        io::ConfigSchema<S> s;
        s.field("name", &S::name, "default: the file's stem")
            .field("description", &S::description)
            .section("start", &S::start, sim::detail::pose_spec_schema(), "start pose, world")
            .field("floor_height_m", &S::floor_height_m, "world z of the floor")
            .field("linger_s", &S::linger_s, "simulated after the end, s", io::Range{.min = 0.0})
            .section("stack", &S::stack, stack_schema())
            .list("recorded_points", &S::recorded_points, recorded_point_schema());
        return s;
    }();
    return schema;
}

/// The root map without the keys read by their own readers.
io::ConfigNode without(const io::ConfigNode& root, std::initializer_list<std::string_view> keys) {
    io::ConfigNode rest = root;
    std::erase_if(rest.map, [&keys](const auto& entry) {
        return std::find(keys.begin(), keys.end(), entry.first) != keys.end();
    });
    return rest;
}

const io::ConfigNode& required(const io::ConfigNode& root, std::string_view key) {
    const io::ConfigNode* node = root.find(key);
    if (node == nullptr) {
        io::detail::fail(root, "", "missing key '" + std::string(key) + "'");
    }
    return *node;
}

/// The robot knows its own mounts and the surveyed UWB anchors.
void calibrate(MissionScenario& m) {
    for (const sim::SensorSpec& sensor : m.simulation.sensors) {
        const Eigen::Isometry3d mount = sensor.T_body_sensor.to_isometry();
        if (sensor.type == sim::SensorType::kSpinningLidar) m.stack.T_body_lidar = mount;
        if (sensor.type == sim::SensorType::kImu) m.stack.local_ekf.T_body_imu = mount;
        if (sensor.type == sim::SensorType::kRangeFinder) {
            // The simulated ranger's beam is its +x axis, the EKF's ray its +z: turn the frame
            // by +90° about y (which takes z onto x) so that both describe the same beam.
            m.stack.local_ekf.T_body_sensor =
                mount * Eigen::AngleAxisd(M_PI / 2.0, Eigen::Vector3d::UnitY());
        }
        for (const sim::UwbAnchor& anchor : sensor.anchors) {
            m.stack.global_ekf.uwb_anchors_world_m[anchor.id] = anchor.position_world;
        }
        if (sensor.type == sim::SensorType::kUwb) {
            m.stack.global_ekf.p_body_uwb_tag_m = mount.translation();
        }
    }
    m.stack.local_ekf.floor_height_m = m.floor_height_m - m.start.xyz.z();
}

MissionScenario from_document(const io::ConfigNode& root, const std::string& name) {
    if (!root.is_map()) io::detail::fail(root, "", "expected a map (a mission scenario)");
    MissionDocument document;
    document_schema().apply(without(root, {"simulation", "mission", "operator"}), document);
    MissionScenario m;
    m.name = document.name.empty() ? std::filesystem::path(name).stem().string() : document.name;
    m.description = document.description;
    m.simulation = sim::scenario_from_node(required(root, "simulation"), "simulation");
    m.start = document.start;
    m.floor_height_m = document.floor_height_m;
    m.linger_s = document.linger_s;
    m.stack = document.stack;
    planning::MissionContext context;
    for (const RecordedPointSpec& point : document.recorded_points) {
        context.recorded_points.record(point.name, {.p_world_m = point.position_m, .yaw_rad = {}});
    }
    context.p_takeoff_world_m = m.start.xyz;
    m.path = planning::mission_from_yaml(required(root, "mission"), context, "mission");
    if (const io::ConfigNode* script = root.find("operator")) {
        m.operator_script = control::operator_script_from_yaml(*script, "operator").commands();
    }
    calibrate(m);
    m.validate();
    return m;
}

}  // namespace

void MissionScenario::validate() const {
    simulation.validate("simulation");
    config_checks::require(linger_s >= 0.0 && std::isfinite(linger_s), "", "linger_s", linger_s,
                           "finite >= 0");
    stack.validate("stack");
    planning::validate(path, "mission");
}

MissionScenario load_mission_scenario(const std::string& path) {
    MissionScenario m = from_document(io::parse_yaml_file(path), path);
    m.simulation.base_directory = std::filesystem::path(path).parent_path().string();
    if (m.simulation.name.empty()) m.simulation.name = m.name;
    return m;
}

MissionScenario parse_mission_scenario(const std::string& yaml_text, const std::string& name) {
    MissionScenario m = from_document(io::parse_yaml_string(yaml_text, name), name);
    if (m.simulation.name.empty()) m.simulation.name = m.name;
    return m;
}

}  // namespace scantling::mission
