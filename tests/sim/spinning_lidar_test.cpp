#include <scantling/core/error.hpp>
#include <scantling/sim/spinning_lidar.hpp>

#include "sensor_test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

namespace scantling::sim {
namespace {

using testing::box_exit_range;
using testing::box_room;
using testing::noiseless;
using testing::TestScene;

// Hit ranges are refined in double precision (RayCaster), so noise-free points are exact to
// rounding at room scale.
constexpr double kExact_m = 1e-9;
// Intensities are stored as float.
constexpr double kFloatTol = 1e-6;
constexpr double kPi = std::numbers::pi;

// Low enough that the ±22.5° beams reach floor and ceiling as well as the walls.
const Eigen::Vector3d kLo(-4.0, -3.0, -1.2);
const Eigen::Vector3d kHi(5.0, 3.5, 1.5);

SpinningLidarConfig noiseless_os1() {
    SpinningLidarConfig config = ouster_os1_64();
    config.returns = noiseless(config.returns);
    return config;
}

TEST(SpinningLidar, PresetsHaveSixtyFourRingsAscendingOverTheDatasheetFov) {
    const SpinningLidarConfig os1 = ouster_os1_64(2048, 10.0);
    ASSERT_EQ(os1.rings(), 64);
    EXPECT_NEAR(os1.ring_elevations_rad.front(), -22.5 * kPi / 180.0, 1e-12);
    EXPECT_NEAR(os1.ring_elevations_rad.back(), 22.5 * kPi / 180.0, 1e-12);
    EXPECT_EQ(os1.columns, 2048);
    const SpinningLidarConfig hdl = velodyne_hdl64e();
    ASSERT_EQ(hdl.rings(), 64);
    EXPECT_NEAR(hdl.ring_elevations_rad.front(), -24.8 * kPi / 180.0, 1e-12);
    EXPECT_NEAR(hdl.ring_elevations_rad.back(), 2.0 * kPi / 180.0, 1e-12);
    EXPECT_NEAR(hdl.ring_elevations_rad[63] - hdl.ring_elevations_rad[62], kPi / 540.0, 1e-12);
    EXPECT_NO_THROW(hdl.validate());
}

TEST(SpinningLidar, Os0PresetSpansNinetyDegreesVerticallyWithAShortRangeWindow) {
    const SpinningLidarConfig os0 = ouster_os0_64(2048, 10.0);
    ASSERT_EQ(os0.rings(), 64);
    EXPECT_NEAR(os0.ring_elevations_rad.front(), -kPi / 4.0, 1e-12);
    EXPECT_NEAR(os0.ring_elevations_rad.back(), kPi / 4.0, 1e-12);
    for (int r = 1; r < 64; ++r) {
        EXPECT_NEAR(os0.ring_elevations_rad[r] - os0.ring_elevations_rad[r - 1], kPi / 2.0 / 63.0,
                    1e-12);
    }
    EXPECT_EQ(os0.columns, 2048);
    EXPECT_EQ(os0.rate_hz, 10.0);
    EXPECT_EQ(os0.min_range_m, 0.3);
    EXPECT_EQ(os0.max_range_m, 50.0);
    EXPECT_EQ(os0.returns.sigma_m, ouster_os1_returns().sigma_m);
    EXPECT_NO_THROW(os0.validate());
    EXPECT_EQ(ouster_os0_64().columns, 1024);
    EXPECT_THROW(ouster_os0_64(2048, 20.0), ConfigError);
    EXPECT_THROW(ouster_os0_64(1000, 10.0), ConfigError);
}

TEST(SpinningLidar, Os0SeesFloorAndCeilingOfANarrowShaftAndNothingWithinItsMinimumRange) {
    // A 2 m wide, 10 m tall shaft: every beam returns; the top ring climbs at 45°.
    const Eigen::Vector3d lo(-1.0, -1.0, -5.0), hi(1.0, 1.0, 5.0);
    SpinningLidarConfig config = ouster_os0_64();
    config.returns = noiseless(config.returns);
    const SpinningLidar lidar(config);
    Rng rng(11);
    const TestScene shaft(box_room(lo, hi));
    const PointCloud cloud = lidar.scan(shaft.view(), Eigen::Isometry3d::Identity(), rng);
    ASSERT_EQ(cloud.size(), 64u * 1024u);
    double highest_rad = -kPi;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const Eigen::Vector3d& p = cloud.points[i];
        ASSERT_NEAR(p.norm(), box_exit_range(Eigen::Vector3d::Zero(), p.normalized(), lo, hi),
                    kExact_m);
        highest_rad = std::max(highest_rad, std::asin(p.z() / p.norm()));
    }
    EXPECT_NEAR(highest_rad, kPi / 4.0, 1e-12);
    // Every wall of a 0.3 m cube is nearer than 0.3 m (corners at 0.26 m): no returns.
    const Eigen::Vector3d small(0.15, 0.15, 0.15);
    const TestScene cube(box_room(-small, small));
    const PointCloud none = lidar.scan(cube.view(), Eigen::Isometry3d::Identity(), rng);
    EXPECT_EQ(none.size(), 0u);
}

TEST(SpinningLidar, NoiselessSweepInBoxRoomMeasuresExactWallDistances) {
    const TestScene scene(box_room(kLo, kHi));
    const SpinningLidar lidar(noiseless_os1());
    Rng rng(1);
    const PointCloud cloud = lidar.scan(scene.view(), Eigen::Isometry3d::Identity(), rng, 7.0);
    ASSERT_EQ(cloud.size(), 64u * 1024u);  // a closed room: every beam returns
    EXPECT_EQ(cloud.stamp_s, 7.0);
    for (const Eigen::Vector3d& p : cloud.points) {
        const double expected_m = box_exit_range(Eigen::Vector3d::Zero(), p.normalized(), kLo, kHi);
        ASSERT_NEAR(p.norm(), expected_m, kExact_m);
    }
}

TEST(SpinningLidar, NoisySweepMeasuresEachWallWithinFourSigma) {
    const TestScene scene(box_room(kLo, kHi));
    const SpinningLidar lidar(ouster_os1_64());
    const ReturnModel& model = lidar.config().returns;
    Rng rng(2);
    const PointCloud cloud = lidar.scan(scene.view(), Eigen::Isometry3d::Identity(), rng);
    ASSERT_GT(cloud.size(), 60000u);
    // Per wall: mean and count of the coordinate across the wall; per point: normalised residual.
    double sum[6] = {}, count[6] = {}, z_sum = 0.0, z_sq = 0.0;
    for (const Eigen::Vector3d& p : cloud.points) {
        const Eigen::Vector3d d = p.normalized();
        const double true_m = box_exit_range(Eigen::Vector3d::Zero(), d, kLo, kHi);
        const double z = (p.norm() - true_m) / model.sigma_at(true_m);
        z_sum += z;
        z_sq += z * z;
        const Eigen::Vector3d hit = true_m * d;
        for (int w = 0; w < 6; ++w) {
            const double wall = w % 2 ? kHi[w / 2] : kLo[w / 2];
            if (std::abs(hit[w / 2] - wall) < 1e-9) {
                sum[w] += p[w / 2];
                count[w] += 1.0;
                break;
            }
        }
    }
    const double n = static_cast<double>(cloud.size());
    const double sigma_max_m = model.sigma_at((kHi - kLo).norm());
    for (int w = 0; w < 6; ++w) {
        ASSERT_GT(count[w], 100.0) << "wall " << w;
        const double wall = w % 2 ? kHi[w / 2] : kLo[w / 2];
        EXPECT_NEAR(sum[w] / count[w], wall, 4.0 * sigma_max_m / std::sqrt(count[w]))
            << "wall " << w;
    }
    EXPECT_NEAR(z_sum / n, 0.0, 4.0 / std::sqrt(n));
    // Standard deviation of the normalised residual within 10 % of 1 (the model's σ).
    EXPECT_NEAR(std::sqrt(z_sq / n), 1.0, 0.1);
}

TEST(SpinningLidar, RingsFollowElevationAndTimesFollowColumns) {
    const TestScene scene(box_room(kLo, kHi));
    const SpinningLidar lidar(noiseless_os1());
    Rng rng(3);
    const PointCloud cloud = lidar.scan(scene.view(), Eigen::Isometry3d::Identity(), rng);
    ASSERT_TRUE(cloud.has_rings() && cloud.has_times() && cloud.has_intensities());
    const auto& elevations = lidar.config().ring_elevations_rad;
    std::set<int> rings;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const int ring = cloud.rings[i];
        rings.insert(ring);
        ASSERT_NEAR(std::asin(cloud.points[i].z() / cloud.points[i].norm()), elevations[ring],
                    1e-12);
        ASSERT_EQ(ring, static_cast<int>(i % 64));
        ASSERT_FLOAT_EQ(cloud.times_s[i], static_cast<float>((i / 64) / (1024.0 * 10.0)));
        ASSERT_GE(cloud.times_s[i], 0.0f);
        ASSERT_LT(cloud.times_s[i], 0.1f);
    }
    EXPECT_EQ(rings.size(), 64u);
    // Clockwise from the back: column 0 at azimuth pi, column 1 at pi - 2 pi / 1024.
    EXPECT_NEAR(std::abs(std::atan2(cloud.points[0].y(), cloud.points[0].x())), kPi, 1e-12);
    EXPECT_NEAR(std::atan2(cloud.points[64].y(), cloud.points[64].x()), kPi - 2.0 * kPi / 1024.0,
                1e-12);
}

