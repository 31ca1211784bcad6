// Through-holes and the outline of a plate world (plate_holes.hpp).
#include "plate_holes.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>

#include <scantling/core/error.hpp>
#include <scantling/sim/scenario_limits.hpp>

#include "tank_parts.hpp"

namespace scantling::sim::detail {
namespace {

/// [lo, hi] intervals of a hole along x and y.
struct HoleBox {
    double x0, x1, y0, y1;
};

HoleBox box_of(const PlateHoleConfig& h) {
    const double hx = 0.5 * h.size_m[0], hy = 0.5 * h.size_m[1];
    return {h.centre_m[0] - hx, h.centre_m[0] + hx, h.centre_m[1] - hy, h.centre_m[1] + hy};
}

std::string pair_text(const std::vector<double>& v) {
    return v.size() == 2 ? fmt::format("[{}, {}]", v[0], v[1]) : fmt::format("{} values", v.size());
}

void check_pair(const std::vector<double>& v, const std::string& field_key, bool positive) {
    const bool ok = v.size() == 2 && std::all_of(v.begin(), v.end(), [&](double x) {
                        return std::isfinite(x) && (!positive || x > 0.0);
                    });
    if (ok) return;
    throw ConfigError(fmt::format("{} = {}, expected two finite values{}", field_key, pair_text(v),
                                  positive ? " > 0" : ""));
}

[[noreturn]] void refuse_place(const std::string& hole_key, const PlateHoleConfig& h,
                               std::string_view why) {
    throw ConfigError(fmt::format("{}.centre_m = {} (size_m = {}): {}", hole_key,
                                  pair_text(h.centre_m), pair_text(h.size_m), why));
}

/// Clear of each other by at least the margin along x or along y.
bool apart(const HoleBox& a, const HoleBox& b) {
    const double m = kPlateHoleMargin_m;
    return a.x1 + m <= b.x0 || b.x1 + m <= a.x0 || a.y1 + m <= b.y0 || b.y1 + m <= a.y0;
}

void check_stiffeners(const PlateConfig& c, const HoleBox& b, const std::string& hole_key,
                      const PlateHoleConfig& h) {
    if (c.stiffener_spacing_m <= 0.0) return;
    const double t = c.stiffener.thickness_m;
    const double flange =
        c.stiffener.profile == ProfileKind::Angle ? c.stiffener.flange_width_m : 0;
    const auto positions = even_positions(c.width_m, c.stiffener_spacing_m);
    for (std::size_t k = 0; k < positions.size(); ++k) {
        // As tank_parts.cpp's add_longitudinal on the plate's top seen as a wall from y = -w/2.
        const double y = -0.5 * c.width_m + positions[k];
        const double lo = y - 0.5 * t - kPlateHoleMargin_m;
        const double hi = y + 0.5 * t + flange + kPlateHoleMargin_m;
        if (b.y1 > lo && b.y0 < hi) {
            refuse_place(hole_key, h,
                         fmt::format("the hole runs under longitudinal_{} at y = {} m, expected "
                                     "{} m clear of it",
                                     k + 1, y, kPlateHoleMargin_m));
        }
    }
}

void check_hole(const PlateConfig& c, std::size_t i, const std::string& hole_key) {
    const PlateHoleConfig& h = c.holes[i];
    check_pair(h.centre_m, hole_key + ".centre_m", false);
    check_pair(h.size_m, hole_key + ".size_m", true);
    const HoleBox b = box_of(h);
    const double ex = 0.5 * c.length_m - kPlateHoleMargin_m;
    const double ey = 0.5 * c.width_m - kPlateHoleMargin_m;
    if (!(b.x0 >= -ex && b.x1 <= ex && b.y0 >= -ey && b.y1 <= ey)) {
        refuse_place(hole_key, h,
                     fmt::format("expected the hole inside x in [{}, {}], y in [{}, {}] ({} m "
                                 "inside the plate's outline)",
                                 -ex, ex, -ey, ey, kPlateHoleMargin_m));
    }
    for (std::size_t j = 0; j < i; ++j) {
        if (!apart(b, box_of(c.holes[j]))) {
            refuse_place(hole_key, h,
                         fmt::format("the hole overlaps holes[{}], expected {} m apart", j,
                                     kPlateHoleMargin_m));
        }
    }
    check_stiffeners(c, b, hole_key, h);
}

}  // namespace

void check_plate_holes(const PlateConfig& config, std::string_view prefix) {
    if (config.holes.size() > limits::kMaxSurfaceObstacles) {
        throw ConfigError(fmt::format("{}.holes has {} holes, expected at most {}", prefix,
                                      config.holes.size(), limits::kMaxSurfaceObstacles));
    }
    for (std::size_t i = 0; i < config.holes.size(); ++i) {
        check_hole(config, i, fmt::format("{}.holes[{}]", prefix, i));
    }
}

std::vector<Loop3> plate_hole_loops(const PlateConfig& config, double z) {
    std::vector<Loop3> loops;
    for (const PlateHoleConfig& h : config.holes) {
        const HoleBox b = box_of(h);
        loops.push_back({{b.x0, b.y0, z}, {b.x1, b.y0, z}, {b.x1, b.y1, z}, {b.x0, b.y1, z}});
    }
    return loops;
}

std::vector<ObstacleTruth> plate_obstacle_truths(const PlateConfig& config) {
    const double hx = 0.5 * config.length_m, hy = 0.5 * config.width_m;
    const std::vector<Eigen::Vector3d> corners{
        {-hx, -hy, 0}, {hx, -hy, 0}, {hx, hy, 0}, {-hx, hy, 0}};
    std::vector<ObstacleTruth> truths;
    for (std::size_t k = 0; k < corners.size(); ++k) {
        truths.push_back({.kind = ObstacleKind::kPlateEdge,
                          .name = fmt::format("plate_edge_{}", k + 1),
                          .a_world_m = corners[k],
                          .b_world_m = corners[(k + 1) % corners.size()],
                          .radius_m = kPlateEdgeRadius_m,
                          .height_m = -config.thickness_m});
    }
    for (std::size_t i = 0; i < config.holes.size(); ++i) {
        const PlateHoleConfig& h = config.holes[i];
        // The inscribed capsule: its axis along the longer side, radius half the shorter.
        const bool along_x = h.size_m[0] >= h.size_m[1];
        const double half_axis = 0.5 * std::abs(h.size_m[0] - h.size_m[1]);
        const Eigen::Vector3d c(h.centre_m[0], h.centre_m[1], 0.0);
        const Eigen::Vector3d u = along_x ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
        truths.push_back({.kind = ObstacleKind::kHole,
                          .name = fmt::format("hole_{}", i + 1),
                          .a_world_m = c - half_axis * u,
                          .b_world_m = c + half_axis * u,
                          .radius_m = 0.5 * std::min(h.size_m[0], h.size_m[1]),
                          .height_m = -config.thickness_m});
    }
    return truths;
}

}  // namespace scantling::sim::detail
