#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <scantling/core/error.hpp>
#include <scantling/core/random.hpp>
#include <scantling/core/se3.hpp>
#include <scantling/registration/stein_icp.hpp>

#include "../../src/registration/detail/stein_gradient.hpp"
#include "scenes.hpp"

namespace scantling::registration {
namespace {

constexpr double kPi = std::numbers::pi;
// Points noisy at 5 mm and ~2000 per scan: the mode lands within a few mm and a few 0.1°; the
// tolerances leave room for the spread of the σ = 5 cm posterior the particles sample.
constexpr double kTranslationTolM = 0.02;
constexpr double kRotationTolRad = 0.01;

struct Rect {
    Eigen::Vector3d origin, u, v;
};

PointCloud sample(const std::vector<Rect>& rects, std::size_t n, std::uint64_t seed,
                  double noise_sigma_m = 0.005) {
    Rng rng(seed);
    std::vector<double> areas;
    double total = 0.0;
    for (const Rect& r : rects) total += areas.emplace_back(r.u.cross(r.v).norm());
    PointCloud cloud;
    for (std::size_t i = 0; i < n; ++i) {
        double pick = rng.uniform(0.0, total);
        std::size_t k = 0;
        while (k + 1 < rects.size() && pick > areas[k]) pick -= areas[k++];
        const Rect& r = rects[k];
        cloud.normals.push_back(r.u.cross(r.v).normalized());
        cloud.points.push_back(r.origin + rng.uniform() * r.u + rng.uniform() * r.v +
                               rng.normal3(noise_sigma_m));
    }
    return cloud;
}

/// Exact normals. Two parallel walls 2 m apart and a floor, 20 m long in x: x is unconstrained.
std::vector<Rect> corridor() {
    const Eigen::Vector3d ex(20, 0, 0), ey(0, 2, 0), ez(0, 0, 2.5);
    return {{{-10, -1, 0}, ex, ey}, {{-10, -1, 0}, ex, ez}, {{-10, 1, 0}, ex, ez}};
}

/// A closed 6 × 4 × 3 m box centred on the origin: yaw θ and θ + π fit equally.
std::vector<Rect> rectangular_room() {
    const Eigen::Vector3d o(-3, -2, -1.5), ex(6, 0, 0), ey(0, 4, 0), ez(0, 0, 3);
    return {{o, ex, ey},      {o + ez, ex, ey}, {o, ex, ez},
            {o + ey, ex, ez}, {o, ey, ez},      {o + ex, ey, ez}};
}

/// Floor and two walls of a 4 × 4 × 3 m corner, normals into the room: every DoF constrained.
std::vector<Rect> plated_corner() {
    const Eigen::Vector3d o(-2, -2, 0), ex(4, 0, 0), ey(0, 4, 0), ez(0, 0, 3);
    return {{o, ex, ey}, {o, ey, ez}, {o, ez, ex}};
}

struct Pair {
    PointCloud source, target;
};

/// Target sampled in its frame; source sampled independently and expressed in a frame such
/// that T_target_source = T_true.
Pair make_pair(const PointCloud& target, PointCloud source_in_target,
               const Eigen::Isometry3d& T_true) {
    return {transformed(source_in_target, T_true.inverse()), target};
}

double spread(const SteinIcpResult& r, int dof) { return std::sqrt(r.covariance(dof, dof)); }

TEST(SteinIcp, ModeRecoversKnownPoseOnAsymmetricSceneWithSmallCovariance) {
    const Eigen::Isometry3d T_true = test::make_pose(0.02, -0.01, 0.1, {0.15, -0.1, 0.05});
    const Pair pair = make_pair(test::sample_room_corner(3000, 1, 0.005),
                                test::sample_room_corner(2000, 2, 0.005), T_true);
    // Point-to-point on samples ~0.1 m apart: the residuals are as large as σ, so the default
    // batch's noise, λ ≈ (N / B)(s / σ)² ≈ 20 times the posterior's, would force tiny Langevin
    // steps that do not mix within refine_iterations; B = 400 keeps λ ≈ 4.
    SteinIcpConfig config;
    config.num_particles = 60;
    config.batch_size = 400;
    const SteinIcpResult r =
        stein_icp(pair.source, pair.target, Eigen::Isometry3d::Identity(), config);
    const PoseError e = pose_error(r.T_target_source, T_true);
    EXPECT_LT(e.translation_m, kTranslationTolM);
    EXPECT_LT(e.rotation_rad, kRotationTolRad);
    EXPECT_EQ(r.num_modes, 1);
    EXPECT_GT(r.fitness, 0.95);
    for (int d = 0; d < 3; ++d) EXPECT_LT(spread(r, d), kTranslationTolM) << "dof " << d;
    for (int d = 3; d < 6; ++d) EXPECT_LT(spread(r, d), kRotationTolRad) << "dof " << d;
}

TEST(SteinIcp, SpreadAlongCorridorAxisExceedsSpreadAcrossIt) {
    const Eigen::Isometry3d T_true = test::make_pose(0.0, 0.0, 0.05, {0.1, 0.1, 0.0});
    Pair pair = make_pair(sample(corridor(), 3000, 3), sample(corridor(), 2000, 4), T_true);
    // The exact normals make this point-to-plane: point-to-point (or estimated normals, whose
    // noise correlates with position) would pin x to the random samples instead of leaving it
    // free.
    SteinIcpConfig config;
    config.num_particles = 100;
    // The sensor (the source origin) lies in the floor's plane and one wall's normals face
    // away from it: no face here is "front", so pair with the nearest point.
    config.back_faces = BackFaces::kKeep;
    const SteinIcpResult r =
        stein_icp(pair.source, pair.target, Eigen::Isometry3d::Identity(), config);
    // Across (y) the walls pin the particles to ~mm; along x nothing does, and the spread is
    // the width of the weak prior that bounds an unconstrained direction (0.5 m).
    constexpr double kMinRatio = 10.0;
    EXPECT_GT(spread(r, 0), kMinRatio * spread(r, 1));
    EXPECT_LT(std::abs(r.mode[1] - 0.1), kTranslationTolM);
}

TEST(SteinIcp, SymmetricRoomGivesTwoYawModesAndModeBeatsMean) {
    const double yaw_true = 0.3;
    const Eigen::Isometry3d T_true = test::make_pose(0.0, 0.0, yaw_true, {0.2, -0.1, 0.0});
    const Pair pair =
        make_pair(sample(rectangular_room(), 3000, 5), sample(rectangular_room(), 2000, 6), T_true);
    SteinIcpConfig config;
    config.num_particles = 100;
    config.reduced_3dof = true;
    config.init = SteinInit::kIcpSeeded;
    const SteinIcpResult r =
        stein_icp(pair.source, pair.target, Eigen::Isometry3d::Identity(), config);
    EXPECT_EQ(r.num_modes, 2);
    const double mode_err = std::min(std::abs(std::remainder(r.mode[5] - yaw_true, 2 * kPi)),
                                     std::abs(std::remainder(r.mode[5] - yaw_true + kPi, 2 * kPi)));
    // Silverman's bandwidth over two opposite modes is ~0.5 rad, which smooths each peak.
    constexpr double kModeYawTolRad = 0.05;
    EXPECT_LT(mode_err, kModeYawTolRad);
    // Turning the room by π maps it onto itself, so the second mode sits at (−x, −y): the
    // particle mean of (x, y) falls between the modes, the mode on one of them. (The yaw mean
    // of two tight opposite clusters points exactly at the heavier one, so yaw alone cannot
    // show it.) The spread reports the ambiguity (a single mode: ~0.01).
    const Eigen::Vector2d t_true(0.2, -0.1);
    auto xy_err = [&](const Vector6d& x) {
        return std::min((x.head<2>() - t_true).norm(), (x.head<2>() + t_true).norm());
    };
    EXPECT_GT(xy_err(r.mean), 2.0 * xy_err(r.mode));
    constexpr double kAmbiguousYawSpreadRad = 1.0;
    EXPECT_GT(spread(r, 5), kAmbiguousYawSpreadRad);
}

/// Mean NEES of the mode against the particle covariance over `seeds` registrations of the
/// plated corner with i.i.d. noise of `noise_m` per coordinate on both clouds and exact normals:
/// the point-to-plane residual is N(0, 2 noise²), so σ = noise √2 is the true likelihood.
double mean_nees_on_plated_corner(double noise_m, int seeds, SteinIcpConfig config) {
    config.noise_sigma_m = noise_m * std::sqrt(2.0);
    double sum = 0.0;
    for (int s = 0; s < seeds; ++s) {
        const Eigen::Isometry3d T_true =
            test::make_pose(0.02 * s, -0.01, 0.05 * s - 0.1, {0.1, -0.05 * s, 0.03});
        const auto seed = static_cast<std::uint64_t>(s);
        const Pair pair = make_pair(sample(plated_corner(), 2000, 20 + 2 * seed, noise_m),
                                    sample(plated_corner(), 1000, 21 + 2 * seed, noise_m), T_true);
        config.seed = seed + 1;
        const SteinIcpResult r =
            stein_icp(pair.source, pair.target, Eigen::Isometry3d::Identity(), config);
        Vector6d e = r.mode - pose_params_from_isometry(T_true);
        for (int d = 3; d < 6; ++d) e[d] = std::remainder(e[d], 2 * kPi);
        sum += e.dot(r.covariance.ldlt().solve(e));
    }
    return sum / seeds;
}

TEST(SteinIcp, CovarianceDescribesTheErrorWhenTheLikelihoodIsRight) {
    // With the likelihood right, the particle covariance must describe the mode's error at any
    // noise level: mean NEES ≈ 6, biased up by (K − 1) / (K − 8) ≈ 1.22 as 40 particles
    // estimate a 6 × 6 covariance. With Adam steps alone (refine_iterations = 0) the spread
    // follows the learning rate, not the noise: measured 2.35 at 1 mm.
    SteinIcpConfig config;
    config.num_particles = 40;
    config.iterations = 50;
    config.batch_size = 300;  // 1000 points: batch noise within the Langevin budget
    constexpr int kSeeds = 3;
    for (const double noise_m : {0.001, 0.02}) {
        const double nees = mean_nees_on_plated_corner(noise_m, kSeeds, config);
        // Mean of 3 χ²(6) (scaled by 1.22): 95 % within [2.7, 14]; a factor ~2 beyond that in
        // variance would be a wrong spread.
        EXPECT_GT(nees, 3.0) << "noise " << noise_m;
        EXPECT_LT(nees, 16.0) << "noise " << noise_m;
    }
}

TEST(SteinIcp, PreferringFrontFacesRemovesTheBiasOfAMapWithBothPlateFaces) {
    // A CAD map holds both faces of every 1 cm plate; the scan sees only the room-side ones.
    const PointCloud map = test::sample_plated_room_corner(20000, 61, 0.01, true);
    const Eigen::Isometry3d T_true = test::make_pose(0.01, -0.01, 0.02, {0.02, -0.01, 0.03});
    const PointCloud scan =
        transformed(test::sample_plated_room_corner(3000, 62, 0.01, false), T_true.inverse());
    SteinIcpConfig config;
    config.num_particles = 30;
    config.iterations = 60;
    config.noise_sigma_m = 0.005;  // a tight posterior: the bias, not the spread, decides
    config.init_half_widths << 0.05, 0.05, 0.05, 0.02, 0.02, 0.02;
    config.back_faces = BackFaces::kKeep;
    const SteinIcpResult both = stein_icp(scan, map, Eigen::Isometry3d::Identity(), config);
    config.back_faces = BackFaces::kPreferFront;  // the default
    const SteinIcpResult front = stein_icp(scan, map, Eigen::Isometry3d::Identity(), config);
    const double both_err = pose_error(both.T_target_source, T_true).translation_m;
    const double front_err = pose_error(front.T_target_source, T_true).translation_m;
    EXPECT_GT(both_err, 0.003);  // pulled towards the hidden faces 1 cm behind the walls
    EXPECT_LT(front_err, 0.001);
}

TEST(SteinIcp, ReducedThreeDofKeepsZRollPitchExactlyFixed) {
    const Pair pair =
        make_pair(test::sample_room_corner(1000, 7, 0.005), test::sample_room_corner(500, 8, 0.005),
                  test::make_pose(0.0, 0.0, 0.1, {0.1, 0.1, 0.0}));
    const Eigen::Isometry3d guess = test::make_pose(0.01, -0.02, 0.0, {0.0, 0.0, 0.03});
    const Vector6d g = pose_params_from_isometry(guess);
    SteinIcpConfig config;
    config.num_particles = 20;
    config.iterations = 10;
    config.reduced_3dof = true;
    const SteinIcpResult r = stein_icp(pair.source, pair.target, guess, config);
    for (const Vector6d& x : r.particles) {
        EXPECT_EQ(x[2], g[2]);
        EXPECT_EQ(x[3], g[3]);
        EXPECT_EQ(x[4], g[4]);
    }
    EXPECT_EQ(r.mode[2], g[2]);
}

TEST(SteinIcp, SameSeedGivesIdenticalParticlesForOneAndTwoThreads) {
    const Pair pair = make_pair(test::sample_room_corner(1000, 9, 0.005),
                                test::sample_room_corner(500, 10, 0.005),
                                test::make_pose(0.0, 0.0, 0.1, {0.1, 0.1, 0.0}));
    SteinIcpConfig config;
    config.num_particles = 30;
    config.iterations = 10;
    config.parallel.num_threads = 1;
    const SteinIcpResult a =
        stein_icp(pair.source, pair.target, Eigen::Isometry3d::Identity(), config);
    config.parallel.num_threads = 2;
    const SteinIcpResult b =
        stein_icp(pair.source, pair.target, Eigen::Isometry3d::Identity(), config);
    ASSERT_EQ(a.particles.size(), b.particles.size());
    for (std::size_t i = 0; i < a.particles.size(); ++i) EXPECT_EQ(a.particles[i], b.particles[i]);
    config.seed = 2;
    const SteinIcpResult c =
        stein_icp(pair.source, pair.target, Eigen::Isometry3d::Identity(), config);
    EXPECT_NE(a.particles[0], c.particles[0]);
}

TEST(SteinIcp, BadConfigNamesTheField) {
    SteinIcpConfig config;
    config.num_particles = 1;
    try {
        config.validate();
        FAIL() << "expected ConfigError";
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("stein_icp.num_particles = 1"), std::string::npos);
    }
    config = {};
    config.init_half_widths[5] = -1.0;
    EXPECT_THROW(config.validate(), ConfigError);
    config = {};
    config.final_lr_fraction = 0.0;
    EXPECT_THROW(config.validate(), ConfigError);
    config = {};
    config.refine_iterations = -1;
    EXPECT_THROW(config.validate(), ConfigError);
    config = {};
    config.refine_step = 0.0;
    EXPECT_THROW(config.validate(), ConfigError);
    config.refine_step = 1.5;
    EXPECT_THROW(config.validate(), ConfigError);
}

TEST(SteinIcp, EmptyOrNonFiniteInputThrowsInputError) {
    const PointCloud cloud = test::sample_room_corner(100, 11, 0.0);
    const SteinIcpConfig config;
    EXPECT_THROW(stein_icp(PointCloud{}, cloud, Eigen::Isometry3d::Identity(), config), InputError);
    EXPECT_THROW(stein_icp(cloud, PointCloud{}, Eigen::Isometry3d::Identity(), config), InputError);
    Eigen::Isometry3d bad = Eigen::Isometry3d::Identity();
    bad.translation().x() = std::nan("");
    EXPECT_THROW(stein_icp(cloud, cloud, bad, config), InputError);
    SteinIcpConfig reject = config;
    reject.back_faces = BackFaces::kReject;  // needs target normals, which `cloud` lacks
    EXPECT_THROW(stein_icp(cloud, cloud, Eigen::Isometry3d::Identity(), reject), InputError);
}

TEST(SteinIcp, PoseParamsRoundTrip) {
    const Vector6d x = (Vector6d() << 1.0, -2.0, 0.5, 0.1, -0.2, 2.5).finished();
    EXPECT_TRUE(pose_params_from_isometry(isometry_from_pose_params(x)).isApprox(x, 1e-12));
}

TEST(SteinKde, FindsTwoModesAndTheDenserOne) {
    Rng rng(12);
    std::vector<double> v;
    for (int i = 0; i < 60; ++i) v.push_back(rng.normal(1.0, 0.05));
    for (int i = 0; i < 40; ++i) v.push_back(rng.normal(-2.0, 0.05));
    const KdeModes m = kde_modes(v, false, 0.1);
    EXPECT_EQ(m.num_modes, 2);
    EXPECT_NEAR(m.mode, 1.0, 0.05);  // 60 % of the mass vs 40 %: well separated peaks
}

TEST(SteinKde, CircularValuesAcrossPiFormOneMode) {
    Rng rng(13);
    std::vector<double> v;
    for (int i = 0; i < 100; ++i) v.push_back(std::remainder(kPi + rng.normal(0.0, 0.05), 2 * kPi));
    const KdeModes m = kde_modes(v, true, 0.1);
    EXPECT_EQ(m.num_modes, 1);
    EXPECT_LT(std::abs(std::remainder(m.mode - kPi, 2 * kPi)), 0.05);
    EXPECT_THROW(kde_modes(std::vector<double>{}, true, 0.1), InputError);
}

Vector6d numeric_gradient(const Vector6d& x, const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                          const Eigen::Vector3d* n) {
    auto cost = [&](const Vector6d& y) {
        const Eigen::Vector3d e = isometry_from_pose_params(y) * p - q;
        return n != nullptr ? std::pow(n->dot(e), 2) : e.squaredNorm();
    };
    constexpr double kStep = 1e-6;
    Vector6d g;
    for (int d = 0; d < 6; ++d) {
        const Vector6d h = Vector6d::Unit(d) * kStep;
        g[d] = (cost(x + h) - cost(x - h)) / (2 * kStep);
    }
    return g;
}

TEST(SteinGradient, MatchesNumericalDerivativeForBothCosts) {
    const Vector6d x = (Vector6d() << 0.3, -0.2, 0.1, 0.2, -0.3, 1.1).finished();
    const Eigen::Vector3d p(1.0, 2.0, -0.5), q(0.5, 1.5, 0.7);
    const Eigen::Vector3d n = Eigen::Vector3d(0.3, -0.5, 0.8).normalized();
    const detail::EulerPose pose = detail::make_euler_pose(x);
    // Central differences with step 1e-6 on O(1) costs are accurate to ~1e-9.
    constexpr double kTol = 1e-6;
    EXPECT_TRUE(detail::residual_sq_gradient(pose, p, q, nullptr)
                    .isApprox(numeric_gradient(x, p, q, nullptr), kTol));
    EXPECT_TRUE(
        detail::residual_sq_gradient(pose, p, q, &n).isApprox(numeric_gradient(x, p, q, &n), kTol));
}

}  // namespace
}  // namespace scantling::registration
