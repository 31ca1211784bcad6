#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <scantling/core/error.hpp>
#include <scantling/core/random.hpp>
#include <scantling/core/se3.hpp>
#include <scantling/registration/robust_registration.hpp>

#include "scenes.hpp"

namespace scantling::registration {
namespace {

using Points = std::vector<Eigen::Vector3d>;

constexpr double kSigmaM = 0.01;              // per-axis noise of the inlier target points
constexpr double kNoiseBoundM = 3 * kSigmaM;  // SPEC §7: beta = 3 sigma
constexpr double kDeg = std::numbers::pi / 180.0;
// 25–1000 inliers with 1 cm noise spread over a 2 m cube: the least-squares rotation is good to
// ~0.1°, the translation to a few millimetres; the bounds leave a factor of 5–10.
constexpr double kTolRad = 1.0 * kDeg;
constexpr double kTolM = 0.02;

struct Problem {
    Points source;
    Points target;
    std::vector<bool> is_inlier;
};

/// `n` correspondences in the 2 m cube around the origin; `outlier_ratio` of them have a random
/// target point (in the target's cube), the rest t = T s + N(0, sigma²) per axis.
Problem make_problem(std::size_t n, double outlier_ratio, const Eigen::Isometry3d& T,
                     std::uint64_t seed) {
    Rng rng(seed);
    Problem p;
    const auto outliers =
        static_cast<std::size_t>(std::llround(outlier_ratio * static_cast<double>(n)));
    for (std::size_t k = 0; k < n; ++k) {
        const Eigen::Vector3d s(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
        const bool inlier = k >= outliers;
        const Eigen::Vector3d t =
            inlier ? Eigen::Vector3d(T * s + rng.normal3(kSigmaM))
                   : Eigen::Vector3d(T * Eigen::Vector3d(rng.uniform(-1, 1), rng.uniform(-1, 1),
                                                         rng.uniform(-1, 1)));
        p.source.push_back(s);
        p.target.push_back(t);
        p.is_inlier.push_back(inlier);
    }
    return p;
}

Eigen::Isometry3d truth() {
    return test::make_pose(0.4, -0.3, 2.2, Eigen::Vector3d(0.5, -1.0, 0.3));
}

RobustRegistrationConfig config() {
    RobustRegistrationConfig c;
    c.noise_bound_m = kNoiseBoundM;
    return c;
}

class OutlierRatio : public ::testing::TestWithParam<double> {};

TEST_P(OutlierRatio, RecoversKnownPose) {
    const Problem p = make_problem(500, GetParam(), truth(), 7);
    const auto r = robust_register(p.source, p.target, config());
    ASSERT_TRUE(r.registration.converged) << r.registration.status;
    const PoseError e = pose_error(r.registration.T_target_source, truth());
    EXPECT_LT(e.rotation_rad, kTolRad);
    EXPECT_LT(e.translation_m, kTolM);
    std::size_t false_inliers = 0;
    for (std::size_t k : r.inliers) false_inliers += p.is_inlier[k] ? 0 : 1;
    EXPECT_LE(false_inliers, 2u);  // a random target lands within beta of T s by chance rarely
    EXPECT_EQ(r.max_clique_method, MaxCliqueMethod::kExact);
}

INSTANTIATE_TEST_SUITE_P(UpToNinetyFivePercent, OutlierRatio,
                         ::testing::Values(0.0, 0.5, 0.8, 0.9, 0.95));

TEST(RobustRegistration, NinetyNinePercentOutliersNeverClaimsAWrongPose) {
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
        const Problem p = make_problem(1000, 0.99, truth(), seed);
        const auto r = robust_register(p.source, p.target, config());
        if (!r.registration.converged) continue;  // declining is acceptable with 10 inliers
        const PoseError e = pose_error(r.registration.T_target_source, truth());
        EXPECT_LT(e.rotation_rad, kTolRad) << "seed " << seed << ": " << r.inliers.size();
    }
}

TEST(RobustRegistration, AllOutliersAreNotConverged) {
    const Problem p = make_problem(300, 1.0, truth(), 3);
    const auto r = robust_register(p.source, p.target, config());
    EXPECT_FALSE(r.registration.converged) << r.registration.status;
}

TEST(RobustRegistration, SameResultForOneAndTwoThreads) {
    const Problem p = make_problem(400, 0.8, truth(), 11);
    RobustRegistrationConfig c1 = config();
    c1.parallel.num_threads = 1;
    RobustRegistrationConfig c2 = config();
    c2.parallel.num_threads = 2;
    const auto r1 = robust_register(p.source, p.target, c1);
    const auto r2 = robust_register(p.source, p.target, c2);
    EXPECT_TRUE(r1.registration.T_target_source.matrix() ==
                r2.registration.T_target_source.matrix());
    EXPECT_EQ(r1.inliers, r2.inliers);
    EXPECT_EQ(r1.num_consistent_pairs, r2.num_consistent_pairs);
}

TEST(RobustRegistration, FewerThanThreeCorrespondencesAreNotConverged) {
    const Points two = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0)};
    EXPECT_FALSE(robust_register(Points{}, Points{}, config()).registration.converged);
    const auto r = robust_register(two, two, config());
    EXPECT_FALSE(r.registration.converged);
    EXPECT_NE(r.registration.status.find("too_few_correspondences"), std::string::npos);
}

