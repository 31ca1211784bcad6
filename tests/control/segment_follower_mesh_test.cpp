// The segment follower (control/segment_follower.hpp) driving along a path that the planner cut
// on a mesh (planning/mesh_path.hpp, SPEC §6): the planner's segments are followed as they are.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <limits>
#include <vector>

#include <scantling/control/segment_follower.hpp>
#include <scantling/core/triangle_mesh.hpp>
#include <scantling/planning/mesh_path.hpp>

namespace scantling::control {
namespace {

constexpr double kDtS = 0.02;              // the simulation step
constexpr double kMeanCrossTrackM = 0.03;  // the brief's bound on a whole run
constexpr double kGoalM = 0.02;            // where the robot stops, from the goal

// 4 × 2 m in the z = 0 plane, 0.25 m cells, two triangles per cell, wound about +z.
TriangleMesh plate() {
    TriangleMesh mesh;
    for (int j = 0; j <= 8; ++j) {
        for (int i = 0; i <= 16; ++i) mesh.vertices.emplace_back(0.25 * i, 0.25 * j, 0.0);
    }
    for (int j = 0; j < 8; ++j) {
        for (int i = 0; i < 16; ++i) {
            const int a = j * 17 + i;
            mesh.triangles.emplace_back(a, a + 1, a + 18);
            mesh.triangles.emplace_back(a, a + 18, a + 17);
        }
    }
    return mesh;
}

// A kinematic unicycle on the plate (as in segment_follower_test.cpp, without the fold).
void crawl(Eigen::Isometry3d& T_world_body, const FollowerCommand& command) {
    T_world_body.translation() += command.v_mps * kDtS * T_world_body.linear().col(0);
    T_world_body.linear() =
        Eigen::AngleAxisd(command.omega_radps * kDtS, Eigen::Vector3d::UnitZ()).matrix() *
        T_world_body.linear();
}

double distance_to_path_m(const Eigen::Vector3d& p, const std::vector<PathSegment>& path) {
    double best_m = std::numeric_limits<double>::infinity();
    for (const PathSegment& s : path) {
        const Eigen::Vector3d d = s.end_world_m - s.begin_world_m;
        const double t = std::clamp((p - s.begin_world_m).dot(d) / d.squaredNorm(), 0.0, 1.0);
        best_m = std::min(best_m, (p - (s.begin_world_m + t * d)).norm());
    }
    return best_m;
}

TEST(SegmentFollowerOnMesh, DrivesAPlannedPlatePathToItsEnd) {
    const Eigen::Vector3d start(0.3, 0.2, 0.0), goal(3.7, 1.65, 0.0);
    const planning::MeshPath planned = planning::shortest_path_on_mesh(plate(), start, goal);
    SegmentFollower follower(planned.segments);

    Eigen::Isometry3d T_world_body = Eigen::Isometry3d::Identity();  // heading +x, 23° off
    T_world_body.translation() = start;
    double sum_m = 0.0;
    int steps = 0;
    FollowerCommand command;
    for (; steps * kDtS < 200.0; ++steps) {
        command = follower.update(T_world_body);
        if (command.done) break;
        sum_m += distance_to_path_m(T_world_body.translation(), planned.segments);
        crawl(T_world_body, command);
    }
    const double mean_m = sum_m / steps;
    std::printf(
        "[ measured ] %zu planned segments: cross-track mean %.4f m, %.1f s, %.4f m from "
        "the goal\n",
        planned.segments.size(), mean_m, steps * kDtS, (T_world_body.translation() - goal).norm());
    EXPECT_TRUE(command.done);
    EXPECT_EQ(command.segment, planned.segments.size());
    EXPECT_LE(mean_m, kMeanCrossTrackM);
    EXPECT_LT((T_world_body.translation() - goal).norm(), kGoalM);
}

}  // namespace
}  // namespace scantling::control
