#include <scantling/core/error.hpp>
#include <scantling/sim/return_model.hpp>
#include <scantling/sim/sensor_mount.hpp>

#include <gtest/gtest.h>

#include <cmath>

namespace scantling::sim {
namespace {

TEST(ReturnModel, SigmaGrowsWithDistanceAsConfigured) {
    const ReturnModel model{.sigma_m = 0.01, .sigma_per_m = 0.002, .sigma_per_m2 = 0.0005};
    EXPECT_DOUBLE_EQ(model.sigma_at(0.0), 0.01);
    EXPECT_DOUBLE_EQ(model.sigma_at(4.0), 0.01 + 0.008 + 0.008);
}

TEST(ReturnModel, WeakReturnsDropWithTheirOwnProbability) {
    const ReturnModel model{
        .dropout_probability = 0.0, .weak_reflectivity = 0.1, .weak_dropout_probability = 1.0};
    Rng rng(1);
    EXPECT_FALSE(sample_return(model, 2.0, 0.05, rng).kept);
    const ReturnSample strong = sample_return(model, 2.0, 0.5, rng);
    EXPECT_TRUE(strong.kept);
    EXPECT_EQ(strong.distance_m, 2.0);
}

TEST(ReturnModel, DropoutRateMatchesTheProbability) {
    const ReturnModel model{.dropout_probability = 0.2};
    Rng rng(2);
    int kept = 0;
    const int n = 20000;
    for (int i = 0; i < n; ++i) kept += sample_return(model, 1.0, 1.0, rng).kept;
    // Binomial std of the kept fraction: sqrt(0.16 / 20000) = 0.0028; 4σ.
    EXPECT_NEAR(kept / double(n), 0.8, 0.012);
}

TEST(ReturnModel, EveryReturnConsumesTheSameNumberOfDraws) {
    const ReturnModel model{.sigma_m = 0.1, .dropout_probability = 0.5};
    Rng a(3), b(3);
    for (int i = 0; i < 100; ++i) sample_return(model, 1.0, 1.0, a);
    for (int i = 0; i < 100; ++i) {
        b.uniform();
        b.normal();
    }
    EXPECT_EQ(a.next_u64(), b.next_u64());
}

TEST(ReturnModel, LambertianReflectivityIsAlbedoTimesCosine) {
    const Eigen::Vector3d d = Eigen::Vector3d(1.0, 0.0, -1.0).normalized();
    EXPECT_NEAR(lambertian_reflectivity(0.6, d, Eigen::Vector3d::UnitZ()), 0.6 * std::sqrt(0.5),
                1e-15);
    // A normal turned away (should not happen with RayHit) gives 0, not a negative value.
    EXPECT_EQ(lambertian_reflectivity(0.6, d, -Eigen::Vector3d::UnitZ()), 0.0);
}

TEST(ReturnModel, BadValuesThrowNamingTheField) {
    ReturnModel model;
    model.dropout_probability = 1.5;
    try {
        model.validate("lidar.returns");
        ADD_FAILURE() << "no error";
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("lidar.returns.dropout_probability = 1.5"),
                  std::string::npos);
    }
    model = ReturnModel{};
    model.sigma_per_m = std::nan("");
    EXPECT_THROW(model.validate("x"), ConfigError);
}

TEST(SensorMount, NonRigidMountsAreRejected) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    EXPECT_NO_THROW(validate_mount(T, "s"));
    T.linear()(0, 0) = -1.0;  // a reflection
    EXPECT_THROW(validate_mount(T, "s"), ConfigError);
    T = Eigen::Isometry3d::Identity();
    T.translation().y() = INFINITY;
    EXPECT_THROW(validate_mount(T, "s"), ConfigError);
}

TEST(SensorMount, UnknownTagsGetTheDefaultSurface) {
    WorldMetadata metadata;
    metadata.surfaces.push_back(Surface{0, "dark", false, 0.1});
    EXPECT_EQ(surface_of(metadata, 0).albedo, 0.1);
    EXPECT_EQ(surface_of(metadata, 5).albedo, 0.5);
    EXPECT_TRUE(surface_of(metadata, -1).textured);
}

}  // namespace
}  // namespace scantling::sim
