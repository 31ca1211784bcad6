// The next-best-view planner closing the loop (SPEC §8): teleport the camera to each plan's
// next goal, insert the exact depth frame seen there, repeat until exhausted, in a box room
// with an internal wall; vanilla uniform sampling against frontier-guided sampling. And the
// planner's YAML binding (`stack.nbv:`).
#include <gtest/gtest.h>

#include <iostream>
#include <string>
#include <vector>

#include <scantling/core/error.hpp>
#include <scantling/io/config_node.hpp>
#include <scantling/mapping/occupancy_octree.hpp>
#include <scantling/planning/config_yaml.hpp>
#include <scantling/planning/nbv_planner.hpp>

#include "expect_error.hpp"
#include "nbv_scene.hpp"

namespace scantling::planning {
namespace {

using Eigen::Vector3d;

// 8 × 5 × 2.5 m, a 0.2 m thick wall across 3 of the 5 m at x ≈ 0.5 (a 2 m gap at +y).
const test::BoxScene kRoom{{Vector3d(-3.975, -2.475, -0.975), Vector3d(4.025, 2.525, 1.525)},
                           {{Vector3d(0.425, -2.475, -0.975), Vector3d(0.625, 0.525, 1.525)}}};
const Vector3d kStart(-2.5, 0.0, 0.275);
constexpr int kMaxIterations = 40;
// SPEC §8's completion criterion for the test: 95 % of the free volume known.
constexpr double kExploredFraction = 0.95;

struct Exploration {
    int iterations = 0;  ///< plans until exhausted (or kMaxIterations)
    bool exhausted = false;
    std::vector<double> known_fraction;  ///< after each frame
    std::size_t gain_evaluations = 0;
};

NbvPlannerConfig room_config(NbvSampling sampling) {
    NbvPlannerConfig config;
    config.bounds_min_world_m = kRoom.room.min();
    config.bounds_max_world_m = kRoom.room.max();
    config.sampling = sampling;
    return config;
}

Exploration explore(const NbvPlannerConfig& config) {
    mapping::OccupancyOctreeConfig map_config;
    map_config.resolution_m = 0.1;
    mapping::OccupancyOctree map(map_config);
    test::look_around(kRoom, kStart, map);
    NbvPlanner planner(config);
    NbvState state{kStart, 0.0};
    Exploration run;
    for (; run.iterations < kMaxIterations; ++run.iterations) {
        const NbvPlan plan = planner.plan(map, state);
        run.gain_evaluations += plan.stats.gain_evaluations;
        if (plan.status == NbvStatus::kExhausted) {
            run.exhausted = true;
            break;
        }
        EXPECT_EQ(plan.status, NbvStatus::kOk) << plan.message;
        if (plan.status != NbvStatus::kOk) break;
        state = plan.next_goal;
        test::observe(kRoom, config, state, map);
        run.known_fraction.push_back(test::known_volume_m3(map, kRoom.room) /
                                     kRoom.free_volume_m3());
    }
    return run;
}

void expect_explored(const Exploration& run, const char* name) {
    ASSERT_FALSE(run.known_fraction.empty()) << name;
    EXPECT_GE(run.known_fraction.back(), kExploredFraction) << name;
    EXPECT_TRUE(run.exhausted) << name << ": not exhausted in " << kMaxIterations;
    for (std::size_t i = 1; i < run.known_fraction.size(); ++i)
        EXPECT_GE(run.known_fraction[i], run.known_fraction[i - 1] - 1e-3) << name << " " << i;
    std::string fractions;
    for (double f : run.known_fraction) fractions += std::to_string(f).substr(0, 5) + " ";
    std::cout << name << ": " << run.iterations << " plans, " << run.gain_evaluations
              << " gain evaluations, known fraction per frame: " << fractions << "\n";
}

TEST(NbvExploration, VanillaExploresNinetyFivePercentOfARoomWithAWall) {
    expect_explored(explore(room_config(NbvSampling::kUniform)), "uniform");
}

TEST(NbvExploration, FrontierGuidedSamplingExploresTheSameRoom) {
    expect_explored(explore(room_config(NbvSampling::kFrontier)), "frontier");
}

TEST(NbvPlannerYaml, ReadsEveryKeyOverTheDefaultsAndRejectsUnknownKeys) {
    const std::string yaml =
        "bounds_min_world_m: [-1, -2, -3]\n"
        "bounds_max_world_m: [1, 2, 3]\n"
        "max_nodes: 180\n"
        "lambda_per_m: 1.0\n"
        "sampling: frontier\n"
        "camera: {rays_horizontal: 16, rays_vertical: 12}\n"
        "parallel: {num_threads: 2}\n";
    NbvPlannerConfig config;
    nbv_planner_config_schema().apply(io::parse_yaml_string(yaml, "nbv.yaml"), config, "nbv");
    EXPECT_EQ(config.max_nodes, 180);
    EXPECT_EQ(config.lambda_per_m, 1.0);
    EXPECT_EQ(config.sampling, NbvSampling::kFrontier);
    EXPECT_EQ(config.camera.rays_horizontal, 16);
    EXPECT_EQ(config.camera.max_depth_m, 5.0);  // untouched default
    EXPECT_EQ(config.parallel.num_threads, 2);
    EXPECT_EQ(config.bounds_min_world_m, Vector3d(-1, -2, -3));
    EXPECT_EQ(config.max_edge_m, NbvPlannerConfig{}.max_edge_m);
    NbvPlannerConfig other;
    SCANTLING_EXPECT_ERROR(nbv_planner_config_schema().apply(
                               io::parse_yaml_string("max_edges_m: 2\n", "nbv.yaml"), other, "nbv"),
                           ParseError, "max_edges_m");
    SCANTLING_EXPECT_ERROR(nbv_planner_config_schema().apply(
                               io::parse_yaml_string("max_nodes: 1\n", "nbv.yaml"), other, "nbv"),
                           ConfigError, "nbv.max_nodes");
}

}  // namespace
}  // namespace scantling::planning