TEST(SpinningLidar, IntensityIsAlbedoTimesCosineAndDarkWallsDropOut) {
    World world = box_room(kLo, kHi);
    world.metadata.surfaces[5].albedo = 0.8;   // ceiling
    world.metadata.surfaces[4].albedo = 0.01;  // floor: every return is weak
    const TestScene scene(std::move(world));
    SpinningLidarConfig config = noiseless_os1();
    config.returns.weak_reflectivity = 0.02;
    config.returns.weak_dropout_probability = 1.0;
    const SpinningLidar lidar(config);
    Rng rng(4);
    const PointCloud cloud = lidar.scan(scene.view(), Eigen::Isometry3d::Identity(), rng);
    int ceiling = 0;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const Eigen::Vector3d& p = cloud.points[i];
        ASSERT_GT(p.z(), kLo.z() + 1e-6) << "a floor return survived";
        if (std::abs(p.z() - kHi.z()) > 1e-9) continue;
        ++ceiling;
        ASSERT_NEAR(cloud.intensities[i], 0.8 * p.z() / p.norm(), kFloatTol);
    }
    EXPECT_GT(ceiling, 1000);
}

TEST(SpinningLidar, MountOffsetMovesTheSensorOrigin) {
    const TestScene scene(box_room(kLo, kHi));
    SpinningLidarConfig config = noiseless_os1();
    config.T_body_sensor.translation() = Eigen::Vector3d(1.0, 0.5, 0.25);
    const SpinningLidar lidar(config);
    Rng rng(5);
    const PointCloud cloud = lidar.scan(scene.view(), Eigen::Isometry3d::Identity(), rng);
    const Eigen::Vector3d origin = config.T_body_sensor.translation();
    for (const Eigen::Vector3d& p : cloud.points) {
        ASSERT_NEAR(p.norm(), box_exit_range(origin, p.normalized(), kLo, kHi), kExact_m);
    }
}

