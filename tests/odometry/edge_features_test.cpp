#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include <scantling/core/error.hpp>
#include <scantling/core/random.hpp>
#include <scantling/io/cloud_io.hpp>
#include <scantling/odometry/edge_features.hpp>

namespace scantling::odometry {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

/// Distance along unit `d` from `o` to the first surface, inf when none.
using Caster = std::function<double(const Eigen::Vector3d& o, const Eigen::Vector3d& d)>;

/// A spinning-LiDAR sweep as the simulator writes it: column after column (clockwise from
/// azimuth π), all rings of a column together, with ring field and per-column times; misses
/// are left out.
PointCloud spinning_sweep(const Eigen::Vector3d& origin, const std::vector<double>& elevations,
                          int columns, const Caster& cast, double noise_m = 0.0,
                          std::uint64_t seed = 1) {
    Rng rng(seed);
    PointCloud sweep;
    for (int c = 0; c < columns; ++c) {
        const double a = std::numbers::pi - 2.0 * std::numbers::pi * c / columns;
        for (std::size_t r = 0; r < elevations.size(); ++r) {
            const double e = elevations[r];
            const Eigen::Vector3d d(std::cos(e) * std::cos(a), std::cos(e) * std::sin(a),
                                    std::sin(e));
            const double t = cast(origin, d);
            if (!std::isfinite(t)) continue;
            sweep.points.push_back((t + (noise_m > 0.0 ? rng.normal(0.0, noise_m) : 0.0)) * d);
            sweep.rings.push_back(static_cast<std::uint16_t>(r));
            sweep.times_s.push_back(static_cast<float>(0.1 * c / columns));
        }
    }
    return sweep;
}

std::vector<double> uniform_elevations(int rings, double lowest_deg, double highest_deg) {
    std::vector<double> e(static_cast<std::size_t>(rings));
    for (int r = 0; r < rings; ++r) {
        e[r] = (lowest_deg + (highest_deg - lowest_deg) * r / (rings - 1)) * kDeg;
    }
    return e;
}

/// An empty room [−4, 4] × [−3, 3] × [−1.2, 1.8] m seen from inside.
const Eigen::Vector3d kRoomMin(-4.0, -3.0, -1.2);
const Eigen::Vector3d kRoomMax(4.0, 3.0, 1.8);

double cast_room(const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
    double t = kInf;
    for (int a = 0; a < 3; ++a) {
        if (d(a) > 1e-12) t = std::min(t, (kRoomMax(a) - o(a)) / d(a));
        if (d(a) < -1e-12) t = std::min(t, (kRoomMin(a) - o(a)) / d(a));
    }
    return t;
}

double distance_to_segment(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                           const Eigen::Vector3d& b) {
    const Eigen::Vector3d ab = b - a;
    const double s = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    return (a + s * ab - p).norm();
}

/// Distance of a point (room frame) to the nearest of the room's 12 edges.
double distance_to_room_edges(const Eigen::Vector3d& p) {
    double best = kInf;
    for (int axis = 0; axis < 3; ++axis) {  // edges parallel to `axis`
        const int u = (axis + 1) % 3;
        const int v = (axis + 2) % 3;
        for (double cu : {kRoomMin(u), kRoomMax(u)}) {
            for (double cv : {kRoomMin(v), kRoomMax(v)}) {
                Eigen::Vector3d a;
                Eigen::Vector3d b;
                a(axis) = kRoomMin(axis);
                b(axis) = kRoomMax(axis);
                a(u) = b(u) = cu;
                a(v) = b(v) = cv;
                best = std::min(best, distance_to_segment(p, a, b));
            }
        }
    }
    return best;
}

const Eigen::Vector3d kSensor(0.3, -0.4, 0.0);
// An edge is the return nearest a room edge in its ring: within one azimuth step (~3 cm at
// 5 m for 1024 columns) of it, and on a wall seen obliquely a little more.
constexpr double kOnEdgeM = 0.1;

EdgeExtractionConfig room_config() {
    EdgeExtractionConfig config;
    config.min_range_m = 0.3;
    config.max_range_m = 20.0;
    return config;
}

TEST(ExtractEdges, FindsTheVerticalCornersOfABoxRoomAndNothingOnItsWalls) {
    const std::vector<double> elevations = uniform_elevations(32, -20.0, 20.0);
    const PointCloud sweep = spinning_sweep(kSensor, elevations, 1024, cast_room, 0.001);
    const EdgeFeatures edges = extract_edges(sweep, room_config());
    EXPECT_EQ(edges.num_input, sweep.size());
    EXPECT_EQ(edges.num_in_range, sweep.size());
    EXPECT_EQ(edges.num_rings, 32u);
    ASSERT_FALSE(edges.empty());
    for (const Eigen::Vector3d& p : edges.points) {
        EXPECT_LT(distance_to_room_edges(p + kSensor), kOnEdgeM) << (p + kSensor).transpose();
    }
    // Each vertical corner, in every ring that sees it on the walls (not where it meets the
    // floor or ceiling, where two corners compete).
    for (double cx : {kRoomMin.x(), kRoomMax.x()}) {
        for (double cy : {kRoomMin.y(), kRoomMax.y()}) {
            const Eigen::Vector2d corner(cx, cy);
            const double rho = (corner - kSensor.head<2>()).norm();
            int expected = 0;
            int found = 0;
            for (double e : elevations) {
                const double z = rho * std::tan(e);
                if (z < kRoomMin.z() + 0.3 || z > kRoomMax.z() - 0.3) continue;
                ++expected;
                const Eigen::Vector3d on_corner(cx, cy, z);
                found += std::any_of(edges.points.begin(), edges.points.end(),
                                     [&](const Eigen::Vector3d& p) {
                                         return (p + kSensor - on_corner).norm() < kOnEdgeM;
                                     });
            }
            EXPECT_GE(expected, 8);
            EXPECT_EQ(found, expected) << "corner " << cx << " " << cy;
        }
    }
    // Sensor frame, ranges and times travel with the points.
    ASSERT_EQ(edges.ranges_m.size(), edges.size());
    ASSERT_EQ(edges.times_s.size(), edges.size());
    ASSERT_EQ(edges.curvatures.size(), edges.size());
    for (std::size_t i = 0; i < edges.size(); ++i) {
        EXPECT_DOUBLE_EQ(edges.ranges_m[i], edges.points[i].norm());
        EXPECT_GT(edges.curvatures[i], room_config().min_edge_curvature);
    }
}

TEST(ExtractEdges, PlanarPointsLieOnTheRoomsFacesAwayFromItsEdgesWithinTheSectorCap) {
    const std::vector<double> elevations = uniform_elevations(32, -20.0, 20.0);
    const PointCloud sweep = spinning_sweep(kSensor, elevations, 1024, cast_room, 0.001);
    EdgeExtractionConfig config = room_config();
    EXPECT_TRUE(extract_edges(sweep, config).plane_points.empty());  // off by default
    config.max_planes_per_sector = 4;
    const EdgeFeatures features = extract_edges(sweep, config);
    const EdgeFeatures edges_only = extract_edges(sweep, room_config());
    EXPECT_EQ(features.points, edges_only.points);  // the edges do not change
    ASSERT_EQ(features.plane_ranges_m.size(), features.plane_points.size());
    EXPECT_LE(features.plane_points.size(), 32U * 6U * 4U);
    EXPECT_GT(features.plane_points.size(), 32U * 6U * 3U);  // flat room: nearly every sector
    for (std::size_t i = 0; i < features.plane_points.size(); ++i) {
        // Away from the vertical corners that the rings cross (a ring running along the wall
        // just above the floor is flat along the ring: a planar point, rightly).
        const Eigen::Vector3d p = features.plane_points[i] + kSensor;
        double to_corner_m = kInf;
        for (double cx : {kRoomMin.x(), kRoomMax.x()}) {
            for (double cy : {kRoomMin.y(), kRoomMax.y()}) {
                to_corner_m = std::min(to_corner_m, (p.head<2>() - Eigen::Vector2d(cx, cy)).norm());
            }
        }
        EXPECT_GT(to_corner_m, 0.1) << p.transpose();
        EXPECT_DOUBLE_EQ(features.plane_ranges_m[i], features.plane_points[i].norm());
    }
    config.max_plane_curvature = 0.0;  // nothing is that flat with 1 mm noise
    EXPECT_TRUE(extract_edges(sweep, config).plane_points.empty());
    config.max_planes_per_sector = -1;
    EXPECT_THROW(extract_edges(sweep, config), ConfigError);
}

/// Ring and position of every output point in the sweep (points are copied, so exact).
std::vector<std::size_t> indices_in(const PointCloud& sweep, const EdgeFeatures& edges) {
    std::map<std::tuple<double, double, double>, std::size_t> index;
    for (std::size_t i = 0; i < sweep.size(); ++i) {
        index[{sweep.points[i].x(), sweep.points[i].y(), sweep.points[i].z()}] = i;
    }
    std::vector<std::size_t> out;
    for (const Eigen::Vector3d& p : edges.points) out.push_back(index.at({p.x(), p.y(), p.z()}));
    return out;
}

TEST(ExtractEdges, OutputIsInRingThenFiringOrderWithTheSweepTimes) {
    const PointCloud sweep =
        spinning_sweep(kSensor, uniform_elevations(16, -15.0, 15.0), 512, cast_room);
    const EdgeFeatures edges = extract_edges(sweep, room_config());
    const std::vector<std::size_t> at = indices_in(sweep, edges);
    ASSERT_FALSE(at.empty());
    for (std::size_t k = 1; k < at.size(); ++k) {
        const bool ring_order = sweep.rings[at[k - 1]] < sweep.rings[at[k]];
        const bool firing_order = sweep.rings[at[k - 1]] == sweep.rings[at[k]] && at[k - 1] < at[k];
        EXPECT_TRUE(ring_order || firing_order) << k;
    }
    for (std::size_t k = 0; k < at.size(); ++k) EXPECT_EQ(edges.times_s[k], sweep.times_s[at[k]]);
}

/// One ring (elevation 0) of a corrugated wall: a triangle wave of period 8 returns in front
/// of the sensor, so it has a corner every 4 returns.
PointCloud corrugated_ring() {
    PointCloud sweep;
    for (int k = 0; k < 600; ++k) {
        const double x = -6.0 + 0.02 * k;
        const double phase = std::fmod(k, 8.0);
        const double y = 5.0 + 0.03 * (phase < 4.0 ? phase : 8.0 - phase);
        sweep.points.emplace_back(x, y, 0.0);
    }
    std::reverse(sweep.points.begin(), sweep.points.end());  // counter-clockwise firing
    sweep.rings.assign(sweep.size(), 0);
    return sweep;
}

TEST(ExtractEdges, RespectsTheSectorCapAndSuppressesNeighboursOfEachPick) {
    const PointCloud sweep = corrugated_ring();
    EdgeExtractionConfig config = room_config();
    config.num_sectors = 4;
    config.max_edges_per_sector = 3;
    const std::vector<std::size_t> capped = indices_in(sweep, extract_edges(sweep, config));
    EXPECT_EQ(capped.size(), 12u);
    for (int s = 0; s < 4; ++s) {
        const auto in_sector = std::count_if(capped.begin(), capped.end(), [&](std::size_t i) {
            return static_cast<int>(i) * 4 / 600 == s;
        });
        EXPECT_EQ(in_sector, 3) << "sector " << s;
    }
    config.max_edges_per_sector = 1000;  // only suppression limits the picks now
    const std::vector<std::size_t> all = indices_in(sweep, extract_edges(sweep, config));
    const auto h = static_cast<std::size_t>(config.curvature_half_window);
    for (std::size_t k = 1; k < all.size(); ++k) EXPECT_GT(all[k] - all[k - 1], h);
    // Corners every 4 returns, a pick blocks 5 on each side: one pick per 6–8 returns.
    EXPECT_GE(all.size(), 590u / 8);
}

TEST(ExtractEdges, RangeGateDropsPointsWithoutMakingEdgesWhereItCutsASurface) {
    const PointCloud sweep =
        spinning_sweep(kSensor, uniform_elevations(32, -20.0, 20.0), 1024, cast_room, 0.001);
    EdgeExtractionConfig config = room_config();
    config.min_range_m = 1.0;  // the floor near the sensor goes
    config.max_range_m = 5.0;  // and so do the far walls and three of the corners
    const EdgeFeatures edges = extract_edges(sweep, config);
    const auto in_gate = std::count_if(sweep.points.begin(), sweep.points.end(), [&](auto& p) {
        return p.norm() >= config.min_range_m && p.norm() <= config.max_range_m;
    });
    EXPECT_EQ(edges.num_in_range, static_cast<std::size_t>(in_gate));
    EXPECT_LT(edges.num_in_range + 1000, sweep.size());
    ASSERT_FALSE(edges.empty());
    for (std::size_t i = 0; i < edges.size(); ++i) {
        EXPECT_GE(edges.ranges_m[i], config.min_range_m);
        EXPECT_LE(edges.ranges_m[i], config.max_range_m);
        // Walls leave the gate mid-surface: a cut, not an outline.
        EXPECT_LT(distance_to_room_edges(edges.points[i] + kSensor), kOnEdgeM);
    }
}

/// The room with a vertical pole (radius 0.1 m) standing 1.9 m in front of the sensor.
const Eigen::Vector2d kPole(2.2, 0.2);
constexpr double kPoleRadiusM = 0.1;

double cast_room_with_pole(const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
    const Eigen::Vector2d oc = o.head<2>() - kPole;
    const Eigen::Vector2d dh = d.head<2>();
    const double a = dh.squaredNorm();
    const double b = oc.dot(dh);
    const double disc = b * b - a * (oc.squaredNorm() - kPoleRadiusM * kPoleRadiusM);
    const double t = disc >= 0.0 ? (-b - std::sqrt(disc)) / a : kInf;
    return t > 0.0 ? std::min(t, cast_room(o, d)) : cast_room(o, d);
}

TEST(ExtractEdges, OutlinesOfAPoleAreEdgesButTheShadowOnTheWallIsNot) {
    const std::vector<double> elevations = uniform_elevations(16, -15.0, 15.0);
    const PointCloud sweep = spinning_sweep(kSensor, elevations, 2048, cast_room_with_pole, 0.001);
    const EdgeFeatures edges = extract_edges(sweep, room_config());
    int on_pole = 0;
    for (const Eigen::Vector3d& p : edges.points) {
        const Eigen::Vector3d q = p + kSensor;
        const bool pole = (q.head<2>() - kPole).norm() < kPoleRadiusM + 0.02;
        on_pole += pole;
        EXPECT_TRUE(pole || distance_to_room_edges(q) < kOnEdgeM) << q.transpose();
    }
    // Both outlines in every ring (the pole is ~6° wide: 34 returns per ring).
    EXPECT_GE(on_pole, 2 * static_cast<int>(elevations.size()));
}

/// One ring (elevation 0) over circular arcs about the sensor (no curvature of their own): a
/// far wall at 10 m, a pole at 3 m (85–87°) and, just right of it, a thin post at 6 m (87–88°,
/// 4 returns) whose left side the pole hides.
PointCloud partly_hidden_post() {
    PointCloud sweep;
    for (int k = 0; k < 240; ++k) {
        const double a_deg = 60.0 + 0.25 * k;
        const double r =
            a_deg >= 85.0 && a_deg < 87.0 ? 3.0 : (a_deg >= 87.0 && a_deg < 88.0 ? 6.0 : 10.0);
        sweep.points.emplace_back(r * std::cos(a_deg * kDeg), r * std::sin(a_deg * kDeg), 0.0);
    }
    sweep.rings.assign(sweep.size(), 0);
    return sweep;
}

TEST(ExtractEdges, OutlineNextToAnOccludedEndIsRejectedAsUnreliable) {
    const PointCloud sweep = partly_hidden_post();
    EdgeExtractionConfig config = room_config();
    // Both outlines of the pole; the post's right outline lies within a window of its left
    // end, which the pole occludes (LOAM's occlusion test), so it is rejected.
    const EdgeFeatures reliable = extract_edges(sweep, config);
    ASSERT_EQ(reliable.size(), 2u);
    for (double r : reliable.ranges_m) EXPECT_NEAR(r, 3.0, 1e-9);
    config.reject_unreliable = false;
    const EdgeFeatures all = extract_edges(sweep, config);
    EXPECT_EQ(all.size(), 3u);
    EXPECT_EQ(std::count_if(all.ranges_m.begin(), all.ranges_m.end(),
                            [](double r) { return std::abs(r - 6.0) < 1e-9; }),
              1);
}

/// One ring (elevation 0) of a straight wall y = 1, from 1° to 89° of azimuth: beyond ~80° of
/// incidence the returns spread so fast that the curvature exceeds the threshold on a flat
/// surface (LOAM's "beam parallel to the surface").
PointCloud grazing_wall() {
    PointCloud sweep;
    for (double a_deg = 1.0; a_deg < 89.0; a_deg += 0.2) {
        const double a = a_deg * kDeg;
        sweep.points.emplace_back(std::cos(a) / std::sin(a), 1.0, 0.0);
    }
    sweep.rings.assign(sweep.size(), 0);
    return sweep;
}

TEST(ExtractEdges, FlatSurfaceSeenAtGrazingIncidenceIsRejectedAsUnreliable) {
    const PointCloud sweep = grazing_wall();
    EdgeExtractionConfig config = room_config();
    config.max_range_m = 100.0;
    // The curvature passes the threshold beyond ~80° of incidence; rejecting from 75° keeps
    // the test clear of that border.
    config.max_incidence_rad = 75.0 * kDeg;
    EXPECT_TRUE(extract_edges(sweep, config).empty());
    config.reject_unreliable = false;
    const EdgeFeatures kept = extract_edges(sweep, config);
    ASSERT_FALSE(kept.empty());
    for (const Eigen::Vector3d& p : kept.points) {
        const double incidence_rad = std::acos(1.0 / p.norm());  // wall normal is +y
        EXPECT_GT(incidence_rad, 75.0 * kDeg);
    }
}

TEST(ExtractEdges, ResultsDoNotDependOnTheThreadCountOrOnNanPoints) {
    PointCloud sweep =
        spinning_sweep(kSensor, uniform_elevations(32, -20.0, 20.0), 1024, cast_room_with_pole);
    EdgeExtractionConfig config = room_config();
    config.parallel.num_threads = 1;
    const EdgeFeatures serial = extract_edges(sweep, config);
    config.parallel.num_threads = 3;
    const EdgeFeatures threaded = extract_edges(sweep, config);
    EXPECT_EQ(serial.points, threaded.points);
    EXPECT_EQ(serial.curvatures, threaded.curvatures);

    // NaN returns (a driver's "no return") are dropped before anything else.
    PointCloud with_nan;
    for (std::size_t i = 0; i < sweep.size(); ++i) {
        if (i % 97 == 0) {
            with_nan.points.push_back(Eigen::Vector3d::Constant(kNaN));
            with_nan.rings.push_back(sweep.rings[i]);
            with_nan.times_s.push_back(sweep.times_s[i]);
        }
        with_nan.points.push_back(sweep.points[i]);
        with_nan.rings.push_back(sweep.rings[i]);
        with_nan.times_s.push_back(sweep.times_s[i]);
    }
    const EdgeFeatures nan_edges = extract_edges(with_nan, config);
    EXPECT_EQ(nan_edges.points, threaded.points);
    EXPECT_EQ(nan_edges.num_input, with_nan.size());
    EXPECT_EQ(nan_edges.num_in_range, serial.num_in_range);
}

TEST(ExtractEdges, EmptyAndNanOnlySweepsGiveNoEdges) {
    const EdgeFeatures none = extract_edges(PointCloud{});
    EXPECT_TRUE(none.empty());
    EXPECT_EQ(none.num_input, 0u);
    PointCloud nan_only;
    nan_only.points.assign(100, Eigen::Vector3d::Constant(kNaN));
    const EdgeFeatures nan_edges = extract_edges(nan_only);
    EXPECT_TRUE(nan_edges.empty());
    EXPECT_EQ(nan_edges.num_input, 100u);
    EXPECT_EQ(nan_edges.num_in_range, 0u);
    EXPECT_EQ(nan_edges.num_rings, 0u);
}

std::string config_error(const EdgeExtractionConfig& config) {
    try {
        config.validate();
    } catch (const ConfigError& e) {
        return e.what();
    }
    return "no error";
}

TEST(ExtractEdges, InvalidConfigsNameTheField) {
    const std::vector<std::pair<std::function<void(EdgeExtractionConfig&)>, std::string>> cases = {
        {[](auto& c) { c.min_range_m = 80.0; }, "features.min_range_m = 80"},
        {[](auto& c) { c.min_range_m = -1.0; }, "features.min_range_m = -1"},
        {[](auto& c) { c.max_range_m = kInf; }, "features.max_range_m"},
        {[](auto& c) { c.curvature_half_window = 0; }, "features.curvature_half_window = 0"},
        {[](auto& c) { c.num_sectors = 0; }, "features.num_sectors = 0"},
        {[](auto& c) { c.max_edges_per_sector = 0; }, "features.max_edges_per_sector = 0"},
        {[](auto& c) { c.min_edge_curvature = kNaN; }, "features.min_edge_curvature"},
        {[](auto& c) { c.max_azimuth_gap_factor = 1.0; }, "features.max_azimuth_gap_factor"},
        {[](auto& c) { c.range_jump_ratio = 0.0; }, "features.range_jump_ratio = 0"},
        {[](auto& c) { c.max_incidence_rad = 2.0; }, "features.max_incidence_rad = 2"},
        {[](auto& c) { c.rings.num_rings = -2; }, "features.rings.num_rings = -2"},
        {[](auto& c) { c.parallel.num_threads = -1; }, "features.parallel.num_threads = -1"},
    };
    EXPECT_EQ(config_error(EdgeExtractionConfig{}), "no error");
    for (const auto& [mutate, expected] : cases) {
        EdgeExtractionConfig config;
        mutate(config);
        EXPECT_NE(config_error(config).find(expected), std::string::npos)
            << config_error(config) << " / " << expected;
        EXPECT_THROW(extract_edges(PointCloud{}, config), ConfigError);
    }
}

// The real 64-beam sweeps with the default (KITTI-sized) configuration and KITTI's sweep
// start: every ring found, and a few thousand edges spread over the rings.
TEST(ExtractEdges, RealSweepsGiveThousandsOfEdgesOverAllRings) {
    const std::filesystem::path dir =
        std::filesystem::path(SCANTLING_SHARED_DATA_DIR) / "lidar-scans";
    if (!std::filesystem::exists(dir / "000000.pcd")) {
        GTEST_SKIP() << "real data not found at " << dir
                     << " (set SCANTLING_SHARED_DATA_DIR to the shared data folder)";
    }
    EdgeExtractionConfig config;
    config.rings.scan_start_azimuth_rad = 0.0;
    for (const char* name : {"000000.pcd", "000009.pcd", "000015.pcd"}) {
        SCOPED_TRACE(name);
        const PointCloud sweep = io::read_cloud((dir / name).string());
        const EdgeFeatures edges = extract_edges(sweep, config);
        EXPECT_EQ(edges.num_rings, 64u);
        EXPECT_GT(edges.num_in_range, 115000u);
        // Measured 2.9–3.4k edges of at most 64 rings × 6 sectors × 10 = 3840.
        EXPECT_GT(edges.size(), 2500u);
        EXPECT_LE(edges.size(), 3840u);
        EXPECT_TRUE(edges.times_s.empty());  // the PCD files carry no time
        for (double r : edges.ranges_m) {
            EXPECT_GE(r, config.min_range_m);
            EXPECT_LE(r, config.max_range_m);
        }
    }
}

}  // namespace
}  // namespace scantling::odometry
