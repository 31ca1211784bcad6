#include <gtest/gtest.h>

#include <scantling/core/error.hpp>
#include <scantling/core/random.hpp>
#include <scantling/core/se3.hpp>
#include <scantling/odometry/edge_registration.hpp>

namespace scantling::odometry {
namespace {

/// Points every 5 cm along `n` lines with the given directions through random anchors.
std::vector<Eigen::Vector3d> lines_cloud(const std::vector<Eigen::Vector3d>& directions,
                                         int per_direction, std::uint64_t seed,
                                         double noise_m = 0.0) {
    Rng rng(seed);
    std::vector<Eigen::Vector3d> pts;
    for (const auto& dir : directions) {
        for (int l = 0; l < per_direction; ++l) {
            const Eigen::Vector3d anchor(rng.uniform(-15, 15), rng.uniform(-15, 15),
                                         rng.uniform(-3, 3));
            for (int s = -40; s <= 40; ++s) {
                Eigen::Vector3d p = anchor + 0.05 * s * dir.normalized();
                p += noise_m * Eigen::Vector3d(rng.normal(), rng.normal(), rng.normal());
                pts.push_back(p);
            }
        }
    }
    return pts;
}

EdgeFeatures edges_from(const std::vector<Eigen::Vector3d>& world,
                        const Eigen::Isometry3d& T_world_sensor, std::size_t stride) {
    EdgeFeatures e;
    for (std::size_t i = 0; i < world.size(); i += stride) {
        const Eigen::Vector3d p = T_world_sensor.inverse() * world[i];
        e.points.push_back(p);
        e.ranges_m.push_back(p.norm());
    }
    return e;
}

LocalMap map_of(const std::vector<Eigen::Vector3d>& world) {
    mapping::CellMapConfig mc;
    mc.max_points_per_cell = 100000;
    mapping::CellMap map(mc);
    map.insert(world);
    LocalMapConfig lc;
    lc.radius_m = 100.0;
    lc.num_recent_sweeps = 0;
    LocalMap local(lc);
    local.update(map, Eigen::Vector3d::Zero(), {});
    return local;
}

TEST(EdgeRegistration, RecoversAnOffsetFromLinesInThreeDirections) {
    const auto world = lines_cloud({{0, 0, 1}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}, 12, 7);
    const LocalMap local = map_of(world);
    const Eigen::Isometry3d T_true =
        make_isometry(rotation_from_euler_zyx(0.01, -0.02, 0.05), Eigen::Vector3d(1.0, -0.5, 0.2));
    // Offset the start by 0.25 m and 2 degrees of yaw.
    const Eigen::Isometry3d T_init =
        se3_exp((Vector6d() << 0.2, -0.15, 0.05, 0.0, 0.0, 0.035).finished()) * T_true;
    const EdgeFeatures edges = edges_from(world, T_true, 3);
    const EdgeRegistrationResult r = register_edges(edges, local, T_init, 0.5, 40.0);
    ASSERT_TRUE(r.registered);
    EXPECT_TRUE(r.converged);
    const PoseError err = pose_error(r.T_world_sensor, T_true);
    EXPECT_LT(err.translation_m, 1e-3);
    EXPECT_LT(err.rotation_rad, 1e-4);
    EXPECT_EQ(r.num_degenerate, 0);
    EXPECT_GT(r.num_correspondences, edges.points.size() / 2);
    EXPECT_LT(r.rmse_m, 1e-3);
}

TEST(EdgeRegistration, ParallelLinesLeaveTheirDirectionAtThePrediction) {
    // Only vertical lines: nothing constrains z, so z must stay where the prediction put it.
    const auto world = lines_cloud({{0, 0, 1}}, 40, 8);
    EdgeRegistrationConfig remap;  // as LiODOM runs it with a motion prior
    remap.remap_degenerate = true;
    const LocalMap local = map_of(world);
    const Eigen::Isometry3d T_true = Eigen::Isometry3d::Identity();
    Eigen::Isometry3d T_init = T_true;
    T_init.translation() = Eigen::Vector3d(0.1, 0.1, 0.3);
    const EdgeRegistrationResult r =
        register_edges(edges_from(world, T_true, 3), local, T_init, 0.5, 40.0, remap);
    ASSERT_TRUE(r.registered);
    EXPECT_GE(r.num_degenerate, 1);
    EXPECT_NEAR(r.T_world_sensor.translation().x(), 0.0, 2e-3);
    EXPECT_NEAR(r.T_world_sensor.translation().y(), 0.0, 2e-3);
    // Kept, not drifted (the small change comes from the roll/pitch steps about the origin).
    EXPECT_NEAR(r.T_world_sensor.translation().z(), 0.3, 1e-4);
}

TEST(EdgeRegistration, ConvergesOnTheObservedDirectionsWhenAskedTo) {
    // Near-vertical lines: height is observed ~1e-4 as strongly as the rest (degenerate). One
    // Gauss-Newton step from 2 cm off horizontally and 0.3 m off in height: the step along the
    // observed directions is below the 5 cm threshold, the one along height is not.
    const auto world = lines_cloud({{0.01, 0, 1}, {0, -0.01, 1}, {-0.01, 0.01, 1}}, 15, 9);
    const LocalMap local = map_of(world);
    const Eigen::Isometry3d T_true =
        make_isometry(rotation_from_euler_zyx(0.02, 0.0, 0.0), Eigen::Vector3d(0.5, -0.3, 0.0));
    Eigen::Isometry3d T_init = T_true;
    T_init.translation() += Eigen::Vector3d(0.02, -0.01, 0.3);
    const EdgeFeatures edges = edges_from(world, T_true, 2);
    EdgeRegistrationConfig plain;
    plain.max_iterations = 1;
    plain.inner_iterations = 1;
    plain.convergence_translation_m = 0.05;
    plain.convergence_rotation_rad = 0.05;
    EdgeRegistrationConfig observed = plain;
    observed.converge_on_observed = true;
    const auto a = register_edges(edges, local, T_init, 0.5, 40.0, plain);
    const auto b = register_edges(edges, local, T_init, 0.5, 40.0, observed);
    ASSERT_TRUE(a.registered && b.registered);
    EXPECT_EQ(a.num_degenerate, 1);
    EXPECT_GT(std::abs(a.degenerate_directions(2, 0)), 0.99);  // along z
    EXPECT_FALSE(a.converged);
    EXPECT_TRUE(b.converged);
    // The flag changes the test, not the step.
    EXPECT_TRUE(a.T_world_sensor.isApprox(b.T_world_sensor, 0.0));
    EXPECT_LT((b.T_world_sensor.translation() - T_true.translation()).head<2>().norm(), 1e-3);
}

/// A floor at z = −1.7 m sampled every 0.2 m over 30 m × 30 m, tilted by 2° about x.
std::vector<Eigen::Vector3d> tilted_floor() {
    std::vector<Eigen::Vector3d> pts;
    const Eigen::Matrix3d tilt = rotation_from_euler_zyx(0.0, 0.0, 0.035);
    for (double x = -15.0; x <= 15.0; x += 0.2) {
        for (double y = -15.0; y <= 15.0; y += 0.2)
            pts.push_back(tilt * Eigen::Vector3d(x, y, -1.7));
    }
    return pts;
}

TEST(EdgeRegistration, PlanarPointsObserveWhatVerticalLinesCannot) {
    // Vertical lines leave z (and, on a small scene, roll and pitch) to the prediction; a floor
    // of planar points observes them.
    const auto lines = lines_cloud({{0, 0, 1}}, 40, 8);
    const auto floor = tilted_floor();
    const LocalMap line_map = map_of(lines);
    const LocalMap floor_map = map_of(floor);
    const Eigen::Isometry3d T_true =
        make_isometry(rotation_from_euler_zyx(0.3, 0.01, -0.01), Eigen::Vector3d(0.5, 0.2, 0.1));
    const Eigen::Isometry3d T_init =
        se3_exp((Vector6d() << 0.05, -0.05, 0.08, 0.005, -0.005, 0.01).finished()) * T_true;
    EdgeFeatures features = edges_from(lines, T_true, 3);
    const EdgeFeatures floor_points = edges_from(floor, T_true, 7);
    features.plane_points = floor_points.points;
    features.plane_ranges_m = floor_points.ranges_m;
    EdgeRegistrationConfig config;
    config.remap_degenerate = true;
    const auto edges_only = register_edges(features, line_map, T_init, 0.5, 40.0, config);
    ASSERT_TRUE(edges_only.registered);
    EXPECT_GT(edges_only.num_degenerate, 0);
    EXPECT_GT(std::abs((edges_only.T_world_sensor.inverse() * T_true).translation().z()), 0.05);

    for (const double refit_m : {0.0, 0.01}) {
        config.refit_distance_m = refit_m;
        const auto both = register_edges(features, line_map, T_init, 0.5, 40.0, config, &floor_map);
        ASSERT_TRUE(both.registered);
        EXPECT_TRUE(both.converged);
        EXPECT_EQ(both.num_degenerate, 0) << refit_m;
        EXPECT_GT(both.num_correspondences, features.points.size() + floor_points.size() / 2);
        const PoseError err = pose_error(both.T_world_sensor, T_true);
        EXPECT_LT(err.translation_m, 1e-3) << refit_m;
        EXPECT_LT(err.rotation_rad, 1e-4) << refit_m;
    }
}

TEST(EdgeRegistration, TooFewCorrespondencesReturnThePriorUnregistered) {
    const auto world = lines_cloud({{0, 0, 1}, {1, 0, 0}}, 5, 9);
    const LocalMap local = map_of(world);
    EdgeFeatures far;  // points nowhere near the map
    for (int i = 0; i < 100; ++i) {
        far.points.emplace_back(500.0 + i, 500.0, 0.0);
        far.ranges_m.push_back(far.points.back().norm());
    }
    Eigen::Isometry3d T_init = Eigen::Isometry3d::Identity();
    T_init.translation().x() = 3.0;
    const EdgeRegistrationResult r = register_edges(far, local, T_init, 0.5, 40.0);
    EXPECT_FALSE(r.registered);
    EXPECT_TRUE(r.T_world_sensor.isApprox(T_init));
    EXPECT_FALSE(register_edges(EdgeFeatures{}, local, T_init, 0.5, 40.0).registered);
}

TEST(EdgeRegistration, HuberKeepsOutliersFromPullingThePose) {
    const auto world = lines_cloud({{0, 0, 1}, {1, 0, 0}, {0, 1, 0}}, 12, 10);
    const LocalMap local = map_of(world);
    const Eigen::Isometry3d T_true = Eigen::Isometry3d::Identity();
    EdgeFeatures edges = edges_from(world, T_true, 3);
    // 15 % of the edges displaced by 0.5 m (moving objects, wrong lines).
    Rng rng(11);
    for (std::size_t i = 0; i < edges.points.size(); i += 7) {
        edges.points[i] += Eigen::Vector3d(0.5, 0.0, 0.0);
    }
    const EdgeRegistrationResult r = register_edges(edges, local, T_true, 0.5, 40.0);
    ASSERT_TRUE(r.registered);
    EXPECT_LT(pose_error(r.T_world_sensor, T_true).translation_m, 0.03);
}

TEST(EdgeRegistration, BadConfigNamesTheField) {
    EdgeRegistrationConfig c;
    c.line_eigen_ratio = 0.5;
    try {
        c.validate();
        FAIL();
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("registration.line_eigen_ratio"), std::string::npos);
    }
}

}  // namespace
}  // namespace scantling::odometry
