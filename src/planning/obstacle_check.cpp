#include <scantling/planning/obstacle_check.hpp>

#include <cmath>
#include <cstddef>
#include <limits>

#include <fmt/format.h>

#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>
#include <scantling/core/kdtree.hpp>

namespace scantling::planning {
namespace {

double nearest_distance_m(const KdTree& tree, const Eigen::Vector3d& p_world_m) {
    const auto nearest = tree.nearest(p_world_m);
    return nearest ? std::sqrt(nearest->distance_sq_m2) : std::numeric_limits<double>::infinity();
}

[[noreturn]] void refuse(std::string_view prefix, std::size_t index, const Eigen::Vector3d& p,
                         double distance_m, double clearance_m) {
    throw ConfigError(fmt::format(
        "{}.waypoints[{}] = ({:.2f}, {:.2f}, {:.2f}) is {:.2f} m from the map, expected >= "
        "clearance {:.2f} m",
        prefix, index, p.x(), p.y(), p.z(), distance_m, clearance_m));
}

}  // namespace

std::vector<double> check_path_clear(const WaypointPath& path, const PointCloud& map_world,
                                     double clearance_m, std::string_view prefix) {
    validate(path, prefix);
    config_checks::require_non_negative(clearance_m, prefix, "clearance_m");
    const KdTree tree(remove_non_finite(map_world).points);
    std::vector<double> distances_m;
    for (const Waypoint& waypoint : path.waypoints) {
        const double distance_m = nearest_distance_m(tree, waypoint.p_world_m);
        if (distance_m < clearance_m) {
            refuse(prefix, distances_m.size(), waypoint.p_world_m, distance_m, clearance_m);
        }
        distances_m.push_back(distance_m);
    }
    return distances_m;
}

}  // namespace scantling::planning
