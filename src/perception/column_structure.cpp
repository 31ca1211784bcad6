// Column structure detection, SPEC §7 art. F: floor/ceiling, wall, downcomer.
#include <scantling/perception/column_structure.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <utility>
#include <vector>

#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>

#include "detail/angles.hpp"

namespace scantling::perception {
namespace {

using detail::radians;

using config_checks::require;
using config_checks::require_positive;

// Extents are taken between the 2nd and 98th percentiles: a plane's 2 cm band also catches
// stray points where it crosses other surfaces, which would stretch a min–max extent.
constexpr double kExtentQuantile = 0.02;
// A vertical plane wider than this many times the widest strip a wall can give (below) is a
// flat plate: 25 % covers the strip's PCA refit spreading past the band's ideal width.
constexpr double kWallStripMargin = 1.25;
// A downcomer's points are mostly off the wall: a vertical plane through the column meets the
// wall in two vertical lines, and a plane made of little else is no plate.
constexpr double kMinOffWallShare = 0.5;
// Wall fits: the first, and refits after leaving out plates it placed inside the wall (one
// more is enough when one plate is in view; the cap bounds the cost).
constexpr int kMaxWallFits = 3;
// The known-radius centre refit converges quadratically from the free fit's centre (a few
// steps); the cap only guards a degenerate normal matrix.
constexpr int kMaxGaussNewtonSteps = 20;
constexpr double kStepToleranceM = 1e-10;
// A plate's continuous height is counted in 5 cm bins of at least 5 points: a depth frame at
// 2–3 m puts hundreds of a plate's points in each, stray points in a plane's band a few.
constexpr double kHeightBinM = 0.05;
constexpr std::ptrdiff_t kMinPointsPerBin = 5;

/// The inputs' geometry: unit `up`, the sensor, and the angle tests of the config.
struct Setting {
    Eigen::Vector3d up;
    Eigen::Vector3d viewpoint;
    double sin_tolerance = 0.0;  ///< |n · up| at most this: vertical plane
    double cos_tolerance = 0.0;  ///< |n · up| at least this: horizontal plane

