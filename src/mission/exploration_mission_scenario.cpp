// Exploration mission scenario files (exploration_mission.hpp).
#include <fmt/format.h>

#include <cmath>
#include <filesystem>

#include <scantling/control/config_yaml.hpp>
#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>
#include <scantling/io/config_node.hpp>
#include <scantling/io/config_schema.hpp>
#include <scantling/mission/exploration_mission.hpp>
#include <scantling/planning/config_yaml.hpp>
#include <scantling/safety/config_yaml.hpp>
#include <scantling/sim/scenario_schema.hpp>
#include <scantling/sim/sensor_configs.hpp>

#include "detail/config_nodes.hpp"
#include "detail/mission_schemas.hpp"

namespace scantling::mission {
namespace {

using detail::required;
using detail::without;

struct Bounds {
    Eigen::Vector3d min = Eigen::Vector3d::Zero();
    Eigen::Vector3d max = Eigen::Vector3d::Zero();
};

/// `mission:` of an exploration document.
struct ExploreMission {
    std::string type;
    Bounds bounds{};
    int record_depth_every = 25;
    double volume_every_s = 10.0;
};

const io::ConfigSchema<mapping::OccupancyOctreeConfig>& map_schema() {
    using S = mapping::OccupancyOctreeConfig;
    static const io::ConfigSchema<S> schema = [] {
        io::ConfigSchema<S> s;
        s.field("resolution_m", &S::resolution_m, "voxel edge, m", io::kPositive)
            .field("max_range_m", &S::max_range_m, "rays cut here clear free space only, m",
                   io::kPositive)
            .field("prob_hit", &S::prob_hit, "P(occupied | return)", io::kUnitInterval)
            .field("prob_miss", &S::prob_miss, "P(occupied | crossed)", io::kUnitInterval)
            .field("clamp_min", &S::clamp_min, "", io::kUnitInterval)
            .field("clamp_max", &S::clamp_max, "", io::kUnitInterval)
            .field("occupied_threshold", &S::occupied_threshold, "", io::kUnitInterval)
            .field("discretize", &S::discretize, "one ray per end voxel");
        return s;
    }();
    return schema;
}

const io::ConfigSchema<ExplorationStackConfig>& stack_schema() {
    using S = ExplorationStackConfig;
    static const io::ConfigSchema<S> schema = [] {
        io::ConfigSchema<S> s;
        s.field("vio_increment_sigma_m", &S::vio_increment_sigma_m, "m", io::kPositive)
            .field("vio_increment_sigma_rad", &S::vio_increment_sigma_rad, "rad", io::kPositive)
            .field("vio_period_s", &S::vio_period_s, "VIO sample period, s", io::kPositive)
            .field("vio_yaw_period_s", &S::vio_yaw_period_s, "VIO heading fused every, s",
                   io::kPositive)
            .field("barometer_sigma_m", &S::barometer_sigma_m, "m", io::kPositive)
            .section("map", &S::map, map_schema(), "the occupancy octree")
            .section("nbv", &S::nbv, planning::nbv_planner_config_schema(),
                     "the next-best-view planner")
            .field("collision_prevention", &S::collision_prevention, "SPEC §3 on the depth frames")
            .section("collision", &S::collision, safety::collision_prevention_schema())
            .field("obstacle_memory_s", &S::obstacle_memory_s, "depth frames kept, s",
                   io::kPositive)
            .field("max_travel_heading_error_rad", &S::max_travel_heading_error_rad,
                   "turn in place first beyond, rad", io::kPositive)
            .field("takeoff_height_m", &S::takeoff_height_m, "m", io::kPositive)
            .field("max_speed_mps", &S::max_speed_mps, "v_max, m/s", io::kPositive)
            .field("max_yaw_rate_radps", &S::max_yaw_rate_radps, "rad/s", io::kPositive)
            .field("goal_tolerance_m", &S::goal_tolerance_m, "m", io::kPositive)
            .field("yaw_tolerance_rad", &S::yaw_tolerance_rad, "rad", io::kPositive)
            .field("self_clearance_m", &S::self_clearance_m, "m", io::kNonNegative)
            .field("takeoff_clearance_m", &S::takeoff_clearance_m, "m", io::kNonNegative)
            .field("goal_timeout_s", &S::goal_timeout_s, "s", io::kPositive)
            .field("max_depth_age_s", &S::max_depth_age_s, "no plan on older depth, s",
                   io::kPositive)
            .field("depth_lost_abort_s", &S::depth_lost_abort_s, "abort after, s", io::kPositive)
            .field("exhausted_plans_to_finish", &S::exhausted_plans_to_finish,
                   "plans in a row without gain before done", io::kPositive)
            .field("max_failed_plans", &S::max_failed_plans, "failed plans in a row before stop",
                   io::kPositive)
            .field("max_nodes_when_exhausted", &S::max_nodes_when_exhausted,
                   "N_max: tree size after a plan without gain", io::kPositive);
        return s;
    }();
    return schema;
}

const io::ConfigSchema<detail::VehicleDocument<ExplorationStackConfig>>& document_schema() {
    static const auto schema = detail::vehicle_document_schema(stack_schema());
    return schema;
}

const io::ConfigSchema<Bounds>& bounds_schema() {
    static const io::ConfigSchema<Bounds> schema = [] {
        io::ConfigSchema<Bounds> s;
        s.field("min", &Bounds::min, "corner, world, m").field("max", &Bounds::max, "m");
        return s;
    }();
    return schema;
}

const io::ConfigSchema<ExploreMission>& mission_schema() {
    using S = ExploreMission;
    static const io::ConfigSchema<S> schema = [] {
        io::ConfigSchema<S> s;
        s.field("type", &S::type, "explore")
            .section("bounds", &S::bounds, bounds_schema(), "the exploration volume")
            .field("record_depth_every", &S::record_depth_every,
                   "one depth frame in this many is recorded (0: none)", io::kNonNegative)
            .field("volume_every_s", &S::volume_every_s, "explored-volume curve period, s",
                   io::kPositive);
        return s;
    }();
    return schema;
}

/// The robot knows its mounts and cameras; the planner sees what the depth camera sees, as far
/// as the map reaches, inside the mission's bounds.
void calibrate(ExplorationMissionScenario& m) {
    ExplorationStackConfig& s = m.stack;
    s.nbv.bounds_min_world_m = m.bounds_world.min();
    s.nbv.bounds_max_world_m = m.bounds_world.max();
    for (std::size_t i = 0; i < m.simulation.sensors.size(); ++i) {
        const sim::SensorSpec& spec = m.simulation.sensors[i];
        const std::string prefix = fmt::format("simulation.sensors[{}]", i);
        using T = sim::SensorType;
        if (spec.type == T::kImu) s.local_ekf.T_body_imu = spec.T_body_sensor.to_isometry();
        if (spec.type == T::kDepthCamera) {
            const sim::DepthCameraConfig depth = sim::detail::depth_config(spec, prefix);
            s.T_body_depth = depth.T_body_sensor;
            s.nbv.camera.horizontal_fov_rad = depth.intrinsics.hfov_rad();
            s.nbv.camera.vertical_fov_rad = depth.intrinsics.vfov_rad();
            s.nbv.camera.max_depth_m = s.map.max_range_m;
            s.nbv.p_body_camera_m = depth.T_body_sensor.translation();
            // The optical z axis in the body: the view's pitch (> 0 looking down).
            const Eigen::Vector3d z_body = depth.T_body_sensor.linear().col(2);
            s.nbv.camera_pitch_rad = std::atan2(-z_body.z(), z_body.x());
        }
        if (spec.type == T::kCamera) {
            const sim::PinholeCameraConfig camera = sim::detail::camera_config(spec, prefix);
            s.camera = camera.intrinsics;
            s.T_body_camera = camera.T_body_sensor;
        }
    }
}

ExplorationMissionScenario from_document(const io::ConfigNode& root, const std::string& name) {
    if (!root.is_map()) io::detail::fail(root, "", "expected a map (a mission scenario)");
    detail::VehicleDocument<ExplorationStackConfig> document;
    document_schema().apply(without(root, {"simulation", "mission", "operator"}), document);
    ExploreMission mission;
    const io::ConfigNode& mission_node = required(root, "mission");
    mission_schema().apply(mission_node, mission, "mission");
    if (mission.type != "explore") {
        io::detail::fail(mission_node, "mission.type",
                         fmt::format("'{}', expected explore", mission.type));
    }
    ExplorationMissionScenario m;
    detail::take_common(m, document, root, required(root, "simulation"), name);
    m.bounds_world = Eigen::AlignedBox3d(mission.bounds.min, mission.bounds.max);
    m.record_depth_every = mission.record_depth_every;
    m.volume_every_s = mission.volume_every_s;
    calibrate(m);
    m.validate();
    return m;
}

}  // namespace

void ExplorationMissionScenario::validate() const {
    simulation.validate("simulation");
    if (simulation.vehicle.type != sim::VehicleType::kMav) {
        throw ConfigError("simulation.vehicle.type: an explore mission needs the mav vehicle");
    }
    bool depth = false;
    for (const sim::SensorSpec& spec : simulation.sensors) {
        depth = depth || spec.type == sim::SensorType::kDepthCamera;
    }
    if (!depth) {
        throw ConfigError(
            "simulation.sensors: an explore mission needs a depth_camera (the map is built from "
            "its frames)");
    }
    config_checks::require(linger_s >= 0.0 && std::isfinite(linger_s), "", "linger_s", linger_s,
                           "finite >= 0");
    const bool box_ok = bounds_world.min().allFinite() && bounds_world.max().allFinite() &&
                        (bounds_world.max() - bounds_world.min()).minCoeff() > 0.0;
    if (!box_ok) {
        throw ConfigError(fmt::format(
            "mission.bounds: min [{:g}, {:g}, {:g}] max [{:g}, {:g}, {:g}], expected finite with "
            "max > min on every axis",
            bounds_world.min().x(), bounds_world.min().y(), bounds_world.min().z(),
            bounds_world.max().x(), bounds_world.max().y(), bounds_world.max().z()));
    }
    stack.validate("stack");
    // The ground truth's grid (one byte per voxel, twice) and the planner's samples span the
    // bounds: a hostile box must not ask for gigabytes.
    constexpr double kMaxVoxels = 5e7;
    const double voxels = (bounds_world.sizes() / stack.map.resolution_m).prod();
    if (stack.map.resolution_m > 0.0 && !(voxels <= kMaxVoxels)) {
        throw ConfigError(fmt::format(
            "mission.bounds: {:.3g} voxels at stack.map.resolution_m = {:g}, expected at most "
            "{:.0e} (a smaller volume or a coarser map)",
            voxels, stack.map.resolution_m, kMaxVoxels));
    }
    if (!bounds_world.contains(T_world_body_start().translation())) {
        throw ConfigError("start: the start position lies outside mission.bounds");
    }
    config_checks::require(record_depth_every >= 0, "mission", "record_depth_every",
                           record_depth_every, ">= 0");
    config_checks::require(volume_every_s > 0.0 && std::isfinite(volume_every_s), "mission",
                           "volume_every_s", volume_every_s, "finite > 0");
    for (std::size_t i = 0; i < faults.size(); ++i)
        faults[i].validate(fmt::format("faults[{}]", i));
}

bool is_exploration_mission_file(const std::string& path) {
    return detail::mission_type_of(path) == "explore";
}

ExplorationMissionScenario load_exploration_mission_scenario(
    const std::string& path, const std::vector<std::string>& overrides) {
    return detail::load_scenario(path, overrides, from_document);
}

ExplorationMissionScenario parse_exploration_mission_scenario(const std::string& yaml_text,
                                                              const std::string& name) {
    return detail::parse_scenario(yaml_text, name, from_document);
}

}  // namespace scantling::mission
