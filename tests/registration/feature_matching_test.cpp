#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <scantling/core/error.hpp>
#include <scantling/core/random.hpp>
#include <scantling/registration/feature_matching.hpp>

#include "scenes.hpp"

namespace scantling::registration {
namespace {

/// `n` random 33-D descriptors with entries in [0, 100) (the FPFH range).
FeatureMatrix random_features(Eigen::Index n, std::uint64_t seed) {
    Rng rng(seed);
    FeatureMatrix f(kFpfhDimension, n);
    for (Eigen::Index c = 0; c < n; ++c) {
        for (Eigen::Index r = 0; r < f.rows(); ++r)
            f(r, c) = static_cast<float>(rng.uniform(0, 100));
    }
    return f;
}

TEST(MatchFeatures, RecoversAPermutationOfNoisyDescriptors) {
    const FeatureMatrix target = random_features(300, 1);
    FeatureMatrix source(target.rows(), target.cols());
    Rng rng(2);
    for (Eigen::Index c = 0; c < target.cols(); ++c) {
        // Source c is target (c * 7 + 3) mod 300 with noise far below the descriptor spacing.
        const Eigen::Index t = (c * 7 + 3) % target.cols();
        for (Eigen::Index r = 0; r < target.rows(); ++r) {
            source(r, c) = target(r, t) + static_cast<float>(rng.normal(0.0, 0.5));
        }
    }
    const auto matches = match_features(source, target);
    ASSERT_EQ(matches.size(), 300u);
    for (std::size_t k = 0; k < matches.size(); ++k) {
        EXPECT_EQ(matches[k].source_index, k);
        EXPECT_EQ(matches[k].target_index, (k * 7 + 3) % 300);
        EXPECT_GT(matches[k].feature_distance, 0.0f);
    }
}

/// Nearest and second-nearest column of `data` for column `q` of `queries`, in double.
struct BruteNeighbors {
    Eigen::Index first = -1;
    double d1 = 1e300;
    double d2 = 1e300;
};

BruteNeighbors brute_nearest(const FeatureMatrix& queries, Eigen::Index q,
                             const FeatureMatrix& data) {
    BruteNeighbors b;
    for (Eigen::Index c = 0; c < data.cols(); ++c) {
        const double d = (queries.col(q) - data.col(c)).cast<double>().squaredNorm();
        if (d < b.d1) {
            b.d2 = b.d1;
            b.d1 = d;
            b.first = c;
        } else if (d < b.d2) {
            b.d2 = d;
        }
    }
    return b;
}

// The index sums float squares in rotated coordinates: it agrees with double brute force except
// where the two nearest distances differ by less than rounding (~1e-6 relative); 1e-3 leaves
// a wide margin and still keeps nearly every query.
constexpr double kUnambiguousGap = 1e-3;

bool unambiguous(const BruteNeighbors& b) { return b.d2 - b.d1 > kUnambiguousGap * b.d2; }

TEST(MatchFeatures, EqualsBruteForceMutualAndRatioMatching) {
    // Clustered descriptors (as FPFH are): 40 centres, spread 10, in [0, 100)^33.
    const FeatureMatrix centres = random_features(40, 5);
    Rng rng(6);
    auto clustered = [&](Eigen::Index n) {
        FeatureMatrix f(kFpfhDimension, n);
        for (Eigen::Index c = 0; c < n; ++c) {
            const Eigen::Index k = static_cast<Eigen::Index>(rng.uniform_index(40));
            for (Eigen::Index r = 0; r < f.rows(); ++r) {
                f(r, c) = centres(r, k) + static_cast<float>(rng.normal(0.0, 10.0));
            }
        }
        return f;
    };
    const FeatureMatrix source = clustered(400);
    const FeatureMatrix target = clustered(500);
    MatchConfig config;
    config.ratio = 0.9;
    const auto matches = match_features(source, target, config);
    std::vector<int> matched(400, -1);
    for (const auto& m : matches) matched[m.source_index] = static_cast<int>(m.target_index);
    int checked = 0;
    for (Eigen::Index i = 0; i < source.cols(); ++i) {
        const BruteNeighbors f = brute_nearest(source, i, target);
        const BruteNeighbors b = brute_nearest(target, f.first, source);
        if (!unambiguous(f) || !unambiguous(b) ||
            std::abs(std::sqrt(f.d1 / f.d2) - 0.9) < kUnambiguousGap) {
            continue;
        }
        ++checked;
        const bool expected = b.first == i && std::sqrt(f.d1) < 0.9 * std::sqrt(f.d2);
        EXPECT_EQ(matched[i], expected ? static_cast<int>(f.first) : -1) << "source " << i;
    }
    EXPECT_GT(checked, 380);
    EXPECT_GT(matches.size(), 30u);  // 45: both filters keep some and drop most
}

TEST(MatchFeatures, MutualFilterDropsOneSidedMatches) {
    FeatureMatrix target(2, 2);
    target << 0, 10, 0, 0;  // columns (0, 0) and (10, 0)
    FeatureMatrix source(2, 3);
    source << 0.1f, 0.2f, 9.0f, 0, 0, 0;  // two sources near target 0, one near target 1
    MatchConfig config;
    config.mutual = false;
    EXPECT_EQ(match_features(source, target, config).size(), 3u);
    config.mutual = true;
    const auto mutual = match_features(source, target, config);
    ASSERT_EQ(mutual.size(), 2u);
    EXPECT_EQ(mutual[0].source_index, 0u);  // target 0's nearest source is 0.1, not 0.2
    EXPECT_EQ(mutual[1].source_index, 2u);
    EXPECT_NEAR(mutual[1].feature_distance, 1.0f, 1e-6f);
}

TEST(MatchFeatures, RatioTestDropsAmbiguousMatches) {
    FeatureMatrix target(1, 3);
    target << 0.0f, 1.0f, 10.0f;
    FeatureMatrix source(1, 2);
    source << 0.5f, 9.9f;  // 0.5 is equidistant from 0 and 1; 9.9 is distinctive
    MatchConfig config;
    config.mutual = false;
    config.ratio = 0.8;
    const auto matches = match_features(source, target, config);
    ASSERT_EQ(matches.size(), 1u);
    EXPECT_EQ(matches[0].source_index, 1u);
    EXPECT_EQ(matches[0].target_index, 2u);
}

TEST(MatchFeatures, MaxCorrespondencesKeepsTheClosest) {
    FeatureMatrix target(1, 4);
    target << 0.0f, 10.0f, 20.0f, 30.0f;
    FeatureMatrix source(1, 4);
    source << 0.4f, 10.1f, 20.3f, 30.2f;
    MatchConfig config;
    config.max_correspondences = 2;
    const auto matches = match_features(source, target, config);
    ASSERT_EQ(matches.size(), 2u);
    EXPECT_EQ(matches[0].source_index, 1u);  // sorted by source index
    EXPECT_EQ(matches[1].source_index, 3u);
}

TEST(MatchFeatures, SameResultForOneAndTwoThreads) {
    const FeatureMatrix a = random_features(500, 3);
    const FeatureMatrix b = random_features(400, 4);
    MatchConfig c1;
    c1.parallel.num_threads = 1;
    MatchConfig c2 = c1;
    c2.parallel.num_threads = 2;
    const auto m1 = match_features(a, b, c1);
    const auto m2 = match_features(a, b, c2);
    ASSERT_EQ(m1.size(), m2.size());
    for (std::size_t k = 0; k < m1.size(); ++k) {
        EXPECT_EQ(m1[k].source_index, m2[k].source_index);
        EXPECT_EQ(m1[k].target_index, m2[k].target_index);
    }
}

TEST(MatchFeatures, EmptyInputGivesNoMatches) {
    EXPECT_TRUE(match_features(FeatureMatrix(33, 0), random_features(5, 1)).empty());
    EXPECT_TRUE(match_features(random_features(5, 1), FeatureMatrix(33, 0)).empty());
}

TEST(MatchFeatures, RejectsBadInputAndConfig) {
    EXPECT_THROW(match_features(FeatureMatrix::Zero(33, 2), FeatureMatrix::Zero(32, 2)),
                 InputError);
    FeatureMatrix bad = FeatureMatrix::Zero(33, 2);
    bad(4, 1) = std::nanf("");
    EXPECT_THROW(match_features(bad, FeatureMatrix::Zero(33, 2)), InputError);
    MatchConfig config;
    config.ratio = 1.5;
    EXPECT_THROW(match_features(bad, bad, config), ConfigError);
    config = {};
    config.max_correspondences = -1;
    EXPECT_THROW(match_features(bad, bad, config), ConfigError);
}

TEST(TupleFilter, KeepsRigidMatchesAndDropsMostWrongOnes) {
    const PointCloud cloud = test::sample_clutter(400, 9);
    const Eigen::Isometry3d T = test::make_pose(0.2, 0.1, 1.0, Eigen::Vector3d(1, 2, 0));
    std::vector<Eigen::Vector3d> target;
    for (const auto& p : cloud.points) target.push_back(T * p);
    std::vector<Correspondence> corr;
    Rng rng(10);
    for (std::size_t k = 0; k < 100; ++k) corr.push_back({k, k, 0.0f});  // correct
    for (std::size_t k = 100; k < 200; ++k) corr.push_back({k, 200 + rng.uniform_index(200), 0.0f});
    const auto kept = tuple_filter(corr, cloud.points, target, {}, rng);
    std::size_t good = 0;
    for (const auto& c : kept) good += c.source_index == c.target_index ? 1 : 0;
    EXPECT_GE(good, 95u);  // nearly every correct match is in some accepted triangle
    // A wrong match passes with two correct ones when its two edges happen to agree within 10 %
    // (a few % of such triangles in this 6 × 4 × 3 m box): 39 of 100 survived here. The test is
    // a filter that raises the inlier ratio (50 % -> ~70 %), not a verifier.
    EXPECT_LE(kept.size() - good, 50u);
}

TEST(TupleFilter, RejectsOutOfRangeIndicesAndBadConfig) {
    const std::vector<Eigen::Vector3d> pts(3, Eigen::Vector3d::Zero());
    const std::vector<Correspondence> corr = {{0, 0, 0.f}, {1, 1, 0.f}, {2, 3, 0.f}};
    Rng rng(1);
    EXPECT_THROW(tuple_filter(corr, pts, pts, {}, rng), InputError);
    TupleFilterConfig config;
    config.scale = 1.0;
    EXPECT_THROW(tuple_filter({}, pts, pts, config, rng), ConfigError);
    const std::vector<Correspondence> two = {{0, 0, 0.f}, {1, 1, 0.f}};
    EXPECT_EQ(tuple_filter(two, pts, pts, {}, rng).size(), 2u);
}

}  // namespace
}  // namespace scantling::registration
