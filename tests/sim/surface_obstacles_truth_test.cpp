// Surface obstacles with ground truth (issue 15, item 2): plate holes and edges, bolts,
// brackets and weld beads placed on the crawler's surface from a scenario, checked against the
// geometry a ray sees, and every bad key named.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <scantling/core/error.hpp>
#include <scantling/sim/ray_caster.hpp>
#include <scantling/sim/scenario.hpp>
#include <scantling/sim/scenario_limits.hpp>
#include <scantling/sim/scenario_schema.hpp>
#include <scantling/sim/surface_obstacles.hpp>
#include <scantling/sim/surface_obstacles_truth.hpp>
#include <scantling/sim/world_builders.hpp>

#include "world_test_support.hpp"

namespace scantling::sim {
namespace {

// Hits on flat faces built from the configured sizes: only double rounding.
constexpr double kExact_m = 1e-9;
// A tank shell of 128 facets at R = 2 m lies up to R (1 - cos(π/128)) = 0.6 mm inside the
// analytic cylinder the crawler's surface is.
constexpr double kFacet_m = 1e-3;

const Eigen::Vector3d kDown = -Eigen::Vector3d::UnitZ();

const std::string kPlateYaml = R"(
world:
  type: plate
  plate: {length_m: 5, width_m: 2, holes: [{centre_m: [1.0, 0.5], size_m: [0.10, 0.08]}]}
  obstacles:
    - {kind: bolt, position_world: [0.5, 0.2, 0.0], diameter_m: 0.03, height_m: 0.025}
    - {kind: bracket, position_world: [1.5, -0.4, 0.0], size_m: [0.12, 0.06, 0.08], yaw_deg: 30}
    - {kind: weld_bead, from_world: [-1.0, 0.6, 0.0], to_world: [0.5, 0.6, 0.0], width_m: 0.03,
       height_m: 0.015}
)";

/// A storage tank of radius 2 m without nozzles or defects, then `obstacles`.
std::string tank_yaml(const std::string& obstacles) {
    return "world:\n  type: storage_tank\n"
           "  storage_tank: {diameter_m: 4, height_m: 4.8, num_nozzles: 0, defects: {count: 0}}\n"
           "  obstacles:\n" +
           obstacles;
}

/// "[x, y, z]" at full precision, for YAML.
std::string yaml_point(const Eigen::Vector3d& p) {
    std::ostringstream out;
    out.precision(17);
    out << "[" << p.x() << ", " << p.y() << ", " << p.z() << "]";
    return out.str();
}

/// The point at `azimuth_rad` on the tank's shell (radius 2 m) at height z.
Eigen::Vector3d on_shell(double azimuth_rad, double z) {
    return {2.0 * std::cos(azimuth_rad), 2.0 * std::sin(azimuth_rad), z};
}

World build(const std::string& yaml) { return build_world(parse_scenario(yaml).world); }

const ObstacleTruth& truth(const World& world, const std::string& name) {
    for (const ObstacleTruth& o : world.obstacles) {
        if (o.name == name) return o;
    }
    throw std::runtime_error("no obstacle truth " + name);
}

/// The first hit straight down from 1 m above (x, y).
RayHit down_at(const RayCaster& caster, double x, double y) {
    return caster.cast({x, y, 1.0}, kDown, 10.0);
}

/// parse_scenario (and build_world) of `yaml` throws an Error whose message has every part.
void expect_error(const std::string& yaml, const std::vector<std::string>& parts) {
    try {
        build(yaml);
        ADD_FAILURE() << "no error for:\n" << yaml;
    } catch (const Error& e) {
        for (const std::string& part : parts) {
            EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
        }
    }
}

TEST(SurfaceObstacleTruth, NamesKindsAndMeasuresTheFootprint) {
    EXPECT_EQ(to_string(ObstacleKind::kWeldBead), "weld_bead");
    EXPECT_EQ(to_string(ObstacleKind::kBolt), "bolt");
    EXPECT_EQ(to_string(ObstacleKind::kBracket), "bracket");
    EXPECT_EQ(to_string(ObstacleKind::kHole), "hole");
    EXPECT_EQ(to_string(ObstacleKind::kPlateEdge), "plate_edge");
    const ObstacleTruth bead{.kind = ObstacleKind::kWeldBead,
                             .name = "weld_bead_1",
                             .a_world_m = {0, 0, 0},
                             .b_world_m = {1, 0, 0},
                             .radius_m = 0.1,
                             .height_m = 0.02};
    EXPECT_TRUE(bead.positive());
    EXPECT_NEAR(bead.footprint_distance_m({0.5, 0.0, 0.0}), -0.1, kExact_m);
    EXPECT_NEAR(bead.footprint_distance_m({0.5, 0.3, 0.0}), 0.2, kExact_m);
    EXPECT_NEAR(bead.footprint_distance_m({-0.3, 0.4, 0.0}), 0.4, kExact_m);  // past end a
    ObstacleTruth hole = bead;
    hole.b_world_m = hole.a_world_m;  // a round one
    hole.height_m = -0.01;
    EXPECT_FALSE(hole.positive());
    EXPECT_NEAR(hole.footprint_distance_m({0.0, 0.0, 0.5}), 0.4, kExact_m);
}

TEST(SurfaceObstacleTruth, PlateHasFourEdgesAndHolesThatRaysPassThrough) {
    const World world = build(kPlateYaml);
    check_valid(world, "plate");
    for (int k = 1; k <= 4; ++k) {
        const ObstacleTruth& edge = truth(world, "plate_edge_" + std::to_string(k));
        EXPECT_EQ(edge.kind, ObstacleKind::kPlateEdge);
        EXPECT_EQ(edge.radius_m, kPlateEdgeRadius_m);
        EXPECT_EQ(edge.height_m, -0.01);
        EXPECT_EQ(edge.a_world_m.z(), 0.0);
    }
    EXPECT_EQ(truth(world, "plate_edge_1").a_world_m, Eigen::Vector3d(-2.5, -1.0, 0.0));
    EXPECT_EQ(truth(world, "plate_edge_1").b_world_m, Eigen::Vector3d(2.5, -1.0, 0.0));
    EXPECT_EQ(truth(world, "plate_edge_3").a_world_m, Eigen::Vector3d(2.5, 1.0, 0.0));

    const ObstacleTruth& hole = truth(world, "hole_1");
    EXPECT_EQ(hole.kind, ObstacleKind::kHole);
    EXPECT_FALSE(hole.positive());
    EXPECT_NEAR(hole.radius_m, 0.04, kExact_m);  // half the shorter side
    EXPECT_NEAR((hole.a_world_m - Eigen::Vector3d(0.99, 0.5, 0.0)).norm(), 0.0, kExact_m);
    EXPECT_NEAR((hole.b_world_m - Eigen::Vector3d(1.01, 0.5, 0.0)).norm(), 0.0, kExact_m);
    EXPECT_NEAR(hole.height_m, -0.01, kExact_m);

    const RayCaster caster(world.mesh, world.surface_tags);
    EXPECT_FALSE(down_at(caster, 1.0, 0.5).hit);       // the centre of the hole
    EXPECT_FALSE(down_at(caster, 1.045, 0.535).hit);   // inside its corner
    const RayHit beside = down_at(caster, 1.0, 0.55);  // 1 cm past its side
    ASSERT_TRUE(beside.hit);
    EXPECT_NEAR(beside.point.z(), 0.0, kExact_m);
    EXPECT_EQ(beside.surface_tag, find_surface(world.metadata, "plate"));
}

TEST(SurfaceObstacleTruth, RaysHitBoltBracketAndBeadAtTheirHeights) {
    const World world = build(kPlateYaml);
    const RayCaster caster(world.mesh, world.surface_tags);
    const auto expect_top = [&](double x, double y, double z, const std::string& surface) {
        const RayHit hit = down_at(caster, x, y);
        ASSERT_TRUE(hit.hit) << x << ", " << y;
        EXPECT_NEAR(hit.point.z(), z, kExact_m) << x << ", " << y;
        EXPECT_EQ(hit.surface_tag, find_surface(world.metadata, surface)) << x << ", " << y;
    };
    expect_top(0.5, 0.2, 0.025, "bolt_1");
    expect_top(0.5 + 0.013, 0.2, 0.025, "bolt_1");
    expect_top(0.5 + 0.02, 0.2, 0.0, "plate");
    expect_top(1.5, -0.4, 0.08, "bracket_1");
    // Inside the 12 x 6 cm box unturned, outside it turned by 30°: the yaw is applied.
    expect_top(1.5 + 0.055, -0.4 - 0.025, 0.0, "plate");
    const double c = std::cos(std::numbers::pi / 6), s = std::sin(std::numbers::pi / 6);
    expect_top(1.5 + 0.055 * c, -0.4 + 0.055 * s, 0.08, "bracket_1");  // along its long side
    expect_top(-0.25, 0.6, 0.015, "weld_bead_1");
    expect_top(-0.99, 0.6 + 0.014, 0.015, "weld_bead_1");
    expect_top(-0.25, 0.6 + 0.02, 0.0, "plate");
    expect_top(0.52, 0.6, 0.0, "plate");  // past its end
}

TEST(SurfaceObstacleTruth, TruthsDescribeThePlacedObstacles) {
    const World world = build(kPlateYaml);
    ASSERT_EQ(world.obstacles.size(), 8u);  // 4 edges, 1 hole, 3 placed
    const ObstacleTruth& bolt = truth(world, "bolt_1");
    EXPECT_EQ(bolt.kind, ObstacleKind::kBolt);
    EXPECT_EQ(bolt.a_world_m, Eigen::Vector3d(0.5, 0.2, 0.0));
    EXPECT_EQ(bolt.b_world_m, bolt.a_world_m);
    EXPECT_NEAR(bolt.radius_m, 0.015, kExact_m);
    EXPECT_NEAR(bolt.height_m, 0.025, kExact_m);
    EXPECT_NEAR(bolt.footprint_distance_m({0.5, 0.2, 0.0}), -0.015, kExact_m);
    EXPECT_NEAR(bolt.footprint_distance_m({0.6, 0.2, 0.0}), 0.085, kExact_m);

    const ObstacleTruth& bracket = truth(world, "bracket_1");
    EXPECT_EQ(bracket.kind, ObstacleKind::kBracket);
    EXPECT_NEAR(bracket.radius_m, 0.06 / std::numbers::sqrt2, kExact_m);
    EXPECT_NEAR(bracket.height_m, 0.08, kExact_m);
    const Eigen::Vector3d axis = bracket.b_world_m - bracket.a_world_m;  // the long side, turned
    EXPECT_NEAR(axis.norm(), 0.06, kExact_m);
    EXPECT_NEAR(std::atan2(axis.y(), axis.x()), std::numbers::pi / 6, kExact_m);
    // The capsule bounds the box: its corners are on the footprint's border, not outside.
    const double c = std::cos(std::numbers::pi / 6), s = std::sin(std::numbers::pi / 6);
    const Eigen::Vector3d corner = Eigen::Vector3d(1.5, -0.4, 0.0) +
                                   0.06 * Eigen::Vector3d(c, s, 0) +
                                   0.03 * Eigen::Vector3d(-s, c, 0);
    EXPECT_NEAR(bracket.footprint_distance_m(corner), 0.0, kExact_m);

    const ObstacleTruth& bead = truth(world, "weld_bead_1");
    EXPECT_EQ(bead.kind, ObstacleKind::kWeldBead);
    EXPECT_EQ(bead.a_world_m, Eigen::Vector3d(-1.0, 0.6, 0.0));
    EXPECT_EQ(bead.b_world_m, Eigen::Vector3d(0.5, 0.6, 0.0));
    EXPECT_NEAR(bead.radius_m, 0.015, kExact_m);
    EXPECT_NEAR(bead.footprint_distance_m({-0.25, 0.65, 0.0}), 0.035, kExact_m);
}

TEST(SurfaceObstacleTruth, ObstaclesAreClosedOutwardMeshesSunkIntoTheWall) {
    const World world = build(kPlateYaml);
    // Volume of each closed mesh: its footprint times (height + kEmbed_m); > 0 faces outward.
    const double bolt_area = 8.0 * 0.015 * 0.015 * std::sin(2.0 * std::numbers::pi / 16.0);
    EXPECT_NEAR(testing::volume_of(world, "bolt_1"), bolt_area * (0.025 + kEmbed_m), kExact_m);
    EXPECT_NEAR(testing::volume_of(world, "bracket_1"), 0.12 * 0.06 * (0.08 + kEmbed_m), kExact_m);
    EXPECT_NEAR(testing::volume_of(world, "weld_bead_1"), 1.5 * 0.03 * (0.015 + kEmbed_m),
                kExact_m);
}

TEST(SurfaceObstacleTruth, SameScenarioBuildsTheSameWorld) {
    const Scenario scenario = parse_scenario(kPlateYaml);
    const World a = build_world(scenario.world);
    const World b = build_world(scenario.world);
    testing::expect_identical(a, b);
    ASSERT_EQ(a.obstacles.size(), b.obstacles.size());
    for (std::size_t i = 0; i < a.obstacles.size(); ++i) {
        EXPECT_EQ(a.obstacles[i].name, b.obstacles[i].name);
        EXPECT_EQ(a.obstacles[i].a_world_m, b.obstacles[i].a_world_m);
        EXPECT_EQ(a.obstacles[i].b_world_m, b.obstacles[i].b_world_m);
        EXPECT_EQ(a.obstacles[i].radius_m, b.obstacles[i].radius_m);
    }
}

TEST(SurfaceObstacleTruth, ScenarioKeysRoundTrip) {
    const Scenario s = parse_scenario(kPlateYaml);
    ASSERT_EQ(s.world.plate.holes.size(), 1u);
    EXPECT_EQ(s.world.plate.holes[0].centre_m, (std::vector<double>{1.0, 0.5}));
    EXPECT_EQ(s.world.plate.holes[0].size_m, (std::vector<double>{0.10, 0.08}));
    ASSERT_EQ(s.world.obstacles.size(), 3u);
    EXPECT_EQ(s.world.obstacles[0].kind, ObstacleKind::kBolt);
    EXPECT_EQ(s.world.obstacles[0].position_world, Eigen::Vector3d(0.5, 0.2, 0.0));
    EXPECT_EQ(s.world.obstacles[0].diameter_m, 0.03);
    EXPECT_EQ(s.world.obstacles[1].kind, ObstacleKind::kBracket);
    EXPECT_EQ(s.world.obstacles[1].size_m, Eigen::Vector3d(0.12, 0.06, 0.08));
    EXPECT_EQ(s.world.obstacles[1].yaw_deg, 30.0);
    EXPECT_EQ(s.world.obstacles[2].kind, ObstacleKind::kWeldBead);
    EXPECT_EQ(s.world.obstacles[2].to_world, Eigen::Vector3d(0.5, 0.6, 0.0));
    EXPECT_EQ(s.world.obstacles[2].width_m, 0.03);
    EXPECT_EQ(s.world.obstacles[2].height_m, 0.015);
    // The schema documents the keys.
    const std::string doc = scenario_schema().describe();
    EXPECT_NE(doc.find("obstacles"), std::string::npos);
    EXPECT_NE(doc.find("holes"), std::string::npos);
}

TEST(SurfaceObstacleTruth, BoltOnATankShellStandsRadiallyOut) {
    const double azimuth = 0.3, r = 2.0;
    const Eigen::Vector3d radial(std::cos(azimuth), std::sin(azimuth), 0.0);
    const Eigen::Vector3d p = 2.05 * radial + Eigen::Vector3d(0, 0, 1.0);  // 5 cm off the shell
    const World world = build(
        tank_yaml("    - {kind: bolt, position_world: " + yaml_point(p) + ", height_m: 0.025}\n" +
                  "    - {kind: weld_bead, from_world: " + yaml_point(on_shell(1.0, 0.5)) +
                  ", to_world: " + yaml_point(on_shell(1.0, 2.0)) + "}\n"));
    const ObstacleTruth& bolt = truth(world, "bolt_1");
    EXPECT_NEAR((bolt.a_world_m - (r * radial + Eigen::Vector3d(0, 0, 1.0))).norm(), 0.0, kExact_m);
    const RayCaster caster(world.mesh, world.surface_tags);
    const Eigen::Vector3d from = 3.0 * radial + Eigen::Vector3d(0, 0, 1.0);
    const RayHit hit = caster.cast(from, -radial, 5.0);
    ASSERT_TRUE(hit.hit);
    EXPECT_EQ(hit.surface_tag, find_surface(world.metadata, "bolt_1"));
    EXPECT_NEAR(hit.point.head<2>().norm(), r + 0.025, kExact_m);
    EXPECT_NEAR(hit.normal.dot(radial), 1.0, kExact_m);
    // Beside it, the shell.
    const Eigen::Vector3d aside(std::cos(azimuth + 0.1), std::sin(azimuth + 0.1), 0.0);
    const RayHit shell = caster.cast(3.0 * aside + Eigen::Vector3d(0, 0, 1.0), -aside, 5.0);
    ASSERT_TRUE(shell.hit);
    EXPECT_EQ(shell.surface_tag, find_surface(world.metadata, "shell"));
    EXPECT_NEAR(shell.point.head<2>().norm(), r, kFacet_m);
    // A vertical bead along the axis is straight on the cylinder.
    const ObstacleTruth& bead = truth(world, "weld_bead_1");
    EXPECT_NEAR((bead.b_world_m - bead.a_world_m).norm(), 1.5, kExact_m);
    EXPECT_GT(testing::volume_of(world, "weld_bead_1"), 0.0);
}

TEST(SurfaceObstacleTruth, PlacementErrorsNameTheField) {
    const std::string plate = "world:\n  type: plate\n  obstacles:\n";
    expect_error(
        plate + "    - {kind: bolt, position_world: [0.5, 0.2, 0.35]}\n",
        {"world.obstacles[0].position_world", "is 0.35 m off the surface", "within 0.1 m"});
    // Beyond the plate's edge: the crawler's plate surface is bounded.
    expect_error(plate + "    - {kind: bolt, position_world: [3.0, 0.0, 0.0]}\n",
                 {"world.obstacles[0].position_world", "is 0.5 m off the surface"});
    // On the tank's cylinder 2 m above its roof: on the crawler's (infinite) surface, not on the
    // world's mesh.
    expect_error(tank_yaml("    - {kind: bolt, position_world: [2.0, 0.0, 6.8]}\n"),
                 {"world.obstacles[0].position_world", "from the world's mesh"});
    expect_error(plate + "    - {kind: weld_bead, from_world: [0, 0, 0], to_world: [0, 0, 0.5]}\n",
                 {"world.obstacles[0].to_world", "off the surface"});
    // 1.5 m around a tank of radius 2 m: the chord is 14 cm inside the shell.
    expect_error(tank_yaml("    - {kind: weld_bead, from_world: " + yaml_point(on_shell(0.3, 1.0)) +
                           ", to_world: " + yaml_point(on_shell(1.05, 1.0)) + "}\n"),
                 {"world.obstacles[0].to_world", "bends 0.139 m"});
}

TEST(SurfaceObstacleTruth, KeyErrorsNameTheField) {
    const std::string head = "world:\n  type: plate\n  obstacles:\n    - {";
    const std::string at = "position_world: [0, 0, 0]";
    expect_error(head + "kind: rivet, " + at + "}\n",
                 {"world.obstacles[0].kind", "bolt", "bracket", "weld_bead"});
    expect_error(head + "kind: hole, " + at + "}\n", {"world.obstacles[0].kind"});
    expect_error(head + at + "}\n", {"world.obstacles[0].kind", "required"});
    expect_error(head + "kind: bolt}\n", {"world.obstacles[0].position_world", "required"});
    expect_error(head + "kind: weld_bead, from_world: [0, 0, 0]}\n",
                 {"world.obstacles[0].to_world", "required"});
    expect_error(head + "kind: bolt, " + at + ", size_m: [1, 1, 1]}\n",
                 {"world.obstacles[0].size_m", "does not apply to kind 'bolt'"});
    expect_error(head + "kind: bolt, " + at + ", diameter_m: 0}\n",
                 {"world.obstacles[0].diameter_m"});
    expect_error(head + "kind: bolt, " + at + ", height_m: .nan}\n",
                 {"world.obstacles[0].height_m"});
    expect_error(head + "kind: bolt, " + at + ", height_m: 20}\n", {"world.obstacles[0].height_m"});
    expect_error(head + "kind: bracket, " + at + ", size_m: [0.1, -1, 0.1]}\n",
                 {"world.obstacles[0].size_m"});
    expect_error(head + "kind: bracket, " + at + ", yaw_deg: 1000}\n",
                 {"world.obstacles[0].yaw_deg"});
    expect_error(head + "kind: weld_bead, from_world: [0, 0, 0], to_world: [0, 0, 0]}\n",
                 {"world.obstacles[0].to_world", "long"});
    expect_error(head +
                     "kind: weld_bead, from_world: [0, 0, 0], to_world: [1, 0, 0], "
                     "width_m: 0}\n",
                 {"world.obstacles[0].width_m"});
}

TEST(SurfaceObstacleTruth, ConfigErrorsNameTheField) {
    SurfaceObstacleConfig c;
    c.kind = ObstacleKind::kHole;
    EXPECT_THROW(c.validate("o"), ConfigError);
    try {
        c.validate("world.obstacles[2]");
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("world.obstacles[2].kind = hole, expected one of "
                                             "bolt, bracket, weld_bead"),
                  std::string::npos)
            << e.what();
    }
    c.kind = ObstacleKind::kBolt;
    c.diameter_m = std::nan("");
    EXPECT_THROW(c.validate("o"), ConfigError);
    c.diameter_m = 0.03;
    c.position_world.x() = std::numeric_limits<double>::infinity();
    EXPECT_THROW(c.validate("o"), ConfigError);
}