    bool horizontal(const Plane& p) const { return std::abs(p.normal.dot(up)) >= cos_tolerance; }
    bool vertical(const Plane& p) const { return std::abs(p.normal.dot(up)) <= sin_tolerance; }
    double height(const Eigen::Vector3d& p) const { return up.dot(p); }
};

/// Robust extent (98th − 2nd percentile) of the values.
double robust_extent(std::vector<double> values) {
    if (values.empty()) return 0.0;
    const auto at = [&](double q) {
        const auto k = static_cast<std::ptrdiff_t>(q * static_cast<double>(values.size() - 1));
        std::nth_element(values.begin(), values.begin() + k, values.end());
        return values[static_cast<std::size_t>(k)];
    };
    return at(1.0 - kExtentQuantile) - at(kExtentQuantile);
}

double extent_along(const PointCloud& cloud, const std::vector<std::size_t>& indices,
                    const Eigen::Vector3d& direction) {
    std::vector<double> values;
    values.reserve(indices.size());
    for (const std::size_t i : indices) values.push_back(direction.dot(cloud.points[i]));
    return robust_extent(std::move(values));
}

/// The widest flat strip a plane search with bands of ±t cuts from a wall of radius R: the
/// wall leaves the band where its sagitta w²/(2R) reaches 2t, so 2w = 2 √(4 R t). Taken at the
/// largest accepted radius.
double max_wall_strip_width_m(const ColumnStructureConfig& config) {
    const double radius_m = 0.5 * (config.diameter_m + config.diameter_tolerance_m);
    return 2.0 * std::sqrt(4.0 * radius_m * config.planes.distance_threshold_m);
}

/// A vertical plane too wide to be a strip of the wall: its points stay out of the wall fit.
bool is_flat_plate(const PointCloud& cloud, const Plane& plane, const Setting& s,
                   const ColumnStructureConfig& config) {
    if (!s.vertical(plane)) return false;
    const Eigen::Vector3d across = s.up.cross(plane.normal).normalized();
    return extent_along(cloud, plane.inliers, across) >
           kWallStripMargin * max_wall_strip_width_m(config);
}

void find_floor_and_ceiling(const std::vector<Plane>& planes, const Setting& s,
                            ColumnStructure& out) {
    // Planes come largest first: the first match on each side is the largest.
    for (const Plane& plane : planes) {
        if (!s.horizontal(plane)) continue;
        const bool below = s.height(plane.centroid) < s.height(s.viewpoint);
        std::optional<Plane>& slot = below ? out.floor : out.ceiling;
        if (!slot) slot = facing(plane, s.viewpoint);
    }
}

/// A candidate downcomer: the plane made exactly vertical, relative to the axis.
struct Chord {
    Eigen::Vector3d normal;  ///< horizontal, unit, facing the viewpoint
    double offset_m = 0.0;   ///< plate = axis + offset · normal (any axis point: n ⟂ up)
};

Chord chord_of(const Plane& plane, const Eigen::Vector3d& axis_point, const Setting& s) {
    Eigen::Vector3d n = (plane.normal - plane.normal.dot(s.up) * s.up).normalized();
    if (n.dot(s.viewpoint - plane.centroid) < 0.0) n = -n;
    return {n, n.dot(plane.centroid - axis_point)};
}

/// A vertical plane clearly inside the wall: a chord, not a strip of the wall.
bool is_chord(const Plane& plane, const Cylinder& wall, const Setting& s,
              const ColumnStructureConfig& config) {
    return s.vertical(plane) && std::abs(chord_of(plane, wall.centre, s).offset_m) <
                                    wall.radius_m - config.min_chord_depth_m;
}

/// Points kept out of the wall fit: those on horizontal planes and flat plates.
std::vector<bool> not_wall(const PointCloud& cloud, const std::vector<Plane>& planes,
                           const Setting& s, const ColumnStructureConfig& config) {
    std::vector<bool> excluded(cloud.size(), false);
    for (const Plane& plane : planes) {
        if (!s.horizontal(plane) && !is_flat_plate(cloud, plane, s, config)) continue;
        for (const std::size_t i : plane.inliers) excluded[i] = true;
    }
    return excluded;
}

/// Also keeps the chords of `wall` out; true when that excluded more points.
bool exclude_chords(const std::vector<Plane>& planes, const Cylinder& wall, const Setting& s,
                    const ColumnStructureConfig& config, std::vector<bool>& excluded) {
    bool more = false;
    for (const Plane& plane : planes) {
        if (!is_chord(plane, wall, s, config)) continue;
        for (const std::size_t i : plane.inliers) {
            more = more || !excluded[i];
            excluded[i] = true;
        }
    }
    return more;
}

/// The cylinder over the points not excluded; its inliers index `cloud`.
std::optional<Cylinder> fit_wall(const PointCloud& cloud, const std::vector<bool>& excluded,
                                 const Setting& s, const ColumnStructureConfig& config,
                                 std::size_t& num_candidates) {
    std::vector<std::size_t> candidates;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        if (!excluded[i]) candidates.push_back(i);
    }
    num_candidates = candidates.size();
    auto wall = fit_cylinder(select(cloud, candidates), s.up, config.cylinder);
    if (wall) {
        for (std::size_t& i : wall->inliers) i = candidates[i];
    }
    return wall;
}

/// The axis fitted to the wall's inliers with the radius held at `radius_m`: Gauss–Newton on
/// r_i = |q_i − c| − R over the centre c alone, from the free fit's centre.
Eigen::Vector3d known_radius_centre(const PointCloud& cloud, const Cylinder& wall,
                                    double radius_m) {
    const Eigen::Vector3d e1 = wall.axis.unitOrthogonal(), e2 = wall.axis.cross(e1);
    Eigen::Vector2d c(e1.dot(wall.centre), e2.dot(wall.centre));
    for (int step = 0; step < kMaxGaussNewtonSteps; ++step) {
        Eigen::Matrix2d H = Eigen::Matrix2d::Zero();
        Eigen::Vector2d g = Eigen::Vector2d::Zero();
        for (const std::size_t i : wall.inliers) {
            const Eigen::Vector2d d =
                Eigen::Vector2d(e1.dot(cloud.points[i]), e2.dot(cloud.points[i])) - c;
            const double r = d.norm();
            if (!(r > 0.0)) continue;
            H += (d / r) * (d / r).transpose();  // J = −d/r
            g -= (d / r) * (r - radius_m);
        }
        const Eigen::Vector2d delta = -H.ldlt().solve(g);
        if (!delta.allFinite()) break;
        c += delta;
        if (delta.norm() < kStepToleranceM) break;
    }
    return c.x() * e1 + c.y() * e2;
}

/// The wall and its diameter check. A plate seen beside the wall pulls the circle towards
/// itself; once a fit places it inside the wall its points are left out and the wall refitted.
/// Returns how many points the last fit ran on.
std::size_t find_wall(const PointCloud& cloud, const std::vector<Plane>& planes, const Setting& s,
                      const ColumnStructureConfig& config, ColumnStructure& out) {
    std::vector<bool> excluded = not_wall(cloud, planes, s, config);
    std::size_t num_candidates = 0;
    std::optional<Cylinder> wall;
    for (int pass = 0; pass < kMaxWallFits; ++pass) {
        wall = fit_wall(cloud, excluded, s, config, num_candidates);
        if (!wall || !exclude_chords(planes, *wall, s, config, excluded)) break;
    }
    if (!wall) return num_candidates;
    out.diameter_ok =
        std::abs(2.0 * wall->radius_m - config.diameter_m) <= config.diameter_tolerance_m;
    const Eigen::Vector3d centre = out.diameter_ok && config.axis_from_known_diameter
                                       ? known_radius_centre(cloud, *wall, 0.5 * config.diameter_m)
                                       : wall->centre;
    out.axis_point = centre + s.height(s.viewpoint) * s.up;
    out.wall = std::move(wall);
    return num_candidates;
}

/// The plane's inliers farther than the wall fit's band from the wall.
std::vector<std::size_t> off_wall(const PointCloud& cloud, const Plane& plane, const Cylinder& wall,
                                  const ColumnStructureConfig& config) {
    std::vector<std::size_t> kept;
    for (const std::size_t i : plane.inliers) {
        const Eigen::Vector3d d = cloud.points[i] - wall.centre;
        const double radial_m = (d - d.dot(wall.axis) * wall.axis).norm();
        if (std::abs(radial_m - wall.radius_m) > config.cylinder.distance_threshold_m) {
            kept.push_back(i);
        }
    }
    return kept;
}

/// The longest stretch along `up` that the points cover without a gap: kHeightBinM bins each
/// holding kMinPointsPerBin points. A plane's band also crosses the floor and stray points, so
/// the span of all its points would make a beam's face as tall as the room.
double continuous_height_m(const PointCloud& cloud, const std::vector<std::size_t>& indices,
                           const Setting& s) {
    if (indices.empty()) return 0.0;
    std::vector<long long> bins;
    bins.reserve(indices.size());
    for (const std::size_t i : indices) {
        bins.push_back(std::llround(std::floor(s.height(cloud.points[i]) / kHeightBinM)));
    }
    std::sort(bins.begin(), bins.end());
    long long run = 0, best = 0, previous = 0;
    for (auto it = bins.begin(); it != bins.end();) {
        const auto next = std::upper_bound(it, bins.end(), *it);
        if (next - it >= kMinPointsPerBin) {
            run = (run > 0 && *it == previous + 1) ? run + 1 : 1;
            previous = *it;
            best = std::max(best, run);
        } else {
            run = 0;
        }
        it = next;
    }
    return static_cast<double>(best) * kHeightBinM;
}

/// The plane through the points at `indices`, facing the viewpoint, with those inliers.
Plane refit(const PointCloud& cloud, std::vector<std::size_t> indices, const Setting& s) {
    std::vector<Eigen::Vector3d> points;
    points.reserve(indices.size());
    for (const std::size_t i : indices) points.push_back(cloud.points[i]);
    Plane plane = fit_plane(points, s.viewpoint);
    plane.inliers = std::move(indices);
    return plane;
}

/// Art. F's downcomer: a chord of the wall, a plate rather than the wall lines a vertical plane
/// also cuts, and taller than the beams. Refitted to its points off the wall: where the plane's
/// band meets the wall it takes wall points, which tilt a plate seen over a short width.
std::optional<Plane> as_downcomer(const PointCloud& cloud, const Plane& plane, const Cylinder& wall,
                                  const Setting& s, const ColumnStructureConfig& config) {
    if (!is_chord(plane, wall, s, config)) return std::nullopt;
    std::vector<std::size_t> plate = off_wall(cloud, plane, wall, config);
    const double share =
        static_cast<double>(plate.size()) / static_cast<double>(plane.inliers.size());
    // The height test also guarantees the >= 3 non-collinear points the refit needs: a
    // continuous run of kMinPointsPerBin-point bins, each point with its own noise.
    if (share < kMinOffWallShare ||
        continuous_height_m(cloud, plate, s) < config.min_downcomer_height_m) {
        return std::nullopt;
    }
    return refit(cloud, std::move(plate), s);
}

void find_downcomer(const PointCloud& cloud, const std::vector<Plane>& planes, const Setting& s,
                    const ColumnStructureConfig& config, ColumnStructure& out) {
    for (const Plane& plane : planes) {  // largest first: the first candidate is kept
        std::optional<Plane> plate = as_downcomer(cloud, plane, *out.wall, s, config);
        if (!plate) continue;
        ++out.downcomer_candidates;
        if (out.downcomer) continue;
        const Chord chord = chord_of(*plate, *out.axis_point, s);
        out.downcomer_normal = chord.normal;
        out.downcomer_offset_m = chord.offset_m;
        out.downcomer = std::move(plate);
    }
}

std::string describe_planes(const ColumnStructure& out) {
    return fmt::format("{}; {}", out.floor ? "floor" : "no floor: no horizontal plane below",
                       out.ceiling ? "ceiling" : "no ceiling: no horizontal plane above");
}

std::string describe_wall(const ColumnStructure& out, std::size_t candidates,
                          const ColumnStructureConfig& config) {
    if (!out.wall) {
        return fmt::format(
            "no wall: no circle about up with >= {} inliers among the {} points off the "
            "horizontal planes and flat plates",
            config.cylinder.min_inliers, candidates);
    }
    return fmt::format("wall Ø {:.3f} m {} the expected {} ± {} m", 2.0 * out.wall->radius_m,
                       out.diameter_ok ? "within" : "NOT within", config.diameter_m,
                       config.diameter_tolerance_m);
}

std::string describe_downcomer(const ColumnStructure& out, const ColumnStructureConfig& config) {
    if (!out.wall) return "no downcomer: no wall to place it against";
    if (!out.downcomer) {
        return fmt::format(
            "no downcomer: no vertical plate >= {} m inside the wall seen over >= {} m of height "
            "without a gap",
            config.min_chord_depth_m, config.min_downcomer_height_m);
    }
    const std::string unique =
        out.downcomer_candidates > 1
            ? fmt::format(" (the largest of {} candidates: not unique)", out.downcomer_candidates)
            : "";
    return fmt::format("downcomer {:.3f} m from the axis{}", std::abs(out.downcomer_offset_m),
                       unique);
}

void check_inputs(const PointCloud& cloud, const Eigen::Vector3d& up,
                  const Eigen::Vector3d& viewpoint) {
    check_consistent(cloud, "detect_column_structure");
    check_finite(cloud, "detect_column_structure");
    if (!up.allFinite() || !(up.stableNorm() > 0.0)) {
        throw InputError(
            fmt::format("detect_column_structure: up ({}, {}, {}) must be finite and non-zero",
                        up.x(), up.y(), up.z()));
    }
    if (!viewpoint.allFinite()) {
        throw InputError("detect_column_structure: the viewpoint must be finite");
    }
}

}  // namespace