TEST(SpinningLidar, MotionDistortionExpressesEachPointInItsFiringFrame) {
    const TestScene scene(box_room(kLo, kHi));
    const SpinningLidar lidar(noiseless_os1());
    const double speed_mps = 2.0;  // along +x: 0.2 m during the sweep
    const PoseAtTime pose_at = [&](double t) {
        Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
        T.translation().x() = speed_mps * (t - 10.0);
        return T;
    };
    Rng rng_static(6), rng_moving(6);
    const PointCloud still = lidar.scan(scene.view(), pose_at(10.0), rng_static, 10.0);
    const PointCloud moving = lidar.scan_moving(scene.view(), pose_at, 10.0, rng_moving);
    ASSERT_EQ(still.size(), moving.size());
    EXPECT_EQ(moving.stamp_s, 10.0);
    int on_front_wall = 0;
    for (std::size_t i = 0; i < still.size(); ++i) {
        ASSERT_EQ(still.times_s[i], moving.times_s[i]);
        if (std::abs(still.points[i].x() - kHi.x()) > 1e-9) continue;
        ++on_front_wall;
        const double t = lidar.column_times_s()[i / 64];
        ASSERT_NEAR(moving.points[i].x(), kHi.x() - speed_mps * t, kExact_m);
    }
    EXPECT_GT(on_front_wall, 5000);
}

