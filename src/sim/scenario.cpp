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
#include <scantling/sim/scenario_schema.hpp>

namespace scantling::sim {
namespace {

std::string key(std::string_view prefix, std::string_view field) {
    return prefix.empty() ? std::string(field) : std::string(prefix) + "." + std::string(field);
}

double deg_to_rad(double deg) { return deg * std::numbers::pi / 180.0; }

/// `path` relative to `base_directory` unless absolute (or no base is given).
std::string resolve_path(const std::string& path, const std::string& base_directory) {
    const std::filesystem::path file(path);
    if (path.empty() || file.is_absolute() || base_directory.empty()) return path;
    return (std::filesystem::path(base_directory) / file).string();
}

Scenario apply_document(const io::ConfigNode& root) {
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
    const std::string p = key(prefix, to_string(type));
    switch (type) {
        case WorldType::kBallastTankMockup:
            return ballast_tank_mockup.validate(p);
        case WorldType::kBallastTankLarge:
            return ballast_tank_large.validate(p);
        case WorldType::kStorageTank:
            return storage_tank.validate(p);
        case WorldType::kDistillationColumn:
            return distillation_column.validate(p);
        case WorldType::kCylinder:
            return cylinder.validate(p);
        case WorldType::kPlate:
            return plate.validate(p);
        case WorldType::kMesh:
            return mesh.validate(p);
        case WorldType::kShipHull:
            return ship_hull.validate(p);
        case WorldType::kMoebius:
            return moebius.validate(p);
        case WorldType::kShipHullMesh:
            return ship_hull_mesh.validate(p);
        case WorldType::kUrban:
            return urban.validate(p);
    }
}

void TrajectorySpec::validate(std::string_view prefix) const {
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
    if (!(rate_hz >= 0.0) || !std::isfinite(rate_hz)) {
        throw ConfigError(key(prefix, "rate_hz") + " = " + std::to_string(rate_hz) +
                          ", expected >= 0 (0 = the preset's rate)");
    }
    if (columns < 0 || width < 0 || height < 0 || num_beams < 0 || num_bins < 0 ||
        !(max_range_m >= 0.0)) {
        throw ConfigError(std::string(prefix) +
                          ": columns, width, height, num_beams, num_bins and max_range_m must be "
                          ">= 0");
    }
    if (type == SensorType::kUwb && anchors.empty()) {
        throw ConfigError(key(prefix, "anchors") + " is empty, expected at least one anchor");
    }
    if (!(ambient_light >= 0.0 && ambient_light <= 1.0)) {
        throw ConfigError(key(prefix, "ambient_light") + " = " + std::to_string(ambient_light) +
                          ", expected in [0, 1]");
    }
    if (motion_distortion && type != SensorType::kSpinningLidar) {
        throw ConfigError(key(prefix, "motion_distortion") + " applies to spinning_lidar only");
    }
}

void ExportSpec::validate(std::string_view prefix) const {
    if (!(map_spacing_m > 0.0)) {
        throw ConfigError(key(prefix, "map_spacing_m") + " = " + std::to_string(map_spacing_m) +
                          ", expected > 0");
    }
}

void Scenario::validate(std::string_view prefix) const {
    if (!(duration_s >= 0.0) || !std::isfinite(duration_s)) {
        throw ConfigError(key(prefix, "duration_s") + " = " + std::to_string(duration_s) +
                          ", expected >= 0");
    }
    if (!(dt_s > 0.0) || !(dt_s <= 1.0)) {
        throw ConfigError(key(prefix, "dt_s") + " = " + std::to_string(dt_s) +
                          ", expected in (0, 1]");
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

World build_world(const WorldSpec& spec, const std::string& base_directory) {
    switch (spec.type) {
        case WorldType::kBallastTankMockup:
            return build_ballast_tank_mockup(spec.ballast_tank_mockup);
        case WorldType::kBallastTankLarge:
            return build_ballast_tank_large(spec.ballast_tank_large);
        case WorldType::kStorageTank:
            return build_storage_tank(spec.storage_tank);
        case WorldType::kDistillationColumn:
            return build_distillation_column(spec.distillation_column);
        case WorldType::kCylinder:
            return build_cylinder(spec.cylinder);
        case WorldType::kPlate:
            return build_plate(spec.plate);
        case WorldType::kShipHull:
            return build_ship_hull(spec.ship_hull);
        case WorldType::kMoebius:
            return build_moebius(spec.moebius);
        case WorldType::kUrban:
            return build_urban(spec.urban);
        case WorldType::kShipHullMesh: {
            HullMeshDockConfig config = spec.ship_hull_mesh;
            config.path = resolve_path(config.path, base_directory);
            return build_hull_mesh_in_dock(config);
        }
        case WorldType::kMesh: {
            MeshWorldConfig config = spec.mesh;
            config.path = resolve_path(config.path, base_directory);
            return build_mesh_world(config);
        }
    }
    throw ConfigError("world.type: unknown value");
}

}  // namespace scantling::sim
