// Moving obstacles seen by the sensors: SceneView combines them with the mesh (and is the
// caster bit for bit without them), the Simulator's range finder and LiDAR see a sphere
// approach as the geometry predicts, the runner stays deterministic and writes no obstacle,
// and the scenario keys are checked.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <variant>
#include <vector>

#include <scantling/core/error.hpp>
#include <scantling/core/random.hpp>
#include <scantling/sim/scenario.hpp>
#include <scantling/sim/scenario_runner.hpp>
#include <scantling/sim/simulator.hpp>

#include "scenario_test_support.hpp"
#include "sensor_test_support.hpp"

namespace scantling::sim {
namespace {

using testing::box_room;
using testing::TestScene;

constexpr double kExact_m = 1e-12;
// LIDAR-Lite v3 range noise (1σ, RangeFinderConfig default); 5σ keeps the test stable.
constexpr double kRangeSigma_m = 0.025;
// The LiDAR stores points as float32 (~1e-6 m at 10 m) and casts to the double-precision
// surface: points on the sphere lie on it to well below a millimetre without noise.
constexpr double kOnSurface_m = 1e-3;

MovingObstacle ball(const Eigen::Vector3d& from, const Eigen::Vector3d& to, double duration_s) {
    MovingObstacle o;
    o.name = "ball";
    o.radius_m = 0.3;
    o.waypoints = {{0.0, from}, {duration_s, to}};
    return o;
}

std::vector<Ray> random_rays(std::size_t n, std::uint64_t seed) {
    Rng rng(seed);
    std::vector<Ray> rays(n);
    for (Ray& ray : rays) {
        ray.origin = Eigen::Vector3d(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), 0.0);
        ray.direction = Eigen::Vector3d(rng.normal(), rng.normal(), rng.normal()).normalized();
        ray.max_range_m = 20.0;
    }
    return rays;
}

void expect_identical(const RayHit& a, const RayHit& b) {
    EXPECT_EQ(a.hit, b.hit);
    EXPECT_EQ(a.range_m, b.range_m);
    EXPECT_EQ(a.point, b.point);
    EXPECT_EQ(a.normal, b.normal);
    EXPECT_EQ(a.triangle, b.triangle);
    EXPECT_EQ(a.surface_tag, b.surface_tag);
}

TEST(SceneView, WithoutObstaclesEveryQueryIsTheCastersBitForBit) {
    const TestScene room(box_room({-4.0, -3.0, -1.5}, {5.0, 3.5, 2.0}));
    const MovingObstacles none;
    const std::vector<Ray> rays = random_rays(1000, 3);
    const std::vector<RayHit> reference = room.caster.cast_batch(rays);
    for (const SceneView& view :
         {room.view(), SceneView{room.caster, room.world.metadata, &none, 1.0}}) {
        const std::vector<RayHit> batch = view.cast_batch(rays);
        for (std::size_t i = 0; i < rays.size(); ++i) {
            expect_identical(batch[i], reference[i]);
            expect_identical(view.cast(rays[i]), room.caster.cast(rays[i]));
        }
        EXPECT_FALSE(view.occluded({0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}));
        EXPECT_TRUE(view.occluded({0.0, 0.0, 0.0}, {9.0, 0.0, 0.0}));
    }
}

TEST(SceneView, TakesTheNearerOfMeshAndObstacle) {
    const TestScene room(box_room({-4.0, -3.0, -1.5}, {5.0, 3.5, 2.0}));
    // Inside the room at x = 3 (the wall at x = 5); a twin outside, behind the wall at x = −4.
    MovingObstacle inside = ball({3.0, 0.0, 0.0}, {3.0, 0.0, 0.0}, 1.0);
    MovingObstacle outside = ball({-6.0, 0.0, 0.0}, {-6.0, 0.0, 0.0}, 1.0);
    outside.name = "outside";
    const MovingObstacles obstacles({inside, outside});
    const SceneView view{room.caster, room.world.metadata, &obstacles, 0.0};
    const Eigen::Vector3d o = Eigen::Vector3d::Zero();
    const RayHit ball_hit = view.cast(o, Eigen::Vector3d::UnitX(), 10.0);
    EXPECT_NEAR(ball_hit.range_m, 2.7, kExact_m);
    EXPECT_EQ(ball_hit.surface_tag, MovingObstacles::kSurfaceTag);
    EXPECT_EQ(ball_hit.triangle, RayHit::kNoTriangle);
    EXPECT_LT((ball_hit.normal + Eigen::Vector3d::UnitX()).norm(), kExact_m);
    const RayHit wall_hit = view.cast(o, -Eigen::Vector3d::UnitX(), 10.0);
    EXPECT_NEAR(wall_hit.range_m, 4.0, kExact_m);
    EXPECT_NE(wall_hit.triangle, RayHit::kNoTriangle);
    // Beyond max range: nothing.
    EXPECT_FALSE(view.cast(o, Eigen::Vector3d::UnitX(), 2.0).hit);
    EXPECT_TRUE(view.occluded(o, {4.0, 0.0, 0.0}));
    EXPECT_FALSE(view.occluded(o, {0.0, 3.0, 0.0}));
}

TEST(SceneView, BatchEqualsSingleCastsForAnyThreadCountAndFollowsTime) {
    const TestScene room(box_room({-4.0, -3.0, -1.5}, {5.0, 3.5, 2.0}));
    const MovingObstacles obstacles({ball({3.0, -2.0, 0.0}, {3.0, 2.0, 0.0}, 4.0)});
    const SceneView view{room.caster, room.world.metadata, &obstacles, 0.0};
    const std::vector<Ray> rays = random_rays(20000, 4);
    const std::vector<RayHit> serial = view.cast_batch(rays, ParallelConfig{.num_threads = 1});
    const std::vector<RayHit> parallel = view.cast_batch(rays, ParallelConfig{.num_threads = 0});
    int on_ball = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        expect_identical(serial[i], parallel[i]);
        if (i % 50 == 0) expect_identical(serial[i], view.cast(rays[i]));
        on_ball += serial[i].surface_tag == MovingObstacles::kSurfaceTag ? 1 : 0;
    }
    EXPECT_GT(on_ball, 0);
    // At t = 2 s the ball is at (3, 0, 0): straight ahead of the origin.
    const Eigen::Vector3d x = Eigen::Vector3d::UnitX();
    EXPECT_NEAR(view.at_time(2.0).cast({0.0, 0.0, 0.0}, x, 10.0).range_m, 2.7, kExact_m);
    EXPECT_NEAR(view.cast({0.0, 0.0, 0.0}, x, 10.0).range_m, 5.0, kExact_m);  // t = 0: the wall
}

