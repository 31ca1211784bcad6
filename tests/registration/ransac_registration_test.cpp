#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include <scantling/core/error.hpp>
#include <scantling/core/random.hpp>
#include <scantling/core/se3.hpp>
#include <scantling/registration/ransac_registration.hpp>

#include "scenes.hpp"

namespace scantling::registration {
namespace {

constexpr double kSigmaM = 0.01;  // per-axis noise of the inlier target points
// RANSAC refits on ~100–250 inliers with 1 cm noise over a 2 m cube: ~0.1° and a few mm.
constexpr double kTolRad = 1.0 * std::numbers::pi / 180.0;
constexpr double kTolM = 0.02;

struct Problem {
    std::vector<Eigen::Vector3d> source;
    std::vector<Eigen::Vector3d> target;
    std::vector<Correspondence> correspondences;
};

/// Source points in a 2 m cube, target = T source + noise; the first `outlier_ratio` of the
/// correspondences point at a random other target point.
Problem make_problem(std::size_t n, double outlier_ratio, const Eigen::Isometry3d& T,
                     std::uint64_t seed) {
    Rng rng(seed);
    Problem p;
    for (std::size_t k = 0; k < n; ++k) {
        p.source.emplace_back(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
        p.target.push_back(T * p.source.back() + rng.normal3(kSigmaM));
    }
    const auto outliers =
        static_cast<std::size_t>(std::llround(outlier_ratio * static_cast<double>(n)));
    for (std::size_t k = 0; k < n; ++k) {
        p.correspondences.push_back({k, k < outliers ? rng.uniform_index(n) : k, 0.0f});
    }
    return p;
}

Eigen::Isometry3d truth() {
    return test::make_pose(-0.5, 0.2, 1.2, Eigen::Vector3d(0.2, 0.8, -0.6));
}

RansacConfig config() {
    RansacConfig c;
    c.max_correspondence_distance_m = 3 * kSigmaM * std::sqrt(3.0);
    return c;
}

class RansacOutliers : public ::testing::TestWithParam<double> {};

TEST_P(RansacOutliers, RecoversKnownPose) {
    const Problem p = make_problem(500, GetParam(), truth(), 21);
    const RansacResult r = ransac_register(p.source, p.target, p.correspondences, config());
    ASSERT_TRUE(r.registration.converged) << r.registration.status;
    const PoseError e = pose_error(r.registration.T_target_source, truth());
    EXPECT_LT(e.rotation_rad, kTolRad);
    EXPECT_LT(e.translation_m, kTolM);
    EXPECT_NEAR(r.registration.fitness, 1.0 - GetParam(), 0.03);
    EXPECT_GT(r.registration.iterations, 0);
}

INSTANTIATE_TEST_SUITE_P(FiftyToEightyPercent, RansacOutliers, ::testing::Values(0.5, 0.8));

TEST(Ransac, SameResultForOneAndTwoThreads) {
    const Problem p = make_problem(300, 0.7, truth(), 22);
    RansacConfig c1 = config();
    c1.parallel.num_threads = 1;
    RansacConfig c2 = config();
    c2.parallel.num_threads = 2;
    const RansacResult r1 = ransac_register(p.source, p.target, p.correspondences, c1);
    const RansacResult r2 = ransac_register(p.source, p.target, p.correspondences, c2);
    EXPECT_TRUE(r1.registration.T_target_source.matrix() ==
                r2.registration.T_target_source.matrix());
    EXPECT_EQ(r1.inliers, r2.inliers);
    EXPECT_EQ(r1.registration.iterations, r2.registration.iterations);
}

TEST(Ransac, DegenerateInputsAreNotConverged) {
    const Problem p = make_problem(10, 0.0, truth(), 23);
    const std::vector<Correspondence> two(p.correspondences.begin(), p.correspondences.begin() + 2);
    EXPECT_FALSE(ransac_register(p.source, p.target, two, config()).registration.converged);
    std::vector<Eigen::Vector3d> line, line_t;
    std::vector<Correspondence> corr;
    for (std::size_t k = 0; k < 30; ++k) {
        line.emplace_back(0.05 * static_cast<double>(k), 0.0, 0.0);
        line_t.push_back(truth() * line.back());
        corr.push_back({k, k, 0.0f});
    }
    const RansacResult r = ransac_register(line, line_t, corr, config());
    EXPECT_FALSE(r.registration.converged);
    EXPECT_NE(r.registration.status.find("degenerate"), std::string::npos) << r.registration.status;
}

TEST(Ransac, RejectsBadInputAndConfig) {
    const Problem p = make_problem(10, 0.0, truth(), 24);
    std::vector<Correspondence> bad = p.correspondences;
    bad[3].target_index = 10;
    EXPECT_THROW(ransac_register(p.source, p.target, bad, config()), InputError);
    auto expect_config_error = [&](auto mutate) {
        RansacConfig c = config();
        mutate(c);
        EXPECT_THROW(ransac_register(p.source, p.target, p.correspondences, c), ConfigError);
    };
    expect_config_error([](auto& c) { c.max_correspondence_distance_m = 0.0; });
    expect_config_error([](auto& c) { c.edge_length_ratio = 1.0; });
    expect_config_error([](auto& c) { c.confidence = 1.0; });
    expect_config_error([](auto& c) { c.max_iterations = 0; });
    expect_config_error([](auto& c) { c.min_inliers = 2; });
}

}  // namespace
}  // namespace scantling::registration
