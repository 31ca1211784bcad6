// Obstacles on the world's surface in a scenario (surface_obstacles.hpp): `world.obstacles`,
// `world.plate.holes`, and the keys that apply to each obstacle kind (scenario_schema.hpp).
#include <scantling/sim/scenario_schema.hpp>

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

namespace scantling::sim::detail {
namespace {

using io::ConfigSchema;

/// Any size of a surface obstacle.
constexpr io::Range kObstacleSize = positive_up_to(limits::kMaxSurfaceObstacleSize_m);

struct KindKeys {
    std::string kind;
    std::vector<std::string> required;
    std::vector<std::string> optional;
};

const std::vector<KindKeys>& kind_keys() {
    static const std::vector<KindKeys> keys{
        {"bolt", {"position_world"}, {"diameter_m", "height_m"}},
        {"bracket", {"position_world"}, {"size_m", "yaw_deg"}},
        {"weld_bead", {"from_world", "to_world"}, {"width_m", "height_m"}}};
    return keys;
}

bool contains(const std::vector<std::string>& names, const std::string& name) {
    return std::find(names.begin(), names.end(), name) != names.end();
}

}  // namespace

ConfigSchema<PlateHoleConfig> plate_hole_schema() {
    ConfigSchema<PlateHoleConfig> s;
    s.field("centre_m", &PlateHoleConfig::centre_m, "[x, y] on the plate", kCoordinate)
        .field("size_m", &PlateHoleConfig::size_m, "[along x, along y]", kExtent);
    return s;
}

const ConfigSchema<SurfaceObstacleConfig>& surface_obstacle_schema() {
    static const ConfigSchema<SurfaceObstacleConfig> schema = [] {
        using C = SurfaceObstacleConfig;
        ConfigSchema<C> s;
        s.enum_field("kind", &C::kind,
                     {{"bolt", ObstacleKind::kBolt},
                      {"bracket", ObstacleKind::kBracket},
                      {"weld_bead", ObstacleKind::kWeldBead}},
                     "required; its keys below")
            .field("position_world", &C::position_world,
                   "bolt, bracket: required, within 0.1 m of the surface", kCoordinate)
            .field("diameter_m", &C::diameter_m, "bolt", kObstacleSize)
            .field("height_m", &C::height_m, "bolt, weld_bead: proud of the surface", kObstacleSize)
            .field("size_m", &C::size_m, "bracket: along local x, local y, the normal",
                   kObstacleSize)
            .field("yaw_deg", &C::yaw_deg, "bracket: about the normal from local x",
                   between(-360.0, 360.0))
            .field("from_world", &C::from_world, "weld_bead: required, one end", kCoordinate)
            .field("to_world", &C::to_world, "weld_bead: required, the other end", kCoordinate)
            .field("width_m", &C::width_m, "weld_bead", kObstacleSize);
        return s;
    }();
    return schema;
}

void check_surface_obstacle(const io::ConfigNode& item, const std::string& path) {
    if (!item.is_map()) return;  // the schema reports it
    const io::ConfigNode* kind = item.find("kind");
    if (kind == nullptr) io::detail::fail(item, io::detail::join_key(path, "kind"), "required");
    if (!kind->is_scalar()) return;  // the schema reports it
    const auto& all = kind_keys();
    const auto it = std::find_if(all.begin(), all.end(),
                                 [&](const KindKeys& k) { return k.kind == kind->scalar; });
    if (it == all.end()) return;  // the schema names the bad kind and lists the kinds
    for (const std::string& key : it->required) {
        if (item.find(key) == nullptr) {
            io::detail::fail(item, io::detail::join_key(path, key),
                             "required for kind '" + it->kind + "'");
        }
    }
    for (const auto& [key, value] : item.map) {
        const bool applies =
            key == "kind" || contains(it->required, key) || contains(it->optional, key);
        if (!applies && contains(surface_obstacle_schema().keys(), key)) {
            io::detail::fail(value, io::detail::join_key(path, key),
                             "does not apply to kind '" + it->kind + "'");
        }
    }
}

}  // namespace scantling::sim::detail