/// A hovering MAV 2 m above a 40 m plate with a forward range finder and a LiDAR; a ball flies at
/// it along body x at 2 m/s, from 10 m to 2 m ahead over 4 s.
const std::string kApproach = R"(
world: {type: plate, plate: {length_m: 40, width_m: 40}}
vehicle: {type: mav}
sensors:
  - {type: range_finder, rate_hz: 20}
  - {type: spinning_lidar, columns: 512, noise: false}
duration_s: 5.0
seed: 3
export: {world: false}
moving_obstacles:
  - name: ball
    shape: sphere
    radius_m: 0.3
    waypoints: [{t_s: 0, xyz: [10, 0, 2]}, {t_s: 4, xyz: [2, 0, 2]}]
)";

const Eigen::Isometry3d kHover(Eigen::Translation3d(0.0, 0.0, 2.0));

/// World points of a LiDAR reading within `tolerance_m` of the ball's surface at its stamp.
int points_on_ball(const LidarReading& lidar, const MovingObstacle& o, double stamp_s) {
    int n = 0;
    for (const Eigen::Vector3d& p : lidar.sweep.points) {
        n += std::abs(o.distance_m(lidar.T_world_sensor * p, stamp_s)) < kOnSurface_m ? 1 : 0;
    }
    return n;
}

