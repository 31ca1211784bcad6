// Mission scenario files (mission_scenario.hpp).
#include <scantling/mission/mission_scenario.hpp>

#include <fmt/format.h>

#include <filesystem>
#include <optional>
#include <string>

#include <scantling/control/config_yaml.hpp>
#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>
#include <scantling/io/config_node.hpp>
#include <scantling/io/config_schema.hpp>
#include <scantling/odometry/liodom.hpp>
#include <scantling/planning/config_yaml.hpp>
#include <scantling/safety/config_yaml.hpp>
#include <scantling/sim/scenario_schema.hpp>

#include "detail/config_nodes.hpp"
#include "detail/mission_schemas.hpp"

namespace scantling::mission {
namespace {

using detail::apply_override;
using detail::required;
using detail::without;

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
    std::vector<SensorFault> faults;
};

/// The global EKF's tuning (its anchors come from the simulated UWB: calibrate()).
const io::ConfigSchema<localization::GlobalEkfConfig>& global_ekf_schema() {
    using S = localization::GlobalEkfConfig;
    static const io::ConfigSchema<S> schema = [] {
        io::ConfigSchema<S> s;
        s.field("uwb_range_sigma_m", &S::uwb_range_sigma_m, "UWB range 1σ, m", io::kPositive)
            .field("uwb_gate_chi2", &S::uwb_gate_chi2, "χ² gate of one range", io::kPositive)
            .field("translation_random_walk_m_per_sqrt_s", &S::translation_random_walk_m_per_sqrt_s,
                   "T_world_odom drift, m/√s", io::kNonNegative)
            .field("yaw_random_walk_rad_per_sqrt_s", &S::yaw_random_walk_rad_per_sqrt_s,
                   "T_world_odom yaw drift, rad/√s", io::kNonNegative)
            .field("drift_velocity_random_walk_mps_per_sqrt_s",
                   &S::drift_velocity_random_walk_mps_per_sqrt_s,
                   "drift velocity random walk, m/s/√s", io::kNonNegative)
            .field("uwb_reacquire_window", &S::uwb_reacquire_window,
                   "ranges judged for re-acquisition (0: never)");
        return s;
    }();
    return schema;
}

const io::ConfigSchema<DroneStackConfig>& stack_schema() {
    using S = DroneStackConfig;
    static const io::ConfigSchema<S> schema = [] {
        io::ConfigSchema<S> s;
        s.field("odometry_sigma_m", &S::odometry_sigma_m,
                "point-to-line noise scaling LiODOM's information, m", io::kPositive)
            .field("odometry_min_sigma_m", &S::odometry_min_sigma_m,
                   "floor of one LiODOM increment's σ, m", io::kPositive)
            .field("odometry_lever_m", &S::odometry_lever_m, "m per rad when capping rotations",
                   io::kPositive)
            .field("barometer_sigma_m", &S::barometer_sigma_m, "barometer 1σ, m", io::kPositive)
            .field("collision_prevention", &S::collision_prevention, "SPEC §3 on the sweep")
            .section("collision", &S::collision, safety::collision_prevention_schema())
            .field("height_keeping", &S::height_keeping, "floor and ceiling clearance")
            .section("height", &S::height, safety::height_keeping_schema())
            .field("max_sweep_age_s", &S::max_sweep_age_s,
                   "older: no safety data, the LiDAR is lost, s", io::kPositive)
            .field("max_imu_age_s", &S::max_imu_age_s,
                   "IMU silent longer: the estimate is invalid, s", io::kPositive)
            .field("imu_coast_s", &S::imu_coast_s,
                   "after the IMU is lost, keep the last command this long, s", io::kNonNegative)
            .field("max_position_sigma_m", &S::max_position_sigma_m,
                   "larger horizontal σ: estimate invalid, hover, m", io::kPositive)
            .section("global_ekf", &S::global_ekf, global_ekf_schema())
            .section("manager", &S::manager, control::mission_manager_schema())
            .field("wind_compensation", &S::wind_compensation,
                   "disturbance observer under the safety layer")
            .section("wind", &S::wind, control::disturbance_observer_schema());
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
            .list("recorded_points", &S::recorded_points, recorded_point_schema())
            .list("faults", &S::faults, detail::fault_schema());
        return s;
    }();
    return schema;
}

/// The robot knows its own mounts and the surveyed UWB anchors.
void calibrate(MissionScenario& m) {
    m.stack.lidar_expected = false;
    for (const sim::SensorSpec& sensor : m.simulation.sensors) {
        if (sensor.type == sim::SensorType::kSpinningLidar) m.stack.lidar_expected = true;
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
    io::ConfigNode rest = without(root, {"simulation", "mission", "operator", "coverage"});
    // stack.odometry is LiODOM's own schema (with its presets), read over the stack's default.
    std::optional<io::ConfigNode> odometry;
    for (auto& [key, value] : rest.map) {
        if (key != "stack" || !value.is_map()) continue;
        if (const io::ConfigNode* node = value.find("odometry")) odometry = *node;
        value = without(value, {"odometry"});
    }
    document_schema().apply(rest, document);
    if (odometry) {
        document.stack.odometry =
            odometry::liodom_config_from_node(*odometry, document.stack.odometry);
    }
    MissionScenario m;
    m.name = document.name.empty() ? std::filesystem::path(name).stem().string() : document.name;
    m.description = document.description;
    m.simulation = sim::scenario_from_node(required(root, "simulation"), "simulation");
    m.start = document.start;
    m.floor_height_m = document.floor_height_m;
    m.linger_s = document.linger_s;
    m.stack = document.stack;
    m.faults = document.faults;
    planning::MissionContext context;
    for (const RecordedPointSpec& point : document.recorded_points) {
        context.recorded_points.record(point.name, {.p_world_m = point.position_m, .yaw_rad = {}});
    }
    context.p_takeoff_world_m = m.start.xyz;
    m.path = planning::mission_from_yaml(required(root, "mission"), context, "mission");
    if (const io::ConfigNode* script = root.find("operator")) {
        m.operator_script = control::operator_script_from_yaml(*script, "operator").commands();
    }
    if (const io::ConfigNode* coverage = root.find("coverage")) {
        std::optional<planning::WallRectangle> mission_rectangle;
        if (const io::ConfigNode* r = required(root, "mission").find("rectangle")) {
            mission_rectangle.emplace();
            planning::wall_rectangle_schema().apply(*r, *mission_rectangle);
        }
        m.coverage = coverage_from_yaml(*coverage, mission_rectangle, "the mission has none");
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
    for (std::size_t i = 0; i < faults.size(); ++i)
        faults[i].validate(fmt::format("faults[{}]", i));
    if (coverage) coverage->validate("coverage");
}

MissionScenario load_mission_scenario(const std::string& path,
                                      const std::vector<std::string>& overrides) {
    return detail::load_scenario(path, overrides, from_document);
}

MissionScenario parse_mission_scenario(const std::string& yaml_text, const std::string& name) {
    return detail::parse_scenario(yaml_text, name, from_document);
}

}  // namespace scantling::mission
