// Tests of the ICP family's private pass and what rests on it: the block formulas must equal the
// generic products of the public, numerically checked Jacobians (factors_test.cpp), the scores
// must add up to the gradient, back faces must be dropped, and the covariance models
// (detail/icp_covariance) must be consistent in Monte-Carlo runs with known truth.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <map>

#include <scantling/core/normals.hpp>
#include <scantling/core/random.hpp>
#include <scantling/core/se3.hpp>
#include <scantling/registration/factors.hpp>
#include <scantling/registration/icp.hpp>

#include "../../src/registration/detail/icp_covariance.hpp"
#include "../../src/registration/detail/linearize.hpp"
#include "scenes.hpp"

namespace scantling::registration {
namespace {

// Sums of ~1000 terms of size ~10: rounding differences between the two summation forms stay
// near 1e-12 relative; 1e-9 still catches any wrong term.
constexpr double kRelTol = 1e-9;

struct Reference {
    Matrix6d H = Matrix6d::Zero();
    Vector6d b = Vector6d::Zero();
};

Reference brute_force(const detail::Problem& p, const Eigen::Isometry3d& T) {
    Reference ref;
    for (std::size_t i = 0; i < p.source_points->size(); ++i) {
        const Eigen::Vector3d q = T * (*p.source_points)[i];
        const auto nn = p.target_tree->nearest(q);
        if (!nn ||
            nn->distance_sq_m2 > p.max_correspondence_distance_m * p.max_correspondence_distance_m)
            continue;
        const Eigen::Vector3d& t = p.target_tree->points()[nn->index];
        const double w = robust_weight(p.kernel, std::sqrt(nn->distance_sq_m2), p.kernel_scale_m);
        if (p.method == IcpMethod::kPointToPlane) {
            const Eigen::Vector3d& n = (*p.target_normals)[nn->index];
            const double r = point_to_plane_residual(q, t, n);
            const RowVector6d J = point_to_plane_jacobian(q, n);
            const double wp = robust_weight(p.kernel, r, p.kernel_scale_m);
            ref.H += wp * J.transpose() * J;
            ref.b += wp * r * J.transpose();
            continue;
        }
        const Eigen::Matrix3d Omega = p.method == IcpMethod::kGeneralized
                                          ? gicp_weight((*p.target_covariances)[nn->index],
                                                        (*p.source_covariances)[i], T.linear())
                                          : Eigen::Matrix3d::Identity();
        const Matrix36d J = point_to_point_jacobian(q);
        ref.H += w * J.transpose() * Omega * J;
        ref.b += w * J.transpose() * Omega * point_to_point_residual(q, t);
    }
    return ref;
}

/// Two samples of the room corner with normals and covariances (built once).
struct RoomPair {
    PointCloud target = with_normals(test::sample_room_corner(3000, 31, 0.005));
    PointCloud source = with_normals(test::sample_room_corner(1000, 32, 0.005));
    KdTree tree{target.points};