TEST(SimulatorObstacles, RangeFinderAndLidarSeeTheBallApproachAsTheGeometryPredicts) {
    Simulator sim(parse_scenario(kApproach, "approach.yaml"), kHover);
    ASSERT_EQ(sim.moving_obstacles().size(), 1u);
    const MovingObstacle& o = sim.moving_obstacles()[0];
    int ranges = 0, sweeps_seeing_ball = 0;
    const auto check = [&](const SimStep& step) {
        for (const SensorReading& r : step.readings) {
            if (const auto* range = std::get_if<RangeMeasurement>(&r.data)) {
                // The beam runs along the line of centres: range = |centre − eye| − radius.
                const double centre_x = 10.0 - 2.0 * std::min(r.stamp_s, 4.0);
                ASSERT_TRUE(range->valid) << r.stamp_s;
                EXPECT_NEAR(range->range_m, centre_x - 0.3, 5.0 * kRangeSigma_m) << r.stamp_s;
                EXPECT_NEAR(o.distance_m(kHover.translation(), r.stamp_s), centre_x - 0.3,
                            kExact_m);
                ++ranges;
            } else if (const auto* lidar = std::get_if<LidarReading>(&r.data)) {
                sweeps_seeing_ball += points_on_ball(*lidar, o, r.stamp_s) > 0 ? 1 : 0;
            }
        }
    };
    check(sim.start());
    for (int k = 0; k < 1000; ++k) check(sim.step({}));
    EXPECT_EQ(ranges, 101);
    EXPECT_EQ(sweeps_seeing_ball, 51);
    // scene() follows the clock: at t = 5 s the ball rests at x = 2.
    EXPECT_NEAR(sim.scene().cast(kHover.translation(), Eigen::Vector3d::UnitX(), 40.0).range_m, 1.7,
                kExact_m);
}

TEST(ScenarioRunnerObstacles, SameRecordingForAnyThreadCountAndNoObstacleFiles) {
    namespace fs = std::filesystem;
    std::string yaml = kApproach;
    // Scripted on the default helix (radius 2 about z), 2 m up: the ball stays in view.
    yaml.replace(yaml.find("{type: mav}"), 11,
                 "{type: scripted, trajectory: {type: helix, helix: {z0_m: 2.0}}}");
    yaml.replace(yaml.find("duration_s: 5.0"), 15, "duration_s: 0.5");
    Scenario with = parse_scenario(yaml, "approach.yaml");
    Scenario without = with;
    without.moving_obstacles.clear();
    const fs::path a = test::scenario_temp_dir("obstacles", "a");
    const fs::path b = test::scenario_temp_dir("obstacles", "b");
    const fs::path c = test::scenario_temp_dir("obstacles", "c");
    run_scenario(with, a.string());
    with.parallel.num_threads = 1;
    run_scenario(with, b.string());
    run_scenario(without, c.string());
    const auto files_a = test::read_tree(a), files_b = test::read_tree(b);
    const auto files_c = test::read_tree(c);
    EXPECT_TRUE(files_a == files_b);
    ASSERT_EQ(files_a.size(), files_c.size());
    for (const auto& [name, bytes] : files_a) EXPECT_TRUE(files_c.contains(name)) << name;
    EXPECT_NE(files_a.at("lidar/000000.bin"), files_c.at("lidar/000000.bin"));
    for (const fs::path& dir : {a, b, c}) fs::remove_all(dir);
}

