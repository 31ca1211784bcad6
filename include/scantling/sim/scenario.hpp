#pragma once
/// @file
/// A simulation scenario (issue 3, item 4): world, vehicle, sensors, duration and seed, read
/// from YAML by scenario_schema.hpp and run by scenario_runner.hpp.
///
/// Every struct starts from the defaults of the configs it wraps (each default is written
/// once, in the builder or sensor config). Type-dependent parts use a `type` key plus one
/// section named after the type, e.g. `world: {type: storage_tank, storage_tank: {...}}`.
///
/// Frames: world z up (world.hpp); the vehicle pose is T_world_body; sensor mounts are
/// T_body_sensor given as translation `xyz` (m) and roll/pitch/yaw `rpy_deg`
/// (R = Rz(yaw) Ry(pitch) Rx(roll)).

#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <scantling/core/parallel.hpp>
#include <scantling/sim/crawler_dynamics.hpp>
#include <scantling/sim/helix_trajectory.hpp>
#include <scantling/sim/laser_spots.hpp>
#include <scantling/sim/lawnmower_trajectory.hpp>
#include <scantling/sim/legged_base.hpp>
#include <scantling/sim/mav_dynamics.hpp>
#include <scantling/sim/moving_obstacles.hpp>
#include <scantling/sim/rov_dynamics.hpp>
#include <scantling/sim/surface_obstacles.hpp>
#include <scantling/sim/trajectory.hpp>
#include <scantling/sim/uwb.hpp>
#include <scantling/sim/waypoint_trajectory.hpp>
#include <scantling/sim/world.hpp>
#include <scantling/sim/world_builders.hpp>
#include <scantling/sim/world_hull.hpp>
#include <scantling/sim/world_urban.hpp>