TEST(RobustRegistration, CoincidentPointsAreDegenerate) {
    const Points source(50, Eigen::Vector3d(1, 2, 3));
    const Points target(50, Eigen::Vector3d(-1, 0, 2));
    const auto r = robust_register(source, target, config());
    EXPECT_FALSE(r.registration.converged);
    EXPECT_NE(r.registration.status.find("degenerate"), std::string::npos) << r.registration.status;
}

TEST(RobustRegistration, CollinearPointsAreDegenerate) {
    Points source, target;
    for (int k = 0; k < 50; ++k) {
        source.emplace_back(0.04 * k, 0.0, 0.0);
        target.push_back(truth() * source.back());
    }
    const auto r = robust_register(source, target, config());
    EXPECT_FALSE(r.registration.converged);
    EXPECT_NE(r.registration.status.find("degenerate"), std::string::npos) << r.registration.status;
}

TEST(RobustRegistration, RejectsBadInput) {
    const Points three(3, Eigen::Vector3d::Zero());
    const Points two(2, Eigen::Vector3d::Zero());
    EXPECT_THROW(robust_register(three, two, config()), InputError);
    Points bad = three;
    bad[1].x() = std::nan("");
    EXPECT_THROW(robust_register(bad, three, config()), InputError);
    PointCloud cloud;
    cloud.points = three;
    const std::vector<Correspondence> out_of_range = {{0, 0, 0.f}, {1, 5, 0.f}, {2, 2, 0.f}};
    EXPECT_THROW(robust_register(cloud, cloud, out_of_range, config()), InputError);
}

TEST(RobustRegistration, RejectsBadConfig) {
    const Points three(3, Eigen::Vector3d::Zero());
    auto expect_config_error = [&](auto mutate) {
        RobustRegistrationConfig c = config();
        mutate(c);
        EXPECT_THROW(robust_register(three, three, c), ConfigError);
    };
    expect_config_error([](auto& c) { c.noise_bound_m = 0.0; });
    expect_config_error([](auto& c) { c.cbar2 = -1.0; });
    expect_config_error([](auto& c) { c.estimate_scaling = true; });
    expect_config_error([](auto& c) { c.gnc_factor = 1.0; });
    expect_config_error([](auto& c) { c.gnc_max_iterations = 0; });
    expect_config_error([](auto& c) { c.min_inliers = 2; });
    expect_config_error([](auto& c) { c.max_clique.max_search_nodes = 0; });
}

