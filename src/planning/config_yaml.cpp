#include <scantling/planning/config_yaml.hpp>

#include <algorithm>
#include <string_view>
#include <utility>
#include <vector>

#include <scantling/core/error.hpp>

namespace scantling::planning {
namespace {

using io::ConfigNode;
using io::ConfigSchema;
using io::kNonNegative;
using io::kPositive;
using io::detail::join_key;

enum class MissionType { kSweep, kVertical, kCircular, kGoTo, kHome };
const std::vector<std::string> kMissionTypes = {"sweep", "vertical", "circular", "goto", "home"};

/// The value of `key` in the map `node`, removed from it (nullopt when absent or not a map):
/// keys the table-driven schemas cannot hold are read by hand.
std::optional<ConfigNode> take(ConfigNode& node, std::string_view key) {
    if (!node.is_map()) return std::nullopt;
    const auto it = std::find_if(node.map.begin(), node.map.end(),
                                 [&](const auto& entry) { return entry.first == key; });
    if (it == node.map.end()) return std::nullopt;
    ConfigNode value = std::move(it->second);
    node.map.erase(it);
    return value;
}

/// take() one level down: `section.key`.
std::optional<ConfigNode> take_nested(ConfigNode& node, std::string_view section,
                                      std::string_view key) {
    if (!node.is_map()) return std::nullopt;
    for (auto& entry : node.map) {
        if (entry.first == section) return take(entry.second, key);
    }
    return std::nullopt;
}

/// A request and its planner's config.
template <class Request, class Config>
struct Spec {
    Request request{};
    Config config{};
};

template <class Request, class Config>
ConfigSchema<Spec<Request, Config>> spec_schema(const std::string& request_key,
                                                const ConfigSchema<Request>& request_schema,
                                                const ConfigSchema<Config>& config_schema) {
    using S = Spec<Request, Config>;
    ConfigSchema<S> s;
    s.section(request_key, &S::request, request_schema, "what to inspect")
        .section("config", &S::config, config_schema, "the planner's settings");
    return s;
}

/// Validates as "<prefix>.<request_key>.<field>" and "<prefix>.config.<field>", the file named.
template <class Request, class Config>
void validate_spec(const Spec<Request, Config>& spec, const std::string& request_key,
                   const ConfigNode& node, const std::string& prefix) {
    try {
        spec.request.validate(join_key(prefix, request_key));
        spec.config.validate(join_key(prefix, "config"));
    } catch (const ConfigError& error) {
        io::detail::rethrow_validation(error, node.file);
    }
}

/// goto and home: only the config (goto's `point` is a scalar, read by hand).
struct GoToSpec {
    GoToConfig config{};
};

const ConfigSchema<GoToSpec>& go_to_spec_schema() {
    static const ConfigSchema<GoToSpec> schema = [] {
        ConfigSchema<GoToSpec> s;
        s.section("config", &GoToSpec::config, go_to_config_schema(), "the planner's settings");
        return s;
    }();
    return schema;
}

const ConfigSchema<CircleRequest>& circle_schema() {
    static const ConfigSchema<CircleRequest> schema = [] {
        ConfigSchema<CircleRequest> s;
        s.field("radius_m", &CircleRequest::radius_m, "structure radius + stand-off, m", kPositive)
            .field("heights_m", &CircleRequest::heights_m, "world z of each ring, in order");
        return s;
    }();
    return schema;
}

WaypointPath plan_sweep_request(const ConfigNode& body, const std::string& prefix) {
    static const auto schema =
        spec_schema("rectangle", wall_rectangle_schema(), sweep_config_schema());
    Spec<WallRectangle, SweepConfig> spec;
    schema.apply(body, spec, prefix);
    validate_spec(spec, "rectangle", body, prefix);
    return plan_sweep(spec.request, spec.config);
}

WaypointPath plan_vertical_request(ConfigNode body, const std::string& prefix) {
    static const auto schema =
        spec_schema("rectangle", wall_rectangle_schema(), vertical_inspection_config_schema());
    const std::optional<ConfigNode> spacing = take_nested(body, "config", "leg_spacing_m");
    Spec<WallRectangle, VerticalInspectionConfig> spec;
    schema.apply(body, spec, prefix);
    if (spacing) {
        spec.config.leg_spacing_m =
            io::detail::parse_real(*spacing, prefix + ".config.leg_spacing_m", kPositive);
    }
    validate_spec(spec, "rectangle", body, prefix);
    return plan_vertical_inspection(spec.request, spec.config);
}

Eigen::Vector2d parse_vector2(const ConfigNode& node, const std::string& path) {
    const std::vector<double> values = io::detail::parse_real_list(node, path, {});
    if (values.size() != 2) {
        io::detail::fail(
            node, path,
            "expected a sequence of 2 numbers, got " + std::to_string(values.size()) + " items");
    }
    return {values[0], values[1]};
}

WaypointPath plan_circular_request(ConfigNode body, const std::string& prefix) {
    static const auto schema =
        spec_schema("circle", circle_schema(), circular_inspection_config_schema());
    const std::optional<ConfigNode> centre = take_nested(body, "circle", "centre_xy_world_m");
    Spec<CircleRequest, CircularInspectionConfig> spec;
    schema.apply(body, spec, prefix);
    if (centre) {
        spec.request.centre_xy_world_m =
            parse_vector2(*centre, prefix + ".circle.centre_xy_world_m");
    }
    validate_spec(spec, "circle", body, prefix);
    return plan_circular_inspection(spec.request, spec.config);
}

WaypointPath plan_go_to_request(const ConfigNode& body, const RecordedPoints& points,
                                const std::string& prefix) {
    ConfigNode rest = body;
    const std::optional<ConfigNode> point = take(rest, "point");
    const std::string point_key = join_key(prefix, "point");
    if (!point) io::detail::fail(body, point_key, "missing: a recorded point's name");
    GoToSpec spec;
    go_to_spec_schema().apply(rest, spec, prefix);
    const std::string name = io::detail::parse_string(*point, point_key);
    try {
        return plan_go_to_point(points, name, spec.config);
    } catch (const InputError& error) {  // an unknown name: point at the line that asks for it
        io::detail::fail(*point, point_key, error.what());
    }
}

WaypointPath plan_home_request(const ConfigNode& body, const ConfigNode& type,
                               const MissionContext& context, const std::string& prefix) {
    GoToSpec spec;
    go_to_spec_schema().apply(body, spec, prefix);
    if (!context.p_takeoff_world_m) {
        io::detail::fail(type, join_key(prefix, "type"),
                         "home needs the take-off point, none given");
    }
    return plan_go_home(*context.p_takeoff_world_m, spec.config);
}

}  // namespace

const ConfigSchema<WallRectangle>& wall_rectangle_schema() {
    static const ConfigSchema<WallRectangle> schema = [] {
        using R = WallRectangle;
        ConfigSchema<R> s;
        s.field("corner_world_m", &R::corner_world_m, "lower-left corner, on the wall, m")
            .field("normal_world", &R::normal_world, "out of the wall, towards the vehicle")
            .field("width_m", &R::width_m, "along the wall's right, m", kPositive)
            .field("height_m", &R::height_m, "along the wall's up, m", kPositive);
        return s;
    }();
    return schema;
}

const ConfigSchema<SweepConfig>& sweep_config_schema() {
    static const ConfigSchema<SweepConfig> schema = [] {
        using C = SweepConfig;
        ConfigSchema<C> s;
        s.field("standoff_m", &C::standoff_m, "distance from the wall, m", kNonNegative)
            .field("line_spacing_m", &C::line_spacing_m, "largest distance between lines, m",
                   kPositive)
            .field("waypoint_tolerance_m", &C::waypoint_tolerance_m, "WP_tol, m", kPositive)
            .field("face_wall", &C::face_wall, "give each waypoint the yaw facing the wall");
        return s;
    }();
    return schema;
}

const ConfigSchema<VerticalInspectionConfig>& vertical_inspection_config_schema() {
    static const ConfigSchema<VerticalInspectionConfig> schema = [] {
        using C = VerticalInspectionConfig;
        ConfigSchema<C> s;
        s.field("standoff_m", &C::standoff_m, "distance from the structure, m", kNonNegative)
            .field("waypoint_tolerance_m", &C::waypoint_tolerance_m, "WP_tol, m", kPositive)
            .field("face_wall", &C::face_wall, "give each waypoint the yaw facing the structure");
        return s;
    }();
    return schema;
}

const ConfigSchema<CircularInspectionConfig>& circular_inspection_config_schema() {
    static const ConfigSchema<CircularInspectionConfig> schema = [] {
        using C = CircularInspectionConfig;
        ConfigSchema<C> s;
        s.field("points_per_turn", &C::points_per_turn, "N, waypoints per turn (>= 3)",
                io::Range{.min = 3.0})
            .field("start_angle_rad", &C::start_angle_rad, "theta_0 from world x, rad")
            .field("clockwise", &C::clockwise, "seen from above")
            .field("waypoint_tolerance_m", &C::waypoint_tolerance_m, "WP_tol, m", kPositive);
        return s;
    }();
    return schema;
}

const ConfigSchema<GoToConfig>& go_to_config_schema() {
    static const ConfigSchema<GoToConfig> schema = [] {
        ConfigSchema<GoToConfig> s;
        s.field("waypoint_tolerance_m", &GoToConfig::waypoint_tolerance_m, "WP_tol, m", kPositive);
        return s;
    }();
    return schema;
}

WaypointPath mission_from_yaml(const ConfigNode& node, const MissionContext& context,
                               const std::string& prefix) {
    if (!node.is_map()) {
        io::detail::fail(node, prefix,
                         "expected a map with a type, got " + io::describe_kind(node));
    }
    ConfigNode body = node;
    const std::optional<ConfigNode> type = take(body, "type");
    const std::string type_key = join_key(prefix, "type");
    if (!type)
        io::detail::fail(node, type_key,
                         "missing: one of " + io::detail::join_names(kMissionTypes));
    switch (static_cast<MissionType>(io::detail::parse_choice(*type, type_key, kMissionTypes))) {
        case MissionType::kSweep:
            return plan_sweep_request(body, prefix);
        case MissionType::kVertical:
            return plan_vertical_request(body, prefix);
        case MissionType::kCircular:
            return plan_circular_request(body, prefix);
        case MissionType::kGoTo:
            return plan_go_to_request(body, context.recorded_points, prefix);
        case MissionType::kHome:
            return plan_home_request(body, *type, context, prefix);
    }
    return {};
}

}  // namespace scantling::planning
