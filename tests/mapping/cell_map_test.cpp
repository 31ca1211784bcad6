#include <scantling/core/error.hpp>
#include <scantling/core/random.hpp>
#include <scantling/mapping/cell_map.hpp>
#include <scantling/mapping/cell_thinning.hpp>

#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace scantling::mapping {
namespace {

// Points are stored as float offsets from their cell centre: for cells of a few metres the
// round trip is exact to about 2 m · 2^-24 ≈ 1.2e-7 m; 1e-6 m leaves margin.
constexpr double kStorageTolM = 1e-6;
constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

CellMapConfig config_with(double xy_m, double z_m, std::size_t budget = 100000,
                          double voxel_m = 0.1, CellHashKind hash = CellHashKind::kMixed) {
    CellMapConfig c;
    c.cell_size_xy_m = xy_m;
    c.cell_size_z_m = z_m;
    c.max_points_per_cell = budget;
    c.thinning_voxel_m = voxel_m;
    c.hash = hash;
    return c;
}

std::vector<Eigen::Vector3d> random_points(std::size_t n, double half_extent_m,
                                           std::uint64_t seed) {
    Rng rng(seed);
    std::vector<Eigen::Vector3d> pts(n);
    for (auto& p : pts) {
        p = {rng.uniform(-half_extent_m, half_extent_m), rng.uniform(-half_extent_m, half_extent_m),
             rng.uniform(-half_extent_m, half_extent_m)};
    }
    return pts;
}

void expect_same_points(const std::vector<Eigen::Vector3d>& got,
                        const std::vector<Eigen::Vector3d>& want) {
    ASSERT_EQ(got.size(), want.size());
    for (std::size_t i = 0; i < got.size(); ++i) {
        ASSERT_LE((got[i] - want[i]).norm(), kStorageTolM) << "point " << i;
    }
}

TEST(CellMap, KeyUsesFloorNotTruncation) {
    const CellMap map(config_with(2.0, 0.5));
    EXPECT_EQ(map.key_of({-0.1, -2.0, -0.01}), (CellKey{-1, -1, -1}));
    EXPECT_EQ(map.key_of({-2.0001, 1.999, 0.5}), (CellKey{-2, 0, 1}));
    EXPECT_EQ(map.key_of({2.0, -4.5, -1.2}), (CellKey{1, -3, -3}));
}

TEST(CellMap, CellCentreFollowsTheSpecFormula) {
    const CellMap map(config_with(2.0, 0.5));
    EXPECT_TRUE(map.cell_center({-1, 3, -2}).isApprox(Eigen::Vector3d(-1.0, 7.0, -0.75)));
    for (const Eigen::Vector3d& p : random_points(200, 50.0, 1)) {
        const Eigen::Vector3d spec(std::floor(p.x() / 2.0) * 2.0 + 1.0,
                                   std::floor(p.y() / 2.0) * 2.0 + 1.0,
                                   std::floor(p.z() / 0.5) * 0.5 + 0.25);
        EXPECT_TRUE(map.cell_center(map.key_of(p)).isApprox(spec, 1e-14)) << p.transpose();
    }
}

TEST(CellMap, KeyOfRejectsNonFiniteAndOutOfRangePoints) {
    const CellMap map(config_with(1.0, 1.0));
    EXPECT_THROW(map.key_of({kNan, 0.0, 0.0}), InputError);
    EXPECT_THROW(map.key_of({0.0, 0.0, 1e12}), InputError);
}

TEST(CellMap, InsertCountsPointsCellsAndSkipsNonFinite) {
    CellMap map(config_with(1.0, 1.0));
    const std::vector<Eigen::Vector3d> pts{{0.5, 0.5, 0.5},
                                           {0.6, 0.5, 0.5},
                                           {kNan, 0.0, 0.0},
                                           {-0.5, 0.5, 0.5},
                                           {0.0, std::numeric_limits<double>::infinity(), 0.0},
                                           {1e12, 0.0, 0.0}};
    const InsertStats s = map.insert(pts);
    EXPECT_EQ(s.points_added, 3U);
    EXPECT_EQ(s.non_finite_skipped, 2U);
    EXPECT_EQ(s.out_of_range_skipped, 1U);
    EXPECT_EQ(s.cells_created, 2U);
    EXPECT_EQ(s.cells_modified, 2U);
    EXPECT_EQ(s.cells_thinned, 0U);
    EXPECT_EQ(map.num_points(), 3U);
    EXPECT_EQ(map.num_cells(), 2U);
    EXPECT_EQ(map.num_points_in({0, 0, 0}), 2U);
    EXPECT_EQ(map.num_points_in({-1, 0, 0}), 1U);
    EXPECT_EQ(map.num_points_in({5, 5, 5}), 0U);

    const InsertStats again = map.insert(std::vector<Eigen::Vector3d>{{0.1, 0.1, 0.1}});
    EXPECT_EQ(again.cells_created, 0U);
    EXPECT_EQ(again.cells_modified, 1U);
    EXPECT_EQ(map.num_points(), 4U);
}

TEST(CellMap, PointsRoundTripFarFromTheOrigin) {
    CellMap map(config_with(4.0, 4.0));
    std::vector<Eigen::Vector3d> pts = random_points(500, 2.0, 2);
    for (auto& p : pts) p += Eigen::Vector3d(8000.0, -8000.0, 30.0);
    map.insert(pts);
    std::vector<Eigen::Vector3d> all;
    map.all_points(all);
    ASSERT_EQ(all.size(), pts.size());
    // all_points is ordered by cell; match each input point to its cell's output in order.
    std::map<CellKey, std::vector<Eigen::Vector3d>> by_cell;
    for (const auto& p : pts) by_cell[map.key_of(p)].push_back(p);
    std::vector<Eigen::Vector3d> want;
    for (const auto& [key, cell_pts] : by_cell)
        want.insert(want.end(), cell_pts.begin(), cell_pts.end());
    expect_same_points(all, want);
}

TEST(CellMap, ThinningReplacesAnOverBudgetCellByVoxelCentroids) {
    // 2 m cells, 1 m voxels anchored at the cell corner (0, 0, 0); budget 3.
    CellMap map(config_with(2.0, 2.0, 3, 1.0));
    const std::vector<Eigen::Vector3d> pts{
        {1.8, 1.8, 1.8}, {0.2, 0.2, 0.2}, {1.6, 1.2, 1.4}, {0.4, 0.6, 0.8}};
    const InsertStats s = map.insert(pts);
    EXPECT_EQ(s.cells_thinned, 1U);
    std::vector<Eigen::Vector3d> out;
    map.all_points(out);
    expect_same_points(out, {{0.3, 0.4, 0.5}, {1.7, 1.5, 1.6}});  // ordered by voxel
    EXPECT_EQ(map.num_points(), 2U);
}

TEST(CellMap, ThinningCoarsensTheVoxelUntilTheCellFitsItsBudget) {
    for (const std::size_t budget : {1, 7, 50}) {
        CellMap map(config_with(2.0, 1.0, budget, 0.05));
        map.insert(random_points(2000, 0.99, 3));  // 8 cells around the origin
        for (const CellKey& key : map.keys()) EXPECT_LE(map.num_points_in(key), budget);
    }
    std::vector<Eigen::Vector3f> offsets{{0.1F, 0.2F, 0.3F}, {-0.3F, -0.2F, -0.1F}};
    EXPECT_DOUBLE_EQ(thin_cell(offsets, Eigen::Vector3d(2, 2, 2), 0.5, 1), 2.0);
    ASSERT_EQ(offsets.size(), 1U);
    EXPECT_TRUE(offsets[0].isApprox(Eigen::Vector3f(-0.1F, 0.0F, 0.1F)));
    // Offsets an ulp outside the cell (float rounding on a face) still end in one voxel.
    offsets = {{std::nextafter(-1.0F, -2.0F), 0.0F, 0.0F},
               {std::nextafter(1.0F, 2.0F), 0.0F, 0.0F}};
    thin_cell(offsets, Eigen::Vector3d(2, 2, 2), 0.5, 1);
    EXPECT_EQ(offsets.size(), 1U);
}

TEST(CellMap, ThinningTouchesOnlyCellsModifiedAndOverBudget) {
    CellMap map(config_with(1.0, 1.0, 4, 0.5));
    // Cell (0,0,0) holds four copies of one point: thinning would merge them, but it is within
    // budget. Cell (1,0,0) is filled over budget in a second call.
    const std::vector<Eigen::Vector3d> dup(4, Eigen::Vector3d(0.3, 0.3, 0.3));
    EXPECT_EQ(map.insert(dup).cells_thinned, 0U);
    std::vector<Eigen::Vector3d> over;
    for (int i = 0; i < 6; ++i) over.emplace_back(1.1 + 0.01 * i, 0.2, 0.2);
    const InsertStats s = map.insert(over);
    EXPECT_EQ(s.cells_modified, 1U);
    EXPECT_EQ(s.cells_thinned, 1U);
    EXPECT_EQ(map.num_points_in({0, 0, 0}), 4U);  // untouched
    EXPECT_EQ(map.num_points_in({1, 0, 0}), 1U);  // all six in one 0.5 m voxel
    EXPECT_EQ(map.num_points(), 5U);
    // Once modified and over budget, the duplicate cell is thinned too.
    EXPECT_EQ(map.insert(std::vector<Eigen::Vector3d>{{0.3, 0.3, 0.3}}).cells_thinned, 1U);
    EXPECT_EQ(map.num_points_in({0, 0, 0}), 1U);
}

/// Brute force: cells whose centre is within the radius of the query cell's centre, sorted by
/// key, each with its points in insertion order.
std::vector<Eigen::Vector3d> brute_force_near(const CellMap& map,
                                              const std::vector<Eigen::Vector3d>& inserted,
                                              const Eigen::Vector3d& position, double radius_m) {
    const Eigen::Vector3d c = map.cell_center(map.key_of(position));
    std::map<CellKey, std::vector<Eigen::Vector3d>> by_cell;
    for (const auto& p : inserted) {
        const CellKey key = map.key_of(p);
        if ((map.cell_center(key) - c).norm() <= radius_m) by_cell[key].push_back(p);
    }
    std::vector<Eigen::Vector3d> want;
    for (const auto& [key, pts] : by_cell) want.insert(want.end(), pts.begin(), pts.end());
    return want;
}

TEST(CellMap, GatherNearReturnsExactlyTheCellsInTheBallInKeyOrder) {
    CellMap map(config_with(1.5, 1.0));
    const std::vector<Eigen::Vector3d> pts = random_points(4000, 10.0, 4);
    map.insert(pts);
    // Radii avoid exact centre distances so the brute force's rounding cannot differ. 100 m
    // holds more keys than the map has cells: the scanning path.
    for (const double r : {0.0, 1.2, 3.1, 7.3, 100.0}) {
        for (const Eigen::Vector3d& q : random_points(5, 9.0, 5)) {
            std::vector<Eigen::Vector3d> got{{42.0, 42.0, 42.0}};  // appended after this
            map.gather_near(q, r, got);
            ASSERT_FALSE(got.empty());
            EXPECT_EQ(got.front(), Eigen::Vector3d(42.0, 42.0, 42.0));
            got.erase(got.begin());
            expect_same_points(got, brute_force_near(map, pts, q, r));
        }
    }
    std::vector<Eigen::Vector3d> all;
    map.gather_near(Eigen::Vector3d::Zero(), 100.0, all);
    EXPECT_EQ(all.size(), pts.size());
}

TEST(CellMap, OutputDoesNotDependOnHashKindOrBucketLayout) {
    const std::vector<Eigen::Vector3d> a = random_points(3000, 6.0, 6);
    const std::vector<Eigen::Vector3d> b = random_points(3000, 6.0, 7);
    std::vector<std::vector<Eigen::Vector3d>> near, all;
    for (const CellHashKind kind : {CellHashKind::kMixed, CellHashKind::kSourceXor}) {
        for (const std::size_t reserve : {0, 100000}) {
            CellMap map(config_with(1.0, 1.0, 20, 0.25, kind));
            map.reserve(reserve);
            map.insert(a);
            map.insert(b);
            near.emplace_back();
            map.gather_near({0.3, -0.2, 1.0}, 2.5, near.back());
            all.emplace_back();
            map.all_points(all.back());
        }
    }
    ASSERT_FALSE(near[0].empty());
    for (std::size_t i = 1; i < near.size(); ++i) {
        EXPECT_EQ(near[i], near[0]) << "variant " << i;
        EXPECT_EQ(all[i], all[0]) << "variant " << i;
    }
}

TEST(CellMap, SourceHashCollisionsKeepTheMapCorrect) {
    CellMap map(config_with(1.0, 1.0, 100, 0.1, CellHashKind::kSourceXor));
    ASSERT_EQ(hash_cell({2, 0, 0}, CellHashKind::kSourceXor),
              hash_cell({0, 1, 0}, CellHashKind::kSourceXor));
    map.insert(std::vector<Eigen::Vector3d>{{2.5, 0.5, 0.5}, {0.5, 1.5, 0.5}, {2.6, 0.5, 0.5}});
    EXPECT_EQ(map.num_cells(), 2U);
    EXPECT_EQ(map.num_points_in({2, 0, 0}), 2U);
    EXPECT_EQ(map.num_points_in({0, 1, 0}), 1U);
    std::vector<Eigen::Vector3d> out;
    map.gather_near({0.1, 1.9, 0.2}, 0.0, out);
    expect_same_points(out, {{0.5, 1.5, 0.5}});
    const HashStats s = map.hash_stats();
    EXPECT_EQ(s.num_cells, 2U);
    EXPECT_EQ(s.distinct_hashes, 1U);
    EXPECT_EQ(s.cells_sharing_hash, 2U);
    EXPECT_EQ(s.max_bucket_occupancy, 2U);  // equal hashes always share a bucket
    EXPECT_EQ(s.empty_buckets, s.bucket_count - 1);
    EXPECT_DOUBLE_EQ(s.mean_chain_seen, 2.0);
}

TEST(CellMap, GatherNearRejectsBadQueries) {
    const CellMap map;
    std::vector<Eigen::Vector3d> out;
    EXPECT_THROW(map.gather_near({kNan, 0, 0}, 1.0, out), InputError);
    EXPECT_THROW(map.gather_near({0, 0, 0}, -1.0, out), InputError);
    EXPECT_THROW(map.gather_near({0, 0, 0}, kNan, out), InputError);
}

TEST(CellMap, MemoryCoversPointsAndTableAndClearEmptiesTheMap) {
    CellMap map(config_with(1.0, 1.0));
    const std::size_t empty_bytes = map.memory_bytes();
    map.insert(random_points(10000, 20.0, 8));
    EXPECT_GE(map.memory_bytes(), empty_bytes + 10000 * sizeof(Eigen::Vector3f) +
                                      map.num_cells() * (sizeof(void*) + sizeof(CellKey)));
    map.clear();
    EXPECT_EQ(map.num_cells(), 0U);
    EXPECT_EQ(map.num_points(), 0U);
    std::vector<Eigen::Vector3d> out;
    map.gather_near(Eigen::Vector3d::Zero(), 50.0, out);
    EXPECT_TRUE(out.empty());
}

void expect_config_error(const CellMapConfig& c, const std::string& field) {
    try {
        c.validate("odometry.map");
        FAIL() << "expected ConfigError for " << field;
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("odometry.map." + field + " = "), std::string::npos)
            << e.what();
    }
}

TEST(CellMapConfig, DefaultsAreValidAndErrorsNameTheField) {
    EXPECT_NO_THROW(CellMapConfig{}.validate());
    EXPECT_EQ(CellMapConfig{}.hash, CellHashKind::kMixed);
    CellMapConfig c;
    c.cell_size_xy_m = -1.0;
    expect_config_error(c, "cell_size_xy_m");
    c = {};
    c.cell_size_z_m = kNan;
    expect_config_error(c, "cell_size_z_m");
    c = {};
    c.max_points_per_cell = 0;
    expect_config_error(c, "max_points_per_cell");
    c = {};
    c.thinning_voxel_m = 0.0;
    expect_config_error(c, "thinning_voxel_m");
    c = {};
    c.thinning_voxel_m = 5.0;  // larger than the 4 m cell
    expect_config_error(c, "thinning_voxel_m");
    c = {};
    c.thinning_voxel_m = 1e-7;  // 4e7 voxels per cell edge
    expect_config_error(c, "thinning_voxel_m");
    c = {};
    c.cell_size_xy_m = 0.0;
    EXPECT_THROW(CellMap{c}, ConfigError);
}

}  // namespace
}  // namespace scantling::mapping
