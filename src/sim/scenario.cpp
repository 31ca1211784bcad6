// Scenario validation, loading and the world / trajectory factories (scenario.hpp).
#include <scantling/sim/scenario.hpp>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <set>
#include <string>

#include <scantling/core/error.hpp>
#include <scantling/core/se3.hpp>
#include <scantling/io/config_node.hpp>
#include <scantling/sim/scenario_estimate.hpp>
#include <scantling/sim/scenario_limits.hpp>
#include <scantling/sim/scenario_schema.hpp>

#include "detail/scenario_checks.hpp"

#include <fmt/format.h>

namespace scantling::sim {
namespace {

std::string key(std::string_view prefix, std::string_view field) {
    return prefix.empty() ? std::string(field) : std::string(prefix) + "." + std::string(field);
}

double deg_to_rad(double deg) { return deg * std::numbers::pi / 180.0; }

/// ConfigError "<prefix>.<field> = <value>, expected <expected>".
[[noreturn]] void refuse(std::string_view prefix, std::string_view field, double value,
                         std::string_view expected) {
    throw ConfigError(fmt::format("{} = {}, expected {}", key(prefix, field), value, expected));
}

/// A size key: 0 (the model's default) up to `max`.
void check_size(std::string_view prefix, std::string_view field, double value, double max) {
    if (!(value >= 0.0 && value <= max)) {
        refuse(prefix, field, value, fmt::format("in [0, {}] (0 = the model's)", max));
    }
}

/// The clock fires each sensor at most once per tick: a faster sensor would be recorded at
/// 1 / dt_s while summary.json states its rate.
void check_clock(const Scenario& s, const RecordingEstimate& estimate, std::string_view prefix) {
    for (std::size_t i = 0; i < estimate.sensors.size(); ++i) {
        const SensorOutputEstimate& sensor = estimate.sensors[i];
        if (sensor.rate_hz * s.dt_s <= 1.0 + 1e-9) continue;
        const char* preset = s.sensors[i].rate_hz > 0.0 ? "" : " (the preset's rate)";
        throw ConfigError(fmt::format(
            "{}.rate_hz = {:g} Hz{}, more than the simulation clock's 1 / dt_s = {:g} Hz (dt_s = "
            "{}): a sensor fires at most once per tick; lower rate_hz or dt_s",
            key(prefix, sensor.key), sensor.rate_hz, preset, 1.0 / s.dt_s, s.dt_s));
    }
}

/// Duration and tick count: the state of every tick is held in memory. duration_s 0 takes the
/// trajectory's duration, which no key range bounds.
void check_ticks(const Scenario& s, const RecordingEstimate& estimate, std::string_view prefix) {
    const std::string source = s.duration_s > 0.0 ? key(prefix, "duration_s")
                                                  : key(prefix, "vehicle.trajectory") + " duration";
    if (!(estimate.duration_s <= limits::kMaxDuration_s)) {
        throw ConfigError(fmt::format("{} = {} s, expected <= {} s", source, estimate.duration_s,
                                      limits::kMaxDuration_s));
    }
    if (estimate.ticks > limits::kMaxTicks) {
        throw ConfigError(fmt::format(
            "{} / dt_s = {} s / {} s = {} clock ticks, expected <= {} (the state of every tick "
            "is held in memory); raise dt_s or shorten the run",
            source, estimate.duration_s, s.dt_s, estimate.ticks, limits::kMaxTicks));
    }
}

/// The section of the selected world type.
void validate_section(const WorldSpec& w, const std::string& p) {
    switch (w.type) {
        case WorldType::kBallastTankMockup:
            return w.ballast_tank_mockup.validate(p);
        case WorldType::kBallastTankLarge:
            return w.ballast_tank_large.validate(p);
        case WorldType::kStorageTank:
            return w.storage_tank.validate(p);
        case WorldType::kDistillationColumn:
            return w.distillation_column.validate(p);
        case WorldType::kCylinder:
            return w.cylinder.validate(p);
        case WorldType::kPlate:
            return w.plate.validate(p);
        case WorldType::kMesh:
            return w.mesh.validate(p);
        case WorldType::kShipHull:
            return w.ship_hull.validate(p);
        case WorldType::kMoebius:
            return w.moebius.validate(p);
        case WorldType::kShipHullMesh:
            return w.ship_hull_mesh.validate(p);
        case WorldType::kUrban:
            return w.urban.validate(p);
    }
}

Scenario apply_document(const io::ConfigNode& root) {
    if (root.is_null()) {
        io::detail::fail(root, "",
                         "the scenario is empty, expected a map with keys " +
                             io::detail::join_names(scenario_schema().keys()));
    }
    check_scenario_document(root);
    Scenario scenario;
    scenario_schema().apply(root, scenario);
    return scenario;
}

}  // namespace

Eigen::Isometry3d PoseSpec::to_isometry() const {
    return make_isometry(rotation_from_euler_zyx(deg_to_rad(rpy_deg.x()), deg_to_rad(rpy_deg.y()),
                                                 deg_to_rad(rpy_deg.z())),
                         xyz);
}

void WorldSpec::validate(std::string_view prefix) const {
    validate_section(*this, key(prefix, to_string(type)));
    detail::check_world_size(*this, prefix);
    validate_surface_obstacles(obstacles, key(prefix, "obstacles"));
}

void TrajectorySpec::validate(std::string_view prefix) const {
    if (waypoints.waypoints.size() > limits::kMaxWaypoints) {
        refuse(key(prefix, "waypoints"), "waypoints",
               static_cast<double>(waypoints.waypoints.size()),
               fmt::format("at most {} waypoints", limits::kMaxWaypoints));
    }
    switch (type) {
        case TrajectoryType::kWaypoints:
            return waypoints.validate(key(prefix, "waypoints"));
        case TrajectoryType::kHelix:
            return helix.validate(key(prefix, "helix"));
        case TrajectoryType::kOrbit:
            return orbit.validate(key(prefix, "orbit"));
        case TrajectoryType::kLawnmower: {
            LawnmowerTrajectoryConfig config = lawnmower;
            config.T_world_wall = lawnmower.wall.to_isometry();
            return config.validate(key(prefix, "lawnmower"));
        }
    }
}

std::unique_ptr<Trajectory> make_trajectory(const TrajectorySpec& spec) {
    switch (spec.type) {
        case TrajectoryType::kWaypoints:
            return std::make_unique<WaypointTrajectory>(spec.waypoints);
        case TrajectoryType::kHelix:
            return std::make_unique<HelixTrajectory>(spec.helix);
        case TrajectoryType::kOrbit:
            return std::make_unique<OrbitTrajectory>(spec.orbit);
        case TrajectoryType::kLawnmower: {
            LawnmowerTrajectoryConfig config = spec.lawnmower;
            config.T_world_wall = spec.lawnmower.wall.to_isometry();
            return std::make_unique<LawnmowerTrajectory>(config);
        }
    }
    throw ConfigError("trajectory.type: unknown value");
}

void VehicleSpec::validate(std::string_view prefix) const {
    trajectory.validate(key(prefix, "trajectory"));
    if (type == VehicleType::kMav) mav.validate(key(prefix, "mav"));
    if (type == VehicleType::kRov) rov.validate(key(prefix, "rov"));
    if (type == VehicleType::kCrawler) crawler.validate(key(prefix, "crawler"));
    if (type == VehicleType::kLegged) legged.validate(key(prefix, "legged"));
    if (!(position_gain_per_s > 0.0)) {
        throw ConfigError(key(prefix, "position_gain_per_s") + " = " +
                          std::to_string(position_gain_per_s) + ", expected > 0");
    }
}

void SensorSpec::validate(std::string_view prefix) const {
    if (!(rate_hz == 0.0 || (rate_hz >= limits::kMinRate_hz && rate_hz <= limits::kMaxRate_hz))) {
        refuse(prefix, "rate_hz", rate_hz,
               fmt::format("0 (the preset's rate) or in [{}, {}] Hz", limits::kMinRate_hz,
                           limits::kMaxRate_hz));
    }
    check_size(prefix, "columns", columns, limits::kMaxLidarColumns);
    check_size(prefix, "width", width, limits::kMaxImageSide_px);
    check_size(prefix, "height", height, limits::kMaxImageSide_px);
    check_size(prefix, "num_beams", num_beams, limits::kMaxSonarBeams);
    check_size(prefix, "num_bins", num_bins, limits::kMaxSonarBins);
    check_size(prefix, "max_range_m", max_range_m, limits::kMaxSensorRange_m);
    if (type == SensorType::kUwb && anchors.empty()) {
        throw ConfigError(key(prefix, "anchors") + " is empty, expected at least one anchor");
    }
    if (anchors.size() > limits::kMaxUwbAnchors) {
        refuse(prefix, "anchors", static_cast<double>(anchors.size()),
               fmt::format("at most {} anchors", limits::kMaxUwbAnchors));
    }
    if (!(ambient_light >= 0.0 && ambient_light <= 1.0)) {
        refuse(prefix, "ambient_light", ambient_light, "in [0, 1]");
    }
    if (motion_distortion && type != SensorType::kSpinningLidar) {
        throw ConfigError(key(prefix, "motion_distortion") + " applies to spinning_lidar only");
    }
}

void ExportSpec::validate(std::string_view prefix) const {
    if (!(std::isfinite(map_spacing_m) && map_spacing_m >= limits::kMinMapSpacing_m)) {
        refuse(prefix, "map_spacing_m", map_spacing_m,
               fmt::format(">= {} m", limits::kMinMapSpacing_m));
    }
}

void Scenario::validate(std::string_view prefix) const {
    if (!(duration_s >= 0.0 && duration_s <= limits::kMaxDuration_s)) {
        refuse(prefix, "duration_s", duration_s,
               fmt::format("in [0, {}] s (0 = the trajectory's)", limits::kMaxDuration_s));
    }
    if (!(dt_s >= limits::kMinDt_s && dt_s <= limits::kMaxDt_s)) {
        refuse(prefix, "dt_s", dt_s,
               fmt::format("in [{}, {}] s", limits::kMinDt_s, limits::kMaxDt_s));
    }
    world.validate(key(prefix, "world"));
    vehicle.validate(key(prefix, "vehicle"));
    std::set<SensorType> seen;
    for (std::size_t i = 0; i < sensors.size(); ++i) {
        const std::string p = key(prefix, "sensors[" + std::to_string(i) + "]");
        sensors[i].validate(p);
        if (!seen.insert(sensors[i].type).second) {
            throw ConfigError(p + ".type = " + std::string(to_string(sensors[i].type)) +
                              ", expected at most one sensor of each type");
        }
    }
    export_world.validate(key(prefix, "export"));
    parallel.validate(key(prefix, "parallel"));
    detail::check_moving_obstacles(moving_obstacles, key(prefix, "moving_obstacles"));
    // Builds each sensor's effective config (the runner's): its rate and frame size.
    const RecordingEstimate estimate = estimate_recording(*this);
    check_clock(*this, estimate, prefix);
    check_ticks(*this, estimate, prefix);
    check_recording_estimate(estimate);
}

Scenario scenario_from_node(const io::ConfigNode& node, const std::string& prefix) {
    if (!node.is_map()) io::detail::fail(node, prefix, "expected a map (a scenario)");
    check_scenario_document(node);
    Scenario scenario;
    scenario_schema().apply(node, scenario, prefix);
    return scenario;
}

Scenario load_scenario(const std::string& path) {
    Scenario scenario = apply_document(io::parse_yaml_file(path));
    const std::filesystem::path file(path);
    if (scenario.name.empty()) scenario.name = file.stem().string();
    scenario.base_directory = file.parent_path().string();
    return scenario;
}

Scenario parse_scenario(const std::string& yaml_text, const std::string& name) {
    Scenario scenario = apply_document(io::parse_yaml_string(yaml_text, name));
    if (scenario.name.empty()) scenario.name = std::filesystem::path(name).stem().string();
    return scenario;
}

}  // namespace scantling::sim
