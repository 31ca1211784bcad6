#include <gtest/gtest.h>

#include <scantling/core/random.hpp>
#include <scantling/core/se3.hpp>
#include <scantling/registration/factors.hpp>
#include <scantling/registration/icp.hpp>

namespace scantling::registration {
namespace {

// Central differences with h = 1e-6 on O(1) quantities: truncation ~h² and rounding
// ~1e-16 / h leave ~1e-9; 1e-7 is a clear margin that a wrong sign or term would break.
constexpr double kStep = 1e-6;
constexpr double kJacobianTol = 1e-7;

/// d f(se3_exp(delta) * T * p) / d delta at delta = 0, by central differences.
template <typename F>
Eigen::MatrixXd numeric_jacobian(const F& f, const Eigen::Isometry3d& T, const Eigen::Vector3d& p) {
    const Eigen::VectorXd f0 = f(T * p);
    Eigen::MatrixXd J(f0.size(), 6);
    for (int k = 0; k < 6; ++k) {
        const Vector6d d = Vector6d::Unit(k) * kStep;
        J.col(k) = (f(se3_exp(d) * T * p) - f(se3_exp(-d) * T * p)) / (2.0 * kStep);
    }
    return J;
}

struct Sample {
    Eigen::Isometry3d T;
    Eigen::Vector3d p, t, n;
};

Sample random_sample(Rng& rng) {
    Vector6d xi;
    for (int k = 0; k < 6; ++k) xi(k) = rng.uniform(-1.0, 1.0);
    return {se3_exp(xi), rng.normal3(2.0), rng.normal3(2.0), rng.normal3(1.0).normalized()};
}

TEST(FactorsTest, PointToPointJacobianMatchesNumericalDerivative) {
    Rng rng(11);
    for (int trial = 0; trial < 20; ++trial) {
        const Sample s = random_sample(rng);
        const auto f = [&](const Eigen::Vector3d& q) -> Eigen::VectorXd {
            return point_to_point_residual(q, s.t);
        };
        const Eigen::MatrixXd numeric = numeric_jacobian(f, s.T, s.p);
        const Matrix36d analytic = point_to_point_jacobian(s.T * s.p);
        EXPECT_LT((numeric - analytic).cwiseAbs().maxCoeff(), kJacobianTol) << trial;
    }
}

TEST(FactorsTest, PointToPlaneJacobianMatchesNumericalDerivative) {
    Rng rng(12);
    for (int trial = 0; trial < 20; ++trial) {
        const Sample s = random_sample(rng);
        const auto f = [&](const Eigen::Vector3d& q) -> Eigen::VectorXd {
            return Eigen::VectorXd::Constant(1, point_to_plane_residual(q, s.t, s.n));
        };
        const Eigen::MatrixXd numeric = numeric_jacobian(f, s.T, s.p);
        const RowVector6d analytic = point_to_plane_jacobian(s.T * s.p, s.n);
        EXPECT_LT((numeric - analytic).cwiseAbs().maxCoeff(), kJacobianTol) << trial;
    }
}

TEST(FactorsTest, GicpWeightIsTheInverseOfTheCombinedCovariance) {
    Eigen::Matrix3d C_t = Eigen::Vector3d(1e-3, 1.0, 1.0).asDiagonal();
    Eigen::Matrix3d C_s = Eigen::Vector3d(1.0, 1e-3, 1.0).asDiagonal();
    const Eigen::Matrix3d R = so3_exp(Eigen::Vector3d(0.1, -0.2, 0.3));
    const Eigen::Matrix3d Omega = gicp_weight(C_t, C_s, R);
    const Eigen::Matrix3d C = C_t + R * C_s * R.transpose();
    EXPECT_TRUE((Omega * C).isApprox(Eigen::Matrix3d::Identity(), 1e-12));
}

TEST(DegeneracyTest, PlaneFarFromTheOriginStillShowsThreeFreeDirections) {
    // A plane z = 0 around (50, −30, 0): about the origin its yaw looks like a translation.
    const Eigen::Vector3d c(50.0, -30.0, 0.0);
    Rng rng(13);
    Matrix6d H = Matrix6d::Zero();
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    double norm_sq = 0.0;
    const int n = 500;
    for (int i = 0; i < n; ++i) {
        const Eigen::Vector3d q = c + Eigen::Vector3d(rng.uniform(-2, 2), rng.uniform(-2, 2), 0);
        const RowVector6d J = point_to_plane_jacobian(q, Eigen::Vector3d::UnitZ());
        H += J.transpose() * J;
        sum += q;
        norm_sq += q.squaredNorm();
    }
    const Eigen::Vector3d mean = sum / n;
    const double radius = std::sqrt(norm_sq / n - mean.squaredNorm());
    const DegeneracyReport r = analyze_degeneracy(H, mean, radius, 1e-2);
    ASSERT_EQ(r.weak_directions.size(), 3u);
    for (const Vector6d& v : r.weak_directions) {
        // A free direction moves no point off the plane: H v = 0.
        EXPECT_LT((H * v).norm(), 1e-6 * H.norm()) << v.transpose();
    }
    EXPECT_GT(r.eigenvalues(3), 0.1);  // z, roll, pitch: comparable once scaled
    EXPECT_DOUBLE_EQ(r.eigenvalues(5), 1.0);
}

TEST(DegeneracyTest, ZeroHessianReportsAllSixDirections) {
    const DegeneracyReport r =
        analyze_degeneracy(Matrix6d::Zero(), Eigen::Vector3d::Zero(), 1.0, 1e-2);
    EXPECT_EQ(r.weak_directions.size(), 6u);
    EXPECT_TRUE(r.degenerate);
}

/// Point-to-plane Hessian of a plate (z = 0, 2000 points over 2 × 2 m) with a wall x = 1 of
/// `wall_points` points over y, z in [−1, 1] × [0, 0.02], and one y = 1 of as many.
Matrix6d plate_with_walls(int wall_points, Rng& rng) {
    Matrix6d H = Matrix6d::Zero();
    const auto add = [&H](const Eigen::Vector3d& q, const Eigen::Vector3d& n) {
        const RowVector6d J = point_to_plane_jacobian(q, n);
        H += J.transpose() * J;
    };
    for (int i = 0; i < 2000; ++i) {
        add({rng.uniform(-1, 1), rng.uniform(-1, 1), 0.0}, Eigen::Vector3d::UnitZ());
    }
    for (int i = 0; i < wall_points; ++i) {
        add({1.0, rng.uniform(-1, 1), rng.uniform(0, 0.02)}, Eigen::Vector3d::UnitX());
        add({rng.uniform(-1, 1), 1.0, rng.uniform(0, 0.02)}, Eigen::Vector3d::UnitY());
    }
    return H;
}

Eigen::Matrix<double, 6, Eigen::Dynamic> planar_basis() {
    Eigen::Matrix<double, 6, Eigen::Dynamic> B = Eigen::Matrix<double, 6, 3>::Zero();
    B(0, 0) = B(1, 1) = B(5, 2) = 1.0;  // x, y, yaw
    return B;
}

TEST(DegeneracyTest, AFreeBasisJudgesOnlyTheDirectionsASolveMayMove) {
    Rng rng(17);
    // 1 % of the points on low walls: among six directions x and y look weak next to the
    // plate's z, roll and pitch; among the planar solve's x, y, yaw they are what there is.
    const Matrix6d H = plate_with_walls(20, rng);
    const Eigen::Vector3d c = Eigen::Vector3d::Zero();
    EXPECT_TRUE(analyze_degeneracy(H, c, 0.8, 1e-1).degenerate);
    const DegeneracyReport free = analyze_degeneracy(H, c, 0.8, 1e-1, planar_basis());
    EXPECT_FALSE(free.degenerate) << free.eigenvalues.transpose();
    EXPECT_DOUBLE_EQ(free.eigenvalues(5), 1.0);  // a fixed direction
    // The bare plate: nothing in x, y or yaw, all three weak and within the basis.
    const DegeneracyReport bare =
        analyze_degeneracy(plate_with_walls(0, rng), c, 0.8, 1e-2, planar_basis());
    ASSERT_EQ(bare.weak_directions.size(), 3u);
    for (const Vector6d& v : bare.weak_directions) {
        EXPECT_NEAR(v(2), 0.0, 1e-12);  // no z, roll or pitch in a weak planar direction
        EXPECT_NEAR(v(3), 0.0, 1e-12);
        EXPECT_NEAR(v(4), 0.0, 1e-12);
    }
}

}  // namespace
}  // namespace scantling::registration
