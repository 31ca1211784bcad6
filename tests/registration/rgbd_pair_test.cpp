#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <numbers>
#include <string>
#include <utility>

#include <scantling/core/normals.hpp>
#include <scantling/core/se3.hpp>
#include <scantling/core/voxel_grid.hpp>
#include <scantling/io/cloud_io.hpp>
#include <scantling/registration/ransac_registration.hpp>
#include <scantling/registration/robust_registration.hpp>

namespace scantling::registration {
namespace {

// 3DMatch's success criterion for a registered fragment pair (Zeng et al. 2017; as used by
// GeoTransformer, whose demo pair this is).
constexpr double kMaxRotationRad = 15.0 * std::numbers::pi / 180.0;
constexpr double kMaxTranslationM = 0.3;
constexpr double kVoxelM = 0.05;  // SPEC §7 and the usual 3DMatch setting

std::filesystem::path pair_dir() {
    return std::filesystem::path(SCANTLING_SHARED_DATA_DIR) / "rgbd-pair";
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

FpfhPipelineConfig pipeline_config() {
    FpfhPipelineConfig c;
    c.voxel_size_m = kVoxelM;
    c.fpfh.radius_m = 5 * kVoxelM;
    c.robust.noise_bound_m = kVoxelM;
    IcpConfig icp;
    icp.method = IcpMethod::kPointToPlane;
    icp.max_correspondence_distance_m = 2 * kVoxelM;  // the global estimate is within ~1 voxel
    c.refine = icp;
    return c;
}

class RgbdPairTest : public ::testing::Test {
  protected:
    void SetUp() override {
        if (!std::filesystem::exists(pair_dir() / "src.ply")) {
            GTEST_SKIP() << "real data not found at " << pair_dir()
                         << " (set SCANTLING_SHARED_DATA_DIR to the shared data folder)";
        }
        source_ = io::read_cloud((pair_dir() / "src.ply").string());
        target_ = io::read_cloud((pair_dir() / "ref.ply").string());
        truth_ = read_transform(pair_dir() / "T_ref_src.txt");
    }

    PointCloud source_;
    PointCloud target_;
    Eigen::Isometry3d truth_ = Eigen::Isometry3d::Identity();
};

TEST_F(RgbdPairTest, FpfhTeaserWithoutInitialGuessMeetsThe3DMatchCriterion) {
    const FpfhPipelineResult r = register_fpfh_teaser(source_, target_, pipeline_config());
    ASSERT_TRUE(r.robust.registration.converged) << r.robust.registration.status;
    const PoseError global = pose_error(r.robust.registration.T_target_source, truth_);
    const PoseError refined = pose_error(r.registration.T_target_source, truth_);
    std::cout << "[ rgbd-pair ] " << r.num_correspondences << " correspondences, clique "
              << r.robust.max_clique_size << " (" << to_string(r.robust.max_clique_method) << "), "
              << r.robust.inliers.size() << " inliers; global error "
              << global.rotation_rad * 180 / std::numbers::pi << " deg / " << global.translation_m
              << " m; refined " << refined.rotation_rad * 180 / std::numbers::pi << " deg / "
              << refined.translation_m << " m\n";
    EXPECT_LT(global.rotation_rad, kMaxRotationRad);
    EXPECT_LT(global.translation_m, kMaxTranslationM);
    EXPECT_TRUE(r.refined);
    EXPECT_LT(refined.rotation_rad, kMaxRotationRad);
    EXPECT_LT(refined.translation_m, kMaxTranslationM);
}

TEST_F(RgbdPairTest, RansacBaselineOnTheSameMatchesMeetsThe3DMatchCriterion) {
    const FpfhPipelineConfig c = pipeline_config();
    auto prepare = [&](const PointCloud& in) {
        PointCloud cloud = voxel_downsample(in, c.voxel_size_m);
        estimate_normals(cloud, c.normals);
        return std::make_pair(cloud, compute_fpfh(cloud, c.fpfh));
    };
    const auto [source, source_features] = prepare(source_);
    const auto [target, target_features] = prepare(target_);
    const auto matches = match_features(source_features, target_features, c.match);
    RansacConfig ransac;
    ransac.max_correspondence_distance_m = 1.5 * kVoxelM;  // Open3D's example setting
    const RansacResult r = ransac_register(source.points, target.points, matches, ransac);
    ASSERT_TRUE(r.registration.converged) << r.registration.status;
    const PoseError e = pose_error(r.registration.T_target_source, truth_);
    std::cout << "[ rgbd-pair ] RANSAC: " << r.registration.iterations << " hypotheses, "
              << r.inliers.size() << " inliers; error " << e.rotation_rad * 180 / std::numbers::pi
              << " deg / " << e.translation_m << " m\n";
    EXPECT_LT(e.rotation_rad, kMaxRotationRad);
    EXPECT_LT(e.translation_m, kMaxTranslationM);
}

}  // namespace
}  // namespace scantling::registration