/// Runs parse_scenario on `yaml` and expects a ParseError or ConfigError naming `key`.
void expect_error_naming(const std::string& yaml, const std::string& key) {
    try {
        parse_scenario(yaml, "bad.yaml");
        ADD_FAILURE() << "no error for:\n" << yaml;
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
}

TEST(ScenarioObstacles, ParsesTheListAndNamesTheBadField) {
    const Scenario s = parse_scenario(
        "moving_obstacles:\n"
        "  - {name: ball, radius_m: 0.3, waypoints: [{t_s: 0, xyz: [0, 0, 2]}]}\n"
        "  - {name: crate, shape: box, half_extents_m: [1, 2, 3],\n"
        "     waypoints: [{t_s: 0, xyz: [0, 0, 2]}, {t_s: 10, xyz: [5, 0, 2]}]}\n");
    ASSERT_EQ(s.moving_obstacles.size(), 2u);
    EXPECT_EQ(s.moving_obstacles[0].shape, ObstacleShape::kSphere);
    EXPECT_EQ(s.moving_obstacles[1].shape, ObstacleShape::kBox);
    EXPECT_EQ(s.moving_obstacles[1].half_extents_m, Eigen::Vector3d(1.0, 2.0, 3.0));
    EXPECT_EQ(s.moving_obstacles[1].waypoints[1].xyz, Eigen::Vector3d(5.0, 0.0, 2.0));

    const std::string head = "moving_obstacles:\n  - {name: b, ";
    const std::string one = "waypoints: [{t_s: 0, xyz: [0, 0, 2]}]";
    expect_error_naming(head + "radius_m: 0, " + one + "}\n", "moving_obstacles[0].radius_m");
    expect_error_naming(head + "radius_m: .nan, " + one + "}\n", "moving_obstacles[0].radius_m");
    expect_error_naming(head + "shape: cone, " + one + "}\n", "moving_obstacles[0].shape");
    expect_error_naming(head + "colour: red, " + one + "}\n", "moving_obstacles[0].colour");
    expect_error_naming(head + "half_extents_m: [1, 1, 1], " + one + "}\n",
                        "moving_obstacles[0].half_extents_m");
    expect_error_naming(head + "shape: box, radius_m: 1, " + one + "}\n",
                        "moving_obstacles[0].radius_m");
    expect_error_naming(head + "shape: box, half_extents_m: [1, 0, 1], " + one + "}\n",
                        "moving_obstacles[0].half_extents_m");
    expect_error_naming(head + "waypoints: []}\n", "moving_obstacles[0].waypoints");
    expect_error_naming(head + "}\n", "moving_obstacles[0].waypoints");
    expect_error_naming(head + "waypoints: [{t_s: 1, xyz: [0, 0, 0]}, {t_s: 1, xyz: [1, 0, 0]}]}\n",
                        "moving_obstacles[0].waypoints[1].t_s");
    expect_error_naming(head + "waypoints: [{t_s: -1, xyz: [0, 0, 0]}]}\n",
                        "moving_obstacles[0].waypoints[0].t_s");
    expect_error_naming(head + "waypoints: [{t_s: 0, xyz: [0, 0]}]}\n",
                        "moving_obstacles[0].waypoints[0].xyz");
    expect_error_naming(head + "waypoints: [{t_s: 0, speed: 1}]}\n",
                        "moving_obstacles[0].waypoints[0].speed");
    expect_error_naming("moving_obstacles:\n  - {" + one + "}\n", "moving_obstacles[0].name");
    expect_error_naming("moving_obstacles: {name: b}\n", "moving_obstacles");
    expect_error_naming(
        "moving_obstacles:\n  - {name: b, " + one + "}\n  - {name: b, " + one + "}\n",
        "moving_obstacles[1].name");
}

TEST(SimulatorObstacles, RefusesABadObstacleGivenInCode) {
    Scenario s = parse_scenario(kApproach, "approach.yaml");
    s.moving_obstacles[0].waypoints.clear();
    EXPECT_THROW(Simulator(s, kHover), ConfigError);
    EXPECT_THROW(run_scenario(s, test::scenario_temp_dir("obstacles", "bad").string()),
                 ConfigError);
    Scenario crowded = parse_scenario(kApproach, "approach.yaml");
    for (std::size_t i = 0; i < 256; ++i) {
        crowded.moving_obstacles.push_back(crowded.moving_obstacles[0]);
        crowded.moving_obstacles.back().name = "ball_" + std::to_string(i);
    }
    EXPECT_THROW(Simulator(crowded, kHover), ConfigError);  // 257 > limits::kMaxMovingObstacles
}

}  // namespace
}  // namespace scantling::sim
