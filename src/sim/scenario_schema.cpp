// Sensor and top-level sections of the scenario schema, and the type-dependent checks.
#include <scantling/sim/scenario_schema.hpp>

#include <algorithm>
#include <map>
#include <string>
#include <vector>

namespace scantling::sim {
namespace detail {
namespace {

using io::ConfigNode;
using io::ConfigSchema;
using io::Range;
using io::detail::fail;
using io::detail::join_key;
using io::detail::join_names;

const std::vector<std::pair<std::string, SensorType>> kSensorTypes{
    {"spinning_lidar", SensorType::kSpinningLidar},
    {"imu", SensorType::kImu},
    {"vio", SensorType::kVio},
    {"depth_camera", SensorType::kDepthCamera},
    {"camera", SensorType::kCamera},
    {"multibeam_sonar", SensorType::kMultibeamSonar},
    {"rosette_lidar", SensorType::kRosetteLidar},
    {"stereo_points", SensorType::kStereoPoints},
    {"range_finder", SensorType::kRangeFinder},
    {"uwb", SensorType::kUwb},
    {"pressure", SensorType::kPressure},
    {"dvl", SensorType::kDvl},
    {"wheel_odometry", SensorType::kWheelOdometry},
    {"barometer", SensorType::kBarometer}};

const std::vector<std::pair<std::string, SensorPreset>> kPresets{
    {"os1_64", SensorPreset::kOs1_64},
    {"hdl64e", SensorPreset::kHdl64e},
    {"l515", SensorPreset::kL515},
    {"azure_nfov", SensorPreset::kAzureNfov},
    {"azure_nfov_binned", SensorPreset::kAzureNfovBinned},
    {"uav3d", SensorPreset::kUav3d},
    {"rov", SensorPreset::kRov},
    {"consumer_mems", SensorPreset::kConsumerMems},
    {"industrial_mems", SensorPreset::kIndustrialMems},
    {"t265", SensorPreset::kT265},
    {"lidar_lite_v3", SensorPreset::kLidarLiteV3},
    {"teraranger_evo_60m", SensorPreset::kTerarangerEvo60m},
    {"hc_sr04", SensorPreset::kHcSr04},
    {"livox_mid70", SensorPreset::kLivoxMid70},
    {"os0_64", SensorPreset::kOs0_64}};

/// Keys and presets that apply to each sensor type.
struct SensorKeys {
    std::vector<std::string> keys;
    std::vector<std::string> presets;
};

const std::map<std::string, SensorKeys>& sensor_keys() {
    static const std::map<std::string, SensorKeys> table{
        {"spinning_lidar",
         {{"type", "preset", "rate_hz", "columns", "noise", "motion_distortion", "write_ply",
           "T_body_sensor"},
          {"os1_64", "hdl64e", "os0_64"}}},
        {"imu",
         {{"type", "preset", "rate_hz", "noise", "T_body_sensor"},
          {"consumer_mems", "industrial_mems"}}},
        {"vio",
         {{"type", "preset", "rate_hz", "noise", "ambient_light", "T_body_sensor"}, {"t265"}}},
        {"depth_camera",
         {{"type", "preset", "rate_hz", "width", "noise", "T_body_sensor"},
          {"l515", "azure_nfov", "azure_nfov_binned"}}},
        {"camera",
         {{"type", "preset", "rate_hz", "width", "height", "noise", "lasers", "T_body_sensor"},
          {"uav3d", "rov"}}},
        {"multibeam_sonar",
         {{"type", "rate_hz", "num_beams", "num_bins", "max_range_m", "noise", "T_body_sensor"},
          {}}},
        {"rosette_lidar",
         {{"type", "preset", "rate_hz", "noise", "T_body_sensor"}, {"livox_mid70"}}},
        {"stereo_points", {{"type", "rate_hz", "width", "noise", "T_body_sensor"}, {}}},
        {"range_finder",
         {{"type", "preset", "rate_hz", "max_range_m", "noise", "T_body_sensor"},
          {"lidar_lite_v3", "teraranger_evo_60m", "hc_sr04"}}},
        {"uwb", {{"type", "rate_hz", "noise", "anchors", "T_body_sensor"}, {}}},
        {"pressure", {{"type", "rate_hz", "noise", "surface_z_m", "T_body_sensor"}, {}}},
        {"dvl", {{"type", "rate_hz", "noise", "T_body_sensor"}, {}}},
        {"wheel_odometry", {{"type", "rate_hz", "noise"}, {}}}};
    return table;
}

bool contains(const std::vector<std::string>& names, const std::string& name) {
    return std::find(names.begin(), names.end(), name) != names.end();
}

/// Text of the `type` scalar of a map node, or `fallback` when absent (the schema reports a
/// malformed type itself).
std::string type_of(const ConfigNode& node, const std::string& fallback) {
    const ConfigNode* type = node.find("type");
    return type != nullptr && type->is_scalar() ? type->scalar : fallback;
}

/// Only the section named after the selected type may appear among `sections`.
void check_sections(const ConfigNode& node, const std::string& path, const std::string& fallback,
                    const std::vector<std::string>& sections) {
    if (!node.is_map()) return;
    const std::string type = type_of(node, fallback);
    for (const auto& [key, value] : node.map) {
        if (key != type && contains(sections, key)) {
            fail(value, join_key(path, key),
                 "section applies to type '" + key + "', but type is '" + type + "'");
        }
    }
}

void check_sensor(const ConfigNode& item, const std::string& path) {
    if (!item.is_map()) return;
    const auto it = sensor_keys().find(type_of(item, "imu"));
    if (it == sensor_keys().end()) return;  // the schema names the bad type
    const std::string type = it->first;
    for (const auto& [key, value] : item.map) {
        if (!contains(it->second.keys, key) && contains(sensor_spec_schema().keys(), key)) {
            fail(value, join_key(path, key),
                 "does not apply to type '" + type + "' (keys: " + join_names(it->second.keys) +
                     ")");
        }
    }
    const ConfigNode* preset = item.find("preset");
    if (preset != nullptr && preset->is_scalar() && !contains(it->second.presets, preset->scalar)) {
        fail(*preset, join_key(path, "preset"),
             "'" + preset->scalar + "' is not a preset of type '" + type +
                 "', expected one of: " + join_names(it->second.presets));
    }
}

ConfigSchema<UwbAnchor> anchor_schema() {
    ConfigSchema<UwbAnchor> s;
    s.field("id", &UwbAnchor::id, "unique among the anchors")
        .field("position_world", &UwbAnchor::position_world, "antenna, world frame, m",
               kCoordinate);
    return s;
}

ConfigSchema<LaserPointer> laser_schema() {
    ConfigSchema<LaserPointer> s;
    s.field("origin_camera", &LaserPointer::origin_camera, "beam origin, optical frame, m",
            kCoordinate)
        .field("direction_camera", &LaserPointer::direction_camera,
               "beam direction, optical frame; non-zero, normalised", kCoordinate)
        .field("spot_radius_m", &LaserPointer::spot_radius_m, "spot radius on the surface",
               between(1e-6, 1.0))
        .field("rgb", &LaserPointer::rgb, "spot colour, 8-bit channels",
               Range{.min = 0.0, .max = 255.0});
    return s;
}

ConfigSchema<ExportSpec> export_schema() {
    ConfigSchema<ExportSpec> s;
    s.field("world", &ExportSpec::world, "write DIR/world/")
        .field("map_spacing_m", &ExportSpec::map_spacing_m, "CAD-map sample spacing",
               between(limits::kMinMapSpacing_m, limits::kMaxWorldExtent_m));
    return s;
}

ConfigSchema<ParallelConfig> parallel_schema() {
    ConfigSchema<ParallelConfig> s;
    s.field("num_threads", &ParallelConfig::num_threads, "0 = all hardware threads",
            up_to(limits::kMaxThreads));
    return s;
}

}  // namespace

const std::vector<std::pair<std::string, SensorType>>& sensor_type_choices() {
    return kSensorTypes;
}

const ConfigSchema<SensorSpec>& sensor_spec_schema() {
    static const ConfigSchema<SensorSpec> schema = [] {
        using S = SensorSpec;
        ConfigSchema<S> s;
        s.enum_field("type", &S::type, sensor_type_choices())
            .enum_field("preset", &S::preset, kPresets, "model; default: the type's first")
            .field("rate_hz", &S::rate_hz, "0 = the preset's rate; at most 1 / dt_s",
                   up_to(limits::kMaxRate_hz))
            .field("columns", &S::columns, "spinning_lidar: 0 = the preset's",
                   up_to(limits::kMaxLidarColumns))
            .field("width", &S::width, "cameras: image width, 0 = the preset's",
                   up_to(limits::kMaxImageSide_px))
            .field("height", &S::height, "camera: image height, 0 = preset aspect",
                   up_to(limits::kMaxImageSide_px))
            .field("noise", &S::noise, "false: ideal measurements")
            .field("motion_distortion", &S::motion_distortion, "spinning_lidar: cast per column")
            .field("write_ply", &S::write_ply, "spinning_lidar: also NNNNNN.ply (ring, time)")
            .field("num_beams", &S::num_beams, "multibeam_sonar: 0 = the model's",
                   up_to(limits::kMaxSonarBeams))
            .field("num_bins", &S::num_bins, "multibeam_sonar: 0 = the model's",
                   up_to(limits::kMaxSonarBins))
            .field("max_range_m", &S::max_range_m, "sonar, range_finder: 0 = the model's",
                   up_to(limits::kMaxSensorRange_m))
            .field("surface_z_m", &S::surface_z_m, "pressure: world z of the water surface",
                   kCoordinate)
            .field("ambient_light", &S::ambient_light, "vio: lighting factor, 0 = dark",
                   Range{.min = 0.0, .max = 1.0})
            .list("anchors", &S::anchors, anchor_schema(), "uwb: anchors, world frame")
            .list("lasers", &S::lasers, laser_schema(), "camera: laser pointers, optical frame")
            .section("T_body_sensor", &S::T_body_sensor, pose_spec_schema(), "mount");
        return s;
    }();
    return schema;
}

}  // namespace detail

const io::ConfigSchema<Scenario>& scenario_schema() {
    static const io::ConfigSchema<Scenario> schema = [] {
        using S = Scenario;
        io::ConfigSchema<S> s;
        s.field("name", &S::name, "default: the file stem")
            .field("description", &S::description, "free text")
            .section("world", &S::world, detail::world_spec_schema())
            .section("vehicle", &S::vehicle, detail::vehicle_spec_schema())
            .list("sensors", &S::sensors, detail::sensor_spec_schema(), "at most one per type")
            .field("duration_s", &S::duration_s, "0 = the trajectory's",
                   detail::up_to(limits::kMaxDuration_s))
            .field("dt_s", &S::dt_s, "clock step; ground truth every step",
                   detail::between(limits::kMinDt_s, limits::kMaxDt_s))
            .field("seed", &S::seed, "root of every random stream")
            .section("export", &S::export_world, detail::export_schema())
            .section("parallel", &S::parallel, detail::parallel_schema())
            .list("moving_obstacles", &S::moving_obstacles, detail::moving_obstacle_schema(),
                  "spheres and boxes moving through the world");
        return s;
    }();
    return schema;
}

void check_scenario_document(const io::ConfigNode& root) {
    if (!root.is_map()) return;  // the schema reports it
    if (const io::ConfigNode* world = root.find("world")) {
        detail::check_sections(
            *world, "world", "cylinder",
            {"ballast_tank_mockup", "ballast_tank_large", "storage_tank", "distillation_column",
             "cylinder", "plate", "mesh", "ship_hull", "moebius", "ship_hull_mesh", "urban"});
        const io::ConfigNode* obstacles = world->is_map() ? world->find("obstacles") : nullptr;
        if (obstacles != nullptr && obstacles->is_sequence()) {
            for (std::size_t i = 0; i < obstacles->sequence.size(); ++i) {
                detail::check_surface_obstacle(obstacles->sequence[i],
                                               io::detail::index_key("world.obstacles", i));
            }
        }
    }
    const io::ConfigNode* vehicle = root.find("vehicle");
    if (vehicle != nullptr && vehicle->is_map()) {
        detail::check_sections(*vehicle, "vehicle", "scripted",
                               {"mav", "rov", "crawler", "legged"});
        if (const io::ConfigNode* trajectory = vehicle->find("trajectory")) {
            detail::check_sections(*trajectory, "vehicle.trajectory", "helix",
                                   {"waypoints", "helix", "lawnmower", "orbit"});
        }
    }
    const io::ConfigNode* sensors = root.find("sensors");
    if (sensors != nullptr && sensors->is_sequence()) {
        for (std::size_t i = 0; i < sensors->sequence.size(); ++i) {
            detail::check_sensor(sensors->sequence[i], io::detail::index_key("sensors", i));
        }
    }
    const io::ConfigNode* obstacles = root.find("moving_obstacles");
    if (obstacles == nullptr || !obstacles->is_sequence()) return;
    for (std::size_t i = 0; i < obstacles->sequence.size(); ++i) {
        detail::check_moving_obstacle(obstacles->sequence[i],
                                      io::detail::index_key("moving_obstacles", i));
    }
}

}  // namespace scantling::sim
