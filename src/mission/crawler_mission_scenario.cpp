// Crawler mission scenario files (crawler_mission.hpp).
#include <scantling/mission/crawler_mission.hpp>

#include <fmt/format.h>

#include <cmath>
#include <filesystem>

#include <scantling/control/config_yaml.hpp>
#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>
#include <scantling/io/config_node.hpp>
#include <scantling/io/config_schema.hpp>
#include <scantling/sim/scenario_schema.hpp>
#include <scantling/sim/sensor_configs.hpp>

#include "detail/config_nodes.hpp"
#include "detail/crawler_task_document.hpp"
#include "detail/mission_schemas.hpp"

namespace scantling::mission {
namespace {

using detail::required;
using detail::without;

/// `texture_map:` of a crawler document: the map's extent in its frame, placed in the world.
/// Its defaults are perception::TextureMapConfig's (the YAML is flat, the map pose a PoseSpec).
struct TextureDocument {
    bool enabled = true;  ///< the section's presence enables it
    double cell_size_m = perception::TextureMapConfig{}.cell_size_m;
    double min_x_m = perception::TextureMapConfig{}.min_x_m;
    double max_x_m = perception::TextureMapConfig{}.max_x_m;
    double min_y_m = perception::TextureMapConfig{}.min_y_m;
    double max_y_m = perception::TextureMapConfig{}.max_y_m;
    double max_range_m = perception::TextureMapConfig{}.max_range_m;
    bool uncertain_is_obstacle = perception::TextureMapConfig{}.uncertain_is_obstacle;
    sim::PoseSpec map_pose{};
};

const io::ConfigSchema<TextureDocument>& texture_schema() {
    using S = TextureDocument;
    static const io::ConfigSchema<S> schema = [] {
        io::ConfigSchema<S> s;
        s.field("enabled", &S::enabled, "paint the camera images (needs a camera)")
            .field("cell_size_m", &S::cell_size_m, "a ground cell, m", io::kPositive)
            .field("min_x_m", &S::min_x_m, "extent in the map frame, m")
            .field("max_x_m", &S::max_x_m)
            .field("min_y_m", &S::min_y_m)
            .field("max_y_m", &S::max_y_m)
            .field("max_range_m", &S::max_range_m, "camera to cell at most, m", io::kPositive)
            .field("uncertain_is_obstacle", &S::uncertain_is_obstacle, "paint uncertain red")
            .section("map_pose", &S::map_pose, sim::detail::pose_spec_schema(),
                     "the map frame in the world (z the surface normal)");
        return s;
    }();
    return schema;
}

perception::TextureMapConfig to_config(const TextureDocument& d) {
    perception::TextureMapConfig c;
    c.cell_size_m = d.cell_size_m;
    c.min_x_m = d.min_x_m;
    c.max_x_m = d.max_x_m;
    c.min_y_m = d.min_y_m;
    c.max_y_m = d.max_y_m;
    c.max_range_m = d.max_range_m;
    c.uncertain_is_obstacle = d.uncertain_is_obstacle;
    c.T_world_map = d.map_pose.to_isometry();
    return c;
}

const io::ConfigSchema<control::SegmentFollowerConfig>& follower_schema() {
    using S = control::SegmentFollowerConfig;
    static const io::ConfigSchema<S> schema = [] {
        io::ConfigSchema<S> s;
        s.field("k_y_per_m_s", &S::k_y_per_m_s, "turn rate per metre of cross-track", io::kPositive)
            .field("k_yaw_per_s", &S::k_yaw_per_s, "turn rate per radian of yaw", io::kPositive)
            .field("v_ref_mps", &S::v_ref_mps, "forward speed when not turning", io::kPositive)
            .field("omega0_radps", &S::omega0_radps, "turn rate at which v falls to v_ref/e",
                   io::kPositive)
            .field("max_omega_radps", &S::max_omega_radps, "turn-rate clamp", io::kPositive);
        return s;
    }();
    return schema;
}

const io::ConfigSchema<planning::SurfaceWalkConfig>& walk_schema() {
    using S = planning::SurfaceWalkConfig;
    static const io::ConfigSchema<S> schema = [] {
        io::ConfigSchema<S> s;
        s.field("march_step_m", &S::march_step_m, "a walking step on the surface, m", io::kPositive)
            .field("segment_length_m", &S::segment_length_m, "the follower's segments, m",
                   io::kPositive)
            .field("max_start_distance_m", &S::max_start_distance_m,
                   "how far off the surface a start may be, m", io::kPositive);
        return s;
    }();
    return schema;
}

const io::ConfigSchema<localization::SurfaceParticleFilterConfig>& particle_filter_schema() {
    using S = localization::SurfaceParticleFilterConfig;
    static const io::ConfigSchema<S> schema = [] {
        io::ConfigSchema<S> s;
        s.field("num_particles", &S::num_particles, "N")
            .field("initial_position_sigma_m", &S::initial_position_sigma_m, "m", io::kNonNegative)
            .field("initial_yaw_sigma_rad", &S::initial_yaw_sigma_rad, "rad", io::kNonNegative)
            .field("slip_mean", &S::slip_mean, "longitudinal slip fraction, mean")
            .field("slip_sigma", &S::slip_sigma, "its stationary 1σ", io::kNonNegative)
            .field("slip_correlation_time_s", &S::slip_correlation_time_s, "s", io::kPositive)
            .field("lateral_slip_sigma", &S::lateral_slip_sigma, "lateral / forward speed, 1σ",
                   io::kNonNegative)
            .field("wheel_yaw_slip_sigma", &S::wheel_yaw_slip_sigma,
                   "relative turn-rate error by the wheels, 1σ", io::kNonNegative)
            .field("gyro_yaw_random_walk_rad_per_sqrt_s", &S::gyro_yaw_random_walk_rad_per_sqrt_s,
                   "heading random walk with the gyro, rad/√s", io::kNonNegative)
            .field("wheel_yaw_random_walk_rad_per_sqrt_s", &S::wheel_yaw_random_walk_rad_per_sqrt_s,
                   "heading random walk by the wheels alone, rad/√s", io::kNonNegative)
            .field("uwb_range_sigma_m", &S::uwb_range_sigma_m, "line-of-sight 1σ, m", io::kPositive)
            .field("nlos_probability", &S::nlos_probability, "share of long NLOS ranges")
            .field("nlos_max_excess_m", &S::nlos_max_excess_m, "NLOS excess path limit, m",
                   io::kPositive)
            .field("outlier_probability", &S::outlier_probability, "share of wild ranges")
            .field("uwb_max_range_m", &S::uwb_max_range_m, "the outliers' range, m", io::kPositive)
            .field("resample_threshold_fraction", &S::resample_threshold_fraction,
                   "resample below this share of N as effective sample size", io::kUnitInterval)
            .field("max_wheel_gap_s", &S::max_wheel_gap_s, "a longer wheel interval is a gap, s",
                   io::kPositive);
        return s;
    }();
    return schema;
}

const io::ConfigSchema<perception::SurfaceObstaclesConfig>& obstacles_schema() {
    using S = perception::SurfaceObstaclesConfig;
    static const io::ConfigSchema<S> schema = [] {
        io::ConfigSchema<S> s;
        s.field("voxel_size_m", &S::voxel_size_m, "voxel grid of the stop cloud, m", io::kPositive)
            .field("column_median", &S::column_median,
                   "one point per x-y column at its median height instead of the voxel grid")
            .field("max_range_m", &S::max_range_m, "farther points are dropped, m", io::kPositive)
            .field("inlier_threshold_m", &S::inlier_threshold_m, "free within this, m",
                   io::kPositive)
            .field("obstacle_threshold_m", &S::obstacle_threshold_m, "an obstacle beyond this, m",
                   io::kPositive)
            .field("iterations", &S::iterations, "RANSAC hypotheses")
            .field("min_radius_m", &S::min_radius_m, "tightest surface curvature radius, m",
                   io::kPositive)
            .field("cell_size_m", &S::cell_size_m, "obstacle grid cell, m", io::kPositive)
            .field("min_obstacle_support", &S::min_obstacle_support,
                   "obstacle points of one sign needed in the 3x3 cells around one")
            .field("min_cluster_cells", &S::min_cluster_cells, "smaller clusters are noise, cells")
            .field("rim_cells", &S::rim_cells,
                   "obstacles this close to unobserved cells: uncertain")
            .field("enclosed_unknown_is_negative", &S::enclosed_unknown_is_negative,
                   "an enclosed region without returns is a hole")
            .field("min_enclosed_unknown_cells", &S::min_enclosed_unknown_cells,
                   "smallest such region, cells");
        return s;
    }();
    return schema;
}

const io::ConfigSchema<registration::ConstrainedIcpConfig>& stop_icp_schema() {
    using S = registration::ConstrainedIcpConfig;
    static const io::ConfigSchema<S> schema = [] {
        io::ConfigSchema<S> s;
        s.field("max_iterations", &S::max_iterations, "SPEC: 25")
            .field("max_correspondence_distance_m", &S::max_correspondence_distance_m, "m",
                   io::kPositive)
            .field("max_rotation_rad", &S::max_rotation_rad, "cap, SPEC: 0.05", io::kPositive)
            .field("max_translation_m", &S::max_translation_m, "cap, SPEC: 0.35", io::kPositive)
            .field("degeneracy_threshold", &S::degeneracy_threshold,
                   "weakest / strongest of x, y, yaw below this: not applied", io::kUnitInterval);
        return s;
    }();
    return schema;
}

const io::ConfigSchema<perception::StopAndMapConfig>& stop_and_map_schema() {
    using S = perception::StopAndMapConfig;
    static const io::ConfigSchema<S> schema = [] {
        io::ConfigSchema<S> s;
        s.section("obstacles", &S::obstacles, obstacles_schema())
            .section("icp", &S::icp, stop_icp_schema())
            .field("correct_pose", &S::correct_pose, "register consecutive stop clouds")
            .field("max_points", &S::max_points, "most points accumulated in one stop")
            .field("min_icp_points", &S::min_icp_points, "obstacle points a registration needs")
            .field("missing_returns_are_negative", &S::missing_returns_are_negative,
                   "no return where the LiDAR should see the surface: a hole or an edge")
            .field("fov_margin_rad", &S::fov_margin_rad, "off the cone's rim, rad",
                   io::kNonNegative)
            .field("expected_range_m", &S::expected_range_m, "farthest expected cell, m",
                   io::kPositive);
        return s;
    }();
    return schema;
}

const io::ConfigSchema<perception::FaceCorridorConfig>& corridor_schema() {
    using S = perception::FaceCorridorConfig;
    static const io::ConfigSchema<S> schema = [] {
        io::ConfigSchema<S> s;
        s.field("cell_size_m", &S::cell_size_m, "x-y grid, m", io::kPositive)
            .field("face_tolerance_m", &S::face_tolerance_m,
                   "a cell this near z = 0 is the face, m", io::kPositive)
            .field("min_x_m", &S::min_x_m, "rows ahead from, m")
            .field("max_x_m", &S::max_x_m, "rows ahead to, m")
            .field("max_half_width_m", &S::max_half_width_m, "boundaries looked for within, m",
                   io::kPositive)
            .field("max_gap_cells", &S::max_gap_cells, "empty cells bridged in the face")
            .field("min_rows", &S::min_rows, "rows with both boundaries needed")
            .field("max_boundary_residual_m", &S::max_boundary_residual_m,
                   "a row's boundary off the fitted line by more: an outlier, m", io::kPositive);
        return s;
    }();
    return schema;
}

const io::ConfigSchema<planning::DetourConfig>& detour_schema() {
    using S = planning::DetourConfig;
    static const io::ConfigSchema<S> schema = [] {
        io::ConfigSchema<S> s;
        s.field("clearance_m", &S::clearance_m, "the centre passes footprints this far, m",
                io::kPositive)
            .field("rejoin_m", &S::rejoin_m, "back on the path this far past the obstacle, m",
                   io::kPositive)
            .field("max_offset_m", &S::max_offset_m, "largest lateral offset tried, m",
                   io::kPositive)
            .field("offset_step_m", &S::offset_step_m, "the offset grows by this per try, m",
                   io::kPositive)
            .field("inside_clearance_m", &S::inside_clearance_m,
                   "a footprint the crawler stopped within the clearance of: passed this far, m",
                   io::kPositive);
        return s;
    }();
    return schema;
}

const io::ConfigSchema<CrawlerStackConfig>& stack_schema() {
    using S = CrawlerStackConfig;
    static const io::ConfigSchema<S> schema = [] {
        io::ConfigSchema<S> s;
        s.section("particle_filter", &S::particle_filter, particle_filter_schema())
            .section("follower", &S::follower, follower_schema())
            .section("walk", &S::walk, walk_schema())
            .field("max_wheel_age_s", &S::max_wheel_age_s, "longer without wheels: stop, s",
                   io::kPositive)
            .field("gyro_calibration_s", &S::gyro_calibration_s,
                   "standing still at the start to take the gyro's bias, s (0: off)",
                   io::kNonNegative)
            .field("max_uwb_age_s", &S::max_uwb_age_s, "no UWB range this long: an event, s",
                   io::kPositive)
            .field("max_position_sigma_m", &S::max_position_sigma_m,
                   "a larger position σ stops the crawler, m", io::kPositive)
            .field("anchor_hidden_margin_m", &S::anchor_hidden_margin_m,
                   "ranges of anchors this far behind the surface are dropped, m", io::kNonNegative)
            .field("obstacle_slow_distance_m", &S::obstacle_slow_distance_m,
                   "slow down for an obstacle ahead from this distance, m (0: off)",
                   io::kNonNegative)
            .field("obstacle_stop_distance_m", &S::obstacle_stop_distance_m,
                   "stopped this far from it, m", io::kNonNegative)
            .field("corridor_half_width_m", &S::corridor_half_width_m,
                   "obstacles within this of the heading line count, m", io::kPositive)
            .field("replan_around_obstacles", &S::replan_around_obstacles,
                   "stopped by an obstacle: replan around it (else pause for the operator)")
            .section("detour", &S::detour, detour_schema())
            .field("stop_spacing_m", &S::stop_spacing_m,
                   "stop-and-map after this distance on a leg and at waypoints, m (0: waypoints)",
                   io::kNonNegative)
            .field("stop_settle_s", &S::stop_settle_s, "into a stop: pose and accumulation, s",
                   io::kNonNegative)
            .field("stop_duration_s", &S::stop_duration_s, "a stop in all, s", io::kPositive)
            .section("stop_and_map", &S::stop_and_map, stop_and_map_schema())
            .section("corridor", &S::corridor, corridor_schema(),
                     "the stiffener drives' corridor from a stop's cloud")
            .field("corridor_join_m", &S::corridor_join_m,
                   "join the corridor's centre line this far ahead, m", io::kNonNegative);
        return s;
    }();
    return schema;
}

const io::ConfigSchema<detail::VehicleDocument<CrawlerStackConfig>>& document_schema() {
    static const auto schema = detail::vehicle_document_schema(stack_schema());
    return schema;
}

/// The robot knows the surveyed UWB anchors, its tag's, its IMU's and its LiDAR's mounts, and
/// its LiDAR's cone.
void calibrate(CrawlerMissionScenario& m) {
    for (const sim::SensorSpec& sensor : m.simulation.sensors) {
        if (sensor.type == sim::SensorType::kImu) {
            m.stack.particle_filter.R_body_imu = sensor.T_body_sensor.to_isometry().linear();
        }
        for (const sim::UwbAnchor& anchor : sensor.anchors) {
            m.stack.particle_filter.uwb_anchors_world_m[anchor.id] = anchor.position_world;
        }
        if (sensor.type == sim::SensorType::kCamera) {
            m.stack.T_body_camera = sensor.T_body_sensor.to_isometry();
        }
        if (sensor.type == sim::SensorType::kRosetteLidar) {
            const sim::RosetteLidarConfig lidar =
                sim::detail::rosette_config(sensor, "simulation.sensors");
            m.stack.T_body_lidar = lidar.T_body_sensor;
            m.stack.stop_and_map.lidar_fov_rad = lidar.fov_rad;
        }
        if (sensor.type == sim::SensorType::kUwb) {
            m.stack.particle_filter.p_body_uwb_tag_m =
                sensor.T_body_sensor.to_isometry().translation();
        }
    }
}

CrawlerMissionScenario from_document(const io::ConfigNode& root, const std::string& name) {
    if (!root.is_map()) io::detail::fail(root, "", "expected a map (a mission scenario)");
    detail::VehicleDocument<CrawlerStackConfig> document;
    document_schema().apply(without(root, {"simulation", "mission", "operator", "texture_map"}),
                            document);
    if (const io::ConfigNode* texture = root.find("texture_map")) {
        TextureDocument t;
        texture_schema().apply(*texture, t, "texture_map");
        document.stack.texture = {.enabled = t.enabled, .map = to_config(t)};
    }
    const detail::CrawlerMissionDocument mission =
        detail::crawler_mission_from(required(root, "mission"));
    CrawlerMissionScenario m;
    detail::take_common(m, document, root, required(root, "simulation"), name);
    m.tasks = mission.tasks;
    m.swath_width_m = mission.swath_width_m;
    calibrate(m);
    m.validate();
    return m;
}

}  // namespace

void CrawlerMissionScenario::validate() const {
    simulation.validate("simulation");
    if (simulation.vehicle.type != sim::VehicleType::kCrawler) {
        throw ConfigError(
            "simulation.vehicle.type: a crawler mission (surface_rectangle, surface_tasks) needs "
            "the crawler vehicle");
    }
    config_checks::require(linger_s >= 0.0 && std::isfinite(linger_s), "", "linger_s", linger_s,
                           "finite >= 0");
    config_checks::require_positive(swath_width_m, "mission", "swath_width_m");
    if (tasks.empty()) throw ConfigError("mission.tasks: a crawler mission needs a task");
    stack.validate("stack");
    for (std::size_t i = 0; i < faults.size(); ++i)
        faults[i].validate(fmt::format("faults[{}]", i));
}

bool is_crawler_mission_file(const std::string& path) {
    return detail::is_crawler_mission_type(detail::mission_type_of(path));
}

CrawlerMissionScenario load_crawler_mission_scenario(const std::string& path,
                                                     const std::vector<std::string>& overrides) {
    return detail::load_scenario(path, overrides, from_document);
}

CrawlerMissionScenario parse_crawler_mission_scenario(const std::string& yaml_text,
                                                      const std::string& name) {
    return detail::parse_scenario(yaml_text, name, from_document);
}

}  // namespace scantling::mission
