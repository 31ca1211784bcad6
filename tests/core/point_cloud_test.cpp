#include <scantling/core/error.hpp>
#include <scantling/core/point_cloud.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

namespace scantling {
namespace {

// Rotations and products of small exact numbers: a few ulps.
constexpr double kTol = 1e-12;

PointCloud full_cloud(std::size_t n) {
    PointCloud cloud;
    cloud.stamp_s = 12.5;
    for (std::size_t i = 0; i < n; ++i) {
        const double x = static_cast<double>(i);
        cloud.points.emplace_back(x, 2.0 * x, -x);
        cloud.normals.push_back(Eigen::Vector3d(1.0, x, 0.0).normalized());
        cloud.covariances.push_back(Eigen::Vector3d(1.0 + x, 2.0, 3.0).asDiagonal());
        cloud.intensities.push_back(static_cast<float>(10 * i));
        cloud.rings.push_back(static_cast<std::uint16_t>(i % 16));
        cloud.times_s.push_back(0.01f * static_cast<float>(i));
        cloud.colors.emplace_back(static_cast<std::uint8_t>(i), 0, 255);
    }
    return cloud;
}

PointCloud points_only(std::vector<Eigen::Vector3d> points) {
    PointCloud cloud;
    cloud.points = std::move(points);
    return cloud;
}

std::string message_of(const auto& fn) {
    try {
        fn();
    } catch (const InputError& e) {
        return e.what();
    }
    return "no InputError thrown";
}

TEST(PointCloud, SelectCarriesEveryPresentFieldInIndexOrder) {
    const PointCloud cloud = full_cloud(5);
    const std::vector<std::size_t> indices{4, 1, 1};
    const PointCloud out = select(cloud, indices);
    ASSERT_EQ(out.size(), 3U);
    check_consistent(out, "selected");
    EXPECT_EQ(out.stamp_s, 12.5);
    EXPECT_EQ(out.points[0], cloud.points[4]);
    EXPECT_EQ(out.normals[1], cloud.normals[1]);
    EXPECT_EQ(out.covariances[0], cloud.covariances[4]);
    EXPECT_EQ(out.intensities[2], 10.0f);
    EXPECT_EQ(out.rings[0], 4);
    EXPECT_EQ(out.times_s[0], cloud.times_s[4]);
    EXPECT_EQ(out.colors[0], cloud.colors[4]);
}

TEST(PointCloud, SelectRejectsOutOfRangeIndex) {
    const PointCloud cloud = full_cloud(3);
    const std::vector<std::size_t> indices{0, 3};
    EXPECT_NE(message_of([&] { select(cloud, indices); }).find("index 3"), std::string::npos);
}

TEST(PointCloud, AppendConcatenatesMatchingClouds) {
    PointCloud dst = full_cloud(3);
    append(dst, full_cloud(2));
    EXPECT_EQ(dst.size(), 5U);
    check_consistent(dst, "appended");
    EXPECT_EQ(dst.points[3], Eigen::Vector3d::Zero());
    EXPECT_EQ(dst.rings[4], 1);
}

TEST(PointCloud, AppendToEmptyTakesTheSourceFieldsAndEmptySourceIsANoOp) {
    PointCloud dst;
    append(dst, full_cloud(2));
    EXPECT_EQ(field_names(dst).size(), field_names(full_cloud(1)).size());
    append(dst, PointCloud{});
    EXPECT_EQ(dst.size(), 2U);
    check_consistent(dst, "appended");
}

TEST(PointCloud, AppendWithMismatchedFieldsThrowsAndLeavesDestinationUnchanged) {
    PointCloud dst = full_cloud(2);
    PointCloud src = full_cloud(2);
    src.colors.clear();
    const std::string message = message_of([&] { append(dst, src); });
    EXPECT_NE(message.find("colors"), std::string::npos) << message;
    EXPECT_EQ(dst.size(), 2U);
    EXPECT_EQ(dst.normals.size(), 2U);
    check_consistent(dst, "after failed append");
}

TEST(PointCloud, TransformedMovesPointsAndRotatesNormalsAndCovariances) {
    const PointCloud cloud = full_cloud(4);
    Eigen::Isometry3d T_world_sensor = Eigen::Isometry3d::Identity();
    T_world_sensor.linear() =
        Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, -2.0, 0.5).normalized()).toRotationMatrix();
    T_world_sensor.translation() = Eigen::Vector3d(3.0, -1.0, 2.0);
    const Eigen::Matrix3d R = T_world_sensor.linear();
    const PointCloud out = transformed(cloud, T_world_sensor);
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        EXPECT_LT((out.points[i] - (R * cloud.points[i] + T_world_sensor.translation())).norm(),
                  kTol);
        EXPECT_LT((out.normals[i] - R * cloud.normals[i]).norm(), kTol);
        const Eigen::Matrix3d expected = R * cloud.covariances[i] * R.transpose();
        EXPECT_LT((out.covariances[i] - expected).cwiseAbs().maxCoeff(), kTol);
        EXPECT_EQ(out.intensities[i], cloud.intensities[i]);
    }
    // Translation must not leak into normals: rotate-only check on a pure translation.
    Eigen::Isometry3d T_shift = Eigen::Isometry3d::Identity();
    T_shift.translation() = Eigen::Vector3d(100.0, 0.0, 0.0);
    EXPECT_EQ(transformed(cloud, T_shift).normals, cloud.normals);
}

