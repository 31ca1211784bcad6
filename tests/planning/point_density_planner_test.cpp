#include <scantling/planning/point_density_planner.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include <scantling/core/error.hpp>
#include <scantling/core/random.hpp>

namespace scantling::planning {
namespace {

constexpr double kPi = std::numbers::pi;
// Centroid azimuth of the 30–130 points at half height, uniform over 90°: σ ≤ 0.08 rad, 3σ.
constexpr double kAngleTolerance_rad = 0.25;

// Points on a cylinder (r 1 m, z 0–3 m) about `centre`, `counts[s]` in sector s (uniform in
// azimuth within the sector and in height).
std::vector<Eigen::Vector3d> cylinder_points(const SectorCounts& counts,
                                             const Eigen::Vector2d& centre, std::uint64_t seed) {
    Rng rng(seed);
    std::vector<Eigen::Vector3d> points;
    for (int s = 0; s < kNumSectors; ++s) {
        for (std::size_t k = 0; k < counts[static_cast<std::size_t>(s)]; ++k) {
            const double a = (s + rng.uniform(0.01, 0.99)) * kPi / 2.0;
            points.emplace_back(centre.x() + std::cos(a), centre.y() + std::sin(a),
                                rng.uniform(0.0, 3.0));
        }
    }
    return points;
}

TEST(PointDensityPlanner, LocatesTheDensestVoxelAndItsCentreOfMass) {
    constexpr double kCentreTolerance_m = 0.1;  // 800 points on the circle: mean ~ ±0.04 m
    const Eigen::Vector2d centre(5.0, -3.0);    // the cylinder fills voxel [4, 6) × [-4, -2)
    std::vector<Eigen::Vector3d> points = cylinder_points({200, 200, 200, 200}, centre, 1);
    for (int i = 0; i < 50; ++i) points.emplace_back(-10.0 + 0.3 * i, 8.0, 1.0);  // sparse clutter
    PointDensityPlannerConfig config;
    config.voxel_edge_m = 2.0;
    const ObjectEstimate object = locate_object(points, config);
    ASSERT_TRUE(object.found);
    EXPECT_LT((object.centre_xy_m - centre).norm(), kCentreTolerance_m);
    EXPECT_DOUBLE_EQ(object.object_radius_m, 1.0);
    EXPECT_DOUBLE_EQ(object.flight_radius_m, 2.0);  // 1 m + r_object (SPEC §9)
}

TEST(PointDensityPlanner, FixedCentreAndRadiusOverrideTheEstimate) {
    PointDensityPlannerConfig config;
    config.fixed_centre_xy_m = Eigen::Vector2d(1.0, 2.0);
    config.fixed_flight_radius_m = 3.0;
    const ObjectEstimate object = locate_object({}, config);
    EXPECT_TRUE(object.found);
    EXPECT_EQ(object.centre_xy_m, Eigen::Vector2d(1.0, 2.0));
    EXPECT_DOUBLE_EQ(object.flight_radius_m, 3.0);
    EXPECT_FALSE(locate_object({}, PointDensityPlannerConfig{}).found);
}

TEST(PointDensityPlanner, SectorsRunCounterClockwiseFromTheStartBorder) {
    const Eigen::Vector2d c = Eigen::Vector2d::Zero();
    auto at = [](double deg) {
        return Eigen::Vector3d(std::cos(deg * kPi / 180), std::sin(deg * kPi / 180), 0);
    };
    EXPECT_EQ(sector_of(at(10), c, 0.0), 0);
    EXPECT_EQ(sector_of(at(100), c, 0.0), 1);
    EXPECT_EQ(sector_of(at(190), c, 0.0), 2);
    EXPECT_EQ(sector_of(at(280), c, 0.0), 3);
    EXPECT_EQ(sector_of(at(-10), c, 0.0), 3);
    EXPECT_EQ(sector_of(at(10), c, kPi / 4), 3);
    const std::vector<Eigen::Vector3d> points{at(10), at(20), at(100), at(280)};
    EXPECT_EQ(count_sectors(points, c, 0.0), (SectorCounts{2, 1, 0, 1}));
}

TEST(PointDensityPlanner, VisitsTheSparsestSectorThenItsSparserNeighbourThenOnward) {
    PointDensityPlannerConfig config;
    config.fixed_centre_xy_m = Eigen::Vector2d::Zero();
    config.fixed_flight_radius_m = 2.0;
    config.flight_height_m = 3.0;
    const std::vector<Eigen::Vector3d> points = cylinder_points({400, 200, 100, 150}, {0, 0}, 2);
    const ObjectEstimate object = locate_object(points, config);
    PointDensityPlanner planner(config);
    // From azimuth 0 (border of sectors 0 and 3) the sparsest sector 2 (centroid ~225°) is
    // nearer clockwise; its sparser neighbour is 3 (150 < 200), so the order runs +1.
    DensityStep s1 = planner.next(points, object, 0.0);
    ASSERT_EQ(s1.status, PlannerStatus::kTarget);
    EXPECT_EQ(s1.sector, 2);
    EXPECT_EQ(s1.next_sector, 3);
    EXPECT_EQ(s1.direction, -1);
    EXPECT_NEAR(s1.arc_rad, -3.0 * kPi / 4.0, kAngleTolerance_rad);
    EXPECT_NEAR(s1.target_world_m.head<2>().norm(), 2.0, 1e-12);
    EXPECT_DOUBLE_EQ(s1.target_world_m.z(), 3.0);
    const int expected_sectors[] = {3, 0, 1};
    double angle = s1.target_angle_rad;
    for (const int expected : expected_sectors) {
        const DensityStep s = planner.next(points, object, angle);
        EXPECT_EQ(s.sector, expected);
        EXPECT_EQ(s.direction, 1);
        EXPECT_NEAR(s.arc_rad, kPi / 2.0, kAngleTolerance_rad);
        angle = s.target_angle_rad;
    }
    EXPECT_EQ(planner.steps_taken(), 4u);
    // A new round starts with the sparsest sector again.
    EXPECT_EQ(planner.next(points, object, angle).sector, 2);
}

TEST(PointDensityPlanner, StopsAtTheThresholdOrTheStepLimit) {
    PointDensityPlannerConfig config;
    config.fixed_centre_xy_m = Eigen::Vector2d::Zero();
    config.density_threshold_points = 100;
    config.max_steps = 1;
    const std::vector<Eigen::Vector3d> dense = cylinder_points({100, 120, 100, 130}, {0, 0}, 3);
    PointDensityPlanner planner(config);
    const ObjectEstimate object = locate_object(dense, config);
    EXPECT_EQ(planner.next(dense, object, 0.0).status, PlannerStatus::kThresholdReached);
    const std::vector<Eigen::Vector3d> sparse = cylinder_points({100, 99, 100, 100}, {0, 0}, 3);
    const DensityStep first = planner.next(sparse, object, 0.0);
    EXPECT_EQ(first.status, PlannerStatus::kTarget);
    EXPECT_EQ(first.sector, 1);
    EXPECT_EQ(planner.next(sparse, object, 0.0).status, PlannerStatus::kMaxSteps);
    EXPECT_EQ(planner.next(sparse, ObjectEstimate{}, 0.0).status, PlannerStatus::kNoObject);
}

TEST(PointDensityPlanner, RejectsBadConfigAndInput) {
    PointDensityPlannerConfig config;
    config.voxel_edge_m = 0.0;
    EXPECT_THROW(PointDensityPlanner{config}, ConfigError);
    config = {};
    config.max_steps = 0;
    EXPECT_THROW(PointDensityPlanner{config}, ConfigError);
    config = {};
    config.fixed_centre_xy_m = Eigen::Vector2d(std::nan(""), 0.0);
    EXPECT_THROW(locate_object({}, config), ConfigError);
    try {
        config = {};
        config.half_height_band_m = -1.0;
        PointDensityPlanner{config};
        FAIL();
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("point_density_planner.half_height_band_m"),
                  std::string::npos);
    }
    PointDensityPlanner planner;
    const std::vector<Eigen::Vector3d> bad{{std::nan(""), 0.0, 0.0}};
    EXPECT_THROW(locate_object(bad), InputError);
    EXPECT_THROW(planner.next({}, ObjectEstimate{}, std::nan("")), InputError);
}

}  // namespace
}  // namespace scantling::planning
