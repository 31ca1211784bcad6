// White-box test of the private accumulation: its block formulas must equal the generic
// products of the public, numerically checked Jacobians (factors_test.cpp).
#include <gtest/gtest.h>

#include <scantling/core/normals.hpp>
#include <scantling/core/se3.hpp>
#include <scantling/registration/factors.hpp>

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

class LinearizeTest : public ::testing::TestWithParam<IcpMethod> {};

TEST_P(LinearizeTest, BlockFormulasEqualGenericJacobianProducts) {
    PointCloud target = test::sample_room_corner(3000, 31, 0.005);
    PointCloud source = test::sample_room_corner(1000, 32, 0.005);
    estimate_normals_and_covariances(target, {}, {});
    estimate_normals_and_covariances(source, {}, {});
    const KdTree tree(target.points);
    const detail::Problem p{.source_points = &source.points,
                            .source_covariances = &source.covariances,
                            .target_tree = &tree,
                            .target_normals = &target.normals,
                            .target_covariances = &target.covariances,
                            .method = GetParam(),
                            .max_correspondence_distance_m = 0.5,
                            .kernel = RobustKernel::kCauchy,
                            .kernel_scale_m = 0.05,
                            .parallel = {}};
    const Eigen::Isometry3d T =
        se3_exp((Vector6d() << 0.1, -0.05, 0.02, 0.03, 0.01, -0.04).finished());
    const detail::LinearSystem s = detail::linearize(p, T);
    const Reference ref = brute_force(p, T);
    ASSERT_GT(s.count, 500u);
    EXPECT_LT((s.H - ref.H).norm(), kRelTol * ref.H.norm());
    EXPECT_LT((s.b - ref.b).norm(), kRelTol * ref.b.norm());
}

INSTANTIATE_TEST_SUITE_P(Methods, LinearizeTest,
                         ::testing::Values(IcpMethod::kPointToPoint, IcpMethod::kPointToPlane,
                                           IcpMethod::kGeneralized),
                         [](const auto& param_info) {
                             return std::string(to_string(param_info.param));
                         });

}  // namespace
}  // namespace scantling::registration