TEST(RobustRegistration, YawOnlyRecoversGravityAlignedPose) {
    const Eigen::Isometry3d T = test::make_pose(0.0, 0.0, -2.5, Eigen::Vector3d(1.0, 0.4, -0.2));
    const Problem p = make_problem(500, 0.9, T, 5);
    RobustRegistrationConfig c = config();
    c.rotation = RobustRotation::kYawOnly;
    const auto r = robust_register(p.source, p.target, c);
    ASSERT_TRUE(r.registration.converged) << r.registration.status;
    const PoseError e = pose_error(r.registration.T_target_source, T);
    EXPECT_LT(e.rotation_rad, kTolRad);
    EXPECT_LT(e.translation_m, kTolM);
    // The rotation is exactly about z: roll and pitch stay zero.
    const Eigen::Vector3d z = r.registration.T_target_source.linear() * Eigen::Vector3d::UnitZ();
    EXPECT_NEAR(z.z(), 1.0, 1e-12);
}

TEST(RobustRegistration, YawOnlyOnVerticalLineIsDegenerate) {
    Points source, target;
    for (int k = 0; k < 40; ++k) {
        source.emplace_back(0.3, -0.2, 0.05 * k);
        target.push_back(source.back() + Eigen::Vector3d(1, 2, 3));
    }
    RobustRegistrationConfig c = config();
    c.rotation = RobustRotation::kYawOnly;
    const auto r = robust_register(source, target, c);
    EXPECT_FALSE(r.registration.converged);
    EXPECT_NE(r.registration.status.find("degenerate"), std::string::npos) << r.registration.status;
}

TEST(RobustRegistration, CorrespondenceOverloadMatchesPairedPoints) {
    const Problem p = make_problem(200, 0.5, truth(), 13);
    PointCloud source, target;
    source.points = p.source;
    target.points = p.target;
    std::vector<Correspondence> corr;
    for (std::size_t k = 0; k < p.source.size(); ++k) corr.push_back({k, k, 0.0f});
    RobustRegistrationConfig c = config();
    c.hypotheses.num_hypotheses = 1;  // plain TEASER++: exactly the span overload's method
    const auto a = robust_register(source, target, corr, c);
    const auto b = robust_register(p.source, p.target, config());
    EXPECT_TRUE(a.registration.T_target_source.matrix() == b.registration.T_target_source.matrix());
    EXPECT_EQ(a.inliers, b.inliers);
    EXPECT_EQ(a.num_hypotheses_scored, 0u);
}

/// Clouds and correspondences where the largest consistent set is a decoy: the target is the
/// room corner under `truth()` plus a few points placed at the source's image under
/// `decoy_pose()`; 12 correspondences follow the truth, 30 the decoy, 150 are random.
struct DecoyScene {
    PointCloud source, target;
    std::vector<Correspondence> correspondences;
};

Eigen::Isometry3d decoy_pose() {
    return test::make_pose(-0.2, 0.5, 0.9, Eigen::Vector3d(-0.6, 0.8, 0.1));
}

DecoyScene make_decoy_scene() {
    constexpr std::size_t kPoints = 3000, kTrue = 12, kDecoy = 30, kRandom = 150;
    Rng rng(21);
    DecoyScene d;
    d.source = test::sample_room_corner(kPoints, 17, 0.0);
    for (const Eigen::Vector3d& s : d.source.points) {
        d.target.points.push_back(truth() * s + rng.normal3(kSigmaM));
    }
    auto pick = [&] { return rng.uniform_index(kPoints); };
    for (std::size_t k = 0; k < kTrue; ++k) {
        const std::size_t i = pick();
        d.correspondences.push_back({i, i, 0.0f});
    }
    for (std::size_t k = 0; k < kDecoy; ++k) {
        const std::size_t i = pick();
        d.correspondences.push_back({i, d.target.points.size(), 0.0f});
        d.target.points.push_back(decoy_pose() * d.source.points[i] + rng.normal3(kSigmaM));
    }
    for (std::size_t k = 0; k < kRandom; ++k) d.correspondences.push_back({pick(), pick(), 0.0f});
    return d;
}