TEST(SpinningLidar, StaticPoseFunctionEqualsStaticScan) {
    const TestScene scene(box_room(kLo, kHi));
    const SpinningLidar lidar;
    Rng a(7), b(7);
    const PointCloud still = lidar.scan(scene.view(), Eigen::Isometry3d::Identity(), a, 1.0);
    const PointCloud moving = lidar.scan_moving(
        scene.view(), [](double) { return Eigen::Isometry3d::Identity(); }, 1.0, b);
    EXPECT_EQ(still.points, moving.points);
    EXPECT_EQ(still.times_s, moving.times_s);
}

TEST(SpinningLidar, OneAndTwoThreadsAndSameSeedGiveIdenticalClouds) {
    const TestScene scene(box_room(kLo, kHi));
    const SpinningLidar lidar;
    Rng a(8), b(8), c(9);
    const PointCloud one = lidar.scan(scene.view(), Eigen::Isometry3d::Identity(), a, 0.0, {1});
    const PointCloud two = lidar.scan(scene.view(), Eigen::Isometry3d::Identity(), b, 0.0, {2});
    const PointCloud other = lidar.scan(scene.view(), Eigen::Isometry3d::Identity(), c, 0.0, {2});
    EXPECT_EQ(one.points, two.points);
    EXPECT_EQ(one.rings, two.rings);
    EXPECT_EQ(one.intensities, two.intensities);
    EXPECT_NE(one.points, other.points);
}

TEST(SpinningLidar, BadConfigsThrowNamingTheField) {
    const auto message_of = [](SpinningLidarConfig config) {
        try {
            config.validate();
        } catch (const ConfigError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    SpinningLidarConfig c = ouster_os1_64();
    c.columns = 0;
    EXPECT_NE(message_of(c).find("spinning_lidar.columns = 0"), std::string::npos);
    c = ouster_os1_64();
    std::swap(c.ring_elevations_rad[3], c.ring_elevations_rad[4]);
    EXPECT_NE(message_of(c).find("spinning_lidar.ring_elevations_rad[4]"), std::string::npos);
    c = ouster_os1_64();
    c.max_range_m = 0.2;
    EXPECT_NE(message_of(c).find("spinning_lidar.max_range_m = 0.2"), std::string::npos);
    c = ouster_os1_64();
    c.returns.sigma_m = -1.0;
    EXPECT_NE(message_of(c).find("spinning_lidar.returns.sigma_m = -1"), std::string::npos);
    c = ouster_os1_64();
    c.T_body_sensor.linear() *= 2.0;
    EXPECT_NE(message_of(c).find("spinning_lidar.T_body_sensor"), std::string::npos);
    c = ouster_os1_64();
    c.rate_hz = std::nan("");
    EXPECT_THROW(SpinningLidar{c}, ConfigError);
    EXPECT_THROW(ouster_os1_64(2048, 20.0), ConfigError);
    EXPECT_THROW(ouster_os1_64(300, 10.0), ConfigError);
    EXPECT_THROW(uniform_ring_elevations(1, -0.1, 0.1), ConfigError);
}

TEST(SpinningLidar, EmptyPoseFunctionIsAnInputError) {
    const TestScene scene(box_room(kLo, kHi));
    const SpinningLidar lidar;
    Rng rng(10);
    EXPECT_THROW(lidar.scan_moving(scene.view(), PoseAtTime{}, 0.0, rng), InputError);
    const PoseAtTime nan_pose = [](double) {
        Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
        T.translation().x() = std::nan("");
        return T;
    };
    EXPECT_THROW(lidar.scan_moving(scene.view(), nan_pose, 0.0, rng), InputError);
}

}  // namespace
}  // namespace scantling::sim
