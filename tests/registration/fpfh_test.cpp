#include <gtest/gtest.h>

#include <cmath>

#include <scantling/core/error.hpp>
#include <scantling/core/normals.hpp>
#include <scantling/core/voxel_grid.hpp>
#include <scantling/registration/fpfh.hpp>

#include "scenes.hpp"

namespace scantling::registration {
namespace {

// Histogram entries are in [0, 200]; a rigid motion changes the inputs only by rounding
// (~1e-15 relative), and the float output by at most one float ulp at 200 (1.5e-5).
constexpr float kInvarianceTol = 1e-4f;
constexpr double kVoxelM = 0.1;
constexpr double kRadiusM = 5 * kVoxelM;

/// The room-corner scene at 0.1 m voxels with normals: planes, edges and box corners. With
/// noise, because exactly parallel or anti-parallel normals put pair features exactly on a bin
/// edge (theta = ±pi), where rounding decides the bin: a real discontinuity of FPFH.
PointCloud scene() {
    PointCloud cloud = voxel_downsample(test::sample_room_corner(20000, 3, 0.005), kVoxelM);
    estimate_normals(cloud, {});
    return cloud;
}

FpfhConfig config() {
    FpfhConfig c;
    c.radius_m = kRadiusM;
    return c;
}

TEST(Fpfh, InvariantToRigidTransforms) {
    const PointCloud cloud = scene();
    const Eigen::Isometry3d T = test::make_pose(0.7, -0.4, 2.5, Eigen::Vector3d(3, -2, 1));
    const FeatureMatrix a = compute_fpfh(cloud, config());
    const FeatureMatrix b = compute_fpfh(transformed(cloud, T), config());
    ASSERT_EQ(a.cols(), static_cast<Eigen::Index>(cloud.size()));
    EXPECT_LT((a - b).cwiseAbs().maxCoeff(), kInvarianceTol);
    EXPECT_GT(a.maxCoeff(), 0.0f);
}

TEST(Fpfh, EachBlockSumsToTwoHundred) {
    // SPFH blocks are normalised to 100 and the neighbours' weighted mean adds another 100.
    const FeatureMatrix f = compute_fpfh(scene(), config());
    for (Eigen::Index c = 0; c < f.cols(); ++c) {
        for (Eigen::Index block = 0; block < 3; ++block) {
            EXPECT_NEAR(f.col(c).segment(block * 11, 11).sum(), 200.0f, 1e-3f) << "point " << c;
        }
    }
}

TEST(Fpfh, FlatPatchFillsTheMiddleBins) {
    // Coplanar points with equal normals: alpha = phi = theta = 0, the middle bin of each block.
    PointCloud plane = test::sample_plane(2000, 4, 1.0);
    plane.normals.assign(plane.size(), Eigen::Vector3d::UnitZ());
    FpfhConfig c = config();
    c.radius_m = 0.2;
    c.weighting = FpfhWeighting::kInverseSquaredDistance;
    const FeatureMatrix f = compute_fpfh(plane, c);
    for (Eigen::Index col = 0; col < f.cols(); ++col) {
        EXPECT_NEAR(f(5, col), 200.0f, 1e-3f);
        EXPECT_NEAR(f(16, col), 200.0f, 1e-3f);
        EXPECT_NEAR(f(27, col), 200.0f, 1e-3f);
    }
}

TEST(Fpfh, IsolatedPointHasZeroFeature) {
    PointCloud cloud;
    cloud.points = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.1, 0, 0),
                    Eigen::Vector3d(0, 0.1, 0), Eigen::Vector3d(5, 5, 5)};
    cloud.normals.assign(4, Eigen::Vector3d::UnitZ());
    const FeatureMatrix f = compute_fpfh(cloud, config());
    EXPECT_EQ(f.col(3).cwiseAbs().maxCoeff(), 0.0f);
    EXPECT_GT(f.col(0).sum(), 0.0f);
}

TEST(Fpfh, SameResultForOneAndTwoThreads) {
    const PointCloud cloud = scene();
    FpfhConfig c1 = config();
    c1.parallel.num_threads = 1;
    FpfhConfig c2 = config();
    c2.parallel.num_threads = 2;
    EXPECT_TRUE(compute_fpfh(cloud, c1) == compute_fpfh(cloud, c2));
}

TEST(Fpfh, RejectsBadInputAndConfig) {
    PointCloud cloud = test::sample_plane(50, 1, 1.0);
    EXPECT_THROW(compute_fpfh(cloud, config()), InputError);  // no normals
    EXPECT_THROW(compute_fpfh(PointCloud{}, config()), InputError);
    cloud.normals.assign(cloud.size(), Eigen::Vector3d::UnitZ());
    cloud.normals[7].x() = std::nan("");
    EXPECT_THROW(compute_fpfh(cloud, config()), InputError);
    cloud.normals[7] = Eigen::Vector3d::UnitZ();
    const KdTree small_tree(std::vector<Eigen::Vector3d>(3, Eigen::Vector3d::Zero()));
    EXPECT_THROW(compute_fpfh(cloud, small_tree, config()), InputError);
    FpfhConfig bad = config();
    bad.radius_m = 0.0;
    EXPECT_THROW(compute_fpfh(cloud, bad), ConfigError);
    bad = config();
    bad.max_neighbors = 1;
    EXPECT_THROW(compute_fpfh(cloud, bad), ConfigError);
}

}  // namespace
}  // namespace scantling::registration