TEST(SurfaceObstacleTruth, HoleErrorsNameTheField) {
    const auto plate = [](const std::string& holes, const std::string& extra = "") {
        return "world:\n  type: plate\n  plate: {length_m: 5, width_m: 2" + extra + ", holes: [" +
               holes + "]}\n";
    };
    expect_error(plate("{centre_m: [2.45, 0], size_m: [0.1, 0.1]}"),
                 {"world.plate.holes[0].centre_m", "inside"});
    expect_error(plate("{centre_m: [0, 0], size_m: [0.1, 0.1]}, {centre_m: [0.1, 0.05], "
                       "size_m: [0.1, 0.1]}"),
                 {"world.plate.holes[1].centre_m", "overlaps holes[0]"});
    expect_error(plate("{centre_m: [0, 0], size_m: [0.1, 0.1]}", ", stiffener_spacing_m: 1"),
                 {"world.plate.holes[0].centre_m", "longitudinal_1"});
    // Clear of the stiffener at y = 0.
    EXPECT_NO_THROW(
        build(plate("{centre_m: [0, 0.5], size_m: [0.1, 0.1]}", ", stiffener_spacing_m: 1")));
    expect_error(plate("{centre_m: [0, 0], size_m: [0, 0.1]}"), {"world.plate.holes[0].size_m"});
    expect_error(plate("{centre_m: [0], size_m: [0.1, 0.1]}"),
                 {"world.plate.holes[0].centre_m", "two"});
}

TEST(SurfaceObstacleTruth, CountsAreBoundedBeforeAnythingIsBuilt) {
    WorldSpec spec;
    spec.type = WorldType::kPlate;
    spec.obstacles.resize(limits::kMaxSurfaceObstacles + 1);
    try {
        spec.validate("world");
        ADD_FAILURE() << "no error";
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("world.obstacles"), std::string::npos) << e.what();
    }
    World world = build_plate();
    const PlaneSurface surface(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ());
    EXPECT_THROW(add_surface_obstacles(world, surface, spec.obstacles), ConfigError);
    PlateConfig plate;
    plate.holes.resize(limits::kMaxSurfaceObstacles + 1);
    EXPECT_THROW(build_plate(plate), ConfigError);
}

TEST(SurfaceObstacleTruth, CheckValidRefusesABadTruth) {
    World world = build(kPlateYaml);
    world.obstacles.push_back(world.obstacles.front());  // a repeated name
    EXPECT_THROW(check_valid(world, "w"), InputError);
    world.obstacles.pop_back();
    world.obstacles.front().radius_m = 0.0;
    EXPECT_THROW(check_valid(world, "w"), InputError);
}

}  // namespace
}  // namespace scantling::sim
