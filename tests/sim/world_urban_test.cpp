// The KITTI-like urban world: route, buildings on both sides, facade distances, determinism,
// validation, export, and the shipped drive that uses it.
#include <scantling/core/error.hpp>
#include <scantling/io/recording.hpp>
#include <scantling/sim/ray_caster.hpp>
#include <scantling/sim/scenario.hpp>
#include <scantling/sim/scenario_runner.hpp>
#include <scantling/sim/world_export.hpp>
#include <scantling/sim/world_urban.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>

#include "scenario_test_support.hpp"
#include "world_test_support.hpp"

namespace scantling::sim {
namespace {

namespace fs = std::filesystem;

// Route corners come from a few exact additions.
constexpr double kExactTol_m = 1e-9;
// Ray ranges are refined on the hit plane (ray_caster.hpp).
constexpr double kRayTol_m = 1e-6;
// KITTI's Velodyne is 1.73 m above the road.
constexpr double kLidarHeight_m = 1.73;
// Facade hits nearer than this are on the street's own building line; farther ones may be
// across a block seen through a gap.
constexpr double kNearFacade_m = 40.0;
// Rays nearer a crossing may run along a cross street's building line.
constexpr double kCrossingClearance_m = 20.0;
// The issue asks for at least 1.1 km of route and well under ~500k triangles.
constexpr double kMinRoute_m = 1100.0;
constexpr std::size_t kMaxTriangles = 500000;
// Road returns in the sensor frame: the HDL-64E's σ = 2 cm, 5σ.
constexpr double kRoadNoise_m = 0.1;

// Built once: every test reads the same default city.
const World& default_city() {
    static const World world = build_urban();
    return world;
}

std::string config_error(const std::function<void()>& run) {
    try {
        run();
    } catch (const ConfigError& e) {
        return e.what();
    }
    return "no ConfigError";
}

/// The first 0.2 s of a shipped scenario (two sweeps), without the world export.
io::Recording run_start_of(const std::string& file) {
    Scenario s = load_scenario((fs::path(SCANTLING_SOURCE_DIR) / "scenarios" / file).string());
    s.duration_s = 0.2;
    s.export_world.world = false;
    const fs::path dir = test::scenario_temp_dir("urban_test", s.name);
    run_scenario(s, dir.string());
    return io::open_recording(dir.string());
}

Eigen::Vector2d node_xy(const UrbanConfig& c, const UrbanRouteNode& n) {
    return {n.i * c.pitch_x_m(), n.j * c.pitch_y_m()};
}

TEST(WorldUrban, DefaultRouteIsAClosedRightHandLoopLongerThan1100Metres) {
    const UrbanConfig c;
    const std::vector<Eigen::Vector3d> corners = urban_route(c, kLidarHeight_m);
    ASSERT_EQ(corners.size(), c.route.size());
    // Centre lines: 2 (4 · 92 m + 3 · 72 m); the right-hand lane of a counter-clockwise
    // rectilinear loop runs outside it, 2 lane offsets longer per net quarter turn (4 of them).
    const double centre_line_m = 2.0 * (4.0 * c.pitch_x_m() + 3.0 * c.pitch_y_m());
    EXPECT_NEAR(urban_route_length_m(c), centre_line_m + 8.0 * c.lane_offset_m, kExactTol_m);
    EXPECT_GE(urban_route_length_m(c), kMinRoute_m);
    for (std::size_t k = 0; k < corners.size(); ++k) {
        const Eigen::Vector3d& p = corners[k];
        const Eigen::Vector3d& q = corners[(k + 1) % corners.size()];
        EXPECT_EQ(p.z(), kLidarHeight_m);
        // Straight legs along x or y, and every corner a lane offset from both centre lines.
        EXPECT_TRUE(std::abs(p.x() - q.x()) < kExactTol_m || std::abs(p.y() - q.y()) < kExactTol_m)
            << "leg " << k;
        const Eigen::Vector2d node = node_xy(c, c.route[k]);
        EXPECT_NEAR(std::abs(p.x() - node.x()), c.lane_offset_m, kExactTol_m) << "corner " << k;
        EXPECT_NEAR(std::abs(p.y() - node.y()), c.lane_offset_m, kExactTol_m) << "corner " << k;
    }
    // The first leg runs east on the south (right) side of street j = 0.
    EXPECT_NEAR(corners[0].y(), -c.lane_offset_m, kExactTol_m);
    EXPECT_GT(corners[1].x(), corners[0].x());
}

TEST(WorldUrban, FacadesLineBothSidesOfEveryRouteStreetAtTheBuildingLine) {
    const UrbanConfig c;
    const World& w = default_city();
    const RayCaster caster(w.mesh, w.surface_tags);
    const int facade = find_surface(w.metadata, "facade");
    const int window = find_surface(w.metadata, "window");
    const double line_m = 0.5 * c.street_width_m + c.sidewalk_width_m;
    const std::size_t n = c.route.size();
    for (std::size_t k = 0; k < n; ++k) {
        const Eigen::Vector2d a = node_xy(c, c.route[k]), b = node_xy(c, c.route[(k + 1) % n]);
        const Eigen::Vector2d d = (b - a).normalized();
        const Eigen::Vector3d left(-d.y(), d.x(), 0.0);
        int rays = 0, hits[2] = {0, 0};
        // Rays across the street from its centre line, away from the crossings (a long leg
        // passes some).
        const double pitch_m = std::abs(d.x()) > 0.5 ? c.pitch_x_m() : c.pitch_y_m();
        for (double s = 0.0; s <= (b - a).norm(); s += 2.0) {
            if (std::abs(std::remainder(s, pitch_m)) < kCrossingClearance_m) continue;
            ++rays;
            const Eigen::Vector3d origin(a.x() + s * d.x(), a.y() + s * d.y(), kLidarHeight_m);
            for (int side = 0; side < 2; ++side) {
                const RayHit hit = caster.cast(origin, side == 0 ? left : -left, kNearFacade_m);
                if (!hit.hit || (hit.surface_tag != facade && hit.surface_tag != window)) continue;
                ++hits[side];
                ASSERT_GE(hit.range_m, line_m - kRayTol_m) << "leg " << k << " s " << s;
                ASSERT_LE(hit.range_m, line_m + c.facade_recess_m + kRayTol_m)
                    << "leg " << k << " s " << s;
            }
        }
        ASSERT_GT(rays, 10);

        // Gaps, trees and block corners take the rest.
        EXPECT_GT(hits[0], rays / 2) << "left of leg " << k;
        EXPECT_GT(hits[1], rays / 2) << "right of leg " << k;
    }
}

TEST(WorldUrban, EverySurfaceIsPresentAndTheMeshIsValidAndSmall) {
    const World& w = default_city();
    check_valid(w, "urban");

    EXPECT_LT(w.mesh.num_triangles(), kMaxTriangles);
    EXPECT_GT(w.mesh.num_triangles(), 20000u);
    for (const char* name : {"road", "sidewalk", "kerb", "building_wall", "window", "facade",
                             "roof", "balcony", "pole", "tree_trunk", "tree_crown", "parked_car"}) {
        EXPECT_GT(testing::area_of(w, name), 0.0) << name;
    }
    // One compartment per street: 5 along y, 4 along x.
    ASSERT_EQ(w.metadata.compartments.size(), 9u);
    EXPECT_EQ(w.metadata.compartments[0].name, "street_i0");
    EXPECT_EQ(w.metadata.compartments[8].name, "street_j3");
    EXPECT_EQ(io::compartment_at(w.metadata, {1.0, 30.0, 1.0}), 0);
    EXPECT_EQ(io::compartment_at(w.metadata, {30.0, 30.0, 1.0}), std::nullopt);  // in a block
    // Buildings from 5 m to 25 m above the 15 cm sidewalk; nothing below the road.
    const Aabb b = compute_bounds(w.mesh.vertices);
    EXPECT_NEAR(b.min.z(), 0.0, kExactTol_m);
    EXPECT_LE(b.max.z(), 25.15 + kExactTol_m);
    EXPECT_GT(b.max.z(), 20.0);
}

TEST(WorldUrban, SameSeedGivesIdenticalWorldsAndAnotherSeedAnotherCity) {
    UrbanConfig c;
    c.blocks_x = 2;
    c.blocks_y = 1;
    c.route = {{0, 0}, {2, 0}, {2, 1}, {0, 1}};
    testing::expect_identical(build_urban(c), build_urban(c));
    UrbanConfig other = c;
    other.seed = 2;
    const World a = build_urban(c), b = build_urban(other);
    EXPECT_TRUE(a.mesh.num_triangles() != b.mesh.num_triangles() ||
                a.mesh.vertices != b.mesh.vertices);
}

TEST(WorldUrban, BadConfigsNameTheField) {
    const auto error_of = [](const std::function<void(UrbanConfig&)>& edit) {
        UrbanConfig c;
        edit(c);
        return config_error([&] { build_urban(c); });
    };
    EXPECT_NE(error_of([](UrbanConfig& c) {
                  c.street_width_m = 0.0;
              }).find("urban.street_width_m = 0, expected > 0"),
              std::string::npos);
    EXPECT_NE(error_of([](UrbanConfig& c) { c.max_height_m = 4.0; }).find("urban.max_height_m"),
              std::string::npos);
    EXPECT_NE(error_of([](UrbanConfig& c) { c.block_width_m = 40.0; }).find("urban.block_width_m"),
              std::string::npos);
    EXPECT_NE(error_of([](UrbanConfig& c) { c.lane_offset_m = 6.0; }).find("urban.lane_offset_m"),
              std::string::npos);
    EXPECT_NE(error_of([](UrbanConfig& c) {
                  c.route[2] = {3, 1};
              }).find("urban.route[2] = (3, 1), expected a straight street"),
              std::string::npos);
    EXPECT_NE(error_of([](UrbanConfig& c) {
                  c.route[1] = {5, 0};
              }).find("urban.route[1] = (5, 0), expected i in [0, 4]"),
              std::string::npos);
    EXPECT_NE(error_of([](UrbanConfig& c) {
                  c.route = {{0, 0}, {2, 0}, {1, 0}, {1, 1}, {0, 1}};
              }).find("turns back"),
              std::string::npos);
    EXPECT_NE(error_of([](UrbanConfig& c) { c.route.resize(3); }).find("urban.route.size = 3"),
              std::string::npos);
    EXPECT_NE(error_of([](UrbanConfig& c) { c.defects.count = -1; }).find("urban.defects.count"),
              std::string::npos);
    EXPECT_THROW(urban_route(UrbanConfig{.blocks_x = 0}), ConfigError);
}

TEST(WorldUrban, ScenarioSectionParsesValidatesAndExports) {
    const Scenario s = parse_scenario(
        "world:\n  type: urban\n  urban: {blocks_x: 1, blocks_y: 1, route: [{i: 0, j: 0}, "
        "{i: 1, j: 0}, {i: 1, j: 1}, {i: 0, j: 1}], seed: 3}\n");
    ASSERT_EQ(s.world.type, WorldType::kUrban);
    EXPECT_EQ(to_string(s.world.type), "urban");
    EXPECT_EQ(s.world.urban.seed, 3u);
    ASSERT_EQ(s.world.urban.route.size(), 4u);
    EXPECT_EQ(s.world.urban.route[2].i, 1);
    const World w = build_world(s.world);
    EXPECT_EQ(w.metadata.name, "urban");
    const PointCloud map = sample_map(w, 2.0, 1);
    EXPECT_GT(map.size(), 1000u);
    EXPECT_NE(io::structural_map_to_json(w.metadata).find("\"street_j1\""), std::string::npos);
    // The schema checks ranges with the line; validate() checks what a table cannot.
    EXPECT_THROW(parse_scenario("world:\n  type: urban\n  urban: {street_width_m: 0}\n"),
                 ParseError);
    EXPECT_THROW(parse_scenario("world:\n  type: cylinder\n  urban: {blocks_x: 2}\n"), ParseError);
    Scenario bad = s;
    bad.world.urban.route[1] = {1, 1};
    EXPECT_NE(config_error([&] { bad.validate(); }).find("world.urban.route[1]"),
              std::string::npos);
}

TEST(WorldUrban, ShippedDriveFollowsTheRouteOfItsWorld) {
    const fs::path file = fs::path(SCANTLING_SOURCE_DIR) / "scenarios" / "urban_drive_hdl64.yaml";
    const Scenario s = load_scenario(file.string());
    ASSERT_EQ(s.world.type, WorldType::kUrban);
    const auto& waypoints = s.vehicle.trajectory.waypoints.waypoints;
    const std::vector<Eigen::Vector3d> corners = urban_route(s.world.urban);
    // The loop, closed by returning to the first corner.
    ASSERT_EQ(waypoints.size(), corners.size() + 1);
    for (std::size_t k = 0; k < waypoints.size(); ++k) {
        const Eigen::Vector3d& expected = corners[k % corners.size()];
        EXPECT_NEAR((waypoints[k].position_m - expected).norm(), 0.0, 1e-6) << "waypoint " << k;
    }
    EXPECT_GE(urban_route_length_m(s.world.urban), kMinRoute_m);
    ASSERT_FALSE(s.sensors.empty());
    EXPECT_EQ(s.sensors[0].type, SensorType::kSpinningLidar);
    EXPECT_NEAR(s.sensors[0].T_body_sensor.xyz.z(), kLidarHeight_m, kExactTol_m);
}

TEST(WorldUrban, ShippedDriveSeesTheRoad173MetresBelowAndFacadesBeside) {
    const io::Recording rec = run_start_of("urban_drive_hdl64.yaml");
    ASSERT_EQ(rec.num_sweeps(), 2u);
    const PointCloud sweep = rec.read_sweep(1);
    EXPECT_GT(sweep.size(), 50000u);  // 64 × 1024 beams, nearly all return in a street
    // The car starts in the first crossing facing +x, 1.75 m right of street j = 0's centre
    // line: the building lines are 10 − 1.75 m to its right and 10 + 1.75 m to its left, from
    // 11.75 m ahead; the glazing is 0.3 m behind them. Above z = −0.2 m (parked cars are lower).
    const UrbanConfig c;
    const double right_m = 0.5 * c.street_width_m + c.sidewalk_width_m - c.lane_offset_m;
    const double left_m = right_m + 2.0 * c.lane_offset_m;
    int road = 0, facade[2] = {0, 0};
    for (const Eigen::Vector3d& p : sweep.points) {
        if (std::abs(p.z() + kLidarHeight_m) < kRoadNoise_m && p.head<2>().norm() < 6.0) ++road;
        if (p.x() < 15.0 || p.x() > 40.0 || p.z() < -0.2) continue;
        const double slack_m = c.facade_recess_m + kRoadNoise_m;
        if (p.y() < -right_m + kRoadNoise_m && p.y() > -right_m - slack_m) ++facade[0];
        if (p.y() > left_m - kRoadNoise_m && p.y() < left_m + slack_m) ++facade[1];
    }
    EXPECT_GT(road, 5000);
    EXPECT_GT(facade[0], 100);
    EXPECT_GT(facade[1], 100);
}

TEST(WorldUrban, ShippedTankFlightsRunInsideAndAroundTheirTanks) {
    const io::Recording ballast = run_start_of("ballast_large_os0.yaml");
    ASSERT_EQ(ballast.num_sweeps(), 2u);
    const PointCloud inside = ballast.read_sweep(0);
    // A closed tank: every one of the 64 × 1024 beams returns (a few drop out at random).
    EXPECT_GT(inside.size(), 64u * 1024u * 99u / 100u);
    for (const Eigen::Vector3d& p : inside.points) {
        const Eigen::Vector3d w = ballast.sweep_pose_gt(0) * p;
        ASSERT_TRUE(w.x() > -0.1 && w.x() < 18.1 && w.y() > -0.1 && w.y() < 2.1 && w.z() > -0.1 &&
                    w.z() < 9.1);
    }
    const io::Recording tank = run_start_of("storage_tank_orbit_os1.yaml");
    ASSERT_EQ(tank.num_sweeps(), 2u);
    const PointCloud outside = tank.read_sweep(1);
    EXPECT_GT(outside.size(), 5000u);
    std::size_t on_tank = 0;
    for (const Eigen::Vector3d& p : outside.points) {
        // The shell (r 6 m) and what stands proud of it (seams, nozzles up to 6.5 m + flange),
        // within range noise,
        // or the tank farm: the ground (z = 0, within noise), the bund wall (within 14.15 m, up
        // to 1.2 m high) and the pipe supports beyond it (up to 18 m out, 4.2 m high).
        const Eigen::Vector3d w = tank.sweep_pose_gt(1) * p;
        const bool tank_part = w.head<2>().norm() < 7.0;
        on_tank += tank_part ? 1 : 0;
        ASSERT_TRUE(tank_part || w.z() < 0.1 ||
                    (w.cwiseAbs().head<2>().maxCoeff() < 14.3 && w.z() < 1.3) ||
                    (w.x() > 16.3 && w.x() < 19.7 && w.z() < 4.3))
            << w.transpose();
        ASSERT_GT(p.norm(), 3.5);  // 5 m stand-off, less the nozzles
    }
    EXPECT_GT(on_tank, 5000u);
}

}  // namespace
}  // namespace scantling::sim
