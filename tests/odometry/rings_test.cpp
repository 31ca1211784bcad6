#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <numeric>
#include <string>
#include <vector>

#include <scantling/core/error.hpp>
#include <scantling/core/random.hpp>
#include <scantling/io/cloud_io.hpp>
#include <scantling/odometry/rings.hpp>

namespace scantling::odometry {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// One laser of a synthetic spinning LiDAR.
struct Laser {
    double elevation_rad = 0.0;
    double azimuth_offset_rad = 0.0;  // rotational calibration correction
    double vertical_offset_m = 0.0;   // beam origin above the sensor origin
};

/// HDL-64E-like table, listed top to bottom as in KITTI files: upper block every 1/3° from
/// +2°, lower block every ~0.515° from −8.83° to −24.8°, with per-laser calibration offsets
/// (elevation ±0.05°, azimuth ±3°, and ±0.2 m vertically when `vertical_offsets`).
std::vector<Laser> hdl64_lasers(Rng& rng, bool vertical_offsets) {
    std::vector<Laser> lasers;
    for (int i = 0; i < 64; ++i) {
        const double nominal_deg = i < 32 ? 2.0 - i / 3.0 : -8.83 - (i - 32) * (15.97 / 31.0);
        Laser laser;
        laser.elevation_rad = (nominal_deg + rng.uniform(-0.05, 0.05)) * kDeg;
        laser.azimuth_offset_rad = rng.uniform(-3.0, 3.0) * kDeg;
        laser.vertical_offset_m = vertical_offsets ? rng.uniform(-0.2, 0.2) : 0.0;
        lasers.push_back(laser);
    }
    return lasers;
}

/// The true ring of each laser: its rank by elevation, 0 = lowest.
std::vector<int> ring_of_laser(const std::vector<Laser>& lasers) {
    std::vector<int> order(lasers.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(),
              [&](int a, int b) { return lasers[a].elevation_rad < lasers[b].elevation_rad; });
    std::vector<int> ring(lasers.size());
    for (std::size_t r = 0; r < order.size(); ++r) ring[order[r]] = static_cast<int>(r);
    return ring;
}

/// A ring-major sweep as KITTI stores it: laser after laser, each from azimuth 0 round to 2π
/// (counter-clockwise), 5 % of the returns missing, ranges 4–60 m. `laser_of` gets the laser of
/// every point.
PointCloud ring_major_sweep(const std::vector<Laser>& lasers, int columns, Rng& rng,
                            std::vector<int>& laser_of) {
    PointCloud sweep;
    for (std::size_t i = 0; i < lasers.size(); ++i) {
        std::vector<double> azimuths;
        for (int c = 0; c < columns; ++c) {
            const double a =
                (c + 0.5) * 2.0 * std::numbers::pi / columns + lasers[i].azimuth_offset_rad;
            azimuths.push_back(std::fmod(a + 2.0 * std::numbers::pi, 2.0 * std::numbers::pi));
        }
        std::sort(azimuths.begin(), azimuths.end());
        for (double a : azimuths) {
            if (rng.uniform() < 0.05) continue;
            const double e = lasers[i].elevation_rad;
            const double r = rng.uniform(4.0, 60.0);
            sweep.points.emplace_back(r * std::cos(e) * std::cos(a), r * std::cos(e) * std::sin(a),
                                      r * std::sin(e) + lasers[i].vertical_offset_m);
            laser_of.push_back(static_cast<int>(i));
        }
    }
    return sweep;
}

/// Every point of ring r belongs to the laser of rank r, and every point is in a ring.
void expect_rings_match_lasers(const RingLayout& layout, const std::vector<int>& laser_of,
                               const std::vector<int>& ring_of) {
    ASSERT_EQ(layout.rings.size(), 64u);
    std::size_t wrong = 0;
    std::size_t total = 0;
    for (std::size_t r = 0; r < layout.rings.size(); ++r) {
        for (std::uint32_t i : layout.rings[r])
            wrong += ring_of[laser_of[i]] != static_cast<int>(r);
        total += layout.rings[r].size();
    }
    EXPECT_EQ(wrong, 0u);
    EXPECT_EQ(total, laser_of.size());
    EXPECT_EQ(layout.num_dropped, 0u);
}

TEST(OrganizeRings, ScanOrderRecoversHdl64RingsDespiteVerticalBeamOffsets) {
    Rng rng(7);
    const std::vector<Laser> lasers = hdl64_lasers(rng, true);
    std::vector<int> laser_of;
    PointCloud sweep = ring_major_sweep(lasers, 2000, rng, laser_of);
    // The first laser sees nothing in its first 10° (sky), so the sweep's first return is at
    // 10° while the other rings start at 0°: the start must be given, as for KITTI.
    std::vector<std::size_t> keep;
    for (std::size_t i = 0; i < sweep.size(); ++i) {
        const double a = std::atan2(sweep.points[i].y(), sweep.points[i].x());
        if (laser_of[i] != 0 || a < 0.0 || a > 10.0 * kDeg) keep.push_back(i);
    }
    sweep = select(sweep, keep);
    std::vector<int> kept_laser(keep.size());
    for (std::size_t k = 0; k < keep.size(); ++k) kept_laser[k] = laser_of[keep[k]];

    RingOrganizerConfig config;
    config.scan_start_azimuth_rad = 0.0;
    const RingLayout layout = organize_rings(sweep, config);
    EXPECT_EQ(layout.source, RingSource::kScanOrder);
    expect_rings_match_lasers(layout, kept_laser, ring_of_laser(lasers));
    for (const auto& ring : layout.rings) {  // firing order is the file order
        EXPECT_TRUE(std::is_sorted(ring.begin(), ring.end()));
    }
    config.num_rings = 64;
    EXPECT_EQ(organize_rings(sweep, config).source, RingSource::kScanOrder);
    config.num_rings = 32;  // a count the order contradicts: elevation clustering instead
    EXPECT_EQ(organize_rings(sweep, config).source, RingSource::kElevation);
}

TEST(OrganizeRings, ElevationClusteringRecoversShuffledHdl64Rings) {
    Rng rng(8);
    const std::vector<Laser> lasers = hdl64_lasers(rng, false);
    std::vector<int> laser_of;
    PointCloud sweep = ring_major_sweep(lasers, 2000, rng, laser_of);
    std::vector<std::size_t> order(sweep.size());
    std::iota(order.begin(), order.end(), 0);
    rng.shuffle(std::span<std::size_t>(order));
    PointCloud shuffled = select(sweep, order);
    std::vector<int> shuffled_laser(order.size());
    for (std::size_t k = 0; k < order.size(); ++k) shuffled_laser[k] = laser_of[order[k]];

    const RingLayout layout = organize_rings(shuffled);
    EXPECT_EQ(layout.source, RingSource::kElevation);
    expect_rings_match_lasers(layout, shuffled_laser, ring_of_laser(lasers));
    for (const auto& ring : layout.rings) {  // no firing order to keep: sorted by azimuth
        EXPECT_TRUE(std::is_sorted(ring.begin(), ring.end(), [&](std::uint32_t a, std::uint32_t b) {
            return layout.azimuths_rad[a] < layout.azimuths_rad[b];
        }));
    }
}

TEST(OrganizeRings, ElevationClusteringSplitsOrMergesBandsToTheKnownRingCount) {
    Rng rng(9);
    const std::vector<Laser> lasers = hdl64_lasers(rng, false);
    std::vector<int> laser_of;
    const PointCloud sweep = ring_major_sweep(lasers, 500, rng, laser_of);
    RingOrganizerConfig config;
    config.source = RingSource::kElevation;
    // A gap wider than some of the upper block's spacings (1/3° ± 0.1°) merges those rings...
    config.min_ring_gap_rad = 0.3 * kDeg;
    EXPECT_LT(organize_rings(sweep, config).rings.size(), 64u);
    // ... and knowing the count splits them again at their inner gaps.
    config.num_rings = 64;
    expect_rings_match_lasers(organize_rings(sweep, config), laser_of, ring_of_laser(lasers));

    // One ring fewer than the bands: the closest two bands become one ring.
    config.min_ring_gap_rad = 0.1 * kDeg;
    config.num_rings = 63;
    const RingLayout merged = organize_rings(sweep, config);
    ASSERT_EQ(merged.rings.size(), 63u);
    std::vector<double> elevations(lasers.size());
    for (std::size_t i = 0; i < lasers.size(); ++i) elevations[i] = lasers[i].elevation_rad;
    std::sort(elevations.begin(), elevations.end());
    std::size_t closest = 0;
    for (std::size_t r = 1; r + 1 < elevations.size(); ++r) {
        if (elevations[r + 1] - elevations[r] < elevations[closest + 1] - elevations[closest]) {
            closest = r;
        }
    }
    const std::vector<int> ring_of = ring_of_laser(lasers);
    for (std::uint32_t i : merged.rings[closest]) {
        const int truth = ring_of[laser_of[i]];
        EXPECT_TRUE(truth == static_cast<int>(closest) || truth == static_cast<int>(closest) + 1);
    }
}

TEST(OrganizeRings, ColumnMajorCloudWithoutRingFieldFallsBackToElevation) {
    // Ouster/simulator order (column after column, clockwise), but the ring field was lost.
    const int rings = 16;
    const int columns = 512;
    PointCloud sweep;
    for (int c = 0; c < columns; ++c) {
        const double a = std::numbers::pi - 2.0 * std::numbers::pi * c / columns;
        for (int r = 0; r < rings; ++r) {
            const double e = (-15.0 + 2.0 * r) * kDeg;
            sweep.points.emplace_back(10.0 * std::cos(e) * std::cos(a),
                                      10.0 * std::cos(e) * std::sin(a), 10.0 * std::sin(e));
        }
    }
    const RingLayout layout = organize_rings(sweep);
    EXPECT_EQ(layout.source, RingSource::kElevation);
    ASSERT_EQ(layout.rings.size(), static_cast<std::size_t>(rings));
    for (int r = 0; r < rings; ++r) {
        ASSERT_EQ(layout.rings[r].size(), static_cast<std::size_t>(columns));
        for (int c = 0; c < columns; ++c) {  // the clockwise file order is kept: it sweeps
            EXPECT_EQ(layout.rings[r][c], static_cast<std::uint32_t>(c * rings + r));
        }
    }
}

TEST(OrganizeRings, RingFieldIsUsedAndOutOfRangeRingsAreDropped) {
    PointCloud sweep;
    const std::vector<std::uint16_t> rings = {2, 0, 1, 2, 0, 7};
    for (std::size_t i = 0; i < rings.size(); ++i) {
        const double a = 0.1 * static_cast<double>(i);
        sweep.points.emplace_back(std::cos(a), std::sin(a), 0.0);
    }
    sweep.rings = rings;
    const RingLayout all = organize_rings(sweep);
    EXPECT_EQ(all.source, RingSource::kRingField);
    ASSERT_EQ(all.rings.size(), 8u);
    EXPECT_EQ(all.rings[0], (std::vector<std::uint32_t>{1, 4}));
    EXPECT_EQ(all.rings[2], (std::vector<std::uint32_t>{0, 3}));
    EXPECT_EQ(all.rings[7], (std::vector<std::uint32_t>{5}));
    EXPECT_EQ(all.num_dropped, 0u);

    RingOrganizerConfig config;
    config.num_rings = 3;
    const RingLayout three = organize_rings(sweep, config);
    ASSERT_EQ(three.rings.size(), 3u);
    EXPECT_EQ(three.num_dropped, 1u);
}

TEST(OrganizeRings, UnorderedRingFieldPointsAreSortedByAzimuth) {
    PointCloud sweep;
    const std::vector<double> azimuths_deg = {50, -170, 120, 10, -60, 170, -100, 80};
    for (double a : azimuths_deg) {
        sweep.points.emplace_back(std::cos(a * kDeg), std::sin(a * kDeg), 0.0);
    }
    sweep.rings.assign(sweep.size(), 0);
    const RingLayout layout = organize_rings(sweep);
    ASSERT_EQ(layout.rings.size(), 1u);
    EXPECT_EQ(layout.rings[0], (std::vector<std::uint32_t>{1, 6, 4, 3, 0, 7, 2, 5}));
}

TEST(OrganizeRings, NonFiniteAxisAndOutlierPointsAreDropped) {
    PointCloud sweep;
    for (int c = 0; c < 360; ++c) {
        for (double e_deg : {-10.0, 0.0, 10.0}) {
            const double a = c * kDeg;
            sweep.points.emplace_back(5 * std::cos(e_deg * kDeg) * std::cos(a),
                                      5 * std::cos(e_deg * kDeg) * std::sin(a),
                                      5 * std::sin(e_deg * kDeg));
        }
    }
    sweep.points.emplace_back(kNaN, 1.0, 0.0);
    sweep.points.emplace_back(0.0, 0.0, 3.0);  // on the axis: no azimuth
    for (int i = 0; i < 3; ++i) {
        sweep.points.emplace_back(std::cos(i * 1.0), std::sin(i * 1.0), 0.8);  // stray at ~39°
    }
    const RingLayout layout = organize_rings(sweep);
    EXPECT_EQ(layout.source, RingSource::kElevation);
    ASSERT_EQ(layout.rings.size(), 3u);
    for (const auto& ring : layout.rings) EXPECT_EQ(ring.size(), 360u);
    EXPECT_EQ(layout.num_dropped, 5u);
    EXPECT_TRUE(std::isnan(layout.azimuths_rad[std::size_t{3} * 360]));
}

TEST(OrganizeRings, EmptyAndNonFiniteSweepsGiveNoRings) {
    EXPECT_TRUE(organize_rings(PointCloud{}).rings.empty());
    PointCloud nan_only;
    nan_only.points.assign(10, Eigen::Vector3d::Constant(kNaN));
    const RingLayout layout = organize_rings(nan_only);
    EXPECT_TRUE(layout.rings.empty());
    EXPECT_EQ(layout.num_dropped, 10u);
}

TEST(OrganizeRings, ContractViolationsThrow) {
    PointCloud sweep;
    sweep.points.emplace_back(1.0, 0.0, 0.0);
    RingOrganizerConfig config;
    config.source = RingSource::kRingField;
    EXPECT_THROW(organize_rings(sweep, config), InputError);
    sweep.rings = {0, 1};  // longer than points
    EXPECT_THROW(organize_rings(sweep), InputError);

    auto message = [](const RingOrganizerConfig& c) {
        try {
            c.validate();
        } catch (const ConfigError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    RingOrganizerConfig bad;
    bad.num_rings = -1;
    EXPECT_NE(message(bad).find("rings.num_rings = -1"), std::string::npos);
    bad = {};
    bad.min_ring_gap_rad = 0.0;
    EXPECT_NE(message(bad).find("rings.min_ring_gap_rad"), std::string::npos);
    bad = {};
    bad.min_ring_points = 0;
    EXPECT_NE(message(bad).find("rings.min_ring_points"), std::string::npos);
}

TEST(OrganizeRings, SourceNamesRoundTrip) {
    for (RingSource s : {RingSource::kAuto, RingSource::kRingField, RingSource::kScanOrder,
                         RingSource::kElevation}) {
        EXPECT_EQ(ring_source_from_string(to_string(s)), s);
    }
    EXPECT_THROW(ring_source_from_string("columns", "features.rings.source"), ConfigError);
}

// Real 64-beam sweeps (KITTI-like, no ring field, stored ring after ring, every ring cut at
// azimuth 0). Besides the vertical beam offsets, the points are motion-compensated (the car
// moves ~0.8 m per sweep), which shifts near returns of one laser by degrees of elevation:
// only far returns show the rings as narrow elevation bands.
TEST(OrganizeRings, RealSweepsSplitIntoTheirSixtyFourRings) {
    const std::filesystem::path dir =
        std::filesystem::path(SCANTLING_SHARED_DATA_DIR) / "lidar-scans";
    if (!std::filesystem::exists(dir / "000000.pcd")) {
        GTEST_SKIP() << "real data not found at " << dir
                     << " (set SCANTLING_SHARED_DATA_DIR to the shared data folder)";
    }
    // Returns beyond 30 m lie within 0.31° of their ring's median elevation (measured over the
    // 16 sweeps), while neighbouring rings are 0.27–0.52° apart: a return of the wrong laser
    // (e.g. the sweep start taken from the first return, which puts ~50 returns per ring into
    // the ring above in 7 of the sweeps) stands out.
    constexpr double kFarM = 30.0;
    constexpr double kMaxFromMedianRad = 0.35 * kDeg;
    RingOrganizerConfig config;
    config.scan_start_azimuth_rad = 0.0;
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
        SCOPED_TRACE(entry.path().filename().string());
        const PointCloud sweep = io::read_cloud(entry.path().string());
        const RingLayout layout = organize_rings(sweep, config);
        EXPECT_EQ(layout.source, RingSource::kScanOrder);
        ASSERT_EQ(layout.rings.size(), 64u);
        EXPECT_EQ(layout.num_dropped, 0u);
        double previous_median = -std::numbers::pi;
        std::size_t banded = 0;
        for (const auto& ring : layout.rings) {
            std::vector<double> far;
            std::size_t forward = 0;
            for (std::size_t k = 0; k < ring.size(); ++k) {
                const Eigen::Vector3d& p = sweep.points[ring[k]];
                const double rho = p.head<2>().norm();
                if (rho > kFarM) far.push_back(std::atan2(p.z(), rho));
                if (k > 0) {
                    forward += std::remainder(
                                   layout.azimuths_rad[ring[k]] - layout.azimuths_rad[ring[k - 1]],
                                   2.0 * std::numbers::pi) >= 0.0;
                }
            }
            // Firing order: counter-clockwise, apart from a few returns per ring whose
            // azimuth depends slightly on their range (per-laser horizontal offsets).
            EXPECT_GT(static_cast<double>(forward), 0.98 * static_cast<double>(ring.size() - 1));
            if (far.size() < 50) continue;
            std::vector<double> sorted = far;
            std::sort(sorted.begin(), sorted.end());
            const double median = sorted[sorted.size() / 2];
            EXPECT_GT(median, previous_median);
            EXPECT_LT(sorted.back() - median, kMaxFromMedianRad);
            EXPECT_LT(median - sorted.front(), kMaxFromMedianRad);
            previous_median = median;
            ++banded;
        }
        EXPECT_GE(banded, 15u);  // the upper block sees far buildings
    }
}

}  // namespace
}  // namespace scantling::odometry