TEST(RobustRegistration, OverlapVerificationRejectsALargerDecoyClique) {
    const DecoyScene d = make_decoy_scene();
    // Plain TEASER++ trusts the maximum clique: the decoy.
    RobustRegistrationConfig plain = config();
    plain.hypotheses.num_hypotheses = 1;
    const auto wrong = robust_register(d.source, d.target, d.correspondences, plain);
    EXPECT_LT(pose_error(wrong.registration.T_target_source, decoy_pose()).rotation_rad, kTolRad);
    EXPECT_GE(wrong.max_clique_size, 25u);
    EXPECT_EQ(wrong.num_hypotheses_scored, 0u);
    // Verification scores the next clique too, and the whole source overlaps the target there.
    const auto r = robust_register(d.source, d.target, d.correspondences, config());
    ASSERT_TRUE(r.registration.converged) << r.registration.status;
    const PoseError e = pose_error(r.registration.T_target_source, truth());
    EXPECT_LT(e.rotation_rad, kTolRad);
    EXPECT_LT(e.translation_m, kTolM);
    EXPECT_GE(r.num_hypotheses_scored, 2u);
    EXPECT_GE(r.winning_hypothesis, 1u);
    EXPECT_GT(r.overlap, 0.95);
    EXPECT_GE(r.inliers.size(), 10u);
    EXPECT_LE(r.inliers.size(), 14u);
}

TEST(RobustRegistration, PairedPointsOverloadKeepsTheMaximumClique) {
    // Without clouds nothing can outvote the larger decoy: documented behaviour.
    const DecoyScene d = make_decoy_scene();
    Points s, t;
    for (const Correspondence& c : d.correspondences) {
        s.push_back(d.source.points[c.source_index]);
        t.push_back(d.target.points[c.target_index]);
    }
    const auto r = robust_register(s, t, config());
    EXPECT_LT(pose_error(r.registration.T_target_source, decoy_pose()).rotation_rad, kTolRad);
    EXPECT_EQ(r.num_hypotheses_scored, 0u);
}

TEST(RobustRegistration, VerificationIsTheSameForOneAndTwoThreads) {
    const DecoyScene d = make_decoy_scene();
    RobustRegistrationConfig c1 = config();
    c1.parallel.num_threads = 1;
    RobustRegistrationConfig c2 = config();
    c2.parallel.num_threads = 2;
    const auto r1 = robust_register(d.source, d.target, d.correspondences, c1);
    const auto r2 = robust_register(d.source, d.target, d.correspondences, c2);
    EXPECT_TRUE(r1.registration.T_target_source.matrix() ==
                r2.registration.T_target_source.matrix());
    EXPECT_EQ(r1.inliers, r2.inliers);
    EXPECT_EQ(r1.num_hypotheses_scored, r2.num_hypotheses_scored);
    EXPECT_EQ(r1.winning_hypothesis, r2.winning_hypothesis);
    EXPECT_EQ(r1.overlap, r2.overlap);
}

TEST(RobustRegistration, RejectsBadHypothesisConfig) {
    const Points three(3, Eigen::Vector3d::Zero());
    auto expect_config_error = [&](auto mutate, const std::string& field) {
        RobustRegistrationConfig c = config();
        mutate(c);
        try {
            robust_register(three, three, c);
            ADD_FAILURE() << field << ": no ConfigError";
        } catch (const ConfigError& e) {
            EXPECT_NE(std::string(e.what()).find("robust.hypotheses." + field), std::string::npos)
                << e.what();
        }
    };
    expect_config_error([](auto& c) { c.hypotheses.num_hypotheses = 0; }, "num_hypotheses");
    expect_config_error([](auto& c) { c.hypotheses.overlap_distance_m = 0.0; },
                        "overlap_distance_m");
    expect_config_error([](auto& c) { c.hypotheses.overlap_distance_m = std::nan(""); },
                        "overlap_distance_m");
    expect_config_error([](auto& c) { c.hypotheses.max_scored_points = 0; }, "max_scored_points");
}

}  // namespace
}  // namespace scantling::registration
