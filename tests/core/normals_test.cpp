#include <scantling/core/error.hpp>
#include <scantling/core/normals.hpp>

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>
#include <Eigen/Eigenvalues>

namespace scantling {
namespace {

// Noise-free planar points: the PCA normal is exact up to rounding.
constexpr double kPlaneNormalTol = 1e-9;
// 10k points on a 1 m sphere: a 20-neighbour patch spans ~0.09 rad of arc, and the lattice is
// only near-uniform, so the patch is slightly lopsided (worst seen: 0.0105 rad). A wrong normal
// (tangent, or the middle eigenvector) would be off by ~1.57 rad.
constexpr double kSphereNormalTolRad = 0.02;

/// Grid of points on the plane through `origin` spanned by the two unit vectors.
PointCloud plane_cloud(const Eigen::Vector3d& origin, const Eigen::Vector3d& u,
                       const Eigen::Vector3d& v, int side, double spacing_m) {
    PointCloud cloud;
    for (int i = 0; i < side; ++i) {
        for (int j = 0; j < side; ++j) cloud.points.push_back(origin + spacing_m * (i * u + j * v));
    }
    return cloud;
}

/// Fibonacci-lattice sphere: near-uniform spacing, so neighbourhoods are nearly symmetric.
PointCloud sphere_cloud(std::size_t n, double radius_m) {
    const double golden_angle = std::numbers::pi * (3.0 - std::sqrt(5.0));
    PointCloud cloud;
    for (std::size_t i = 0; i < n; ++i) {
        const double z = 1.0 - 2.0 * (static_cast<double>(i) + 0.5) / static_cast<double>(n);
        const double r = std::sqrt(1.0 - z * z);
        const double phi = golden_angle * static_cast<double>(i);
        cloud.points.push_back(radius_m * Eigen::Vector3d(r * std::cos(phi), r * std::sin(phi), z));
    }
    return cloud;
}

TEST(Normals, PlanePointsGetThePlaneNormalFacingTheViewpoint) {
    const Eigen::Vector3d u = Eigen::Vector3d(1, 1, 0).normalized();
    const Eigen::Vector3d v = Eigen::Vector3d(0, 0, 1);
    const Eigen::Vector3d plane_normal = u.cross(v);
    PointCloud cloud = plane_cloud(Eigen::Vector3d(5, 0, 0), u, v, 30, 0.05);
    NormalEstimationConfig config;
    config.viewpoint = Eigen::Vector3d(5, 0, 0) + 10.0 * plane_normal;
    estimate_normals(cloud, config);
    ASSERT_EQ(cloud.normals.size(), cloud.size());
    for (const auto& n : cloud.normals) EXPECT_LT((n - plane_normal).norm(), kPlaneNormalTol);
    config.viewpoint = Eigen::Vector3d(5, 0, 0) - 10.0 * plane_normal;
    estimate_normals(cloud, config);
    for (const auto& n : cloud.normals) EXPECT_LT((n + plane_normal).norm(), kPlaneNormalTol);
}

TEST(Normals, SphereNormalsAreRadialAndPointInwardsToTheCentreViewpoint) {
    PointCloud cloud = sphere_cloud(10000, 1.0);
    estimate_normals(cloud, NormalEstimationConfig{});  // viewpoint = centre
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const double cos_angle = cloud.normals[i].dot(-cloud.points[i].normalized());
        EXPECT_GT(cos_angle, std::cos(kSphereNormalTolRad)) << "point " << i;
        EXPECT_NEAR(cloud.normals[i].norm(), 1.0, 1e-12);
    }
}

TEST(Normals, ReusingATreeGivesTheSameNormals) {
    PointCloud a = sphere_cloud(2000, 2.0);
    PointCloud b = a;
    estimate_normals(a);
    estimate_normals(b, KdTree(b.points));
    EXPECT_EQ(a.normals, b.normals);
}

TEST(Normals, OneAndTwoThreadsAreBitIdentical) {
    PointCloud one = sphere_cloud(20000, 3.0);
    PointCloud two = one;
    NormalEstimationConfig nc;
    CovarianceConfig cc;
    nc.parallel.num_threads = 1;
    estimate_normals_and_covariances(one, nc, cc);
    nc.parallel.num_threads = 2;
    estimate_normals_and_covariances(two, nc, cc);
    EXPECT_EQ(one.normals, two.normals);
    EXPECT_EQ(one.covariances, two.covariances);
}

TEST(Covariances, PlanarPatchHasZeroSmallestEigenvalueAlongTheNormal) {
    PointCloud cloud = plane_cloud(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(),
                                   Eigen::Vector3d::UnitY(), 20, 0.1);
    CovarianceConfig config;
    config.regularize = false;
    estimate_covariances(cloud, config);
    for (const auto& cov : cloud.covariances) {
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
        EXPECT_NEAR(eig.eigenvalues()(0), 0.0, 1e-15);
        EXPECT_GT(eig.eigenvalues()(1), 1e-3);  // ~(0.1 m spacing)² spread in the plane
        EXPECT_NEAR(std::abs(eig.eigenvectors().col(0).z()), 1.0, 1e-9);
    }
}

TEST(Covariances, RegularisedPlanarPatchHasEigenvaluesEpsilonOneOne) {
    PointCloud cloud = plane_cloud(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(),
                                   Eigen::Vector3d::UnitZ(), 20, 0.1);
    CovarianceConfig config;
    config.epsilon = 1e-3;
    estimate_covariances(cloud, config);
    for (const auto& cov : cloud.covariances) {
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
        EXPECT_NEAR(eig.eigenvalues()(0), 1e-3, 1e-12);
        EXPECT_NEAR(eig.eigenvalues()(1), 1.0, 1e-12);
        EXPECT_NEAR(eig.eigenvalues()(2), 1.0, 1e-12);
        EXPECT_NEAR(std::abs(eig.eigenvectors().col(0).y()), 1.0, 1e-9);
    }
}

TEST(Covariances, RegularisationKeepsTheRawSmallestEigenvectorAndMatchesTheCombinedPass) {
    PointCloud raw = sphere_cloud(3000, 1.5);
    PointCloud regularised = raw;
    PointCloud combined = raw;
    CovarianceConfig config;
    config.regularize = false;
    estimate_covariances(raw, config);
    config.regularize = true;
    estimate_covariances(regularised, config);
    estimate_normals_and_covariances(combined, NormalEstimationConfig{}, config);
    EXPECT_EQ(combined.covariances, regularised.covariances);
    for (std::size_t i = 0; i < raw.size(); i += 7) {
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> a(raw.covariances[i]);
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> b(regularised.covariances[i]);
        EXPECT_NEAR(std::abs(a.eigenvectors().col(0).dot(b.eigenvectors().col(0))), 1.0, 1e-9);
        EXPECT_NEAR(std::abs(combined.normals[i].dot(a.eigenvectors().col(0))), 1.0, 1e-9);
    }
}

TEST(Normals, RepeatedPointGetsUpwardNormal) {
    PointCloud cloud;
    cloud.points.assign(5, Eigen::Vector3d(0.1, 0.2, 0.3));
    NormalEstimationConfig config;
    config.viewpoint = Eigen::Vector3d(0, 0, 10);
    estimate_normals(cloud, config);
    for (const auto& n : cloud.normals) EXPECT_EQ(n, Eigen::Vector3d::UnitZ());
}

TEST(Normals, RejectsTooFewPointsAndBadConfig) {
    PointCloud two;
    two.points = {{0, 0, 0}, {1, 0, 0}};
    EXPECT_THROW(estimate_normals(two), InputError);
    EXPECT_THROW(estimate_covariances(two), InputError);
    PointCloud empty;
    EXPECT_THROW(estimate_normals(empty), InputError);
    PointCloud cloud = sphere_cloud(50, 1.0);
    EXPECT_THROW(estimate_normals(cloud, KdTree(two.points)), InputError);
    NormalEstimationConfig two_neighbors;
    two_neighbors.num_neighbors = 2;
    EXPECT_THROW(estimate_normals(cloud, two_neighbors), ConfigError);
    CovarianceConfig bad_eps;
    bad_eps.epsilon = 0.0;
    EXPECT_THROW(estimate_covariances(cloud, bad_eps), ConfigError);
    CovarianceConfig other_k;
    other_k.num_neighbors = 10;
    EXPECT_THROW(estimate_normals_and_covariances(cloud, {}, other_k), ConfigError);
    cloud.points[7].z() = std::nan("");
    EXPECT_THROW(estimate_normals(cloud), InputError);
}

}  // namespace
}  // namespace scantling