TEST(PointCloud, CheckConsistentNamesTheMismatchedField) {
    PointCloud cloud = full_cloud(3);
    cloud.times_s.pop_back();
    const std::string message = message_of([&] { check_consistent(cloud, "scan 7"); });
    EXPECT_NE(message.find("scan 7"), std::string::npos) << message;
    EXPECT_NE(message.find("times_s"), std::string::npos) << message;
    EXPECT_THROW(check_usable(cloud, "scan 7"), InputError);
}

TEST(PointCloud, CheckFiniteNamesTheFirstBadIndex) {
    PointCloud cloud = full_cloud(5);
    cloud.points[3].y() = std::numeric_limits<double>::infinity();
    cloud.points[4].x() = std::nan("");
    const std::string message = message_of([&] { check_finite(cloud, "sweep"); });
    EXPECT_NE(message.find("point 3"), std::string::npos) << message;
    EXPECT_THROW(check_usable(cloud, "sweep"), InputError);
}

TEST(PointCloud, CheckUsableRejectsEmptyAndAcceptsGoodClouds) {
    EXPECT_NE(message_of([] { check_usable(PointCloud{}, "map"); }).find("empty"),
              std::string::npos);
    EXPECT_NO_THROW(check_usable(full_cloud(2), "map"));
}

TEST(PointCloud, FieldNamesFollowTheDocumentedOrder) {
    EXPECT_EQ(field_names(points_only({{0, 0, 0}})), (std::vector<std::string>{"x", "y", "z"}));
    const std::vector<std::string> expected{"x",        "y",        "z",         "normal_x",
                                            "normal_y", "normal_z", "intensity", "ring",
                                            "time",     "rgb",      "covariance"};
    EXPECT_EQ(field_names(full_cloud(1)), expected);
}

TEST(PointCloud, RemoveNonFiniteDropsBadPointsAndBadNormals) {
    PointCloud cloud = full_cloud(6);
    cloud.points[1].z() = std::nan("");
    cloud.normals[4].x() = -std::numeric_limits<double>::infinity();
    const PointCloud out = remove_non_finite(cloud);
    ASSERT_EQ(out.size(), 4U);
    check_consistent(out, "filtered");
    EXPECT_EQ(out.intensities, (std::vector<float>{0.0f, 20.0f, 30.0f, 50.0f}));
    EXPECT_EQ(out.stamp_s, cloud.stamp_s);
}

TEST(PointCloud, BoundsAndReserve) {
    PointCloud cloud = points_only({{1, -2, 3}, {-1, 5, 0}});
    const Aabb box = compute_bounds(cloud);
    EXPECT_EQ(box.min, Eigen::Vector3d(-1, -2, 0));
    EXPECT_EQ(box.max, Eigen::Vector3d(1, 5, 3));
    EXPECT_TRUE(compute_bounds(PointCloud{}).empty());
    PointCloud with_fields = full_cloud(1);
    with_fields.reserve(100);
    EXPECT_GE(with_fields.points.capacity(), 100U);
    EXPECT_GE(with_fields.covariances.capacity(), 100U);
}

}  // namespace
}  // namespace scantling
