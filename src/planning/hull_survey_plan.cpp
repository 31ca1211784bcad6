#include <scantling/planning/hull_survey_plan.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <fmt/format.h>

#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>
#include <scantling/io/config_schema.hpp>

namespace scantling::planning {
namespace {

// A range a hair over a multiple of the spacing (4.000000001 / 1) adds no slice.
constexpr double kRelativeSlack = 1e-9;
// How far the hull z axis may lean off world z in hull_survey_in_world (unit vectors).
constexpr double kVerticalTolerance = 1e-6;

/// Centres of the camera along one hull axis: [from, to].
struct CentreRange {
    double from = 0.0;
    double to = 0.0;
};

/// Where the slices lie: `along` each slice, `across` them (file comment of the header).
struct SliceLayout {
    CentreRange along;
    CentreRange across;
    double max_spacing_m = 0.0;  ///< footprint across the slices × (1 − overlap)
    double num_slices = 0.0;     ///< a double: compared with the cap before any conversion
};

/// x: the footprint reaches both ends of the section (centred when the section is narrower).
CentreRange x_range(double length_m, double width_m) {
    return {std::min(width_m / 2.0, length_m / 2.0),
            std::max(length_m - width_m / 2.0, length_m / 2.0)};
}

/// Depth (positive down): top-justified, so the footprint never leaves the water.
CentreRange depth_range(const HullSurveyPlanConfig& config, double height_m) {
    const double top = config.surface_margin_m + height_m / 2.0;
    return {top, std::max(config.draught_m - height_m / 2.0, top)};
}

SliceLayout slice_layout(const HullSurveyPlanConfig& config) {
    const CameraFootprint footprint = camera_footprint(config);
    const CentreRange x = x_range(config.length_m, footprint.width_m);
    const CentreRange depth = depth_range(config, footprint.height_m);
    const bool horizontal = config.orientation == SliceOrientation::kHorizontal;
    SliceLayout layout{
        horizontal ? x : depth, horizontal ? depth : x,
        (horizontal ? footprint.height_m : footprint.width_m) * (1.0 - config.overlap)};
    const double span_m = layout.across.to - layout.across.from;
    layout.num_slices = 1.0 + std::ceil(span_m / layout.max_spacing_m * (1.0 - kRelativeSlack));
    return layout;
}

void require_fov(double fov_rad, std::string_view prefix, std::string_view field) {
    config_checks::require(fov_rad > 0.0 && fov_rad < std::numbers::pi, prefix, field, fov_rad,
                           "in (0, pi) rad");
}

/// Throws ConfigError naming the fields the slice count follows from.
void require_reasonable_size(const HullSurveyPlanConfig& config, std::string_view prefix) {
    const double num_slices = slice_layout(config).num_slices;
    if (num_slices * 2.0 <= static_cast<double>(kMaxHullSurveyWaypoints)) return;
    throw ConfigError(fmt::format(
        "{}: the plan needs {} slices, expected at most {} ({} waypoints), from length_m = {}, "
        "draught_m = {}, stand_off_m = {}, overlap = {} (a unit mistake?)",
        prefix, num_slices, kMaxHullSurveyWaypoints / 2, kMaxHullSurveyWaypoints, config.length_m,
        config.draught_m, config.stand_off_m, config.overlap));
}

/// Camera centre (along, across) in the hull frame, depth positive down.
Eigen::Vector3d hull_point(const HullSurveyPlanConfig& config, double along, double across) {
    const bool horizontal = config.orientation == SliceOrientation::kHorizontal;
    const double x = horizontal ? along : across;
    const double depth = horizontal ? across : along;
    return {x, -config.stand_off_m, -depth};
}

WaypointPath slice_waypoints(const HullSurveyPlanConfig& config, const SliceLayout& layout,
                             std::size_t num_slices) {
    const double yaw_hull_rad = yaw_facing(Eigen::Vector3d::UnitY());
    const double span_m = layout.across.to - layout.across.from;
    WaypointPath path;
    path.waypoints.reserve(2 * num_slices);
    for (std::size_t i = 0; i < num_slices; ++i) {
        const double across = num_slices == 1
                                  ? layout.across.from
                                  : layout.across.from + span_m * static_cast<double>(i) /
                                                             static_cast<double>(num_slices - 1);
        const bool forward = i % 2 == 0;  // boustrophedon
        const double start = forward ? layout.along.from : layout.along.to;
        const double end = forward ? layout.along.to : layout.along.from;
        for (const double along : {start, end}) {
            path.waypoints.push_back(
                {hull_point(config, along, across), yaw_hull_rad, config.waypoint_tolerance_m});
        }
    }
    return path;
}

double path_length_m(const WaypointPath& path) {
    double length_m = 0.0;
    for (std::size_t i = 1; i < path.waypoints.size(); ++i) {
        length_m += (path.waypoints[i].p_world_m - path.waypoints[i - 1].p_world_m).norm();
    }
    return length_m;
}

void require_upright(const Eigen::Isometry3d& T_world_hull) {
    const Eigen::Vector3d z_world = T_world_hull.linear().col(2);
    if (!T_world_hull.matrix().allFinite() ||
        (z_world - Eigen::Vector3d::UnitZ()).norm() > kVerticalTolerance) {
        throw InputError(fmt::format(
            "hull_survey: T_world_hull must be finite and keep z up, its z axis is ({}, {}, {})",
            z_world.x(), z_world.y(), z_world.z()));
    }
}

}  // namespace

void HullSurveyPlanConfig::validate(std::string_view prefix) const {
    using namespace config_checks;
    require_positive(length_m, prefix, "length_m");
    require_positive(draught_m, prefix, "draught_m");
    require_positive(stand_off_m, prefix, "stand_off_m");
    require_fov(hfov_rad, prefix, "hfov_rad");
    require_fov(vfov_rad, prefix, "vfov_rad");
    require(overlap >= 0.0 && overlap < 1.0, prefix, "overlap", overlap, "in [0, 1)");
    require_non_negative(surface_margin_m, prefix, "surface_margin_m");
    require_positive(speed_m_s, prefix, "speed_m_s");
    require_positive(waypoint_tolerance_m, prefix, "waypoint_tolerance_m");
    require_reasonable_size(*this, prefix);
}

CameraFootprint camera_footprint(const HullSurveyPlanConfig& config) {
    return {2.0 * config.stand_off_m * std::tan(config.hfov_rad / 2.0),
            2.0 * config.stand_off_m * std::tan(config.vfov_rad / 2.0)};
}

HullSurveyPlan plan_hull_survey(const HullSurveyPlanConfig& config) {
    config.validate("hull_survey");
    const SliceLayout layout = slice_layout(config);
    HullSurveyPlan plan;
    plan.num_slices = static_cast<std::size_t>(layout.num_slices);
    plan.path_hull = slice_waypoints(config, layout, plan.num_slices);
    plan.slice_spacing_m = plan.num_slices == 1 ? 0.0
                                                : (layout.across.to - layout.across.from) /
                                                      static_cast<double>(plan.num_slices - 1);
    plan.footprint = camera_footprint(config);
    plan.path_length_m = path_length_m(plan.path_hull);
    plan.estimated_time_s = plan.path_length_m / config.speed_m_s;
    return plan;
}

WaypointPath hull_survey_in_world(const HullSurveyPlan& plan,
                                  const Eigen::Isometry3d& T_world_hull) {
    require_upright(T_world_hull);
    WaypointPath path = plan.path_hull;
    for (Waypoint& waypoint : path.waypoints) {
        waypoint.p_world_m = T_world_hull * waypoint.p_world_m;  // hull → world
        if (waypoint.yaw_rad) {
            const Eigen::Vector3d facing_hull(std::cos(*waypoint.yaw_rad),
                                              std::sin(*waypoint.yaw_rad), 0.0);
            waypoint.yaw_rad = yaw_facing(T_world_hull.linear() * facing_hull);
        }
    }
    return path;
}

const io::ConfigSchema<HullSurveyPlanConfig>& hull_survey_plan_config_schema() {
    static const io::ConfigSchema<HullSurveyPlanConfig> schema = [] {
        using C = HullSurveyPlanConfig;
        using io::kNonNegative;
        using io::kPositive;
        io::ConfigSchema<C> s;
        s.field("length_m", &C::length_m, "surveyed hull section along x, m", kPositive)
            .field("draught_m", &C::draught_m, "water surface to keel, m", kPositive)
            .field("stand_off_m", &C::stand_off_m, "camera to hull, m", kPositive)
            .field("hfov_rad", &C::hfov_rad, "camera horizontal field of view, rad", kPositive)
            .field("vfov_rad", &C::vfov_rad, "camera vertical field of view, rad", kPositive)
            .field("overlap", &C::overlap, "wanted overlap of neighbouring slices, [0, 1)",
                   io::Range{.min = 0.0, .max = 1.0, .max_exclusive = true})
            .enum_field("orientation", &C::orientation,
                        {{"horizontal", SliceOrientation::kHorizontal},
                         {"vertical", SliceOrientation::kVertical}},
                        "slice direction")
            .field("surface_margin_m", &C::surface_margin_m,
                   "water surface to the shallowest footprint's upper edge, m", kNonNegative)
            .field("speed_m_s", &C::speed_m_s, "survey speed for the time estimate, m/s", kPositive)
            .field("waypoint_tolerance_m", &C::waypoint_tolerance_m, "WP_tol, m", kPositive);
        return s;
    }();
    return schema;
}

}  // namespace scantling::planning