void ColumnStructureConfig::validate(std::string_view prefix) const {
    require_positive(diameter_m, prefix, "diameter_m");
    require(std::isfinite(diameter_tolerance_m) && diameter_tolerance_m > 0.0 &&
                diameter_tolerance_m < diameter_m,
            prefix, "diameter_tolerance_m", diameter_tolerance_m, "in (0, diameter_m)");
    require(vertical_tolerance_deg > 0.0 && vertical_tolerance_deg < 45.0, prefix,
            "vertical_tolerance_deg", vertical_tolerance_deg, "in (0, 45)");
    require(std::isfinite(min_chord_depth_m) && min_chord_depth_m > 0.0 &&
                min_chord_depth_m < 0.5 * diameter_m,
            prefix, "min_chord_depth_m", min_chord_depth_m, "in (0, diameter_m / 2)");
    require_positive(min_downcomer_height_m, prefix, "min_downcomer_height_m");
    planes.validate(fmt::format("{}.planes", prefix));
    const std::string cylinder_prefix = fmt::format("{}.cylinder", prefix);
    cylinder.validate(cylinder_prefix);
    // The wall search must be able to return every diameter the check accepts.
    const double smallest_m = 0.5 * (diameter_m - diameter_tolerance_m);
    const double largest_m = 0.5 * (diameter_m + diameter_tolerance_m);
    require(cylinder.min_radius_m <= smallest_m, cylinder_prefix, "min_radius_m",
            cylinder.min_radius_m, fmt::format("<= (diameter_m - tolerance) / 2 = {}", smallest_m));
    require(cylinder.max_radius_m >= largest_m, cylinder_prefix, "max_radius_m",
            cylinder.max_radius_m, fmt::format(">= (diameter_m + tolerance) / 2 = {}", largest_m));
}

ColumnStructure detect_column_structure(const PointCloud& cloud, const Eigen::Vector3d& up,
                                        const Eigen::Vector3d& viewpoint,
                                        const ColumnStructureConfig& config) {
    config.validate();
    check_inputs(cloud, up, viewpoint);
    ColumnStructure out;
    if (cloud.empty()) {
        out.status = "empty cloud: nothing detected";
        return out;
    }
    const double tolerance_rad = radians(config.vertical_tolerance_deg);
    const Setting s{up / up.stableNorm(), viewpoint, std::sin(tolerance_rad),
                    std::cos(tolerance_rad)};
    const std::vector<Plane> planes = segment_planes(cloud, config.planes);
    find_floor_and_ceiling(planes, s, out);
    const std::size_t num_candidates = find_wall(cloud, planes, s, config, out);
    if (out.wall) find_downcomer(cloud, planes, s, config, out);
    out.status =
        fmt::format("{}; {}; {}", describe_planes(out), describe_wall(out, num_candidates, config),
                    describe_downcomer(out, config));
    return out;
}

}  // namespace scantling::perception
