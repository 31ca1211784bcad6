// Reads the real recordings of SCANTLING_SHARED_DATA_DIR (see its README.md). Reference
// numbers were computed independently (python3 + struct on the raw bytes) and are pinned here.
#include <gtest/gtest.h>

#include <scantling/io/kitti.hpp>
#include <scantling/io/mesh_io.hpp>
#include <scantling/io/pcd.hpp>
#include <scantling/io/ply.hpp>

#include <cmath>

#include "test_files.hpp"

namespace scantling::io {
namespace {

constexpr double kBoundsToleranceM = 1e-3;         // reference values printed to ~1e-6 m
constexpr double kOrthonormalityTolerance = 1e-5;  // poses are printed with 7 significant digits

std::string data_path(const std::string& relative) {
    return (test::shared_data_dir() / relative).string();
}

void expect_bounds(const Aabb& box, const Eigen::Vector3d& min, const Eigen::Vector3d& max) {
    for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(box.min[k], min[k], kBoundsToleranceM) << "axis " << k;
        EXPECT_NEAR(box.max[k], max[k], kBoundsToleranceM) << "axis " << k;
    }
}

Aabb bounds_of(const std::vector<Eigen::Vector3d>& points) {
    return compute_bounds(std::span<const Eigen::Vector3d>(points));
}

TEST(RealData, ReadsAllSixteenLidarScansWithTheirHeaderPointCounts) {
    SCANTLING_SKIP_WITHOUT_SHARED_DATA();
    const std::size_t counts[16] = {124668, 124605, 124478, 124167, 123969, 123924, 123373, 122765,
                                    122123, 121357, 121018, 120945, 120503, 120295, 120406, 121023};
    for (int i = 0; i < 16; ++i) {
        const std::string name =
            "lidar-scans/0000" + std::string(i < 10 ? "0" : "") + std::to_string(i) + ".pcd";
        const PointCloud cloud = read_pcd(data_path(name));
        EXPECT_EQ(cloud.size(), counts[i]) << name;
        EXPECT_TRUE(cloud.has_intensities() && cloud.has_normals()) << name;
        EXPECT_FALSE(cloud.has_colors() || cloud.has_rings() || cloud.has_times()) << name;
    }
}

TEST(RealData, FirstLidarScanHasTheIndependentlyComputedBoundsAndValues) {
    SCANTLING_SKIP_WITHOUT_SHARED_DATA();
    const PointCloud cloud = read_pcd(data_path("lidar-scans/000000.pcd"));
    ASSERT_EQ(cloud.size(), 124668u);
    expect_bounds(compute_bounds(cloud), {-78.087395, -55.723412, -11.556541},
                  {77.967331, 44.878613, 2.825341});
    EXPECT_EQ(cloud.points[0],
              Eigen::Vector3d(52.89794158935547, 0.02298973873257637, 1.9979945421218872));
    EXPECT_EQ(cloud.intensities[0], 20.4f);
    EXPECT_EQ(cloud.normals.back(),
              Eigen::Vector3d(-0.16508862376213074, 0.00912927370518446, 0.9862365126609802));
    check_finite(cloud, "000000.pcd");
}

TEST(RealData, ReadsTheLidarPairPlyWithCloudCompareIntensity) {
    SCANTLING_SKIP_WITHOUT_SHARED_DATA();
    const PointCloud source = read_ply(data_path("lidar-pair/source.ply")).cloud;
    ASSERT_EQ(source.size(), 69792u);
    EXPECT_EQ(source.intensities.at(0), 70.0f);
    expect_bounds(compute_bounds(source), {-23.759020, -52.001141, -3.021290},
                  {18.479933, 6.507869, 9.172805});
    const PointCloud target = read_ply(data_path("lidar-pair/target.ply")).cloud;
    ASSERT_EQ(target.size(), 69088u);
    expect_bounds(compute_bounds(target), {-23.337478, -74.681610, -2.957336},
                  {19.024697, 8.919510, 10.795936});
}

TEST(RealData, ReadsTheRgbdPairPly) {
    SCANTLING_SKIP_WITHOUT_SHARED_DATA();
    const PointCloud src = read_ply(data_path("rgbd-pair/src.ply")).cloud;
    ASSERT_EQ(src.size(), 15953u);
    expect_bounds(compute_bounds(src), {-1.398, -1.104, 0.650}, {1.494, 0.810, 2.978});
    const PointCloud ref = read_ply(data_path("rgbd-pair/ref.ply")).cloud;
    ASSERT_EQ(ref.size(), 18977u);
    expect_bounds(compute_bounds(ref), {-1.350, -1.446, 0.800}, {1.494, 0.684, 3.482});
}

TEST(RealData, ReadsTheDtcHullBinaryStlAtModelScale) {
    SCANTLING_SKIP_WITHOUT_SHARED_DATA();
    const TriangleMesh hull =
        read_mesh(data_path("meshes/dtc-container-ship-hull-model-scale.stl"));
    EXPECT_EQ(hull.num_triangles(), 116062u);
    EXPECT_EQ(hull.num_vertices(), 58033u);  // distinct corner positions in the file
    const Aabb box = bounds_of(hull.vertices);
    expect_bounds(box, {-0.113504, -0.429253, 0.0}, {6.162090, 0.429252, 0.572322});
    EXPECT_NEAR(box.size().x(), 6.28, 0.01);  // README: 6.28 m long, 0.86 m beam, 0.57 m high
    EXPECT_NEAR(box.size().y(), 0.86, 0.01);
}

TEST(RealData, ReadsTheStorageTankAsciiStl) {
    SCANTLING_SKIP_WITHOUT_SHARED_DATA();
    const TriangleMesh tank = read_mesh(data_path("meshes/storage-tank-cylinder.stl"));
    EXPECT_EQ(tank.num_triangles(), 1832u);
    EXPECT_EQ(tank.num_vertices(), 918u);
    expect_bounds(bounds_of(tank.vertices), {0.0, 0.004003, 0.0}, {12.0, 11.996, 21.2});
}

TEST(RealData, ReadsTheSmallBoatObj) {
    SCANTLING_SKIP_WITHOUT_SHARED_DATA();
    const TriangleMesh boat = read_mesh(data_path("meshes/small-boat.obj"));
    EXPECT_EQ(boat.num_triangles(), 6339u);
    const Aabb box = bounds_of(boat.vertices);
    expect_bounds(box, {-0.815323, -0.342984, -0.053116}, {1.188254, 0.342853, 0.267713});
    EXPECT_NEAR(box.size().x(), 2.0, 0.01);  // README: 2.0 x 0.68 x 0.32 m
}

TEST(RealData, ReadsKittiGroundTruthPosesAsOrthonormal) {
    SCANTLING_SKIP_WITHOUT_SHARED_DATA();
    const auto poses = read_kitti_poses(data_path("kitti-poses/groundtruth/00.txt"));
    ASSERT_EQ(poses.size(), 4541u);  // one line per frame of sequence 00
    double worst = 0.0;
    for (const auto& T : poses) {
        const Eigen::Matrix3d R = T.linear();
        worst = std::max(worst,
                         (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff());
    }
    EXPECT_LT(worst, kOrthonormalityTolerance);
    EXPECT_NEAR(poses[1].translation().z(), 0.8586941, 1e-9);
    EXPECT_EQ(read_kitti_poses(data_path("kitti-poses/groundtruth/05.txt")).size(), 2761u);
}

}  // namespace
}  // namespace scantling::io
