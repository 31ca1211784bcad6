#include <scantling/mission/reconstruction_experiment.hpp>

#include <gtest/gtest.h>

#include <numbers>

#include <scantling/core/error.hpp>

namespace scantling::mission {
namespace {

// Fewer frames than the camera's 30 Hz keep the tests short; the map's culling window is in
// frames, so the counts differ from the full-rate tables in docs/results.md.
constexpr double kTestFrameRate_hz = 5.0;

ReconstructionExperimentConfig test_config() {
    ReconstructionExperimentConfig config;
    config.frame_rate_hz = kTestFrameRate_hz;
    config.parallel.num_threads = 1;
    return config;
}

planning::PointDensityPlannerConfig planner_config(double radius_m) {
    planning::PointDensityPlannerConfig planner;
    planner.fixed_centre_xy_m = Eigen::Vector2d::Zero();
    planner.fixed_flight_radius_m = radius_m;
    planner.flight_height_m = 3.0;
    planner.max_steps = 4;
    return planner;
}

TEST(ReconstructionExperiment, HelixMapGrowsThenSaturatesAndRawFramesOvercount) {
    const ReconstructionExperimentConfig config = test_config();
    const HelixRun one = run_helix(config, 2.0, 1.0);
    const HelixRun five = run_helix(config, 2.0, 5.0);
    const HelixRun ten = run_helix(config, 2.0, 10.0);
    EXPECT_NEAR(five.v_z_mps, 3.0 * 0.25 / (2.0 * std::numbers::pi * 5.0), 1e-12);
    EXPECT_GT(five.confirmed_points, one.confirmed_points);
    // Saturation: doubling the turns adds less than doubling did from one turn to five.
    EXPECT_LT(ten.confirmed_points - five.confirmed_points,
              five.confirmed_points - one.confirmed_points);
    EXPECT_GT(five.raw_points, 2 * five.confirmed_points);
}

TEST(ReconstructionExperiment, ShadowedSectorTwoHoldsFewestPoints) {
    const HelixRun run = run_helix(test_config(), 2.0, 2.0);
    EXPECT_LT(run.sectors[2], run.sectors[0]);
    EXPECT_LT(run.sectors[2], run.sectors[1]);
    EXPECT_LT(run.sectors[2], run.sectors[3]);
    ReconstructionExperimentConfig no_sun = test_config();
    no_sun.sunlight = false;
    EXPECT_GT(run_helix(no_sun, 2.0, 2.0).confirmed_points, run.confirmed_points);
}

TEST(ReconstructionExperiment, PlannerVisitsEverySectorOnceInFourSteps) {
    const PlannerRun run = run_planner(test_config(), planner_config(2.0));
    ASSERT_EQ(run.steps.size(), 5u);  // step 0 (initial turn) + 4 steps
    EXPECT_EQ(run.stop, planning::PlannerStatus::kMaxSteps);
    std::array<int, 4> visits{};
    for (std::size_t i = 1; i < run.steps.size(); ++i) {
        ++visits[static_cast<std::size_t>(run.steps[i].target_sector)];
    }
    EXPECT_EQ(visits, (std::array<int, 4>{1, 1, 1, 1}));
    // Less than two turns after the initial one: the order rule avoids back-tracking.
    EXPECT_LT(run.steps.back().turns, 3.0);
    EXPECT_GE(run.steps.back().total, run.steps.front().total);
}

TEST(ReconstructionExperiment, PlannerStopsWhenEverySectorReachesTheThreshold) {
    // At 5 Hz and r 2 m the shadowed sector 2 holds ~140 points after the initial turn (see
    // docs/results.md); 150 makes the planner fly to it and then stop.
    constexpr std::size_t kThreshold = 150;
    planning::PointDensityPlannerConfig planner = planner_config(2.0);
    planner.density_threshold_points = kThreshold;
    planner.max_steps = 8;
    const PlannerRun run = run_planner(test_config(), planner);
    ASSERT_EQ(run.stop, planning::PlannerStatus::kThresholdReached);
    ASSERT_GE(run.steps.size(), 2u);
    EXPECT_EQ(run.steps[1].target_sector, 2);
    for (const std::size_t n : run.steps.back().sectors) EXPECT_GE(n, kThreshold);
    EXPECT_LT(run.steps.back().turns, 5.0);  // the smallest helix of Table 1 flies 5 turns
}

// RESULTS-TO-REPRODUCE 4.7: the source's own totals after 4 steps are about half of the
// 5-turn helix's; the simulation agrees (the planner stays at z = 3 m, the helix climbs).
TEST(ReconstructionExperiment, FiveTurnHelixCollectsMoreThanTheFourStepPlanner) {
    const ReconstructionExperimentConfig config = test_config();
    const PlannerRun planner = run_planner(config, planner_config(2.0));
    const HelixRun helix = run_helix(config, 2.0, 5.0);
    EXPECT_GT(helix.confirmed_points, 2 * planner.steps.back().total);
    EXPECT_LT(planner.steps.back().turns, helix.rotations);
}

TEST(ReconstructionExperiment, IsDeterministicForASeed) {
    const ReconstructionExperimentConfig config = test_config();
    const HelixRun a = run_helix(config, 3.0, 1.0);
    const HelixRun b = run_helix(config, 3.0, 1.0);
    EXPECT_EQ(a.confirmed_points, b.confirmed_points);
    EXPECT_EQ(a.sectors, b.sectors);
    ReconstructionExperimentConfig threaded = config;  // ray casting on every thread
    threaded.parallel.num_threads = 0;
    const HelixRun c = run_helix(threaded, 3.0, 1.0);
    EXPECT_EQ(c.raw_points, a.raw_points);
    EXPECT_EQ(c.confirmed_points, a.confirmed_points);
    ReconstructionExperimentConfig other = config;
    other.seed = 2;
    EXPECT_NE(run_helix(other, 3.0, 1.0).raw_points, a.raw_points);
}

TEST(ReconstructionExperiment, RejectsBadConfig) {
    ReconstructionExperimentConfig config = test_config();
    config.omega_radps = 0.0;
    EXPECT_THROW(run_helix(config, 2.0, 1.0), ConfigError);
    config = test_config();
    config.shadow_ambient = 1.5;
    EXPECT_THROW(run_planner(config, planner_config(2.0)), ConfigError);
    EXPECT_THROW(run_helix(test_config(), 0.0, 1.0), ConfigError);
    EXPECT_THROW(run_helix(test_config(), 2.0, -1.0), ConfigError);
}

}  // namespace
}  // namespace scantling::mission