    static PointCloud with_normals(PointCloud c) {
        estimate_normals_and_covariances(c, {}, {});
        return c;
    }
    detail::Problem problem(IcpMethod method, RobustKernel kernel) const {
        return {.source_points = &source.points,
                .source_covariances = &source.covariances,
                .target_tree = &tree,
                .target_normals = &target.normals,
                .target_covariances = &target.covariances,
                .method = method,
                .max_correspondence_distance_m = 0.5,
                .kernel = kernel,
                .kernel_scale_m = 0.05,
                .parallel = {},
                .front_normals = nullptr};
    }
};

const RoomPair& room_pair() {
    static const RoomPair pair;
    return pair;
}

class LinearizeTest : public ::testing::TestWithParam<IcpMethod> {};

TEST_P(LinearizeTest, BlockFormulasEqualGenericJacobianProducts) {
    const detail::Problem p = room_pair().problem(GetParam(), RobustKernel::kCauchy);
    const Eigen::Isometry3d T =
        se3_exp((Vector6d() << 0.1, -0.05, 0.02, 0.03, 0.01, -0.04).finished());
    const detail::LinearSystem s = detail::linearize(p, T);
    const Reference ref = brute_force(p, T);
    ASSERT_GT(s.count, 500u);
    EXPECT_LT((s.H - ref.H).norm(), kRelTol * ref.H.norm());
    EXPECT_LT((s.b - ref.b).norm(), kRelTol * ref.b.norm());
}

TEST_P(LinearizeTest, RecordedScoresSumToTheGradientAndGroupByCell) {
    const detail::Problem p = room_pair().problem(GetParam(), RobustKernel::kNone);
    const Eigen::Isometry3d T = se3_exp((Vector6d() << 0.05, 0, 0, 0, 0.02, 0).finished());
    detail::ScoreRecord record{.cell_size_m = 1.0, .scores = {}};
    const detail::LinearSystem s = detail::linearize(p, T, &record);
    ASSERT_EQ(record.scores.size(), p.source_points->size());
    Vector6d sum = Vector6d::Zero();
    Matrix6d outer = Matrix6d::Zero();
    std::size_t valid = 0;
    for (const detail::CellScore& c : record.scores) {
        if (!c.valid) continue;
        sum += c.score;
        outer += c.score * c.score.transpose();
        ++valid;
    }
    EXPECT_EQ(valid, s.count);
    EXPECT_LT((sum - s.b).norm(), kRelTol * s.b.norm());
    // One cell per point gives Σ g gᵀ (and Σ A Aᵀ = Σ Jᵀ J = H when Ω = 1, w = 1); one cell
    // for all gives b bᵀ.
    for (std::size_t i = 0; i < record.scores.size(); ++i) {
        record.scores[i].cell = {static_cast<std::int64_t>(i), 0, 0};
    }
    const detail::ClusteredScores each = detail::cluster_scores(record.scores);
    EXPECT_EQ(each.num_cells, s.count);
    EXPECT_LT((each.outer - outer).norm(), kRelTol * outer.norm());
    if (GetParam() != IcpMethod::kGeneralized) {
        EXPECT_LT((each.sensitivity_outer - s.H).norm(), kRelTol * s.H.norm());
    }
    for (detail::CellScore& c : record.scores) c.cell = {0, 0, 0};
    const detail::ClusteredScores one = detail::cluster_scores(record.scores);
    EXPECT_EQ(one.num_cells, 1u);
    const Matrix6d bbT = s.b * s.b.transpose();
    EXPECT_LT((one.outer - bbT).norm(), kRelTol * bbT.norm());
}

TEST(LinearizeTest, MapErrorAddsSigmaSquaredTimesTheCellSensitivitiesToTheSandwich) {
    const detail::Problem p = room_pair().problem(IcpMethod::kPointToPlane, RobustKernel::kNone);
    detail::ScoreRecord record{.cell_size_m = 1.0, .scores = {}};
    const detail::LinearSystem s = detail::linearize(p, Eigen::Isometry3d::Identity(), &record);
    const detail::ClusteredScores c = detail::cluster_scores(record.scores);
    const detail::DofBasis basis = Matrix6d::Identity();
    detail::CovarianceSettings settings{
        .model = IcpCovariance::kClusteredSandwich, .cell_size_m = 1.0, .map_error_sigma_m = 0.0};
    const auto u0 = detail::estimate_uncertainty(s, basis, settings, &record, false);
    settings.map_error_sigma_m = 0.002;
    const auto u2 = detail::estimate_uncertainty(s, basis, settings, &record, false);
    ASSERT_TRUE(u0.covariance && u2.covariance);
    const Matrix6d H_inv = s.H.inverse();
    const Matrix6d added = 0.002 * 0.002 * H_inv * c.sensitivity_outer * H_inv;
    EXPECT_LT((*u2.covariance - *u0.covariance - added).norm(), 1e-6 * added.norm());
    EXPECT_TRUE((*u2.covariance * u2.information).isApprox(Matrix6d::Identity(), 1e-6));
}

/// Point-to-plane from `source` (already in the target frame) to `target`, 0.5 m reach.
detail::Problem plane_problem(const PointCloud& source, const PointCloud& target,
                              const KdTree& tree) {
    return {.source_points = &source.points,
            .target_tree = &tree,
            .target_normals = &target.normals,
            .method = IcpMethod::kPointToPlane,
            .max_correspondence_distance_m = 0.5,
            .parallel = {}};
}

TEST(LinearizeTest, BackFaceRejectionDropsExactlyThePairsFacingAwayFromTheSourceOrigin) {
    const PointCloud target = test::sample_plated_room_corner(20000, 41, 0.01, true);
    const PointCloud source = test::sample_plated_room_corner(2000, 42, 0.01, false);
    const KdTree tree(target.points);
    detail::Problem p = plane_problem(source, target, tree);
    const detail::LinearSystem all = detail::linearize(p, Eigen::Isometry3d::Identity());
    p.front_normals = &target.normals;  // the source origin, the sensor, is the room's centre
    p.back_faces = BackFaces::kReject;
    const detail::LinearSystem front = detail::linearize(p, Eigen::Isometry3d::Identity());
    std::size_t facing = 0;
    for (const Eigen::Vector3d& q : source.points) {
        const std::size_t j = tree.nearest(q)->index;
        facing += target.normals[j].dot(-target.points[j]) > 0.0 ? 1 : 0;
    }
    EXPECT_EQ(all.count, source.size());
    EXPECT_EQ(front.count, facing);
    // Hidden faces 1 cm behind the visible ones hold a good share of the nearest points.
    EXPECT_LT(front.count, source.size() * 9 / 10);
    constexpr double kThicknessSqM2 = 1e-4;  // each hidden-face pair: residual = 1 cm
    EXPECT_GT(all.cost, 0.99 * kThicknessSqM2 * static_cast<double>(source.size() - facing));
    EXPECT_LT(front.cost, 0.1 * all.cost);
}

TEST(LinearizeTest, PreferringFrontFacesKeepsEveryPairAndMostlyTheVisibleFace) {
    const PointCloud target = test::sample_plated_room_corner(20000, 41, 0.01, true);
    const PointCloud source = test::sample_plated_room_corner(2000, 42, 0.01, false);
    const KdTree tree(target.points);
    detail::Problem p = plane_problem(source, target, tree);
    p.front_normals = &target.normals;
    const detail::LinearSystem front = detail::linearize(p, Eigen::Isometry3d::Identity());
    p.back_faces = BackFaces::kReject;
    const detail::LinearSystem rejected = detail::linearize(p, Eigen::Isometry3d::Identity());
    EXPECT_EQ(front.count, source.size());  // no pair lost, unlike kReject
    EXPECT_LT(rejected.count, source.size() * 9 / 10);
    // The scan lies on the visible faces; each hidden-face pair adds (1 cm)².
    p.front_normals = nullptr;
    const detail::LinearSystem kept = detail::linearize(p, Eigen::Isometry3d::Identity());
    // Measured: cost 0.011 against 0.103 with the nearest points kept (what remains: pairs whose
    // 8 nearest hold no front face).
    EXPECT_LT(front.cost, 0.2 * kept.cost);
}

TEST(LinearizeTest, PreferringFrontFacesKeepsTheNearestWhereNoNormalFacesTheSensor) {
    // One face per plate, normals flipped: every target point faces away from the sensor (as
    // when a map's normals were oriented towards another viewpoint).
    PointCloud target = test::sample_plated_room_corner(20000, 43, 0.01, false);
    for (Eigen::Vector3d& n : target.normals) n = -n;
    const PointCloud source = test::sample_plated_room_corner(2000, 44, 0.01, false);
    const KdTree tree(target.points);
    detail::Problem p = plane_problem(source, target, tree);
    const detail::LinearSystem plain = detail::linearize(p, Eigen::Isometry3d::Identity());
    p.front_normals = &target.normals;
    const detail::LinearSystem preferred = detail::linearize(p, Eigen::Isometry3d::Identity());
    p.back_faces = BackFaces::kReject;
    const detail::LinearSystem rejected = detail::linearize(p, Eigen::Isometry3d::Identity());
    EXPECT_EQ(plain.count, source.size());
    EXPECT_EQ(preferred.count, plain.count);
    EXPECT_DOUBLE_EQ(preferred.cost, plain.cost);
    EXPECT_EQ(rejected.count, 0u);
}

INSTANTIATE_TEST_SUITE_P(Methods, LinearizeTest,
                         ::testing::Values(IcpMethod::kPointToPoint, IcpMethod::kPointToPlane,
                                           IcpMethod::kGeneralized),
                         [](const auto& param_info) {
                             return std::string(to_string(param_info.param));
                         });

// ---- Covariance models against known truth (Monte-Carlo over seeded trials) ----

constexpr int kTrials = 30;
constexpr double kCorrelationCellM = 0.5;  // the source's errors are shared within such cells

const PointCloud& room_map() {
    static const PointCloud map = [] {
        PointCloud c = test::sample_room_corner(30000, 51, 0.0);
        estimate_normals(c);
        return c;
    }();
    return map;
}

/// A scan of the room corner with 2 mm white noise plus one offset ~ N(0, σ² I) per 0.5 m
/// cell (errors neighbours share, as a scanner's or a map's systematic errors are), given in
/// the sensor frame of the true pose.
PointCloud correlated_scan(std::uint64_t seed, double cell_sigma_m, const Eigen::Isometry3d& T) {
    PointCloud scan = test::sample_room_corner(3000, seed, 0.002);
    Rng rng(seed + 1000);
    std::map<std::array<std::int64_t, 3>, Eigen::Vector3d> offsets;
    for (Eigen::Vector3d& p : scan.points) {
        const Eigen::Vector3d c = (p / kCorrelationCellM).array().floor();
        const auto [it, is_new] =
            offsets.try_emplace({static_cast<std::int64_t>(c.x()), static_cast<std::int64_t>(c.y()),
                                 static_cast<std::int64_t>(c.z())});
        if (is_new) it->second = rng.normal3(cell_sigma_m);  // first-seen order: seeded
        p += it->second;
    }
    return transformed(scan, T.inverse());
}

double nees(const RegistrationResult& r, const Eigen::Isometry3d& T_true) {
    const Vector6d e = se3_log(T_true * r.T_target_source.inverse());  // left error (result.hpp)
    return e.dot(r.covariance->ldlt().solve(e));
}

struct MeanNees {
    double hessian = 0.0, clustered = 0.0;
};

MeanNees mean_nees(double cell_sigma_m) {
    static const KdTree room_tree(room_map().points);
    IcpConfig c;
    c.max_correspondence_distance_m = 0.3;
    c.map_error_sigma_m = 0.0;  // the data-driven part alone (the prior term is tested above)
    MeanNees m;
    for (int i = 0; i < kTrials; ++i) {
        Rng rng(static_cast<std::uint64_t>(700 + i));
        const Eigen::Isometry3d T_true = test::make_pose(
            rng.uniform(-0.02, 0.02), rng.uniform(-0.02, 0.02), rng.uniform(-0.02, 0.02),
            Eigen::Vector3d(rng.uniform(-0.03, 0.03), rng.uniform(-0.03, 0.03), 0.01));
        const PointCloud scan =
            correlated_scan(static_cast<std::uint64_t>(i), cell_sigma_m, T_true);
        for (IcpCovariance model : {IcpCovariance::kHessian, IcpCovariance::kClusteredSandwich}) {
            c.covariance = model;
            const RegistrationResult r =
                align(scan, room_map(), room_tree, Eigen::Isometry3d::Identity(), c);
            EXPECT_TRUE(r.converged && r.covariance) << r.status;
            if (!r.covariance) continue;
            (model == IcpCovariance::kHessian ? m.hessian : m.clustered) +=
                nees(r, T_true) / kTrials;
        }
    }
    return m;
}

// Mean NEES of 30 consistent 6-DoF trials lies in [4.7, 7.4] with 95 % probability; the
// clustered estimate from ~60 cells scatters more than a known covariance, hence the wider band.
// Measured (residual sandwich, map_error_sigma_m = 0): shared errors 20.3 (Hessian) and 4.5
// (clustered); independent noise 8.7 and 5.1 (the Hessian is slightly over-confident even here:
// map samples and normals at the box edges).
constexpr double kNeesLow = 3.5;
constexpr double kNeesHigh = 8.5;

TEST(IcpCovarianceTest, ClusteredModelIsConsistentWhereNeighboursShareTheirErrors) {
    const MeanNees m = mean_nees(0.003);
    EXPECT_GT(m.hessian, 2.0 * kNeesHigh);  // the error the Hessian model cannot see
    EXPECT_GT(m.clustered, kNeesLow);
    EXPECT_LT(m.clustered, kNeesHigh);
}

TEST(IcpCovarianceTest, ClusteredModelIsNotInflatedForIndependentNoise) {
    const MeanNees m = mean_nees(0.0);
    EXPECT_GT(m.clustered, kNeesLow);  // an N / G inflation would give ~0.1
    EXPECT_LT(m.clustered, kNeesHigh);
}

TEST(IcpCovarianceTest, RejectingBackFacesRemovesTheBiasOfAMapWithBothPlateFaces) {
    const PointCloud map = test::sample_plated_room_corner(20000, 61, 0.01, true);
    const Eigen::Isometry3d T_true = test::make_pose(0.01, -0.01, 0.02, {0.02, -0.01, 0.03});
    const PointCloud scan =
        transformed(test::sample_plated_room_corner(3000, 62, 0.01, false), T_true.inverse());
    IcpConfig c;
    c.max_correspondence_distance_m = 0.3;
    c.back_faces = BackFaces::kKeep;
    const RegistrationResult both = align(scan, map, Eigen::Isometry3d::Identity(), c);
    c.back_faces = BackFaces::kReject;
    const RegistrationResult front = align(scan, map, Eigen::Isometry3d::Identity(), c);
    c.back_faces = BackFaces::kPreferFront;  // the default
    const RegistrationResult preferred = align(scan, map, Eigen::Isometry3d::Identity(), c);
    // Measured 8.3 mm (pulled towards the hidden faces 1 cm behind the walls) and 0.17 mm.
    EXPECT_GT(pose_error(both.T_target_source, T_true).translation_m, 0.003);
    EXPECT_LT(pose_error(front.T_target_source, T_true).translation_m, 0.001);
    EXPECT_LT(pose_error(preferred.T_target_source, T_true).translation_m, 0.001);
    EXPECT_TRUE(front.converged) << front.status;
    EXPECT_TRUE(preferred.converged) << preferred.status;
}

}  // namespace
}  // namespace scantling::registration
