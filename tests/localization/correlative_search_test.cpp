#include <gtest/gtest.h>

#include <cmath>

#include <scantling/core/error.hpp>
#include <scantling/core/se3.hpp>
#include <scantling/localization/correlative_search.hpp>

namespace scantling::localization {
namespace {

/// A 4 × 3 × 2 m room (walls, floor, ceiling at 5 cm spacing) with a 1 m pillar near one
/// corner, so that only one pose explains a view of the pillar.
PointCloud room() {
    PointCloud c;
    auto add = [&](const Eigen::Vector3d& p) { c.points.push_back(p); };
    for (double a = 0; a <= 4.0; a += 0.05) {
        for (double b = 0; b <= 2.0; b += 0.05) {
            add({a, 0.0, b});
            add({a, 3.0, b});
        }
        for (double b = 0; b <= 3.0; b += 0.05) {
            add({a, b, 0.0});
            add({a, b, 2.0});
        }
    }
    for (double a = 0; a <= 3.0; a += 0.05) {
        for (double b = 0; b <= 2.0; b += 0.05) {
            add({0.0, a, b});
            add({4.0, a, b});
        }
    }
    for (double z = 0; z <= 1.0; z += 0.05) {  // pillar 0.3 × 0.3 m at (3.2, 2.2)
        for (double s = 0; s <= 0.3; s += 0.05) {
            add({3.2 + s, 2.2, z});
            add({3.2 + s, 2.5, z});
            add({3.2, 2.2 + s, z});
            add({3.5, 2.2 + s, z});
        }
    }
    return c;
}

TEST(CorrelativeSearch, FindsTheBodyPoseOfAViewAmongAllPosesOfTheRoom) {
    const PointCloud map = room();
    const LikelihoodField field(map, LikelihoodFieldConfig{});
    // The body at (1.3, 1.1, 1.0) with yaw 30°: the scan is the map seen from there, in the
    // body's gravity-aligned frame, cut to a forward 120° cone.
    Eigen::Isometry3d T_world_body = Eigen::Isometry3d::Identity();
    T_world_body.linear() = rotation_from_euler_zyx(0.0, 0.0, 30.0 * M_PI / 180.0);
    T_world_body.translation() = Eigen::Vector3d(1.3, 1.1, 1.0);
    PointCloud scan;
    for (const Eigen::Vector3d& p : map.points) {
        const Eigen::Vector3d q = T_world_body.inverse() * p;
        if (q.x() > 0.3 && std::abs(std::atan2(q.y(), q.x())) < M_PI / 3) scan.points.push_back(q);
    }
    Aabb box;
    box.extend({0.0, 0.0, 0.0});
    box.extend({4.0, 3.0, 2.0});
    const auto candidates = correlative_search(field, scan, box, CorrelativeSearchConfig{});
    ASSERT_FALSE(candidates.empty());
    const Eigen::Isometry3d& best = candidates.front().T_world_gravity;
    EXPECT_LT((best.translation() - T_world_body.translation()).norm(), 0.2);
    const double yaw = std::atan2(best(1, 0), best(0, 0));
    EXPECT_NEAR(yaw, 30.0 * M_PI / 180.0, 0.06);
    for (std::size_t i = 1; i < candidates.size(); ++i) {
        EXPECT_LE(candidates[i].score, candidates[i - 1].score);
    }
}

TEST(CorrelativeSearch, RefusesImpossibleSettingsAndEmptyInput) {
    const PointCloud map = room();
    LikelihoodFieldConfig huge;
    huge.resolution_m = 0.001;
    EXPECT_THROW(LikelihoodField(map, huge), ConfigError);  // 10¹⁰ cells: refused, not allocated
    EXPECT_THROW(LikelihoodField(PointCloud{}, LikelihoodFieldConfig{}), InputError);
    const LikelihoodField field(map, LikelihoodFieldConfig{});
    Aabb box;
    box.extend({0.0, 0.0, 0.0});
    box.extend({4.0, 3.0, 2.0});
    EXPECT_TRUE(correlative_search(field, PointCloud{}, box, CorrelativeSearchConfig{}).empty());
    CorrelativeSearchConfig bad;
    bad.yaw_step_rad = 0.0;
    PointCloud one;
    one.points.emplace_back(1.0, 0.0, 0.0);
    EXPECT_THROW(correlative_search(field, one, box, bad), ConfigError);
    EXPECT_EQ(field.score(Eigen::Vector3d(NAN, 0, 0)), 0.0f);
    EXPECT_EQ(field.distance(Eigen::Vector3d(100, 0, 0)), 0.0f);
}

}  // namespace
}  // namespace scantling::localization
