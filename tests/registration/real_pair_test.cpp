#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <scantling/core/se3.hpp>
#include <scantling/core/voxel_grid.hpp>
#include <scantling/io/cloud_io.hpp>
#include <scantling/registration/icp.hpp>

namespace scantling::registration {
namespace {

// The reference transform is itself an estimate: two public tools agree on it to about 2 cm
// and 0.2° (data/README.md), so a correct registration is only known to within 3 cm and 0.3°.
constexpr double kTolM = 0.03;
constexpr double kTolRad = 0.3 * 3.14159265358979323846 / 180.0;
// Measured over voxels 0.1–0.25 m, 0.3–1 m correspondence distance and 10 or 20 neighbours,
// the rotation error ranged 0.001–0.7°: the sparse scan's local shapes change with the
// sampling. 0.1 m voxels with small_gicp's 10 neighbours and 1 m pairs land within 0.001° of
// the reference (which was apparently computed that way), and point-to-plane within 0.08°.
constexpr double kVoxelM = 0.1;

std::filesystem::path pair_dir() {
    return std::filesystem::path(SCANTLING_SHARED_DATA_DIR) / "lidar-pair";
}

/// Reads a 4 × 4 row-major matrix of 16 whitespace-separated numbers.
Eigen::Isometry3d read_transform(const std::filesystem::path& path) {
    std::ifstream in(path);
    Eigen::Matrix4d M;
    for (int i = 0; i < 16; ++i) {
        if (!(in >> M(i / 4, i % 4))) throw std::runtime_error("bad matrix file " + path.string());
    }
    return Eigen::Isometry3d(M);
}

class RealPairTest : public ::testing::Test {
  protected:
    void SetUp() override {
        if (!std::filesystem::exists(pair_dir() / "source.ply")) {
            GTEST_SKIP() << "real data not found at " << pair_dir()
                         << " (set SCANTLING_SHARED_DATA_DIR to the shared data folder)";
        }
        source_ = voxel_downsample(io::read_cloud((pair_dir() / "source.ply").string()), kVoxelM);
        target_ = voxel_downsample(io::read_cloud((pair_dir() / "target.ply").string()), kVoxelM);
        truth_ = read_transform(pair_dir() / "T_target_source.txt");
    }

    PointCloud source_;
    PointCloud target_;
    Eigen::Isometry3d truth_ = Eigen::Isometry3d::Identity();
};

TEST_F(RealPairTest, GicpFromIdentityRecoversTheReferenceTransform) {
    IcpConfig config;
    config.method = IcpMethod::kGeneralized;
    config.num_neighbors = 10;
    config.max_correspondence_distance_m = 1.0;
    const RegistrationResult r = align(source_, target_, Eigen::Isometry3d::Identity(), config);
    const PoseError e = pose_error(r.T_target_source, truth_);
    EXPECT_TRUE(r.converged) << r.status;
    EXPECT_LT(e.translation_m, kTolM);
    EXPECT_LT(e.rotation_rad, kTolRad);
    EXPECT_GT(r.fitness, 0.8);
}

TEST_F(RealPairTest, PointToPlaneFromIdentityRecoversTheReferenceTransform) {
    IcpConfig config;
    config.num_neighbors = 10;
    config.max_correspondence_distance_m = 1.0;
    const RegistrationResult r = align(source_, target_, Eigen::Isometry3d::Identity(), config);
    const PoseError e = pose_error(r.T_target_source, truth_);
    EXPECT_TRUE(r.converged) << r.status;
    EXPECT_LT(e.translation_m, kTolM);
    EXPECT_LT(e.rotation_rad, kTolRad);
}

}  // namespace
}  // namespace scantling::registration
