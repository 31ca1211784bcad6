// Plate, cylinder, storage tank and mesh-file worlds; config validation of every builder.
#include <scantling/core/error.hpp>
#include <scantling/io/mesh_io.hpp>
#include <scantling/sim/ray_caster.hpp>
#include <scantling/sim/world_builders.hpp>

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <numbers>
#include <string>

#include "world_test_support.hpp"

namespace scantling::sim {
namespace {

constexpr double kExactTol_m = 1e-9;
constexpr double kOnSurfaceTol_m = 1e-6;
constexpr double kPi = std::numbers::pi;

namespace fs = std::filesystem;

std::string config_error(const std::function<void()>& build) {
    try {
        build();
    } catch (const ConfigError& e) {
        return e.what();
    }
    return "no ConfigError";
}

TEST(Plate, IsFiveByTwoMetresWithItsTopFaceAtZeroAndDefectsOnIt) {
    const World plate = build_plate();
    const Aabb b = compute_bounds(plate.mesh);
    EXPECT_NEAR((b.min - Eigen::Vector3d(-2.5, -1.0, -0.01)).norm(), 0.0, kExactTol_m);
    EXPECT_NEAR((b.max - Eigen::Vector3d(2.5, 1.0, 0.0)).norm(), 0.0, kExactTol_m);
    EXPECT_NEAR(testing::volume_of(plate, "plate"), 5.0 * 2.0 * 0.01, kExactTol_m);
    EXPECT_EQ(plate.metadata.defects.size(), 4u);
    testing::expect_defects_on_surfaces(plate, kOnSurfaceTol_m);
}

TEST(Plate, StiffenersAreFlatBarsAtTheGivenSpacing) {
    PlateConfig config;
    config.stiffener_spacing_m = 0.5;
    const World plate = build_plate(config);
    ASSERT_EQ(plate.metadata.longitudinals.size(), 3u);  // 2 m / 0.5 m - 1
    const RayCaster caster(plate.mesh, plate.surface_tags);
    for (const FrameLine& l : plate.metadata.longitudinals) {
        EXPECT_NEAR(l.point.z(), 0.1, kExactTol_m);
        const RayHit on_toe = caster.cast({0.3, l.point.y(), 1.0}, -Eigen::Vector3d::UnitZ(), 2.0);
        ASSERT_TRUE(on_toe.hit);
        EXPECT_NEAR(on_toe.point.z(), 0.1, kExactTol_m);
        const RayHit beside =
            caster.cast({0.3, l.point.y() + 0.1, 1.0}, -Eigen::Vector3d::UnitZ(), 2.0);
        EXPECT_NEAR(beside.point.z(), 0.0, kExactTol_m);
    }
    EXPECT_NEAR(plate.metadata.longitudinals[1].point.y(), 0.0, kExactTol_m);
}

TEST(Cylinder, HasTheConfiguredRadiusHeightAndOptionalCaps) {
    const World closed = build_cylinder();
    const Aabb b = compute_bounds(closed.mesh);
    EXPECT_NEAR(b.max.x(), 1.0, kExactTol_m);
    EXPECT_NEAR(b.max.z(), 3.0, kExactTol_m);
    EXPECT_NEAR(b.min.z(), 0.0, kExactTol_m);
    // 64-gon prism: lateral area 64 * 2 sin(π/64) * 3 m.
    EXPECT_NEAR(testing::volume_of(closed, "cylinder"), 3.0 * 32.0 * std::sin(2.0 * kPi / 64),
                kExactTol_m);
    const RayCaster closed_caster(closed.mesh, closed.surface_tags);
    EXPECT_TRUE(closed_caster.cast({0.1, 0, -1}, Eigen::Vector3d::UnitZ(), 10).hit);
    CylinderConfig open;
    open.closed = false;
    const World tube = build_cylinder(open);
    const RayCaster tube_caster(tube.mesh, tube.surface_tags);
    EXPECT_FALSE(tube_caster.cast({0.1, 0, -1}, Eigen::Vector3d::UnitZ(), 10).hit);
    // From outside, the wall is at the polygon's apothem along a facet normal.
    const double apothem = std::cos(kPi / 64);
    const RayHit side = tube_caster.cast({5.0 * std::cos(kPi / 64), 5.0 * std::sin(kPi / 64), 1.0},
                                         {-std::cos(kPi / 64), -std::sin(kPi / 64), 0}, 10);
    ASSERT_TRUE(side.hit);
    EXPECT_NEAR(side.range_m, 5.0 - apothem, kExactTol_m);
    testing::expect_defects_on_surfaces(closed, kOnSurfaceTol_m);
}

TEST(StorageTank, IsATwelveMetreCylinderWithRaisedSeamsAndNozzles) {
    const StorageTankConfig config;
    const World tank = build_storage_tank();
    const Aabb b = compute_bounds(tank.mesh);
    EXPECT_NEAR(b.min.z(), 0.0, kExactTol_m);
    EXPECT_NEAR(b.max.z(), 21.2, kExactTol_m);
    EXPECT_GT(b.max.x(), 6.0);
    EXPECT_LT(b.max.x(), 6.0 + config.nozzle_length_m + 0.5);
    const RayCaster caster(tank.mesh, tank.surface_tags);
    const double step = 2.0 * kPi / config.segments;
    const double apothem = 6.0 * std::cos(0.5 * step);
    // Towards the middle of facet 3 (no vertical seam there): plain shell between the ring
    // seams, proud bead on the ring seam at z = 2.4 m.
    const Eigen::Vector3d facet(std::cos(3.5 * step), std::sin(3.5 * step), 0.0);
    const RayHit plain = caster.cast(20.0 * facet + Eigen::Vector3d(0, 0, 1.2), -facet, 30);
    const RayHit seam = caster.cast(20.0 * facet + Eigen::Vector3d(0, 0, 2.4), -facet, 30);
    ASSERT_TRUE(plain.hit && seam.hit);
    EXPECT_NEAR(plain.range_m, 20.0 - apothem, kExactTol_m);
    EXPECT_EQ(plain.surface_tag, find_surface(tank.metadata, "shell"));
    EXPECT_NEAR(seam.range_m, 20.0 - (6.0 + config.seam_height_m) * std::cos(0.5 * step),
                kExactTol_m);
    EXPECT_EQ(seam.surface_tag, find_surface(tank.metadata, "ring_seams"));
    EXPECT_EQ(tank.metadata.frames.size(), 8u);  // ring seams at 2.4 m .. 19.2 m
    EXPECT_GT(testing::area_of(tank, "nozzles"), 4 * 2 * kPi * 0.3 * 0.5);
    EXPECT_GT(testing::area_of(tank, "vertical_seams"), 0.0);
    testing::expect_defects_on_surfaces(tank, kOnSurfaceTol_m);
}

TEST(StorageTank, RaysTowardsTheAxisFromOutsideAlwaysHit) {
    const World tank = build_storage_tank();
    const RayCaster caster(tank.mesh, tank.surface_tags);
    for (int i = 0; i < 2000; ++i) {
        const double a = 2.0 * kPi * i / 2000.0, z = 0.05 + 21.1 * ((i * 37) % 2000) / 2000.0;
        const Eigen::Vector3d dir(std::cos(a), std::sin(a), 0.0);
        const RayHit hit = caster.cast(20.0 * dir + Eigen::Vector3d(0, 0, z), -dir, 40.0);
        ASSERT_TRUE(hit.hit) << a << " " << z;
        EXPECT_LT(hit.range_m, 20.0 - 5.9);
    }
}

TEST(StorageTank, TankFarmAddsGroundBundWallAndPipeSupports) {
    StorageTankConfig config;
    config.bund_half_size_m = 14.0;
    const World farm = build_storage_tank(config);
    const RayCaster caster(farm.mesh, farm.surface_tags);
    // Down from 5 m beside the tank: the ground's top at z = 0.
    const RayHit ground = caster.cast({9.0, 0.0, 5.0}, {0.0, 0.0, -1.0}, 20.0);
    ASSERT_TRUE(ground.hit);
    EXPECT_NEAR(ground.range_m, 5.0, kExactTol_m);
    EXPECT_EQ(ground.surface_tag, find_surface(farm.metadata, "ground"));
    // Outwards at 0.5 m height, away from the corners: the bund's inner face at 14 - 0.15 m.
    const RayHit bund = caster.cast({7.0, 3.0, 0.5}, {1.0, 0.0, 0.0}, 20.0);
    ASSERT_TRUE(bund.hit);
    EXPECT_NEAR(bund.range_m, 14.0 - 0.15 - 7.0, kExactTol_m);
    EXPECT_EQ(bund.surface_tag, find_surface(farm.metadata, "bund"));
    EXPECT_GT(testing::area_of(farm, "pipe_supports"), 0.0);
    // The tank alone has none of them; a bund inside the tank is refused, naming the field.
    EXPECT_LT(find_surface(build_storage_tank().metadata, "bund"), 0);
    config.bund_half_size_m = 5.0;
    try {
        build_storage_tank(config);
        FAIL();
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("storage_tank.bund_half_size_m"), std::string::npos);
    }
}

TEST(MeshWorld, LoadsAFileWithScaleAndPose) {
    const fs::path path = fs::temp_directory_path() /
                          ("scantling_sim_mesh_world_" + std::to_string(getpid()) + ".ply");
    io::write_mesh(path.string(), build_cylinder({.defects = {.count = 0}}).mesh);
    MeshWorldConfig config;
    config.path = path.string();
    config.scale = 2.0;
    config.position_m = {10.0, 0.0, 0.0};
    config.rpy_rad = {0.5 * kPi, 0.0, 0.0};  // roll 90°: the cylinder axis z turns to -y
    config.defects.count = 2;
    const World world = build_mesh_world(config);
    fs::remove(path);
    const Aabb b = compute_bounds(world.mesh);
    constexpr double kFloatTol_m = 1e-5;  // PLY stores float32
    EXPECT_NEAR(b.min.y(), -6.0, kFloatTol_m);
    EXPECT_NEAR(b.max.y(), 0.0, kFloatTol_m);
    EXPECT_NEAR(b.max.x(), 12.0, kFloatTol_m);
    EXPECT_EQ(world.metadata.surfaces.size(), 1u);
    EXPECT_EQ(world.surface_tags.size(), world.mesh.num_triangles());
    testing::expect_defects_on_surfaces(world, kOnSurfaceTol_m);
    EXPECT_THROW(build_mesh_world({.path = "/nonexistent/mesh.stl"}), FileError);
    EXPECT_NE(config_error([] { build_mesh_world({}); }).find("mesh.path"), std::string::npos);
    EXPECT_NE(config_error([&] {
                  build_mesh_world({.path = "x.stl", .scale = 0.0});
              }).find("mesh.scale = 0"),
              std::string::npos);
}

TEST(MeshWorld, LoadsTheRealStorageTankMesh) {
    const fs::path path =
        fs::path(SCANTLING_SHARED_DATA_DIR) / "meshes" / "storage-tank-cylinder.stl";
    if (!fs::exists(path)) GTEST_SKIP() << "shared data not found at " << path;
    const World world = build_mesh_world({.path = path.string()});
    const Aabb b = compute_bounds(world.mesh);
    EXPECT_NEAR(b.size().z(), 21.2, 0.1);  // README: Ø 12 m x 21.2 m
    EXPECT_NEAR(std::max(b.size().x(), b.size().y()), 12.0, 0.2);
    EXPECT_EQ(world.mesh.num_triangles(), 1832u);
}

TEST(WorldBuilders, SameConfigGivesIdenticalWorlds) {
    testing::expect_identical(build_plate(), build_plate());
    testing::expect_identical(build_cylinder(), build_cylinder());
    testing::expect_identical(build_storage_tank(), build_storage_tank());
}

TEST(WorldBuilders, BadConfigValuesNameTheField) {
    const auto expect_named = [](const std::function<void()>& build, const std::string& field) {
        const std::string message = config_error(build);
        EXPECT_NE(message.find(field), std::string::npos) << message;
    };
    expect_named([] { build_plate({.thickness_m = 0.0}); }, "plate.thickness_m = 0");
    expect_named([] { build_plate({.stiffener_spacing_m = -1.0}); }, "plate.stiffener_spacing_m");
    expect_named([] { build_cylinder({.radius_m = -1.0}); }, "cylinder.radius_m = -1");
    expect_named([] { build_cylinder({.segments = 2}); }, "cylinder.segments = 2");
    expect_named([] { build_cylinder({.defects = {.min_radius_m = 0.2, .max_radius_m = 0.1}}); },
                 "cylinder.defects.max_radius_m");
    expect_named([] { build_storage_tank({.diameter_m = std::nan("")}); },
                 "storage_tank.diameter_m");
    expect_named([] { build_storage_tank({.seam_width_m = 3.0}); }, "storage_tank.seam_width_m");
    expect_named([] { build_storage_tank({.num_nozzles = -1}); }, "storage_tank.num_nozzles");
}

TEST(WorldBuilders, DefectCountZeroGivesNoDefects) {
    EXPECT_TRUE(build_plate({.defects = {.count = 0}}).metadata.defects.empty());
}

}  // namespace
}  // namespace scantling::sim
