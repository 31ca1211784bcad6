// The receding-horizon next-best-view planner (planning/nbv_planner.hpp, SPEC §8) on analytic
// box rooms mapped by exact depth frames: where the best branch goes, collision-free edges
// checked voxel by voxel, the statuses and input contracts, determinism over thread counts,
// re-seeding, and the defect weight μ.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include <scantling/core/error.hpp>
#include <scantling/mapping/occupancy_octree.hpp>
#include <scantling/planning/nbv_planner.hpp>

#include "expect_error.hpp"
#include "nbv_scene.hpp"

namespace scantling::planning {
namespace {

using Eigen::Vector3d;
using mapping::Occupancy;
using mapping::OccupancyOctree;

constexpr double kRes = 0.1;
// Edges are steered to exactly max_edge_m; their measured length may differ by rounding.
constexpr double kLengthTolerance_m = 1e-9;
// Walls at odd multiples of 0.025 m: never on a voxel face at 0.1 m.
const test::BoxScene kCorridor{{Vector3d(-4.975, -1.475, -0.975), Vector3d(5.025, 1.525, 1.525)},
                               {}};
const NbvState kCameraAtEnd{Vector3d(-4.2, 0.0, 0.275), 0.0};
const NbvState kStart{Vector3d(-2.5, 0.0, 0.275), 0.0};

NbvPlannerConfig corridor_config() {
    NbvPlannerConfig config;
    config.bounds_min_world_m = kCorridor.room.min();
    config.bounds_max_world_m = kCorridor.room.max();
    return config;
}

OccupancyOctree map_at(double res_m) {
    mapping::OccupancyOctreeConfig config;
    config.resolution_m = res_m;
    return OccupancyOctree(config);
}

/// The corridor after one frame from near its −x end looking +x.
OccupancyOctree corridor_map() {
    OccupancyOctree map = map_at(kRes);
    test::observe(kCorridor, corridor_config(), kCameraAtEnd, map);
    return map;
}

/// Ground truth for a box: every voxel centre on a grid of half the resolution inside it free.
bool box_known_free_by_queries(const OccupancyOctree& map, const Eigen::AlignedBox3d& box) {
    const double step = map.resolution_m() / 2.0;
    for (double x = box.min().x(); x <= box.max().x() + 1e-9; x += step)
        for (double y = box.min().y(); y <= box.max().y() + 1e-9; y += step)
            for (double z = box.min().z(); z <= box.max().z() + 1e-9; z += step)
                if (map.query(Vector3d(x, y, z)) != Occupancy::kFree) return false;
    return true;
}

Eigen::AlignedBox3d box_at(const NbvPlannerConfig& config, const Vector3d& p) {
    return {p - config.vehicle_box_m / 2.0, p + config.vehicle_box_m / 2.0};
}

TEST(NbvPlanner, FirstFrameSendsTheBestBranchTowardsTheUnknownEnd) {
    const OccupancyOctree map = corridor_map();
    const NbvPlannerConfig config = corridor_config();
    NbvPlanner planner(config);
    const NbvPlan plan = planner.plan(map, kStart);
    ASSERT_EQ(plan.status, NbvStatus::kOk) << plan.message;
    ASSERT_FALSE(plan.branch.empty());
    EXPECT_GT(plan.best_value, config.min_gain_m3);
    EXPECT_EQ(plan.tree.size(), static_cast<std::size_t>(config.max_nodes));
    EXPECT_EQ(plan.stats.gain_evaluations, plan.tree.size() - 1);
    EXPECT_TRUE(map.box_is_free(box_at(config, plan.next_goal.p_world_m)));
    const Eigen::AlignedBox3d bounds(config.bounds_min_world_m, config.bounds_max_world_m);
    for (std::size_t i = 1; i < plan.tree.size(); ++i) {
        const NbvNode& n = plan.tree[i];
        EXPECT_TRUE(bounds.contains(n.state.p_world_m)) << i;
        EXPECT_LE(n.edge_m, config.max_edge_m + kLengthTolerance_m) << i;
        EXPECT_GE(n.unknown_m3, 0.0);
    }
    // The unknown is mostly beyond the frame's 5 m reach (+x): the branch ends farther along.
    // (Its yaw is a random sample: from there the unknown wedges beside the first camera, seen
    // looking back, may be worth more than the far end.)
    EXPECT_GT(plan.branch.back().p_world_m.x(), kStart.p_world_m.x() + 1.0);
}

TEST(NbvPlanner, EveryAcceptedEdgeKeepsTheVehicleBoxInKnownFreeSpace) {
    const OccupancyOctree map = corridor_map();
    NbvPlannerConfig config = corridor_config();
    config.max_nodes = 60;
    const NbvPlan plan = NbvPlanner(config).plan(map, kStart);
    ASSERT_EQ(plan.status, NbvStatus::kOk) << plan.message;
    constexpr double kStepM = 0.05;  // box positions along each edge, half a voxel apart
    for (std::size_t i = 1; i < plan.tree.size(); ++i) {
        const Vector3d a = plan.tree[static_cast<std::size_t>(plan.tree[i].parent)].state.p_world_m;
        const Vector3d b = plan.tree[i].state.p_world_m;
        const int steps = static_cast<int>(std::ceil((b - a).norm() / kStepM));
        for (int k = 0; k <= steps; ++k) {
            const Vector3d p = a + (b - a) * (static_cast<double>(k) / steps);
            // The vehicle box and its clearance on every side.
            const Vector3d half =
                config.vehicle_box_m / 2.0 + Vector3d::Constant(config.clearance_m);
            ASSERT_TRUE(box_known_free_by_queries(map, {p - half, p + half}))
                << "edge " << i << " at " << p.transpose();
        }
    }
}

TEST(NbvPlanner, StartInUnknownOrOccupiedSpaceIsAStatusNotAnError) {
    const NbvPlannerConfig config = corridor_config();
    NbvPlanner planner(config);
    const OccupancyOctree empty = map_at(kRes);
    const NbvPlan before_first_frame = planner.plan(empty, kStart);
    EXPECT_EQ(before_first_frame.status, NbvStatus::kStartNotFree);
    EXPECT_NE(before_first_frame.message.find("unknown"), std::string::npos)
        << before_first_frame.message;
    EXPECT_EQ(before_first_frame.tree.size(), 1u);
    const OccupancyOctree map = corridor_map();
    // The far end wall of the frame: x = 5.025 is beyond reach; the floor at z = −0.975 is hit.
    const NbvPlan in_floor = planner.plan(map, {Vector3d(-1.0, 0.0, -0.95), 0.0});
    EXPECT_EQ(in_floor.status, NbvStatus::kStartNotFree);
    EXPECT_NE(in_floor.message.find("occupied"), std::string::npos) << in_floor.message;
}

TEST(NbvPlanner, RejectsNonFiniteInputsAndNamesBadConfigFields) {
    const OccupancyOctree map = corridor_map();
    NbvPlanner planner(corridor_config());
    const double nan = std::numeric_limits<double>::quiet_NaN();
    SCANTLING_EXPECT_ERROR(planner.plan(map, {Vector3d(nan, 0, 0), 0.0}), InputError, "start");
    SCANTLING_EXPECT_ERROR(planner.plan(map, {kStart.p_world_m, nan}), InputError, "start");
    const std::vector<Vector3d> bad_points{Vector3d(0, 0, nan)};
    SCANTLING_EXPECT_ERROR(planner.plan(map, kStart, bad_points), InputError, "interest point");
    const auto expect_config_error = [](auto mutate, const char* needle) {
        NbvPlannerConfig config;
        mutate(config);
        SCANTLING_EXPECT_ERROR(NbvPlanner{config}, ConfigError, needle);
    };
    expect_config_error([](auto& c) { c.max_edge_m = 0.0; }, "nbv.max_edge_m = 0");
    expect_config_error([](auto& c) { c.max_nodes = 1; }, "nbv.max_nodes = 1");
    expect_config_error([](auto& c) { c.lambda_per_m = -1.0; }, "nbv.lambda_per_m");
    expect_config_error([](auto& c) { c.bounds_max_world_m.y() = -6.0; },
                        "nbv.bounds_max_world_m[1]");
    expect_config_error([](auto& c) { c.vehicle_box_m.z() = 0.0; }, "nbv.vehicle_box_m[2]");
    expect_config_error([](auto& c) { c.clearance_m = -0.1; }, "nbv.clearance_m");
    expect_config_error([](auto& c) { c.camera.max_depth_m = -1.0; }, "nbv.camera.max_depth_m");
    expect_config_error([](auto& c) { c.camera_pitch_rad = 2.0; }, "nbv.camera_pitch_rad");
    expect_config_error([](auto& c) { c.frontier_sample_fraction = 1.5; },
                        "nbv.frontier_sample_fraction");
    expect_config_error([](auto& c) { c.parallel.num_threads = -1; }, "nbv.parallel.num_threads");
}

TEST(NbvPlanner, ExhaustedWhenTheWholeRoomIsKnown) {
    const test::BoxScene room{{Vector3d(-1.475, -1.475, -0.975), Vector3d(1.525, 1.525, 1.525)},
                              {}};
    OccupancyOctree map = map_at(kRes);
    test::look_around(room, Vector3d(0.0, 0.0, 0.275), map);
    NbvPlannerConfig config;
    config.bounds_min_world_m = room.room.min();
    config.bounds_max_world_m = room.room.max();
    const NbvPlan plan = NbvPlanner(config).plan(map, {Vector3d(0.0, 0.0, 0.275), 0.0});
    EXPECT_EQ(plan.status, NbvStatus::kExhausted) << plan.message;
    EXPECT_LT(plan.best_value, config.min_gain_m3);
    EXPECT_GT(plan.tree.size(), 1u);
}

TEST(NbvPlanner, SameSeedGivesTheIdenticalPlanOnOneAndTwoThreads) {
    const OccupancyOctree map = corridor_map();
    NbvPlannerConfig config = corridor_config();
    config.parallel.num_threads = 1;
    const NbvPlan serial = NbvPlanner(config).plan(map, kStart);
    config.parallel.num_threads = 2;
    const NbvPlan parallel = NbvPlanner(config).plan(map, kStart);
    ASSERT_EQ(serial.tree.size(), parallel.tree.size());
    for (std::size_t i = 0; i < serial.tree.size(); ++i) {
        EXPECT_EQ(serial.tree[i].state.p_world_m, parallel.tree[i].state.p_world_m) << i;
        EXPECT_EQ(serial.tree[i].state.yaw_rad, parallel.tree[i].state.yaw_rad) << i;
        EXPECT_EQ(serial.tree[i].value, parallel.tree[i].value) << i;  // bit for bit
    }
    EXPECT_EQ(serial.best_value, parallel.best_value);
}

TEST(NbvPlanner, ReseedingReinsertsThePreviousBranchTailAndCutsItWhereBlocked) {
    const OccupancyOctree map = corridor_map();
    NbvPlannerConfig config = corridor_config();
    config.lambda_per_m = 0.0;  // no discount: longer branches
    NbvPlanner planner(config);
    const NbvPlan first = planner.plan(map, kStart);
    ASSERT_EQ(first.status, NbvStatus::kOk) << first.message;
    const std::vector<NbvState> kept = planner.kept_branch();
    ASSERT_GE(kept.size(), 2u) << "the scene should give a branch of 3+ nodes";
    const NbvPlan second = planner.plan(map, first.next_goal);
    ASSERT_EQ(second.stats.reseeded_nodes, kept.size());
    for (std::size_t i = 0; i < kept.size(); ++i) {
        EXPECT_EQ(second.tree[i + 1].state.p_world_m, kept[i].p_world_m) << i;
        EXPECT_EQ(second.tree[i + 1].parent, static_cast<int>(i)) << i;
    }
    // An obstacle seen on the kept branch's last node cuts the branch before it.
    NbvPlanner blocked_planner(config);
    const NbvPlan again = blocked_planner.plan(map, kStart);
    const std::vector<NbvState> tail = blocked_planner.kept_branch();
    test::BoxScene blocked = kCorridor;
    const Vector3d p_last = tail.back().p_world_m;
    blocked.obstacles.push_back(
        {p_last - Vector3d::Constant(0.2), p_last + Vector3d::Constant(0.2)});
    OccupancyOctree blocked_map = corridor_map();
    test::observe(blocked, config, kCameraAtEnd, blocked_map);
    const NbvPlan cut = blocked_planner.plan(blocked_map, again.next_goal);
    EXPECT_LT(cut.stats.reseeded_nodes, tail.size());
    for (std::size_t i = 0; i < cut.stats.reseeded_nodes; ++i)
        EXPECT_EQ(cut.tree[i + 1].state.p_world_m, tail[i].p_world_m) << i;
}

TEST(NbvPlanner, DefectWeightCountsOnlyDefectsInViewAndInSight) {
    const OccupancyOctree map = corridor_map();
    const mapping::ViewFrustum camera;
    const Eigen::Isometry3d T = nbv_camera_pose(corridor_config(), kCameraAtEnd);
    const std::vector<Vector3d> ahead{kCameraAtEnd.p_world_m + Vector3d(2.0, 0.0, 0.0)};
    EXPECT_NEAR(nbv_defect_weight(map, camera, T, ahead), 1.0 + 1.0 / 2.0, 1e-12);
    const std::vector<Vector3d> behind{kCameraAtEnd.p_world_m - Vector3d(0.5, 0.0, 0.0)};
    EXPECT_EQ(nbv_defect_weight(map, camera, T, behind), 1.0);
    const std::vector<Vector3d> too_far{kCameraAtEnd.p_world_m + Vector3d(5.5, 0.0, 0.0)};
    EXPECT_EQ(nbv_defect_weight(map, camera, T, too_far), 1.0);
    // Behind the floor (z = −0.975, occupied where the frame hit it, x > −1.4): hidden.
    const std::vector<Vector3d> under_floor{Vector3d(0.0, 0.0, -1.3)};
    EXPECT_EQ(nbv_defect_weight(map, camera, T, under_floor), 1.0);
    // On the floor itself, in view: seen, at its distance.
    const Vector3d on_floor(0.0, 0.0, -0.975);
    const std::vector<Vector3d> floor_defect{on_floor};
    EXPECT_NEAR(nbv_defect_weight(map, camera, T, floor_defect),
                1.0 + 1.0 / (on_floor - T.translation()).norm(), 1e-12);
}

TEST(NbvPlanner, DefectAwarePlansPreferTheSideWithTheDefect) {
    // A long hall seen both ways from its middle: equal unknown at both ends; a defect on the
    // point of interest 0.6 m beyond the seen part on the +x side.
    const test::BoxScene hall{{Vector3d(-7.475, -1.475, -0.975), Vector3d(7.525, 1.525, 1.525)},
                              {}};
    NbvPlannerConfig config;
    config.bounds_min_world_m = hall.room.min();
    config.bounds_max_world_m = hall.room.max();
    OccupancyOctree map = map_at(kRes);
    const Vector3d centre(0.025, 0.025, 0.275);
    test::look_around(hall, centre, map);
    const std::vector<Vector3d> defect{Vector3d(5.6, 0.0, 0.3)};
    config.max_nodes = 60;
    int plus_x_vanilla = 0, plus_x_aware = 0;
    constexpr int kSeeds = 8;
    for (int seed = 1; seed <= kSeeds; ++seed) {
        config.seed = static_cast<std::uint64_t>(seed);
        config.defect_aware = false;
        const NbvPlan vanilla = NbvPlanner(config).plan(map, {centre, 0.0}, defect);
        config.defect_aware = true;
        const NbvPlan aware = NbvPlanner(config).plan(map, {centre, 0.0}, defect);
        plus_x_vanilla += vanilla.branch.back().p_world_m.x() > 0.0;
        plus_x_aware += aware.branch.back().p_world_m.x() > 0.0;
        // The same seed grows the same tree: only μ differs, never below 1.
        ASSERT_EQ(aware.tree.size(), vanilla.tree.size());
        bool sees_defect = false;
        for (std::size_t i = 1; i < aware.tree.size(); ++i) {
            EXPECT_EQ(aware.tree[i].state.p_world_m, vanilla.tree[i].state.p_world_m);
            EXPECT_GE(aware.tree[i].value, vanilla.tree[i].value);
            sees_defect = sees_defect || aware.tree[i].mu > 1.0;
        }
        EXPECT_TRUE(sees_defect) << "seed " << seed;
        if (aware.branch.back().p_world_m != vanilla.branch.back().p_world_m) {
            // A changed choice is a branch with a view of the defect on the defect's side.
            EXPECT_GT(aware.branch.back().p_world_m.x(), 0.0) << "seed " << seed;
        }
    }
    EXPECT_GT(plus_x_aware, plus_x_vanilla);
}

}  // namespace
}  // namespace scantling::planning
