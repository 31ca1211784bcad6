// Moving obstacles (sim/moving_obstacles.hpp): analytic ray/sphere and ray/box intersections
// against hand-computed values, the piecewise-linear motion, distances and input contracts.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include <scantling/core/error.hpp>
#include <scantling/sim/moving_obstacles.hpp>

namespace scantling::sim {
namespace {

// Every expected value below is a short exact expression; the analytic intersection only
// rounds (a few ulp of ~10 m).
constexpr double kExact_m = 1e-12;
constexpr double kInf = std::numeric_limits<double>::infinity();
const Eigen::Vector3d kX = Eigen::Vector3d::UnitX();
const Eigen::Vector3d kY = Eigen::Vector3d::UnitY();
const Eigen::Vector3d kOrigin = Eigen::Vector3d::Zero();

MovingObstacle sphere(const std::string& name, const Eigen::Vector3d& centre, double radius_m) {
    MovingObstacle o;
    o.name = name;
    o.radius_m = radius_m;
    o.waypoints = {{0.0, centre}};
    return o;
}

MovingObstacle box(const std::string& name, const Eigen::Vector3d& centre,
                   const Eigen::Vector3d& half_extents_m) {
    MovingObstacle o = sphere(name, centre, 1.0);
    o.shape = ObstacleShape::kBox;
    o.half_extents_m = half_extents_m;
    return o;
}

/// The hit of a ray from `origin` along `direction` (normalised here) at t = 0.
std::optional<ObstacleHit> cast(const MovingObstacles& obstacles, const Eigen::Vector3d& origin,
                                const Eigen::Vector3d& direction, double min_range_m = 0.0,
                                double max_range_m = kInf) {
    return obstacles.intersect(origin, direction.normalized(), min_range_m, max_range_m, 0.0);
}

void expect_hit(const std::optional<ObstacleHit>& hit, double range_m, const Eigen::Vector3d& point,
                const Eigen::Vector3d& normal) {
    ASSERT_TRUE(hit.has_value());
    EXPECT_NEAR(hit->range_m, range_m, kExact_m);
    EXPECT_LT((hit->point - point).norm(), kExact_m) << hit->point.transpose();
    EXPECT_LT((hit->normal - normal).norm(), kExact_m) << hit->normal.transpose();
}

/// Runs `f` and expects a ConfigError whose message names `key`.
template <class F>
void expect_config_error(F&& f, const std::string& key) {
    try {
        f();
        ADD_FAILURE() << "no error, expected one naming " << key;
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
}

TEST(MovingObstacles, RayHitsSphereAtTheHandComputedEntry) {
    const MovingObstacles s({sphere("a", {5.0, 0.0, 0.0}, 1.0)});
    expect_hit(cast(s, kOrigin, kX), 4.0, {4.0, 0.0, 0.0}, -kX);
    // Off-axis by 0.6: half chord sqrt(1 − 0.36) = 0.8, so the entry is at x = 4 − 0.8.
    const MovingObstacles off({sphere("b", {4.0, 0.6, 0.0}, 1.0)});
    expect_hit(cast(off, kOrigin, kX), 3.2, {3.2, 0.0, 0.0}, {-0.8, -0.6, 0.0});
    EXPECT_EQ(cast(s, kOrigin, kX)->obstacle, 0u);
}

TEST(MovingObstacles, SphereFromInsideBehindTangentAndRangeLimits) {
    const MovingObstacles s({sphere("a", {5.0, 0.0, 0.0}, 1.0)});
    // From the centre: the exit, with the normal facing back at the ray.
    expect_hit(cast(s, {5.0, 0.0, 0.0}, kX), 1.0, {6.0, 0.0, 0.0}, -kX);
    EXPECT_FALSE(cast(s, kOrigin, -kX));  // behind the origin
    // Tangent at (5, 1, 0) counts (closed surface); a nanometre further out misses.
    const auto tangent = cast(s, {0.0, 1.0, 0.0}, kX);
    ASSERT_TRUE(tangent);
    EXPECT_NEAR(tangent->range_m, 5.0, kExact_m);
    EXPECT_FALSE(cast(s, {0.0, 1.0 + 1e-9, 0.0}, kX));
    // Max range: the entry at exactly 4 counts, short of it misses.
    EXPECT_TRUE(cast(s, kOrigin, kX, 0.0, 4.0));
    EXPECT_FALSE(cast(s, kOrigin, kX, 0.0, 3.999));
    // Min range past the entry: the exit at 6.
    expect_hit(cast(s, kOrigin, kX, 4.5), 6.0, {6.0, 0.0, 0.0}, -kX);
    EXPECT_FALSE(cast(s, kOrigin, kX, 6.5));
}

TEST(MovingObstacles, RayHitsBoxOnTheHandComputedFace) {
    const MovingObstacles b({box("b", {5.0, 0.0, 0.0}, {1.0, 2.0, 3.0})});
    expect_hit(cast(b, kOrigin, kX), 4.0, {4.0, 0.0, 0.0}, -kX);
    // Along (4, 1, 0): the face x = 4 at y = 1, range |(4, 1)| = sqrt(17).
    expect_hit(cast(b, kOrigin, {4.0, 1.0, 0.0}), std::sqrt(17.0), {4.0, 1.0, 0.0}, -kX);
    // Along (1, 1, 0): y leaves the slab |y| <= 2 before x reaches 4.
    EXPECT_FALSE(cast(b, kOrigin, {1.0, 1.0, 0.0}));
    expect_hit(cast(b, {5.0, 0.0, 0.0}, kY), 2.0, {5.0, 2.0, 0.0}, -kY);  // from inside
    expect_hit(cast(b, {10.0, 0.0, 0.0}, -kX), 4.0, {6.0, 0.0, 0.0}, kX);
}

TEST(MovingObstacles, BoxParallelBehindGrazingAndRangeLimits) {
    const MovingObstacles b({box("b", {5.0, 0.0, 0.0}, {1.0, 2.0, 3.0})});
    EXPECT_FALSE(cast(b, {0.0, 2.5, 0.0}, kX));  // parallel to y's slab, outside it
    EXPECT_TRUE(cast(b, {0.0, 2.0, 0.0}, kX));   // along the face y = 2: grazing counts
    EXPECT_FALSE(cast(b, kOrigin, -kX));
    EXPECT_FALSE(cast(b, kOrigin, kX, 0.0, 3.9));
    expect_hit(cast(b, kOrigin, kX, 4.5), 6.0, {6.0, 0.0, 0.0}, -kX);
}

TEST(MovingObstacles, NearestObstacleWinsAndTiesGoToTheLowestIndex) {
    const MovingObstacles two(
        {sphere("near", {5.0, 0.0, 0.0}, 1.0), box("far", {8.0, 0.0, 0.0}, {1.0, 1.0, 1.0})});
    EXPECT_EQ(cast(two, kOrigin, kX)->obstacle, 0u);
    EXPECT_EQ(cast(two, {10.0, 0.0, 0.0}, -kX)->obstacle, 1u);
    const MovingObstacles twins(
        {sphere("a", {5.0, 0.0, 0.0}, 1.0), sphere("b", {5.0, 0.0, 0.0}, 1.0)});
    EXPECT_EQ(cast(twins, kOrigin, kX)->obstacle, 0u);
    EXPECT_EQ(twins.find("b").value_or(99), 1u);
    EXPECT_FALSE(twins.find("c"));
    EXPECT_FALSE(MovingObstacles().intersect(kOrigin, kX, 0.0, kInf, 0.0));
}

TEST(MovingObstacles, PositionIsLinearBetweenWaypointsAndHeldOutside) {
    MovingObstacle o = sphere("ball", {0.0, 0.0, 2.0}, 0.3);
    o.waypoints = {{0.0, {0.0, 0.0, 2.0}}, {10.0, {5.0, 0.0, 2.0}}, {12.0, {5.0, 4.0, 2.0}}};
    EXPECT_EQ(o.position_at(-1.0), Eigen::Vector3d(0.0, 0.0, 2.0));
    EXPECT_EQ(o.position_at(0.0), Eigen::Vector3d(0.0, 0.0, 2.0));
    EXPECT_LT((o.position_at(5.0) - Eigen::Vector3d(2.5, 0.0, 2.0)).norm(), kExact_m);
    EXPECT_LT((o.position_at(11.0) - Eigen::Vector3d(5.0, 2.0, 2.0)).norm(), kExact_m);
    EXPECT_EQ(o.position_at(12.0), Eigen::Vector3d(5.0, 4.0, 2.0));
    EXPECT_EQ(o.position_at(1e6), Eigen::Vector3d(5.0, 4.0, 2.0));
    EXPECT_LT((o.velocity_at(5.0) - Eigen::Vector3d(0.5, 0.0, 0.0)).norm(), kExact_m);
    EXPECT_LT((o.velocity_at(10.0) - Eigen::Vector3d(0.0, 2.0, 0.0)).norm(), kExact_m);
    EXPECT_EQ(o.velocity_at(12.0), Eigen::Vector3d::Zero());
    EXPECT_EQ(o.velocity_at(-1.0), Eigen::Vector3d::Zero());
    // One waypoint: static.
    const MovingObstacle still = sphere("still", {1.0, 2.0, 3.0}, 0.3);
    EXPECT_EQ(still.position_at(100.0), Eigen::Vector3d(1.0, 2.0, 3.0));
    EXPECT_EQ(still.velocity_at(0.0), Eigen::Vector3d::Zero());
    EXPECT_THROW(o.position_at(std::nan("")), InputError);
    EXPECT_THROW(o.velocity_at(kInf), InputError);
}

TEST(MovingObstacles, RaysSeeTheObstacleWhereItIsAtTheQueryTime) {
    MovingObstacle o = sphere("ball", {0.0, 0.0, 0.0}, 0.3);
    o.waypoints = {{0.0, {10.0, 0.0, 2.0}}, {4.0, {2.0, 0.0, 2.0}}};  // 2 m/s towards −x
    const MovingObstacles s({o});
    const Eigen::Vector3d eye(0.0, 0.0, 2.0);
    for (const double t_s : {0.0, 1.0, 2.5, 4.0, 6.0}) {
        const double centre_x = 10.0 - 2.0 * std::min(t_s, 4.0);
        const auto hit = s.intersect(eye, kX, 0.0, 100.0, t_s);
        ASSERT_TRUE(hit);
        EXPECT_NEAR(hit->range_m, centre_x - 0.3, kExact_m) << t_s;
        EXPECT_NEAR(s.distance_m(eye, t_s), centre_x - 0.3, kExact_m) << t_s;
    }
}

TEST(MovingObstacles, SignedDistanceIsPositiveOutsideAndNegativeInside) {
    const MovingObstacle s = sphere("s", {5.0, 0.0, 0.0}, 1.0);
    EXPECT_NEAR(s.distance_m(kOrigin, 0.0), 4.0, kExact_m);
    EXPECT_NEAR(s.distance_m({5.0, 0.0, 0.5}, 0.0), -0.5, kExact_m);
    const MovingObstacle b = box("b", {5.0, 0.0, 0.0}, {1.0, 2.0, 3.0});
    EXPECT_NEAR(b.distance_m(kOrigin, 0.0), 4.0, kExact_m);
    EXPECT_NEAR(b.distance_m({7.0, 4.0, 0.0}, 0.0), std::sqrt(5.0), kExact_m);  // corner region
    EXPECT_NEAR(b.distance_m({5.0, 0.0, 0.0}, 0.0), -1.0, kExact_m);
    const MovingObstacles both({s, box("b2", {0.0, 0.0, 10.0}, {1.0, 1.0, 1.0})});
    EXPECT_NEAR(both.distance_m({0.0, 0.0, 7.0}, 0.0), 2.0, kExact_m);
    EXPECT_EQ(MovingObstacles().distance_m(kOrigin, 0.0), kInf);
    EXPECT_THROW(s.distance_m({std::nan(""), 0.0, 0.0}, 0.0), InputError);
}

TEST(MovingObstacles, OcclusionIgnoresTheEndMarginsAsTheRayCasterDoes) {
    const MovingObstacles s({sphere("a", {5.0, 0.0, 0.0}, 1.0)});
    EXPECT_TRUE(s.occluded(kOrigin, {10.0, 0.0, 0.0}, 0.0));
    EXPECT_FALSE(s.occluded(kOrigin, {3.9, 0.0, 0.0}, 0.0));
    EXPECT_FALSE(s.occluded({4.0, 0.0, 0.0}, kOrigin, 0.0));  // starts on the surface
    EXPECT_FALSE(s.occluded(kOrigin, {4.0, 0.0, 0.0}, 0.0));  // ends on the surface
    EXPECT_TRUE(s.occluded({5.0, 0.0, 0.0}, kOrigin, 0.0));   // from inside
    EXPECT_FALSE(s.occluded(kOrigin, {0.0, 10.0, 0.0}, 0.0));
    EXPECT_THROW(s.occluded(kOrigin, {kInf, 0.0, 0.0}, 0.0), InputError);
    EXPECT_THROW(s.occluded(kOrigin, kX, std::nan("")), InputError);
}

TEST(MovingObstacles, BadRaysAreInputErrors) {
    const MovingObstacles s({sphere("a", {5.0, 0.0, 0.0}, 1.0)});
    EXPECT_THROW(s.intersect(kOrigin, 2.0 * kX, 0.0, 10.0, 0.0), InputError);
    EXPECT_THROW(s.intersect({std::nan(""), 0.0, 0.0}, kX, 0.0, 10.0, 0.0), InputError);
    EXPECT_THROW(s.intersect(kOrigin, kX, 5.0, 5.0, 0.0), InputError);
    EXPECT_THROW(s.intersect(kOrigin, kX, -1.0, 5.0, 0.0), InputError);
    EXPECT_THROW(s.intersect(kOrigin, kX, 0.0, 5.0, std::nan("")), InputError);
    MovingObstacle no_waypoints = sphere("x", kOrigin, 1.0);
    no_waypoints.waypoints.clear();
    EXPECT_THROW(no_waypoints.position_at(0.0), InputError);  // unvalidated spec: no crash
}

TEST(MovingObstacles, ValidationNamesTheField) {
    const auto with = [](auto change) {
        MovingObstacle o = sphere("ball", kOrigin, 1.0);
        o.waypoints.push_back({1.0, kX});
        change(o);
        return [o] { o.validate("moving_obstacles[0]"); };
    };
    expect_config_error(with([](MovingObstacle& o) { o.radius_m = 0.0; }),
                        "moving_obstacles[0].radius_m");
    expect_config_error(with([](MovingObstacle& o) { o.radius_m = std::nan(""); }),
                        "moving_obstacles[0].radius_m");
    expect_config_error(with([](MovingObstacle& o) {
                            o.shape = ObstacleShape::kBox;
                            o.half_extents_m.y() = -1.0;
                        }),
                        "moving_obstacles[0].half_extents_m");
    expect_config_error(with([](MovingObstacle& o) { o.waypoints.clear(); }),
                        "moving_obstacles[0].waypoints");
    expect_config_error(with([](MovingObstacle& o) { o.waypoints[1].t_s = 0.0; }),
                        "moving_obstacles[0].waypoints[1].t_s");
    expect_config_error(with([](MovingObstacle& o) { o.waypoints[0].t_s = kInf; }),
                        "moving_obstacles[0].waypoints[0].t_s");
    expect_config_error(with([](MovingObstacle& o) { o.waypoints[1].xyz.z() = std::nan(""); }),
                        "moving_obstacles[0].waypoints[1].xyz");
    expect_config_error(with([](MovingObstacle& o) { o.name.clear(); }),
                        "moving_obstacles[0].name");
    // A box does not check the sphere's radius.
    EXPECT_NO_THROW(with([](MovingObstacle& o) {
        o.shape = ObstacleShape::kBox;
        o.radius_m = -1.0;
    })());
    expect_config_error(
        [] {
            MovingObstacles({sphere("a", kOrigin, 1.0), sphere("a", kX, 1.0)});
        },
        "moving_obstacles[1].name");
}

}  // namespace
}  // namespace scantling::sim