namespace scantling::sim {

/// A rigid transform written as translation and roll/pitch/yaw in degrees.
struct PoseSpec {
    Eigen::Vector3d xyz = Eigen::Vector3d::Zero();      ///< translation, metres
    Eigen::Vector3d rpy_deg = Eigen::Vector3d::Zero();  ///< roll, pitch, yaw, degrees
    /// R = Rz(yaw) Ry(pitch) Rx(roll), t = xyz.
    Eigen::Isometry3d to_isometry() const;
};

enum class WorldType {
    kBallastTankMockup,
    kBallastTankLarge,
    kStorageTank,
    kDistillationColumn,
    kCylinder,
    kPlate,
    kMesh,
    kShipHull,
    kMoebius,
    kShipHullMesh,  ///< a hull mesh file in a dock or at a quay (build_hull_mesh_in_dock)
    kUrban,         ///< a KITTI-like city of streets and buildings (world_urban.hpp)
};

/// The world and the parameters of its builder; only the section of `type` is used.
struct WorldSpec {
    WorldType type = WorldType::kCylinder;
    BallastTankMockupConfig ballast_tank_mockup{};
    BallastTankLargeConfig ballast_tank_large{};
    StorageTankConfig storage_tank{};
    DistillationColumnConfig distillation_column{};
    CylinderConfig cylinder{};
    PlateConfig plate{};
    MeshWorldConfig mesh{};  ///< `path` relative to the scenario file's folder
    ShipHullConfig ship_hull{};
    MoebiusConfig moebius{};
    /// `path` relative to the scenario file's folder (or absolute).
    HullMeshDockConfig ship_hull_mesh{};
    UrbanConfig urban{};
    /// Bolts, brackets and weld beads on the crawler's surface, any type (surface_obstacles.hpp;
    /// their ground truth goes to World::obstacles).
    std::vector<SurfaceObstacleConfig> obstacles{};
    /// Validates the section of `type` ("<prefix>.storage_tank.diameter_m = ...") and the
    /// obstacles ("<prefix>.obstacles[0].diameter_m = ..."); where they sit is checked by
    /// build_world, which needs the surface.
    void validate(std::string_view prefix = "world") const;
};

/// A lawnmower sweep whose wall pose is written as a PoseSpec (`T_world_wall`).
struct LawnmowerSpec : LawnmowerTrajectoryConfig {
    PoseSpec wall{};
};

enum class TrajectoryType { kWaypoints, kHelix, kLawnmower, kOrbit };

struct TrajectorySpec {
    TrajectoryType type = TrajectoryType::kHelix;
    WaypointTrajectoryConfig waypoints{};
    HelixTrajectoryConfig helix{};
    LawnmowerSpec lawnmower{};
    OrbitTrajectoryConfig orbit{};
    void validate(std::string_view prefix = "trajectory") const;
};

/// The trajectory of `spec` (ConfigError for a bad config).
std::unique_ptr<Trajectory> make_trajectory(const TrajectorySpec& spec);

enum class VehicleType {
    kScripted,  ///< the vehicle moves exactly along the trajectory
    kMav,       ///< a MAV (mav_dynamics.hpp) tracking the trajectory in wind
    kRov,       ///< a 4-DoF ROV (rov_dynamics.hpp) tracking the trajectory in a current
    /// A crawler (crawler_dynamics.hpp) on the world's surface (plate: its top plane; cylinder
    /// and storage tank: the outside of the shell; otherwise the world mesh) pursuing the
    /// trajectory's position projected on that surface.
    kCrawler,
    kLegged,  ///< a planar legged base (legged_base.hpp) tracking the trajectory's x, y, yaw
};

struct VehicleSpec {
    VehicleType type = VehicleType::kScripted;
    TrajectorySpec trajectory{};
    /// kMav: dynamics (its dt_s is replaced by the scenario's dt_s).
    MavDynamicsConfig mav{};
    /// kRov: dynamics and current (its dt_s is replaced by the scenario's dt_s).
    RovDynamicsConfig rov{};
    /// kCrawler: dynamics and slip (its dt_s is replaced by the scenario's dt_s).
    CrawlerDynamicsConfig crawler{};
    /// kLegged: dynamics (its dt_s is replaced by the scenario's dt_s).
    LeggedBaseConfig legged{};
    /// kMav, kRov, kLegged, kCrawler: position-error gain of the tracking controller, 1/s
    /// (v_cmd = v_ref + gain · (p_ref − p); the crawler steers towards p_ref instead).
    double position_gain_per_s = 1.5;
    /// kMav, kRov, kLegged, kCrawler: yaw-error gain, 1/s (ψ̇_cmd = ψ̇_ref + gain · wrap(ψ_ref − ψ)).
    double yaw_gain_per_s = 2.0;
    void validate(std::string_view prefix = "vehicle") const;
};

enum class SensorType {
    kSpinningLidar,
    kImu,
    kVio,
    kDepthCamera,
    kCamera,
    kMultibeamSonar,
    kRosetteLidar,
    kStereoPoints,
    kRangeFinder,
    kUwb,
    kPressure,
    kDvl,
    kWheelOdometry,
    kBarometer,
};

/// Presets, by sensor type: spinning_lidar os1_64 | hdl64e | os0_64; depth_camera l515 |
/// azure_nfov | azure_nfov_binned; camera uav3d | rov; imu consumer_mems | industrial_mems; vio
/// t265; range_finder lidar_lite_v3 | teraranger_evo_60m | hc_sr04; rosette_lidar livox_mid70.
enum class SensorPreset {
    kDefault,  ///< the first preset of the type
    kOs1_64,
    kHdl64e,
    kL515,
    kAzureNfov,
    kAzureNfovBinned,
    kUav3d,
    kRov,
    kConsumerMems,
    kIndustrialMems,
    kT265,
    kLidarLiteV3,
    kTerarangerEvo60m,
    kHcSr04,
    kLivoxMid70,
    kOs0_64,
};

/// One sensor. Keys that do not apply to `type` are rejected when parsing (with their line).
struct SensorSpec {
    SensorType type = SensorType::kImu;
    SensorPreset preset = SensorPreset::kDefault;
    double rate_hz = 0.0;            ///< 0 = the preset's rate
    int columns = 0;                 ///< spinning_lidar: 0 = the preset's columns
    int width = 0;                   ///< depth_camera (l515) and camera: 0 = the preset's width
    int height = 0;                  ///< camera: 0 = the preset's aspect ratio
    bool noise = true;               ///< false: ideal measurements (no noise, bias, drift, dropout)
    bool motion_distortion = false;  ///< spinning_lidar: each column cast from its own pose
    bool write_ply = false;          ///< spinning_lidar: also write each sweep as PLY (ring, time)
    int num_beams = 0;               ///< multibeam_sonar: 0 = the model's default
    int num_bins = 0;                ///< multibeam_sonar: 0 = the model's default
    double max_range_m = 0.0;        ///< multibeam_sonar, range_finder: 0 = the model's default
    double surface_z_m = 0.0;        ///< pressure: world z of the water surface
    /// vio: lighting factor in [0, 1] scaling the feature quality (vio_features.hpp); 0 = dark.
    double ambient_light = 1.0;
    std::vector<UwbAnchor> anchors;    ///< uwb: at least one, world frame
    std::vector<LaserPointer> lasers;  ///< camera: laser pointers, optical frame; none by default
    /// Mount (body ← sensor). Cameras: optical frame. dvl and vio: unset (zero) keeps the
    /// model's default (dvl down-looking, vio camera looking along body x).
    PoseSpec T_body_sensor{};
    void validate(std::string_view prefix = "sensor") const;
};

/// Name of a sensor type as written in YAML ("spinning_lidar", ...).
std::string_view to_string(SensorType type);
std::string_view to_string(WorldType type);

struct ExportSpec {
    bool world = true;            ///< write DIR/world/{map.ply, mesh.ply, metadata.json}
    double map_spacing_m = 0.05;  ///< CAD-map sample spacing
    void validate(std::string_view prefix = "export") const;
};

struct Scenario {
    std::string name;         ///< default: the scenario file's stem
    std::string description;  ///< free text, copied into summary.json
    WorldSpec world{};
    VehicleSpec vehicle{};
    std::vector<SensorSpec> sensors;
    double duration_s = 0.0;  ///< simulated time; 0 = the trajectory's duration
    double dt_s = 0.005;      ///< fixed step of the clock (ground truth is logged every step)
    std::uint64_t seed = 1;   ///< root of every random stream (vehicle, sensors, map sampling)
    ExportSpec export_world{};
    ParallelConfig parallel{};  ///< threads for ray casting (results do not depend on it)
    /// Spheres and boxes moving through the world, seen by every ray-casting sensor
    /// (moving_obstacles.hpp); not written to the recording.
    std::vector<MovingObstacle> moving_obstacles;
    /// Folder of the scenario file: `world.mesh.path` is relative to it.
    std::string base_directory;
    /// Throws ConfigError naming the field ("duration_s = -1, expected >= 0", "sensors[1]...",
    /// "moving_obstacles[0].radius_m = 0, expected finite > 0"),
    /// also for a value over its bound (scenario_limits.hpp), a world whose repeated structure
    /// multiplies past limits::kMaxWorldElements, a sensor faster than the clock (its
    /// effective rate above 1 / dt_s: the clock fires a sensor at most once per tick, so it
    /// would be recorded slower than summary.json states), a run of more than
    /// limits::kMaxTicks ticks, or a recording estimate over kMaxRecordingBytes
    /// (scenario_estimate.hpp, stating the estimate and the keys that drive it).
    void validate(std::string_view prefix = "") const;
};

/// Reads and validates a scenario file (scenario_schema.hpp). `name` defaults to the file
/// stem. Throws FileError, ParseError naming file, line and key ("s.yaml: line 4: key
/// 'world.type': expected one of ..."), or ConfigError prefixed with the file. An empty
/// document (no bytes, only comments, or `~`) is a ParseError, not a default scenario; the
/// YAML itself is bounded by io::YamlLimits (size, alias expansion, nesting).
Scenario load_scenario(const std::string& path);

/// Same for YAML text; `name` stands for the file in messages; mesh paths are relative to
/// the current directory.
Scenario parse_scenario(const std::string& yaml_text, const std::string& name = "<scenario>");

/// Builds the world of `spec` (ConfigError, or FileError/ParseError for a mesh world), then
/// its obstacles on the crawler's surface (add_surface_obstacles: ConfigError naming
/// "world.obstacles[i]" for one off the surface). `base_directory` resolves a relative mesh path.
World build_world(const WorldSpec& spec, const std::string& base_directory = "");

}  // namespace scantling::sim
