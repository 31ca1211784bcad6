#include <scantling/planning/hole_reinspection.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <fmt/format.h>

#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>

namespace scantling::planning {
namespace {

// Unit length, orthogonality and box containment are checked to this (unit vectors, metres).
constexpr double kTolerance = 1e-6;

void require_finite(const Eigen::Vector3d& v, std::string_view field) {
    if (!v.allFinite()) {
        throw InputError(fmt::format("hole_reinspection: {} = ({}, {}, {}), expected finite", field,
                                     v.x(), v.y(), v.z()));
    }
}

void require_unit(const Eigen::Vector3d& v, std::string_view field) {
    require_finite(v, field);
    if (std::abs(v.norm() - 1.0) > kTolerance) {
        throw InputError(
            fmt::format("hole_reinspection: {} has norm {}, expected 1", field, v.norm()));
    }
}

void require_box(double lo, double hi, const std::string& name, std::string_view axis) {
    if (!std::isfinite(lo) || !std::isfinite(hi) || lo > kTolerance || hi < -kTolerance) {
        throw InputError(fmt::format(
            "hole_reinspection: {}.box_min_{}_m = {}, box_max_{}_m = {}, expected finite with "
            "min <= 0 <= max (relative to the centroid)",
            name, axis, lo, axis, hi));
    }
}

void require_hole(const ReinspectionHole& hole, std::size_t i) {
    const std::string name = fmt::format("holes[{}]", i);
    require_finite(hole.centroid_world_m, name + ".centroid_world_m");
    require_unit(hole.axis_u_world, name + ".axis_u_world");
    require_unit(hole.axis_v_world, name + ".axis_v_world");
    const double dot = hole.axis_u_world.dot(hole.axis_v_world);
    if (std::abs(dot) > kTolerance) {
        throw InputError(fmt::format(
            "hole_reinspection: {}.axis_v_world·axis_u_world = {}, expected 0", name, dot));
    }
    require_box(hole.box_min_u_m, hole.box_max_u_m, name, "u");
    require_box(hole.box_min_v_m, hole.box_max_v_m, name, "v");
}

/// Unit normal; the 4-DoF vehicle can face it only through its horizontal part.
Eigen::Vector3d require_normal(const Eigen::Vector3d& normal_world) {
    require_finite(normal_world, "normal_world");
    const double norm = normal_world.norm();
    if (!(norm > 0.0) || normal_world.head<2>().norm() <= kTolerance * norm) {
        throw InputError(fmt::format(
            "hole_reinspection: normal_world = ({}, {}, {}), expected non-zero and not vertical "
            "(the ROV faces the hull by yaw only)",
            normal_world.x(), normal_world.y(), normal_world.z()));
    }
    return normal_world / norm;
}

/// The hole's waypoint offsets along its wider axis from the centroid: {0}, or the pass.
std::vector<Eigen::Vector3d> pass_offsets(const ReinspectionHole& hole, double footprint_m) {
    const double width_u = hole.box_max_u_m - hole.box_min_u_m;
    const double width_v = hole.box_max_v_m - hole.box_min_v_m;
    const bool along_u = width_u >= width_v;  // ties: u, deterministic
    const double width = along_u ? width_u : width_v;
    if (width <= footprint_m) return {Eigen::Vector3d::Zero()};
    const Eigen::Vector3d& axis = along_u ? hole.axis_u_world : hole.axis_v_world;
    const double lo = (along_u ? hole.box_min_u_m : hole.box_min_v_m) + footprint_m / 2.0;
    const double hi = (along_u ? hole.box_max_u_m : hole.box_max_v_m) - footprint_m / 2.0;
    // The centroid lies in the box but, for an L-shaped hole, may lie outside [lo, hi]: keep
    // the three in order along the axis so the pass never turns back.
    std::vector<double> a{lo, 0.0, hi};
    std::sort(a.begin(), a.end());
    return {a[0] * axis, a[1] * axis, a[2] * axis};
}

/// Appends the hole's waypoints, starting from the pass end nearer to `from`.
void append_hole(const ReinspectionHole& hole, const Eigen::Vector3d& normal, double yaw_rad,
                 const HoleReinspectionConfig& config, const Eigen::Vector3d& from,
                 WaypointPath& path) {
    const Eigen::Vector3d centre = hole.centroid_world_m + config.stand_off_m * normal;
    std::vector<Eigen::Vector3d> offsets = pass_offsets(hole, config.footprint_width_m);
    if ((centre + offsets.back() - from).norm() < (centre + offsets.front() - from).norm()) {
        std::reverse(offsets.begin(), offsets.end());
    }
    for (const Eigen::Vector3d& offset : offsets) {
        path.waypoints.push_back({centre + offset, yaw_rad, config.waypoint_tolerance_m});
    }
}

}  // namespace

void HoleReinspectionConfig::validate(std::string_view prefix) const {
    using namespace config_checks;
    require_positive(stand_off_m, prefix, "stand_off_m");
    require_positive(footprint_width_m, prefix, "footprint_width_m");
    require_positive(waypoint_tolerance_m, prefix, "waypoint_tolerance_m");
}

WaypointPath plan_hole_reinspection(std::span<const ReinspectionHole> holes,
                                    const Eigen::Vector3d& normal_world,
                                    const Eigen::Vector3d& p_start_world_m,
                                    const HoleReinspectionConfig& config) {
    config.validate("hole_reinspection");
    const Eigen::Vector3d normal = require_normal(normal_world);
    require_finite(p_start_world_m, "p_start_world_m");
    for (std::size_t i = 0; i < holes.size(); ++i) require_hole(holes[i], i);

    const double yaw_rad = yaw_facing(-normal);  // facing the hull
    std::vector<bool> done(holes.size(), false);
    Eigen::Vector3d position = p_start_world_m;
    WaypointPath path;
    for (std::size_t k = 0; k < holes.size(); ++k) {
        std::size_t best = holes.size();
        double best_m = std::numeric_limits<double>::infinity();
        for (std::size_t i = 0; i < holes.size(); ++i) {
            const double d =
                (holes[i].centroid_world_m + config.stand_off_m * normal - position).norm();
            if (!done[i] && d < best_m) {  // strict: ties keep the lower index
                best = i;
                best_m = d;
            }
        }
        done[best] = true;
        append_hole(holes[best], normal, yaw_rad, config, position, path);
        position = path.waypoints.back().p_world_m;
    }
    return path;
}

}  // namespace scantling::planning
