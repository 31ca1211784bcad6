// The sonar inspection map (SPEC §5, issue 14 item 4): voxel statistics against the ground truth
// of points sampled on a known plane with known noise, existence and reliability rules, the
// memory bound, coverage holes of a deliberately unscanned patch, determinism, bad input.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <scantling/core/error.hpp>
#include <scantling/core/random.hpp>
#include <scantling/mapping/hull_coverage.hpp>
#include <scantling/mapping/sonar_inspection_map.hpp>

#include "../planning/expect_error.hpp"

namespace scantling::mapping {
namespace {

constexpr double kVoxelM = 0.2;
constexpr double kNoiseM = 0.01;     // range noise of the simulated features, 1σ
constexpr double kPlaneYM = 0.1;     // hull plane y = 0.1: mid voxel layer 0, 10σ from its faces
constexpr double kExact = 1e-12;     // m, m²: same arithmetic up to rounding
constexpr double kAreaExact = 1e-9;  // m²: sums of a few dozen cell areas
const double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Features on the plane y = kPlaneYM over the 0.2 m cells (iu, iv) of x ∈ [0, nu·0.2),
/// z ∈ [0, nv·0.2): `per_cell` uniform points per cell, y with N(0, kNoiseM²) noise, skipping
/// cells for which `skip(x_centre, z_centre)` holds.
template <class Skip>
std::vector<Eigen::Vector3d> plane_points(Rng& rng, int nu, int nv, int per_cell, Skip skip) {
    std::vector<Eigen::Vector3d> points;
    for (int iv = 0; iv < nv; ++iv) {
        for (int iu = 0; iu < nu; ++iu) {
            if (skip((iu + 0.5) * kVoxelM, (iv + 0.5) * kVoxelM)) continue;
            for (int k = 0; k < per_cell; ++k) {
                points.emplace_back(rng.uniform(iu * kVoxelM, (iu + 1) * kVoxelM),
                                    kPlaneYM + rng.normal(0.0, kNoiseM),
                                    rng.uniform(iv * kVoxelM, (iv + 1) * kVoxelM));
            }
        }
    }
    return points;
}

std::vector<Eigen::Vector3d> plane_points(Rng& rng, int nu, int nv, int per_cell) {
    return plane_points(rng, nu, nv, per_cell, [](double, double) { return false; });
}

SonarAddResult add_all(SonarInspectionMap& map, const std::vector<Eigen::Vector3d>& points,
                       double sigma_m = kNoiseM, double stamp_s = 0.0) {
    const std::vector<double> sigmas(points.size(), sigma_m);
    return map.add(points, sigmas, stamp_s);
}

/// The hull side x ∈ [0, 4], z ∈ [0, 2] m in the plane y = 0.
InspectedSurface surface_4x2() {
    InspectedSurface s;
    s.extent_u_m = 4.0;
    s.extent_v_m = 2.0;
    return s;
}

bool in_box(double x, double z, double x0, double x1, double z0, double z1) {
    return x > x0 && x < x1 && z > z0 && z < z1;
}

TEST(SonarInspectionMap, VoxelStatisticsMatchThePlaneAndTheSampleStatistics) {
    Rng rng(7);
    constexpr int kPerCell = 400;
    const std::vector<Eigen::Vector3d> points = plane_points(rng, 5, 5, kPerCell);
    SonarInspectionMap map;
    const SonarAddResult added = add_all(map, points, 0.02, 3.0);
    EXPECT_EQ(added.added, points.size());
    const std::vector<SonarVoxel> voxels = map.voxels();
    ASSERT_EQ(voxels.size(), 25U);
    double worst_plane_error_m = 0.0, worst_spread_error_m = 0.0;
    for (const SonarVoxel& v : voxels) {
        worst_plane_error_m =
            std::max(worst_plane_error_m, std::abs(v.mean_world_m.y() - kPlaneYM));
        worst_spread_error_m =
            std::max(worst_spread_error_m, std::abs(v.normal_spread_m - kNoiseM));
    }
    RecordProperty("worst_plane_error_m", ::testing::PrintToString(worst_plane_error_m));
    RecordProperty("worst_spread_error_m", ::testing::PrintToString(worst_spread_error_m));
    RecordProperty("uncertainty_m_first", ::testing::PrintToString(voxels[0].uncertainty_m));
    // Mean across the plane: 4 standard errors of kNoiseM / sqrt(400) = 0.5 mm → 2 mm.
    const double mean_tolerance_m = 4.0 * kNoiseM / std::sqrt(kPerCell);
    for (std::size_t i = 0; i < voxels.size(); ++i) {
        const SonarVoxel& v = voxels[i];
        EXPECT_EQ(v.num_points, static_cast<std::size_t>(kPerCell));
        EXPECT_NEAR(v.mean_world_m.y(), kPlaneYM, mean_tolerance_m);
        // In-plane the points are uniform over the cell: centre ± 4 · 0.2/√12/√400.
        const Eigen::Vector3d centre =
            (Eigen::Vector3d(v.key.x, v.key.y, v.key.z).array() + 0.5).matrix() * kVoxelM;
        EXPECT_NEAR(v.mean_world_m.x(), centre.x(), 4.0 * kVoxelM / std::sqrt(12.0 * kPerCell));
        EXPECT_NEAR(v.mean_world_m.z(), centre.z(), 4.0 * kVoxelM / std::sqrt(12.0 * kPerCell));
        // Scatter across the plane ≈ the noise: the sample sd of 400 normals is within 20 %.
        EXPECT_NEAR(v.normal_spread_m, kNoiseM, 0.2 * kNoiseM);
        EXPECT_GT(std::abs(v.normal_world.y()), 0.99);
        EXPECT_NEAR(v.mean_point_sigma_m, 0.02, kExact);  // a sum of 400 equal values
        EXPECT_EQ(v.first_stamp_s, 3.0);
        if (i > 0) {
            EXPECT_LT(voxels[i - 1].key, v.key);  // sorted by key
        }
    }
    // The first voxel against a two-pass computation of its points' statistics.
    std::vector<Eigen::Vector3d> mine;
    for (const auto& p : points) {
        if (map.key_of(p) == voxels[0].key) mine.push_back(p);
    }
    ASSERT_EQ(mine.size(), static_cast<std::size_t>(kPerCell));
    const double n = static_cast<double>(mine.size());
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const auto& p : mine) mean += p / n;
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (const auto& p : mine) cov += (p - mean) * (p - mean).transpose() / (n - 1.0);
    EXPECT_LT((voxels[0].mean_world_m - mean).norm(), kExact);
    EXPECT_LT((voxels[0].covariance_m2 - cov).norm(), kExact);
    EXPECT_LT((voxels[0].mean_covariance_m2 - cov / n).norm(), kExact);
    const double lambda_min = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(cov).eigenvalues()(0);
    EXPECT_NEAR(voxels[0].uncertainty_m, std::sqrt(lambda_min / n + 0.02 * 0.02), kExact);
}

TEST(SonarInspectionMap, WelfordStaysAccurateFarFromTheOrigin) {
    // A hull at UTM-like coordinates: a naive Σppᵀ − n·mean·meanᵀ loses all digits here.
    Rng rng(11);
    const Eigen::Vector3d offset(600000.0, 5.0e6, 0.0);
    std::vector<Eigen::Vector3d> points = plane_points(rng, 1, 1, 400);
    std::vector<Eigen::Vector3d> shifted;
    for (const auto& p : points) shifted.push_back(p + offset);
    SonarInspectionMap near_map, far_map;
    add_all(near_map, points);
    add_all(far_map, shifted);
    ASSERT_EQ(far_map.voxels().size(), 1U);
    // Shifting by 5e6 m rounds each coordinate to its ulp (9e-10 m), which bounds the agreement
    // (measured 2.5e-11 m²); a one-pass Σppᵀ − n·mean·meanᵀ would be off by ~mean²·ε ≈ 5 m².
    const double diff_m2 =
        (far_map.voxels()[0].covariance_m2 - near_map.voxels()[0].covariance_m2).norm();
    RecordProperty("far_covariance_diff_m2", ::testing::PrintToString(diff_m2));
    EXPECT_LT(diff_m2, 1e-9);
}

TEST(SonarInspectionMap, VoxelExistsOnlyWithMinPointsOfReliablePoints) {
    SonarInspectionMap map;  // min_points_per_voxel 5, max_point_sigma_m 0.1
    const std::vector<Eigen::Vector3d> four(4, Eigen::Vector3d(0.05, 0.05, 0.05));
    EXPECT_EQ(add_all(map, four).added, 4U);
    EXPECT_EQ(map.num_stored_voxels(), 1U);
    EXPECT_EQ(map.num_existing_voxels(), 0U);
    EXPECT_TRUE(map.voxels().empty());
    // Unreliable points are rejected and do not make the voxel exist.
    const SonarAddResult unreliable = add_all(map, four, 0.11);
    EXPECT_EQ(unreliable.added, 0U);
    EXPECT_EQ(unreliable.rejected_unreliable, 4U);
    EXPECT_EQ(map.num_existing_voxels(), 0U);
    EXPECT_EQ(map.num_points(), 4U);
    // The fifth reliable point does; its mean sigma ignores the rejected ones.
    const std::vector<Eigen::Vector3d> one{Eigen::Vector3d(0.15, 0.15, 0.15)};
    add_all(map, one, 0.05, 9.0);
    ASSERT_EQ(map.voxels().size(), 1U);
    const SonarVoxel v = map.voxels()[0];
    EXPECT_EQ(v.num_points, 5U);
    EXPECT_NEAR(v.mean_point_sigma_m, (4 * kNoiseM + 0.05) / 5.0, kExact);
    EXPECT_NEAR(v.mean_world_m.x(), (4 * 0.05 + 0.15) / 5.0, kExact);
    EXPECT_EQ(v.first_stamp_s, 0.0);
    EXPECT_EQ(v.last_stamp_s, 9.0);
}

TEST(SonarInspectionMap, MemoryBoundRefusesNewVoxelsAndCountsThem) {
    SonarInspectionMapConfig config;
    config.max_voxels = 3;
    SonarInspectionMap map(config);
    Rng rng(3);
    const std::vector<Eigen::Vector3d> points = plane_points(rng, 5, 1, 5);  // 5 voxels
    const SonarAddResult r = add_all(map, points);
    EXPECT_EQ(r.added, 15U);
    EXPECT_EQ(r.refused_memory, 10U);
    EXPECT_EQ(r.voxels_created, 3U);
    EXPECT_EQ(map.num_stored_voxels(), 3U);
    // Existing voxels still accumulate; new ones are still refused.
    const SonarAddResult again = add_all(map, points);
    EXPECT_EQ(again.added, 15U);
    EXPECT_EQ(again.refused_memory, 10U);
    EXPECT_EQ(map.num_points(), 30U);
}

TEST(SonarInspectionMap, SameInputGivesIdenticalVoxelsAndAnyOrderTheSameUpToRounding) {
    Rng rng(5);
    std::vector<Eigen::Vector3d> points = plane_points(rng, 6, 4, 30);
    SonarInspectionMap a, b, shuffled;
    add_all(a, points);
    add_all(b, points);
    std::vector<std::size_t> order(points.size());
    std::iota(order.begin(), order.end(), 0);
    for (std::size_t i = order.size() - 1; i > 0; --i) {
        std::swap(order[i], order[rng.uniform_index(i + 1)]);
    }
    std::vector<Eigen::Vector3d> permuted;
    for (std::size_t i : order) permuted.push_back(points[i]);
    add_all(shuffled, permuted);
    const auto va = a.voxels(), vb = b.voxels(), vs = shuffled.voxels();
    ASSERT_EQ(va.size(), 24U);
    ASSERT_EQ(vs.size(), va.size());
    for (std::size_t i = 0; i < va.size(); ++i) {
        EXPECT_EQ(va[i].key, vb[i].key);
        EXPECT_EQ(va[i].mean_world_m, vb[i].mean_world_m);  // bit-identical
        EXPECT_EQ(va[i].covariance_m2, vb[i].covariance_m2);
        EXPECT_EQ(va[i].uncertainty_m, vb[i].uncertainty_m);
        EXPECT_EQ(va[i].key, vs[i].key);
        EXPECT_EQ(va[i].num_points, vs[i].num_points);
        EXPECT_LT((va[i].mean_world_m - vs[i].mean_world_m).norm(), kExact);
        EXPECT_LT((va[i].covariance_m2 - vs[i].covariance_m2).norm(), kExact);
    }
}

TEST(SonarInspectionMap, UnscannedPatchIsExactlyOneHoleWithItsAreaAndCentroid) {
    Rng rng(21);
    // The 1 × 0.6 m patch x ∈ [1, 2], z ∈ [0.6, 1.2] gets no sonar return.
    const auto points = plane_points(
        rng, 20, 10, 10, [](double x, double z) { return in_box(x, z, 1.0, 2.0, 0.6, 1.2); });
    SonarInspectionMap map;
    add_all(map, points);
    const HullCoverage c = coverage_of(map, surface_4x2());
    EXPECT_EQ(c.num_cells_u, 20U);
    EXPECT_EQ(c.num_cells_v, 10U);
    EXPECT_EQ(c.uncovered_cells.size(), 15U);  // 5 × 3 cells
    ASSERT_EQ(c.holes.size(), 1U);
    const CoverageHole& h = c.holes[0];
    EXPECT_EQ(h.num_cells, 15U);
    EXPECT_NEAR(h.area_m2, 0.6, kAreaExact);
    EXPECT_LT((h.centroid_world_m - Eigen::Vector3d(1.5, 0.0, 0.9)).norm(), kAreaExact);
    EXPECT_LT((h.box_min_plane_m - Eigen::Vector2d(1.0, 0.6)).norm(), kAreaExact);
    EXPECT_LT((h.box_max_plane_m - Eigen::Vector2d(2.0, 1.2)).norm(), kAreaExact);
    EXPECT_NEAR(c.covered_fraction, 1.0 - 0.6 / 8.0, kAreaExact);
    EXPECT_NEAR(c.total_area_m2, 8.0, kAreaExact);
}

// A hull side that is not aligned with the voxel grid (turned 30° about world z, tilted 20°
// off vertical), scanned all over with 1 cm noise: the voxel means do not fall one per cell,
// yet the whole 4 × 2 m rectangle is covered.
TEST(SonarInspectionMap, ATiltedFullyScannedSurfaceHasNoHoles) {
    const Eigen::Matrix3d R = (Eigen::AngleAxisd(0.52, Eigen::Vector3d::UnitZ()) *
                               Eigen::AngleAxisd(0.35, Eigen::Vector3d::UnitX()))
                                  .toRotationMatrix();
    InspectedSurface surface = surface_4x2();
    surface.origin_world_m = Eigen::Vector3d(0.37, 1.13, -0.41);
    surface.axis_u_world = R.col(0);
    surface.axis_v_world = R.col(2);
    Rng rng(5);
    std::vector<Eigen::Vector3d> points;
    for (int k = 0; k < 40000; ++k) {  // 5000 per m²: ~200 per 0.2 m voxel face
        const double u = rng.uniform(0.0, 4.0), v = rng.uniform(0.0, 2.0);
        points.push_back(surface.origin_world_m + u * surface.axis_u_world +
                         v * surface.axis_v_world + rng.normal(0.0, kNoiseM) * R.col(1));
    }
    SonarInspectionMap map;
    add_all(map, points);
    const HullCoverage c = coverage_of(map, surface);
    EXPECT_TRUE(c.holes.empty()) << c.holes.size() << " holes, the largest "
                                 << (c.holes.empty() ? 0.0 : c.holes[0].area_m2) << " m2";
    EXPECT_GT(c.covered_fraction, 0.999);
}

TEST(SonarInspectionMap, HolesAreSortedByAreaAndSmallOnesCanBeIgnored) {
    Rng rng(22);
    const auto points = plane_points(rng, 20, 10, 10, [](double x, double z) {
        return in_box(x, z, 3.0, 3.4, 0.2, 0.6) || in_box(x, z, 1.0, 2.0, 0.6, 1.2);
    });
    SonarInspectionMap map;
    add_all(map, points);
    const HullCoverage c = coverage_of(map, surface_4x2());
    ASSERT_EQ(c.holes.size(), 2U);
    EXPECT_NEAR(c.holes[0].area_m2, 0.6, kAreaExact);  // found second in row-major order
    EXPECT_NEAR(c.holes[1].area_m2, 0.16, kAreaExact);
    EXPECT_LT((c.holes[1].centroid_world_m - Eigen::Vector3d(3.2, 0.0, 0.4)).norm(), kAreaExact);
    HullCoverageConfig config;
    config.min_hole_area_m2 = 0.2;
    const HullCoverage big_only = coverage_of(map, surface_4x2(), config);
    ASSERT_EQ(big_only.holes.size(), 1U);
    EXPECT_EQ(big_only.num_ignored_holes, 1U);
    EXPECT_EQ(big_only.uncovered_cells.size(), 19U);  // still uncovered
    EXPECT_NEAR(big_only.covered_fraction, 1.0 - 0.76 / 8.0, kAreaExact);
}

TEST(SonarInspectionMap, SparseVoxelsAndFarVoxelsDoNotCover) {
    Rng rng(23);
    // Row z ∈ [0, 0.2) has 4 points per cell (< min 5); a second surface 1 m off the plane.
    auto points = plane_points(rng, 20, 10, 10, [](double, double z) { return z < 0.2; });
    const auto sparse = plane_points(rng, 20, 1, 4);
    points.insert(points.end(), sparse.begin(), sparse.end());
    SonarInspectionMap map;
    add_all(map, points);
    InspectedSurface off_plane = surface_4x2();
    off_plane.origin_world_m.y() = -1.0;
    EXPECT_EQ(coverage_of(map, off_plane).covered_fraction, 0.0);
    const HullCoverage c = coverage_of(map, surface_4x2());
    ASSERT_EQ(c.holes.size(), 1U);
    EXPECT_NEAR(c.holes[0].area_m2, 0.8, kAreaExact);  // the 4 × 0.2 m bottom row
}

TEST(SonarInspectionMap, ClippedLastCellsCountTheirTrueArea) {
    Rng rng(24);
    SonarInspectionMap map;
    add_all(map, plane_points(rng, 2, 1, 10));  // covers x ∈ [0, 0.4)
    InspectedSurface s;
    s.extent_u_m = 0.5;  // cells [0, 0.2), [0.2, 0.4), [0.4, 0.5)
    s.extent_v_m = 0.2;
    const HullCoverage c = coverage_of(map, s);
    EXPECT_EQ(c.num_cells_u, 3U);
    ASSERT_EQ(c.holes.size(), 1U);
    EXPECT_NEAR(c.holes[0].area_m2, 0.02, kAreaExact);
    EXPECT_NEAR(c.holes[0].centroid_plane_m.x(), 0.45, kAreaExact);
    EXPECT_NEAR(c.covered_fraction, 0.8, kAreaExact);
}

TEST(SonarInspectionMap, BadInputThrowsNamingTheFieldAndChangesNothing) {
    SonarInspectionMap map;
    const std::vector<Eigen::Vector3d> points{{0, 0, 0}, {kNaN, 0, 0}};
    const std::vector<double> sigmas{0.01, 0.01};
    SCANTLING_EXPECT_ERROR(map.add(points, sigmas, 0.0), InputError, "points_world[1]");
    EXPECT_EQ(map.num_stored_voxels(), 0U);  // the good first point was not added either
    const std::vector<Eigen::Vector3d> good{{0, 0, 0}, {1, 0, 0}};
    SCANTLING_EXPECT_ERROR(map.add(good, std::vector<double>{0.01}, 0.0), InputError, "sigma_m");
    SCANTLING_EXPECT_ERROR(map.add(good, std::vector<double>{0.01, kNaN}, 0.0), InputError,
                           "sigma_m[1]");
    SCANTLING_EXPECT_ERROR(map.add(good, std::vector<double>{-0.01, 0.0}, 0.0), InputError,
                           "sigma_m[0]");
    SCANTLING_EXPECT_ERROR(map.add(good, sigmas, kNaN), InputError, "stamp_s");
    const std::vector<Eigen::Vector3d> huge{{1e300, 0, 0}};
    SCANTLING_EXPECT_ERROR(map.add(huge, std::vector<double>{0.01}, 0.0), InputError,
                           "points_world[0]");
    EXPECT_EQ(map.num_points(), 0U);
}

TEST(SonarInspectionMap, BadConfigsThrowNamingTheField) {
    const auto with = [](auto set) {
        SonarInspectionMapConfig c;
        set(c);
        return c;
    };
    SCANTLING_EXPECT_ERROR(SonarInspectionMap(with([](auto& c) { c.voxel_size_m = 0.0; })),
                           ConfigError, "sonar_map.voxel_size_m = 0");
    SCANTLING_EXPECT_ERROR(SonarInspectionMap(with([](auto& c) { c.min_points_per_voxel = 2; })),
                           ConfigError, "sonar_map.min_points_per_voxel = 2");
    SCANTLING_EXPECT_ERROR(SonarInspectionMap(with([](auto& c) { c.max_point_sigma_m = kNaN; })),
                           ConfigError, "sonar_map.max_point_sigma_m");
    SCANTLING_EXPECT_ERROR(SonarInspectionMap(with([](auto& c) { c.max_voxels = 0; })), ConfigError,
                           "sonar_map.max_voxels = 0");
}

TEST(SonarInspectionMap, BadSurfaceOrCoverageConfigThrowsNamingTheField) {
    const SonarInspectionMap map;
    InspectedSurface s = surface_4x2();
    s.axis_u_world = Eigen::Vector3d(2, 0, 0);
    SCANTLING_EXPECT_ERROR(coverage_of(map, s), ConfigError, "surface.axis_u_world");
    s = surface_4x2();
    s.axis_v_world = Eigen::Vector3d(1, 0, 1).normalized();
    SCANTLING_EXPECT_ERROR(coverage_of(map, s), ConfigError, "surface.axis_v_world");
    s = surface_4x2();
    s.extent_v_m = 0.0;
    SCANTLING_EXPECT_ERROR(coverage_of(map, s), ConfigError, "surface.extent_v_m = 0");
    s = surface_4x2();
    s.tolerance_m = -1.0;
    SCANTLING_EXPECT_ERROR(coverage_of(map, s), ConfigError, "surface.tolerance_m = -1");
    s = surface_4x2();
    s.origin_world_m.x() = kNaN;
    SCANTLING_EXPECT_ERROR(coverage_of(map, s), ConfigError, "surface.origin_world_m");
    HullCoverageConfig config;
    config.min_hole_area_m2 = -1.0;
    SCANTLING_EXPECT_ERROR(coverage_of(map, surface_4x2(), config), ConfigError,
                           "coverage.min_hole_area_m2 = -1");
    s = surface_4x2();
    s.extent_u_m = 1e6;  // 5e6 × 10 cells
    SCANTLING_EXPECT_ERROR(coverage_of(map, s), ConfigError, "coverage.max_cells");
}

}  // namespace
}  // namespace scantling::mapping
