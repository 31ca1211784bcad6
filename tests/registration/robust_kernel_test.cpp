#include <gtest/gtest.h>

#include <string>

#include <scantling/core/error.hpp>
#include <scantling/registration/robust_kernel.hpp>

namespace scantling::registration {
namespace {

constexpr RobustKernel kAll[] = {RobustKernel::kNone, RobustKernel::kHuber, RobustKernel::kCauchy,
                                 RobustKernel::kGemanMcClure, RobustKernel::kTukey};
// Central difference of rho with h = 1e-6 on O(0.1..10) values: error ~1e-10; 1e-7 is margin.
constexpr double kStep = 1e-6;
constexpr double kDerivativeTol = 1e-7;

class RobustKernelTest : public ::testing::TestWithParam<RobustKernel> {};

TEST_P(RobustKernelTest, WeightTimesResidualIsTheLossDerivative) {
    const RobustKernel k = GetParam();
    const double scale = 0.7;
    // Avoid the kinks of Huber and Tukey at |r| = scale, where rho' is continuous but the
    // central difference straddles a change of formula.
    for (double r : {-5.0, -1.3, -0.69, -0.2, 0.01, 0.3, 0.71, 1.0, 2.5, 9.0}) {
        const double derivative =
            (robust_loss(k, r + kStep, scale) - robust_loss(k, r - kStep, scale)) / (2 * kStep);
        EXPECT_NEAR(robust_weight(k, r, scale) * r, derivative, kDerivativeTol)
            << to_string(k) << " r = " << r;
    }
}

TEST_P(RobustKernelTest, BehavesAsLeastSquaresNearZero) {
    const RobustKernel k = GetParam();
    EXPECT_DOUBLE_EQ(robust_weight(k, 0.0, 1.0), 1.0);
    EXPECT_NEAR(robust_loss(k, 1e-3, 1.0), 0.5e-6, 1e-11);
    for (double r = -10.0; r <= 10.0; r += 0.37) {
        const double w = robust_weight(k, r, 1.0);
        EXPECT_GE(w, 0.0);
        EXPECT_LE(w, 1.0);
    }
}

TEST_P(RobustKernelTest, NameRoundTrips) {
    EXPECT_EQ(robust_kernel_from_string(to_string(GetParam())), GetParam());
}

INSTANTIATE_TEST_SUITE_P(All, RobustKernelTest, ::testing::ValuesIn(kAll),
                         [](const auto& param_info) {
                             return std::string(to_string(param_info.param));
                         });

TEST(RobustKernelTest, RobustKernelsDownWeightLargeResiduals) {
    EXPECT_DOUBLE_EQ(robust_weight(RobustKernel::kHuber, 4.0, 1.0), 0.25);
    EXPECT_DOUBLE_EQ(robust_weight(RobustKernel::kCauchy, 2.0, 1.0), 0.2);
    EXPECT_DOUBLE_EQ(robust_weight(RobustKernel::kGemanMcClure, 1.0, 1.0), 0.25);
    EXPECT_DOUBLE_EQ(robust_weight(RobustKernel::kTukey, 1.5, 1.0), 0.0);
}

TEST(RobustKernelTest, UnknownNameThrowsConfigErrorListingTheNames) {
    try {
        robust_kernel_from_string("welsch", "icp.kernel");
        FAIL() << "expected ConfigError";
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("icp.kernel = \"welsch\""), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("geman_mcclure"), std::string::npos);
    }
}

}  // namespace
}  // namespace scantling::registration
