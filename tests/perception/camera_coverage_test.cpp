#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <string>

#include <scantling/core/error.hpp>
#include <scantling/core/random.hpp>
#include <scantling/perception/camera_coverage.hpp>

namespace scantling::perception {
namespace {

constexpr double kCellM = 0.05;
constexpr double kGeometryTol = 1e-9;  // sums of a few hundred exact multiples of 0.05 m

/// The rectangle [0, width] × [0, height] in the world plane z = 0, front face up (+z).
InspectionRectangle floor_rectangle(double width_m, double height_m) {
    return {Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), width_m,
            height_m};
}

/// A centred pinhole camera.
PinholeIntrinsics camera(int width_px, int height_px, double fx, double fy) {
    return {width_px, height_px, fx, fy, 0.5 * (width_px - 1), 0.5 * (height_px - 1)};
}

/// 640 × 480 px with fx = 640, fy = 600: at 1 m head-on it sees exactly 1.0 m × 0.8 m.
PinholeIntrinsics metre_camera() { return camera(640, 480, 640.0, 600.0); }

/// Camera at `p_world` looking along `forward_world` with its x axis along `right_world`.
Eigen::Isometry3d camera_pose(const Eigen::Vector3d& p_world, const Eigen::Vector3d& forward_world,
                              const Eigen::Vector3d& right_world) {
    Eigen::Isometry3d T_world_camera = Eigen::Isometry3d::Identity();
    const Eigen::Vector3d z = forward_world.normalized();
    const Eigen::Vector3d x = right_world.normalized();
    T_world_camera.linear() << x, z.cross(x), z;
    T_world_camera.translation() = p_world;
    return T_world_camera;
}

/// Camera at (u, v, height) looking straight down at the floor rectangle (image x along +u).
Eigen::Isometry3d looking_down(double u_m, double v_m, double height_m) {
    return camera_pose({u_m, v_m, height_m}, -Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitX());
}

/// Cells of `coverage` whose centres are within radius_m of (u, v) on the floor.
std::size_t cells_within(const CameraCoverage& coverage, double u_m, double v_m, double radius_m) {
    std::size_t count = 0;
    for (std::size_t row = 0; row < coverage.rows(); ++row) {
        for (std::size_t column = 0; column < coverage.columns(); ++column) {
            const Eigen::Vector3d p = coverage.cell_centre_world(column, row);
            if (std::hypot(p.x() - u_m, p.y() - v_m) <= radius_m) ++count;
        }
    }
    return count;
}

std::uint32_t count_at(const CameraCoverage& coverage, double u_m, double v_m) {
    const auto column = static_cast<std::size_t>(u_m / coverage.cell_size_u_m());
    const auto row = static_cast<std::size_t>(v_m / coverage.cell_size_v_m());
    return coverage.view_counts()[row * coverage.columns() + column];
}

TEST(CameraCoverage, HeadOnViewCoversExactlyTheImageFootprint) {
    CameraCoverage coverage(floor_rectangle(4.0, 3.0), metre_camera());
    coverage.add_view(looking_down(2.0, 1.5, 1.0));
    // Footprint [1.5, 2.5] × [1.1, 1.9] m: its edges are cell edges, 20 × 16 cells.
    const CoverageResult result = coverage.result();
    EXPECT_EQ(result.cells, 80u * 60u);
    EXPECT_EQ(result.covered_cells, 20u * 16u);
    EXPECT_NEAR(result.covered_fraction, 0.8 / 12.0, 1.0 / 4800.0);
    EXPECT_NEAR(result.covered_area_m2, 0.8, kGeometryTol);
    EXPECT_EQ(count_at(coverage, 1.52, 1.12), 1u);  // just inside the corner
    EXPECT_EQ(count_at(coverage, 1.48, 1.12), 0u);  // just outside
    ASSERT_EQ(result.holes.size(), 1u);             // the ring around it
    EXPECT_EQ(result.holes[0].cells, 4800u - 320u);
}

TEST(CameraCoverage, IncidenceLimitCutsADiscOfHeightTimesTan) {
    CameraCoverageConfig config;
    config.max_incidence_deg = 45.0;
    config.max_range_m = 100.0;
    // ~157° field of view: only the incidence limit cuts.
    CameraCoverage coverage(floor_rectangle(6.0, 6.0), camera(1000, 1000, 100.0, 100.0), config);
    coverage.add_view(looking_down(3.0, 3.0, 1.0));
    const CoverageResult result = coverage.result();
    EXPECT_EQ(result.covered_cells, cells_within(coverage, 3.0, 3.0, 1.0));
    // The disc's area up to the band of cells its circle crosses.
    EXPECT_NEAR(result.covered_area_m2, std::numbers::pi, 2.0 * std::numbers::pi * kCellM);
    EXPECT_EQ(count_at(coverage, 3.0 + 0.97, 3.01), 1u);
    EXPECT_EQ(count_at(coverage, 3.0 + 1.03, 3.01), 0u);
}

TEST(CameraCoverage, RangeLimitCutsADiscOfTheChordRadius) {
    CameraCoverageConfig config;
    config.max_incidence_deg = 90.0;
    config.max_range_m = 1.5;  // in-plane radius √(1.5² − 1²) = √1.25 ≈ 1.118 m
    CameraCoverage coverage(floor_rectangle(6.0, 6.0), camera(1000, 1000, 100.0, 100.0), config);
    coverage.add_view(looking_down(3.0, 3.0, 1.0));
    EXPECT_EQ(coverage.result().covered_cells, cells_within(coverage, 3.0, 3.0, std::sqrt(1.25)));
    EXPECT_EQ(count_at(coverage, 3.0, 3.0 + 1.09), 1u);
    EXPECT_EQ(count_at(coverage, 3.0, 3.0 + 1.16), 0u);
}

TEST(CameraCoverage, ResolutionRequirementKeepsTheSharpDisc) {
    // f = 500 px at 1 m: 2 mm/px head-on; 1000 r / (f cos i) = 2 r² <= 2.5 → r² <= 1.25,
    // in-plane radius 0.5 m.
    CameraCoverageConfig config;
    config.max_mm_per_px = 2.5;
    const PinholeIntrinsics intrinsics = camera(1600, 1200, 500.0, 500.0);
    CameraCoverage sharp(floor_rectangle(4.0, 4.0), intrinsics, config);
    sharp.add_view(looking_down(2.0, 2.0, 1.0));
    EXPECT_EQ(sharp.result().covered_cells, cells_within(sharp, 2.0, 2.0, 0.5));
    EXPECT_GT(sharp.result().covered_cells, 300u);  // ≈ π 0.5² / 0.0025 = 314

    config.max_mm_per_px = 1.9;  // finer than the camera gives anywhere at 1 m
    CameraCoverage too_fine(floor_rectangle(4.0, 4.0), intrinsics, config);
    too_fine.add_view(looking_down(2.0, 2.0, 1.0));
    EXPECT_EQ(too_fine.result().covered_cells, 0u);
}

TEST(CameraCoverage, ViewsFromBehindLookingAwayOrInThePlaneCoverNothing) {
    CameraCoverage coverage(floor_rectangle(4.0, 3.0), metre_camera());
    const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
    const Eigen::Vector3d x = Eigen::Vector3d::UnitX();
    coverage.add_view(camera_pose({2.0, 1.5, -1.0}, up, x));   // behind, facing the back
    coverage.add_view(camera_pose({2.0, 1.5, 1.0}, up, x));    // in front, facing away
    coverage.add_view(camera_pose({-1.0, 1.5, 0.0}, x, -up));  // in the plane, along it
    EXPECT_EQ(coverage.result().covered_cells, 0u);
}

TEST(CameraCoverage, OcclusionCallbackHidesWhatItSaysIsHidden) {
    CameraCoverage blocked(floor_rectangle(4.0, 3.0), metre_camera());
    blocked.add_view(looking_down(2.0, 1.5, 1.0), [](const auto&, const auto&) { return true; });
    EXPECT_EQ(blocked.result().covered_cells, 0u);

    CameraCoverage half(floor_rectangle(4.0, 3.0), metre_camera());
    Eigen::Vector3d from_seen = Eigen::Vector3d::Zero();
    half.add_view(looking_down(2.0, 1.5, 1.0),
                  [&](const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
                      from_seen = from;
                      return to.x() < 2.0;  // a wall hiding the left half
                  });
    EXPECT_EQ(half.result().covered_cells, 10u * 16u);
    EXPECT_TRUE(from_seen.isApprox(Eigen::Vector3d(2.0, 1.5, 1.0)));
}

TEST(CameraCoverage, MinViewsNeedsThatManyViews) {
    CameraCoverageConfig config;
    config.min_views = 2;
    CameraCoverage coverage(floor_rectangle(4.0, 3.0), metre_camera(), config);
    coverage.add_view(looking_down(2.0, 1.5, 1.0));
    EXPECT_EQ(coverage.result().covered_cells, 0u);
    coverage.add_view(looking_down(2.0, 1.5, 1.0));
    EXPECT_EQ(coverage.result().covered_cells, 320u);
    EXPECT_EQ(count_at(coverage, 2.0, 1.5), 2u);
}

TEST(CameraCoverage, TwoDisjointFootprintsLeaveTheTwoHolesBetween) {
    // A 4 m × 0.8 m strip; the views see u ∈ [0, 1] and [1.8, 2.8], leaving [1, 1.8] (16
    // columns) and [2.8, 4] (24 columns), 16 rows each.
    CameraCoverage coverage(floor_rectangle(4.0, 0.8), metre_camera());
    coverage.add_view(looking_down(0.5, 0.4, 1.0));
    coverage.add_view(looking_down(2.3, 0.4, 1.0));
    const CoverageResult result = coverage.result();
    ASSERT_EQ(result.holes.size(), 2u);
    const CoverageHole& large = result.holes[0];
    EXPECT_EQ(large.cells, 24u * 16u);
    EXPECT_NEAR(large.area_m2, 1.2 * 0.8, kGeometryTol);
    EXPECT_TRUE(large.centroid_world.isApprox(Eigen::Vector3d(3.4, 0.4, 0.0), kGeometryTol));
    EXPECT_TRUE(large.min_uv_m.isApprox(Eigen::Vector2d(2.8, 0.0), kGeometryTol));
    EXPECT_TRUE(large.max_uv_m.isApprox(Eigen::Vector2d(4.0, 0.8), kGeometryTol));
    const CoverageHole& small = result.holes[1];
    EXPECT_EQ(small.cells, 16u * 16u);
    EXPECT_NEAR(small.area_m2, 0.8 * 0.8, kGeometryTol);
    EXPECT_TRUE(small.centroid_world.isApprox(Eigen::Vector3d(1.4, 0.4, 0.0), kGeometryTol));
    EXPECT_NEAR(result.covered_area_m2 + large.area_m2 + small.area_m2, 3.2, kGeometryTol);
}

TEST(CameraCoverage, HolesTouchingOnlyAtACornerAreSeparate) {
    CameraCoverage coverage(floor_rectangle(1.0, 0.8), metre_camera());
    // Hide cells (5, 5) and (6, 6): diagonal neighbours, two holes of one cell.
    const auto hidden = [&](const auto&, const Eigen::Vector3d& to) {
        return to.isApprox(coverage.cell_centre_world(5, 5)) ||
               to.isApprox(coverage.cell_centre_world(6, 6));
    };
    coverage.add_view(looking_down(0.5, 0.4, 1.0), hidden);
    const CoverageResult result = coverage.result();
    ASSERT_EQ(result.holes.size(), 2u);
    EXPECT_EQ(result.holes[0].cells, 1u);
    EXPECT_TRUE(result.holes[0].centroid_world.isApprox(coverage.cell_centre_world(5, 5)));
    EXPECT_TRUE(result.holes[1].centroid_world.isApprox(coverage.cell_centre_world(6, 6)));
}

TEST(CameraCoverage, LawnmowerOverAWallCoversIt) {
    // A vertical 8 m × 3 m wall facing −y (u = +x, v = +z: n = u × v = −y), swept at 1 m
    // stand-off by a 60° × 45° camera (1.15 m × 0.83 m footprint) in rows 0.6 m apart.
    const InspectionRectangle wall{Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(),
                                   Eigen::Vector3d::UnitZ(), 8.0, 3.0};
    const auto intrinsics =
        PinholeIntrinsics::from_fov(640, 480, std::numbers::pi / 3.0, std::numbers::pi / 4.0);
    CameraCoverage coverage(wall, intrinsics);
    for (double z_m = 0.3; z_m < 3.0; z_m += 0.6) {
        for (double x_m = 0.0; x_m <= 8.0 + 1e-9; x_m += 0.25) {
            coverage.add_view(
                camera_pose({x_m, -1.0, z_m}, Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitX()));
        }
    }
    const CoverageResult result = coverage.result();
    EXPECT_GE(result.covered_fraction, 0.99);
    EXPECT_TRUE(result.holes.empty());
}

/// Cells of a fresh coverage that one view sees by the plain criteria (written out here for a
/// camera above the floor rectangle), testing every cell.
std::size_t brute_force_seen(const CameraCoverage& coverage, const PinholeIntrinsics& intrinsics,
                             const CameraCoverageConfig& config,
                             const Eigen::Isometry3d& T_world_camera) {
    std::size_t seen = 0;
    const double cos_max = std::cos(config.max_incidence_deg * std::numbers::pi / 180.0);
    const double focal_px = std::min(intrinsics.fx, intrinsics.fy);
    for (std::size_t row = 0; row < coverage.rows(); ++row) {
        for (std::size_t column = 0; column < coverage.columns(); ++column) {
            const Eigen::Vector3d c = coverage.cell_centre_world(column, row);
            const Eigen::Vector3d p_camera = T_world_camera.inverse() * c;
            const double range_m = p_camera.norm();
            const double cos_i = T_world_camera.translation().z() / range_m;
            seen += intrinsics.project(p_camera) && range_m <= config.max_range_m &&
                    cos_i >= cos_max &&
                    (config.max_mm_per_px == 0.0 ||
                     1000.0 * range_m / (focal_px * cos_i) <= config.max_mm_per_px);
        }
    }
    return seen;
}

/// True when some corner ray of the image never meets the floor (the footprint is unbounded).
bool sees_past_horizon(const PinholeIntrinsics& k, const Eigen::Isometry3d& T_world_camera) {
    for (const double x : {-0.5, k.width - 0.5}) {
        for (const double y : {-0.5, k.height - 0.5}) {
            const Eigen::Vector3d d = T_world_camera.linear() * k.unproject({x, y}, 1.0);
            if (d.z() >= 0.0) return true;
        }
    }
    return false;
}

TEST(CameraCoverage, BoundedSearchFindsEveryCellABruteForceTestFinds) {
    // Random poses tilted up to 86° from straight down, many with part of the image above the
    // horizon; every other one with a resolution limit. The search box must not drop a cell
    // the plain criteria accept.
    const auto intrinsics = camera(320, 240, 250.0, 260.0);
    Rng rng(7);
    int trials_seeing = 0;
    int trials_past_horizon = 0;
    for (int trial = 0; trial < 200; ++trial) {
        CameraCoverageConfig config;
        config.max_incidence_deg = 75.0;
        config.max_mm_per_px = trial % 2 == 0 ? 10.0 : 0.0;
        const Eigen::Vector3d p(rng.uniform(-1.0, 6.0), rng.uniform(-1.0, 5.0),
                                rng.uniform(0.2, 2.5));
        const double tilt_rad = rng.uniform(0.0, 1.5);
        const double azimuth_rad = rng.uniform(0.0, 2.0 * std::numbers::pi);
        const Eigen::Vector3d forward(std::sin(tilt_rad) * std::cos(azimuth_rad),
                                      std::sin(tilt_rad) * std::sin(azimuth_rad),
                                      -std::cos(tilt_rad));
        const Eigen::Vector3d right =
            Eigen::AngleAxisd(rng.uniform(0.0, 6.0), forward) * forward.unitOrthogonal();
        const Eigen::Isometry3d T_world_camera = camera_pose(p, forward, right);
        CameraCoverage coverage(floor_rectangle(5.0, 4.0), intrinsics, config);
        coverage.add_view(T_world_camera);
        const std::size_t expected = brute_force_seen(coverage, intrinsics, config, T_world_camera);
        EXPECT_EQ(coverage.result().covered_cells, expected) << "trial " << trial;
        trials_seeing += expected > 0;
        trials_past_horizon += expected > 0 && sees_past_horizon(intrinsics, T_world_camera);
    }
    // The comparison was not all zeros, and it covered the unbounded footprint.
    EXPECT_GE(trials_seeing, 80);
    EXPECT_GE(trials_past_horizon, 20);
}

/// Runs `make` and expects a ConfigError whose message contains `field`.
template <typename Make>
void expect_config_error(Make make, const std::string& field) {
    try {
        make();
        ADD_FAILURE() << "no ConfigError for " << field;
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
}

TEST(CameraCoverage, ConfigErrorsNameTheField) {
    const auto with = [](auto edit, const std::string& field) {
        CameraCoverageConfig config;
        edit(config);
        expect_config_error([&] { config.validate(); }, "camera_coverage." + field);
    };
    with([](auto& c) { c.cell_size_m = 0.0; }, "cell_size_m");
    with([](auto& c) { c.max_range_m = std::nan(""); }, "max_range_m");
    with([](auto& c) { c.max_incidence_deg = 90.5; }, "max_incidence_deg");
    with([](auto& c) { c.max_mm_per_px = -1.0; }, "max_mm_per_px");
    with([](auto& c) { c.min_views = 0; }, "min_views");
    EXPECT_NO_THROW(CameraCoverageConfig{}.validate());
}

TEST(CameraCoverage, RectangleAndIntrinsicsErrorsNameTheField) {
    const auto with = [](auto edit, const std::string& field) {
        InspectionRectangle rectangle = floor_rectangle(4.0, 3.0);
        edit(rectangle);
        expect_config_error(
            [&] {
                (void)CameraCoverage{rectangle, metre_camera()};
            },
            "camera_coverage.rectangle." + field);
    };
    with([](auto& r) { r.corner_world.x() = std::numeric_limits<double>::infinity(); },
         "corner_world");
    with([](auto& r) { r.u_world = Eigen::Vector3d(2.0, 0.0, 0.0); }, "u_world");
    with([](auto& r) { r.v_world = Eigen::Vector3d(0.6, 0.8, 0.0); }, "v_world");  // not ⊥ u
    with([](auto& r) { r.width_m = 0.0; }, "width_m");
    with([](auto& r) { r.height_m = -3.0; }, "height_m");
    // 10 km × 10 km at 5 cm would be 4·10¹⁰ cells.
    with([](auto& r) { r.width_m = r.height_m = 1e4; }, "width_m × height_m");
    PinholeIntrinsics bad = metre_camera();
    bad.fx = 0.0;
    expect_config_error(
        [&] {
            (void)CameraCoverage{floor_rectangle(4.0, 3.0), bad};
        },
        "camera_coverage.intrinsics.fx");
}

TEST(CameraCoverage, NonFiniteOrNonRigidPosesThrowAndCountNothing) {
    CameraCoverage coverage(floor_rectangle(4.0, 3.0), metre_camera());
    Eigen::Isometry3d nan_pose = looking_down(2.0, 1.5, 1.0);
    nan_pose.translation().x() = std::nan("");
    EXPECT_THROW(coverage.add_view(nan_pose), InputError);
    Eigen::Isometry3d scaled = looking_down(2.0, 1.5, 1.0);
    scaled.linear() *= 2.0;
    EXPECT_THROW(coverage.add_view(scaled), InputError);
    try {
        coverage.add_view(nan_pose);
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("T_world_camera"), std::string::npos);
    }
    EXPECT_EQ(coverage.result().covered_cells, 0u);
}

TEST(CameraCoverage, UnevenSidesSplitIntoCellsNoLargerThanConfigured) {
    CameraCoverage coverage(floor_rectangle(1.02, 0.5), metre_camera());
    EXPECT_EQ(coverage.columns(), 21u);  // 1.02 / 0.05 = 20.4 → 21 cells of 4.857 cm
    EXPECT_EQ(coverage.rows(), 10u);     // exactly 10, no sliver row from rounding
    EXPECT_NEAR(coverage.cell_size_u_m() * 21.0, 1.02, kGeometryTol);
    EXPECT_NEAR(coverage.result().covered_area_m2 + coverage.result().holes[0].area_m2, 0.51,
                kGeometryTol);
}

}  // namespace
}  // namespace scantling::perception
