// The ROV's initial hull survey (SPEC §5, issue 14 item 1): the reported surveys' figures
// against hand-computed geometry, coverage of the whole 30 × 5 m section, the boustrophedon
// order, the world placement, the YAML binding and every impossible request.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include <scantling/core/error.hpp>
#include <scantling/io/config_node.hpp>
#include <scantling/io/config_schema.hpp>
#include <scantling/planning/hull_survey_plan.hpp>

#include "expect_error.hpp"

namespace scantling::planning {
namespace {

constexpr double kHandRounding = 1e-6;  // m, s: the hand-computed figures have 6 decimals
constexpr double kExact = 1e-9;         // m, rad: closed-form positions
constexpr double kPi = std::numbers::pi;
const double kNaN = std::numeric_limits<double>::quiet_NaN();

HullSurveyPlanConfig reported_horizontal() { return {}; }  // the defaults are that survey

HullSurveyPlanConfig reported_vertical() {
    HullSurveyPlanConfig config;
    config.orientation = SliceOrientation::kVertical;
    config.stand_off_m = 1.3;
    return config;
}

/// Slice k's two waypoints (hull frame).
Eigen::Vector3d start_of(const HullSurveyPlan& plan, std::size_t k) {
    return plan.path_hull.waypoints[2 * k].p_world_m;
}
Eigen::Vector3d end_of(const HullSurveyPlan& plan, std::size_t k) {
    return plan.path_hull.waypoints[2 * k + 1].p_world_m;
}

/// Whether the hull point (x, z) lies inside the footprint swept along some slice.
bool covered(const HullSurveyPlan& plan, double x, double z) {
    const double half_w = plan.footprint.width_m / 2.0 + kExact;
    const double half_h = plan.footprint.height_m / 2.0 + kExact;
    for (std::size_t k = 0; k < plan.num_slices; ++k) {
        const Eigen::Vector3d a = start_of(plan, k);
        const Eigen::Vector3d b = end_of(plan, k);
        if (x >= std::min(a.x(), b.x()) - half_w && x <= std::max(a.x(), b.x()) + half_w &&
            z >= std::min(a.z(), b.z()) - half_h && z <= std::max(a.z(), b.z()) + half_h) {
            return true;
        }
    }
    return false;
}

/// Hull points of the 30 × 5 m section (5 cm grid, edges included) seen by no slice.
int uncovered_points(const HullSurveyPlan& plan) {
    int uncovered = 0;
    for (int i = 0; i <= 600; ++i) {
        for (int j = 0; j <= 100; ++j) {
            if (!covered(plan, 0.05 * i, -0.05 * j)) ++uncovered;
        }
    }
    return uncovered;
}

TEST(HullSurveyPlan, FootprintAtTheReportedStandOffs) {
    // w = 2 d tan(38.5°), h = 2 d tan(24°)
    const CameraFootprint at_1_0 = camera_footprint(reported_horizontal());
    EXPECT_NEAR(at_1_0.width_m, 1.590872, kHandRounding);
    EXPECT_NEAR(at_1_0.height_m, 0.890457, kHandRounding);
    const CameraFootprint at_1_3 = camera_footprint(reported_vertical());
    EXPECT_NEAR(at_1_3.width_m, 2.068133, kHandRounding);
    EXPECT_NEAR(at_1_3.height_m, 1.157595, kHandRounding);
}

TEST(HullSurveyPlan, ReportedHorizontalSurveyHasSevenSlicesDownToTheKeel) {
    // Depth centres 0.445229 … 5 − 0.445229: 4.109543 m at ≤ 0.8 · 0.890457 = 0.712366 m
    // → 6 gaps, 7 slices 0.684924 m apart; each 30 − 1.590872 m long.
    const HullSurveyPlan plan = plan_hull_survey(reported_horizontal());
    ASSERT_EQ(plan.num_slices, 7u);
    ASSERT_EQ(plan.path_hull.waypoints.size(), 14u);
    EXPECT_NEAR(plan.slice_spacing_m, 0.684924, kHandRounding);
    EXPECT_NEAR(plan.path_length_m, 7 * 28.409128 + 6 * 0.684924, 10 * kHandRounding);
    EXPECT_NEAR(plan.estimated_time_s, plan.path_length_m / 0.25, kExact);
    EXPECT_TRUE(start_of(plan, 0).isApprox(Eigen::Vector3d(0.795436, -1.0, -0.445229), 1e-6));
    EXPECT_NEAR(end_of(plan, 6).z(), -(5.0 - 0.445229), kHandRounding);
    for (const Waypoint& waypoint : plan.path_hull.waypoints) {
        EXPECT_NEAR(waypoint.p_world_m.y(), -1.0, kExact);
        EXPECT_NEAR(*waypoint.yaw_rad, kPi / 2.0, kExact);  // facing +y, the hull
        EXPECT_EQ(waypoint.tolerance_m, 0.20);
    }
}

TEST(HullSurveyPlan, ReportedVerticalSurveyHasEighteenSlicesAlongTheHull) {
    // x centres 1.034067 … 30 − 1.034067: 27.931867 m at ≤ 0.8 · 2.068133 = 1.654507 m
    // → 17 gaps, 18 slices 1.643051 m apart; each 5 − 1.157595 m long.
    const HullSurveyPlan plan = plan_hull_survey(reported_vertical());
    ASSERT_EQ(plan.num_slices, 18u);
    EXPECT_NEAR(plan.slice_spacing_m, 1.643051, kHandRounding);
    EXPECT_NEAR(plan.path_length_m, 18 * 3.842405 + 17 * 1.643051, 20 * kHandRounding);
    EXPECT_TRUE(start_of(plan, 0).isApprox(Eigen::Vector3d(1.034067, -1.3, -0.578797), 1e-6));
    for (const Waypoint& waypoint : plan.path_hull.waypoints) {
        EXPECT_NEAR(waypoint.p_world_m.y(), -1.3, kExact);
    }
}

TEST(HullSurveyPlan, HorizontalSlicesAlternateDirectionFromSurfaceDown) {
    const HullSurveyPlan plan = plan_hull_survey(reported_horizontal());
    for (std::size_t k = 0; k < plan.num_slices; ++k) {
        EXPECT_NEAR(start_of(plan, k).z(), end_of(plan, k).z(), kExact) << k;  // constant depth
        EXPECT_EQ(start_of(plan, k).x() < end_of(plan, k).x(), k % 2 == 0) << k;
        if (k > 0) {
            EXPECT_NEAR(start_of(plan, k).z(), end_of(plan, k - 1).z() - plan.slice_spacing_m,
                        kExact);
            EXPECT_NEAR(start_of(plan, k).x(), end_of(plan, k - 1).x(), kExact);  // no detour
        }
    }
}

TEST(HullSurveyPlan, VerticalSlicesAlternateDirectionFirstDownwards) {
    const HullSurveyPlan plan = plan_hull_survey(reported_vertical());
    for (std::size_t k = 0; k < plan.num_slices; ++k) {
        EXPECT_NEAR(start_of(plan, k).x(), end_of(plan, k).x(), kExact) << k;
        EXPECT_EQ(start_of(plan, k).z() > end_of(plan, k).z(), k % 2 == 0) << k;  // even: down
        if (k > 0) {
            EXPECT_NEAR(start_of(plan, k).x(), end_of(plan, k - 1).x() + plan.slice_spacing_m,
                        kExact);
        }
    }
}

TEST(HullSurveyPlan, ReportedSurveysSeeTheWholeSectionWithTheFootprintInTheWater) {
    for (const HullSurveyPlanConfig& config : {reported_horizontal(), reported_vertical()}) {
        const HullSurveyPlan plan = plan_hull_survey(config);
        EXPECT_EQ(uncovered_points(plan), 0);
        for (const Waypoint& waypoint : plan.path_hull.waypoints) {
            EXPECT_LE(waypoint.p_world_m.z() + plan.footprint.height_m / 2.0, kExact);
        }
        const double across = config.orientation == SliceOrientation::kHorizontal
                                  ? plan.footprint.height_m
                                  : plan.footprint.width_m;
        EXPECT_LE(plan.slice_spacing_m, across * (1.0 - config.overlap));  // at least the overlap
    }
}

TEST(HullSurveyPlan, CoverageCheckSeesAGapWhenASliceIsMissing) {
    HullSurveyPlan plan = plan_hull_survey(reported_horizontal());
    plan.path_hull.waypoints.erase(plan.path_hull.waypoints.begin() + 6,
                                   plan.path_hull.waypoints.begin() + 8);
    plan.num_slices -= 1;
    EXPECT_GT(uncovered_points(plan), 0);  // the neighbours, 1.37 m apart, see 0.89 m each
}

TEST(HullSurveyPlan, ShallowHullNeedsOneSliceBelowTheSurfaceMargin) {
    HullSurveyPlanConfig config;
    config.draught_m = 0.5;
    config.surface_margin_m = 0.1;
    const HullSurveyPlan plan = plan_hull_survey(config);
    ASSERT_EQ(plan.num_slices, 1u);
    EXPECT_EQ(plan.slice_spacing_m, 0.0);
    EXPECT_NEAR(start_of(plan, 0).z(), -(0.1 + 0.890457 / 2.0), kHandRounding);
}

TEST(HullSurveyPlan, ShortSectionGetsOneCentredVerticalSlice) {
    HullSurveyPlanConfig config = reported_vertical();
    config.length_m = 1.0;  // narrower than the 2.07 m footprint
    const HullSurveyPlan plan = plan_hull_survey(config);
    ASSERT_EQ(plan.num_slices, 1u);
    EXPECT_NEAR(start_of(plan, 0).x(), 0.5, kExact);
    EXPECT_NEAR(plan.path_length_m, 3.842405, kHandRounding);
}

TEST(HullSurveyPlan, WorldPlacementMovesPointsAndFacesTheHull) {
    const HullSurveyPlan plan = plan_hull_survey(reported_horizontal());
    const double yaw_hull_in_world_rad = kPi / 6.0;
    const Eigen::Isometry3d T_world_hull =
        Eigen::Translation3d(100.0, 50.0, 2.0) *
        Eigen::AngleAxisd(yaw_hull_in_world_rad, Eigen::Vector3d::UnitZ());
    const WaypointPath path = hull_survey_in_world(plan, T_world_hull);
    ASSERT_EQ(path.waypoints.size(), plan.path_hull.waypoints.size());
    for (std::size_t i = 0; i < path.waypoints.size(); ++i) {
        const Waypoint& waypoint = path.waypoints[i];
        EXPECT_TRUE(waypoint.p_world_m.isApprox(
            T_world_hull * plan.path_hull.waypoints[i].p_world_m, kExact));
        EXPECT_NEAR(*waypoint.yaw_rad, kPi / 2.0 + yaw_hull_in_world_rad, kExact);
        // One stand-off ahead along the heading lies on the hull plane y = 0.
        const Eigen::Vector3d ahead_world =
            waypoint.p_world_m +
            Eigen::Vector3d(std::cos(*waypoint.yaw_rad), std::sin(*waypoint.yaw_rad), 0.0);
        EXPECT_NEAR((T_world_hull.inverse() * ahead_world).y(), 0.0, kExact);
    }
    EXPECT_NEAR(path.waypoints[0].p_world_m.z(), 2.0 - 0.445229, kHandRounding);
}

TEST(HullSurveyPlan, WorldPlacementRefusesATiltedOrNonFiniteHullFrame) {
    const HullSurveyPlan plan = plan_hull_survey();
    const Eigen::Isometry3d tilted(Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitX()));
    SCANTLING_EXPECT_ERROR(hull_survey_in_world(plan, tilted), InputError, "keep z up");
    Eigen::Isometry3d broken = Eigen::Isometry3d::Identity();
    broken.translation().x() = kNaN;
    SCANTLING_EXPECT_ERROR(hull_survey_in_world(plan, broken), InputError, "finite");
}

TEST(HullSurveyPlan, ImpossibleRequestsAreRefusedNamingTheField) {
    const auto expect_refused = [](auto&& edit, const std::string& needle) {
        HullSurveyPlanConfig config;
        edit(config);
        SCANTLING_EXPECT_ERROR(plan_hull_survey(config), ConfigError, needle);
    };
    expect_refused([](auto& c) { c.draught_m = 0.0; }, "hull_survey.draught_m = 0, expected");
    expect_refused([](auto& c) { c.draught_m = -2.0; }, "hull_survey.draught_m = -2");
    expect_refused([](auto& c) { c.length_m = 0.0; }, "hull_survey.length_m = 0");
    expect_refused([](auto& c) { c.length_m = kNaN; }, "hull_survey.length_m = nan");
    expect_refused([](auto& c) { c.overlap = 1.0; }, "hull_survey.overlap = 1, expected in [0, 1)");
    expect_refused([](auto& c) { c.overlap = -0.1; }, "hull_survey.overlap = -0.1");
    expect_refused([](auto& c) { c.overlap = kNaN; }, "hull_survey.overlap = nan");
    expect_refused([](auto& c) { c.stand_off_m = 0.0; }, "hull_survey.stand_off_m = 0");
    expect_refused([](auto& c) { c.stand_off_m = kNaN; }, "hull_survey.stand_off_m = nan");
    expect_refused([](auto& c) { c.hfov_rad = 0.0; },
                   "hull_survey.hfov_rad = 0, expected in (0, pi)");
    expect_refused([](auto& c) { c.hfov_rad = kPi; }, "hull_survey.hfov_rad = 3.14");
    expect_refused([](auto& c) { c.vfov_rad = -1.0; }, "hull_survey.vfov_rad = -1");
    expect_refused([](auto& c) { c.vfov_rad = kNaN; }, "hull_survey.vfov_rad = nan");
    expect_refused([](auto& c) { c.surface_margin_m = -0.1; }, "hull_survey.surface_margin_m");
    expect_refused([](auto& c) { c.speed_m_s = 0.0; }, "hull_survey.speed_m_s = 0");
    expect_refused([](auto& c) { c.waypoint_tolerance_m = 0.0; }, "waypoint_tolerance_m = 0");
}

TEST(HullSurveyPlan, AbsurdlyLargePlansAreRefusedBeforeAllocating) {
    HullSurveyPlanConfig config = reported_vertical();
    config.length_m = 30000.0;  // millimetres typed as metres: ~18 000 slices
    SCANTLING_EXPECT_ERROR(plan_hull_survey(config), ConfigError,
                           "hull_survey: the plan needs 18133 slices, expected at most 5000");
    config.length_m = 3000.0;  // a long quay is still a plan
    EXPECT_EQ(plan_hull_survey(config).num_slices, 1813u);
    config = reported_horizontal();
    config.overlap = 0.999999;
    SCANTLING_EXPECT_ERROR(plan_hull_survey(config), ConfigError, "overlap = 0.999999");
}

TEST(HullSurveyPlan, YamlReadsIntoTheDefaultsAndRejectsUnknownKeys) {
    const auto& schema = hull_survey_plan_config_schema();
    HullSurveyPlanConfig config;
    schema.apply(io::parse_yaml_string("orientation: vertical\nstand_off_m: 1.3\n", "hull.yaml"),
                 config, "hull_survey");
    EXPECT_EQ(plan_hull_survey(config).num_slices, 18u);
    EXPECT_EQ(config.length_m, 30.0);  // untouched default
    HullSurveyPlanConfig other;
    SCANTLING_EXPECT_ERROR(
        schema.apply(io::parse_yaml_string("standoff_m: 1.3\n", "hull.yaml"), other, "hull_survey"),
        ParseError, "key 'hull_survey.standoff_m': unknown key");
    SCANTLING_EXPECT_ERROR(
        schema.apply(io::parse_yaml_string("overlap: 1\n", "hull.yaml"), other, "hull_survey"),
        ParseError, "hull_survey.overlap");
    SCANTLING_EXPECT_ERROR(
        schema.apply(io::parse_yaml_string("orientation: diagonal\n", "hull.yaml"), other,
                     "hull_survey"),
        ParseError, "hull_survey.orientation");
}

}  // namespace
}  // namespace scantling::planning
