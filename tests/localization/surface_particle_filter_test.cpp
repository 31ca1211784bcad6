// The crawler's particle filter (SPEC §6): a slipping unicycle on a plate and on a tank wall,
// its wheels, gyro and UWB ranges (10 % NLOS) simulated here, the estimate checked against
// the truth.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include <scantling/core/error.hpp>
#include <scantling/core/random.hpp>
#include <scantling/core/se3.hpp>
#include <scantling/localization/surface_particle_filter.hpp>

namespace scantling::localization {
namespace {

using Eigen::Isometry3d;
using Eigen::Matrix3d;
using Eigen::Vector3d;

constexpr double kStepS = 0.01;  // truth and gyro at 100 Hz
constexpr int kWheelEvery = 2;   // 50 Hz
constexpr int kUwbEvery = 10;    // 10 Hz
constexpr double kDurationS = 60.0;
constexpr double kWarmUpS = 5.0;          // errors and NEES are averaged after it
constexpr double kGyroBiasRadps = 0.005;  // an uncalibrated residual, 0.3 °/s
const Vector3d kTagLeverBodyM(0.1, 0.0, 0.15);

Matrix3d yaw_rotation(double angle_rad) {
    return Eigen::AngleAxisd(angle_rad, Vector3d::UnitZ()).toRotationMatrix();
}

/// The simulator's crawler, written again: unicycle with OU slip, projected and transported.
class Crawler {
  public:
    Crawler(const SurfaceProjector& surface, const Isometry3d& T_start, bool slipping)
        : surface_(surface),
          slipping_(slipping),
          T_(settle(T_start.translation(), T_start.linear().col(0))) {}

    /// One step of wheel speed v and wheel turn rate w (no slip when not `slipping`, but the
    /// mean slip is still taken off, as a dead reckoner does).
    void step(double v, double turn_rad, double dt, Rng& rng) {
        if (slipping_) {
            const double a = std::exp(-dt / 1.0), b = std::sqrt(1.0 - a * a);
            slip_ = Vector3d(0.02, 0.0, 0.0) + a * (slip_ - Vector3d(0.02, 0.0, 0.0)) +
                    b * Vector3d(0.02 * rng.normal(), 0.01 * rng.normal(), 0.03 * rng.normal());
        }
        const double turn = turn_rad * (1.0 + slip_.z());
        const Vector3d move = T_.linear() * yaw_rotation(0.5 * turn) *
                              Vector3d(v * (1.0 - slip_.x()), std::abs(v) * slip_.y(), 0.0) * dt;
        T_ = settle(T_.translation() + move, T_.linear() * yaw_rotation(turn).col(0));
    }
    const Isometry3d& pose() const { return T_; }

  private:
    Isometry3d settle(const Vector3d& p, const Vector3d& heading) const {
        const SurfacePoint s = surface_.project(p);
        const Vector3d x = (heading - s.normal * s.normal.dot(heading)).normalized();
        Isometry3d T = Isometry3d::Identity();
        T.linear() << x, s.normal.cross(x), s.normal;
        T.translation() = s.point;
        return T;
    }

    const SurfaceProjector& surface_;
    bool slipping_;
    Isometry3d T_;
    Vector3d slip_ = Vector3d(0.02, 0.0, 0.0);
};

struct Tick {
    Isometry3d truth;
    io::ImuRecord imu;
    std::optional<io::WheelOdometryRecord> wheel;
    std::vector<io::UwbRecord> uwb;
};

struct Scenario {
    const SurfaceProjector& surface;
    Isometry3d T_start;
    std::map<int, Vector3d> anchors;
};

/// 60 s of loops at 0.15 m/s with a wobbling turn rate; sensors as the file comment says.
std::vector<Tick> simulate(const Scenario& s, std::uint64_t seed) {
    Rng rng(seed);
    Crawler crawler(s.surface, s.T_start, true);
    std::vector<Tick> ticks;
    for (int k = 1; k * kStepS <= kDurationS + 1e-9; ++k) {
        const double t = k * kStepS;
        const double v = 0.15, w = 0.2 + 0.15 * std::sin(2.0 * std::numbers::pi * t / 9.0);
        const Matrix3d R_before = crawler.pose().linear();
        crawler.step(v, w * kStepS, kStepS, rng);
        Tick tick{crawler.pose(), {}, std::nullopt, {}};
        // The gyro feels the whole body rotation; its z is the turn about the normal.
        const Vector3d omega = so3_log(R_before.transpose() * tick.truth.linear()) / kStepS;
        tick.imu = {
            t, Vector3d::Zero(),
            omega + Vector3d::Constant(kGyroBiasRadps) + rng.normal3(2.4e-4 / std::sqrt(kStepS))};
        if (k % kWheelEvery == 0)
            tick.wheel = io::WheelOdometryRecord{t, v * (1.0 + rng.normal(0.0, 0.005)),
                                                 w + rng.normal(0.0, 0.01), false};
        for (const auto& [id, anchor] : s.anchors) {
            if (k % kUwbEvery != 0) break;
            io::UwbRecord r{t, id, (tick.truth * kTagLeverBodyM - anchor).norm(), true, true};
            r.range_m += rng.normal(0.0, 0.05);
            r.line_of_sight = rng.uniform() >= 0.1;
            if (!r.line_of_sight) r.range_m += rng.uniform(0.5, 3.0);
            tick.uwb.push_back(r);
        }
        ticks.push_back(tick);
    }
    return ticks;
}

SurfaceParticleFilterConfig pf_config(const Scenario& s) {
    SurfaceParticleFilterConfig c;
    c.uwb_anchors_world_m = s.anchors;
    c.p_body_uwb_tag_m = kTagLeverBodyM;
    return c;
}

/// 3-DoF NEES of (tangent position, yaw) in the estimate's body axes.
double nees(const SurfaceParticleEstimate& e, const Isometry3d& truth) {
    const Matrix3d& R = e.T_world_body.linear();
    const Vector3d dp = truth.translation() - e.T_world_body.translation();
    const Vector3d x_true = truth.linear().col(0);
    const Vector3d error(R.col(0).dot(dp), R.col(1).dot(dp),
                         std::atan2(x_true.dot(R.col(1)), x_true.dot(R.col(0))));
    Matrix3d C;
    C.topLeftCorner<2, 2>() =
        R.leftCols<2>().transpose() * e.position_covariance_m2 * R.leftCols<2>();
    C.topRightCorner<2, 1>() = R.leftCols<2>().transpose() * e.position_yaw_covariance;
    C.bottomLeftCorner<1, 2>() = C.topRightCorner<2, 1>().transpose();
    C(2, 2) = e.yaw_variance_rad2;
    return error.dot(C.ldlt().solve(error));
}

struct RunResult {
    double position_rms_m = 0.0;
    double mean_nees = 0.0;
    SurfaceParticleEstimate last;
    SurfaceParticleFilterCounters counters;
};

RunResult run(const Scenario& s, const std::vector<Tick>& ticks, SurfaceParticleFilterConfig c,
              bool use_uwb, std::uint64_t seed = 5) {
    SurfaceParticleFilter pf(std::move(c), s.surface, s.T_start, seed);
    pf.add_wheel_odometry({0.0, 0.0, 0.0, false});
    double sum_sq = 0.0, sum_nees = 0.0;
    int n = 0;
    for (const Tick& tick : ticks) {
        pf.add_imu(tick.imu);
        if (tick.wheel) pf.add_wheel_odometry(*tick.wheel);
        if (use_uwb)
            for (const io::UwbRecord& r : tick.uwb) pf.update_uwb(r);
        if (tick.uwb.empty() || tick.imu.stamp_s < kWarmUpS) continue;
        const SurfaceParticleEstimate e = pf.estimate();
        sum_sq += (e.T_world_body.translation() - tick.truth.translation()).squaredNorm();
        sum_nees += nees(e, tick.truth);
        ++n;
    }
    return {std::sqrt(sum_sq / n), sum_nees / n, pf.estimate(), pf.counters()};
}

/// Wheels (less the mean slip) and gyro integrated without noise: the dead reckoning.
double dead_reckoning_rms_m(const Scenario& s, const std::vector<Tick>& ticks) {
    Crawler reckoner(s.surface, s.T_start, false);
    Rng unused(0);
    double sum_sq = 0.0, v = 0.0;
    int n = 0;
    for (const Tick& tick : ticks) {
        if (tick.wheel) v = tick.wheel->forward_speed_mps;
        reckoner.step(v, tick.imu.angular_rate_radps.z() * kStepS, kStepS, unused);
        if (tick.uwb.empty() || tick.imu.stamp_s < kWarmUpS) continue;
        sum_sq += (reckoner.pose().translation() - tick.truth.translation()).squaredNorm();
        ++n;
    }
    return std::sqrt(sum_sq / n);
}

const PlaneSurface kPlate(Vector3d::Zero(), Vector3d::UnitZ());
const CylinderSurface kTankOutside(Vector3d::Zero(), Vector3d::UnitZ(), 5.0,
                                   CylinderSide::kOutside);
const CylinderSurface kTankInside(Vector3d::Zero(), Vector3d::UnitZ(), 5.0, CylinderSide::kInside);

Isometry3d pose(const Matrix3d& R, const Vector3d& p) { return make_isometry(R, p); }

/// A plate (the crawler loops around (0, 0.75)), anchors 3–6 m away at two heights.
Scenario plate() {
    return {kPlate,
            Isometry3d::Identity(),
            {{1, {-3.0, -3.0, 1.0}},
             {2, {4.0, -3.0, 2.0}},
             {3, {4.0, 4.0, 1.0}},
             {4, {-3.0, 4.0, 2.0}}}};
}

/// A tank wall of radius 5 m; the crawler starts at (±5, 0, 1) heading up (z). Outside: anchors
/// 9 m from the axis; inside: anchors near the axis.
Scenario tank(bool outside) {
    const double r = outside ? 9.0 : 1.5;
    std::map<int, Vector3d> anchors;
    const double angles[] = {-0.6, 0.6, 0.6, -0.6}, heights[] = {-1.0, 0.0, 4.0, 3.0};
    for (int i = 0; i < 4; ++i)
        anchors[i + 1] = Vector3d(r * std::cos(angles[i]), r * std::sin(angles[i]), heights[i]);
    const Vector3d normal = outside ? Vector3d(Vector3d::UnitX()) : Vector3d(-Vector3d::UnitX());
    Matrix3d R;
    R << Vector3d::UnitZ(), normal.cross(Vector3d::UnitZ()), normal;
    return {outside ? static_cast<const SurfaceProjector&>(kTankOutside) : kTankInside,
            pose(R, Vector3d(5.0, 0.0, 1.0)), anchors};
}

/// Measured ×9 to ×13 (0.144 m against 0.011–0.016 m); ×5.8 at worst over 5 other truth seeds.
constexpr double kBetterThanDeadReckoning = 4.0;

void expect_tracks(const Scenario& s, const char* name, double max_rms_m) {
    const std::vector<Tick> ticks = simulate(s, 11);
    const RunResult pf = run(s, ticks, pf_config(s), true);
    const RunResult no_uwb = run(s, ticks, pf_config(s), false);
    const double dr_rms_m = dead_reckoning_rms_m(s, ticks);
    std::printf(
        "%s: PF RMS %.4f m NEES %.2f ESS %.0f resamples %zu; without UWB %.4f m NEES "
        "%.2f; dead reckoning %.4f m\n",
        name, pf.position_rms_m, pf.mean_nees, pf.last.effective_sample_size, pf.counters.resamples,
        no_uwb.position_rms_m, no_uwb.mean_nees, dr_rms_m);
    EXPECT_LE(pf.position_rms_m, max_rms_m);
    EXPECT_GT(dr_rms_m, kBetterThanDeadReckoning * pf.position_rms_m);
    EXPECT_GT(no_uwb.position_rms_m, kBetterThanDeadReckoning * pf.position_rms_m);
    // Roughly consistent covariance: 3 DoF, expectation 3; measured 2.26–3.33 (2.4–4.6 over
    // 5 other truth seeds).
    EXPECT_GT(pf.mean_nees, 0.5);
    EXPECT_LT(pf.mean_nees, 6.0);
    EXPECT_EQ(pf.counters.uwb_applied, 4u * 600u);
    EXPECT_EQ(pf.counters.gyro_turns, pf.counters.predictions);
}

TEST(SurfaceParticleFilter, UwbHoldsThePositionOnAPlateWhereDeadReckoningDrifts) {
    expect_tracks(plate(), "plate", 0.02);  // measured 0.0109 m, NEES 2.26 (other seeds ≤ 0.013)
}

TEST(SurfaceParticleFilter, UwbHoldsThePositionOnATankWallFromOutside) {
    expect_tracks(tank(true), "tank outside", 0.025);  // measured 0.0157 m, NEES 3.33 (≤ 0.018)
}

TEST(SurfaceParticleFilter, UwbHoldsThePositionOnATankWallFromInside) {
    // Measured 0.0159 m, NEES 2.84; 0.020–0.024 m over 5 other truth seeds: the anchors near the
    // axis see the crawler within ±13° across its track, a weaker geometry than outside.
    expect_tracks(tank(false), "tank inside", 0.035);
}

TEST(SurfaceParticleFilter, TheNlosMixtureBeatsAPureGaussianOnLongRanges) {
    const Scenario s = plate();
    const std::vector<Tick> ticks = simulate(s, 11);
    SurfaceParticleFilterConfig gaussian = pf_config(s);
    gaussian.nlos_probability = 0.0;
    gaussian.outlier_probability = 0.0;
    const RunResult robust = run(s, ticks, pf_config(s), true);
    const RunResult plain = run(s, ticks, gaussian, true);
    std::printf("NLOS mixture RMS %.4f m NEES %.2f; pure Gaussian RMS %.4f m NEES %.2f\n",
                robust.position_rms_m, robust.mean_nees, plain.position_rms_m, plain.mean_nees);
    // Measured 0.0911 m against 0.0109 m (×8.4; ×3.5 to ×10 over 5 other truth seeds): the
    // Gaussian's cloud chases every long range and collapses (its NEES is astronomical).
    EXPECT_GT(plain.position_rms_m, 2.5 * robust.position_rms_m);
}

TEST(SurfaceParticleFilter, WithoutTheGyroTheWheelsTurnTheParticles) {
    const Scenario s = plate();
    std::vector<Tick> ticks = simulate(s, 11);
    SurfaceParticleFilter pf(pf_config(s), s.surface, s.T_start, 5);
    pf.add_wheel_odometry({0.0, 0.0, 0.0, false});
    double sum_sq = 0.0;
    int n = 0;
    for (const Tick& tick : ticks) {
        if (tick.wheel) pf.add_wheel_odometry(*tick.wheel);
        for (const io::UwbRecord& r : tick.uwb) pf.update_uwb(r);
        if (tick.uwb.empty() || tick.imu.stamp_s < kWarmUpS) continue;
        sum_sq +=
            (pf.estimate().T_world_body.translation() - tick.truth.translation()).squaredNorm();
        ++n;
    }
    const double rms_m = std::sqrt(sum_sq / n);
    std::printf("wheels only (no gyro) + UWB: RMS %.4f m\n", rms_m);
    EXPECT_EQ(pf.counters().gyro_turns, 0u);
    EXPECT_EQ(pf.counters().predictions, ticks.size() / kWheelEvery);
    EXPECT_LE(rms_m, 0.02);  // measured 0.0107 m (≤ 0.0133 over 5 other seeds; no gyro bias)
}

/// A filter on the plate after 2 s of the scenario (with UWB), for the contract tests.
struct Warm {
    Scenario scenario = plate();
    std::vector<Tick> ticks = simulate(scenario, 11);
    SurfaceParticleFilter pf;
    explicit Warm(std::uint64_t seed = 5)
        : pf(pf_config(scenario), scenario.surface, scenario.T_start, seed) {
        pf.add_wheel_odometry({0.0, 0.0, 0.0, false});
        for (int k = 0; k < 200; ++k) feed(ticks[k]);
    }
    void feed(const Tick& tick) {
        pf.add_imu(tick.imu);
        if (tick.wheel) pf.add_wheel_odometry(*tick.wheel);
        for (const io::UwbRecord& r : tick.uwb) pf.update_uwb(r);
    }
};

void expect_identical(const SurfaceParticleEstimate& a, const SurfaceParticleEstimate& b) {
    EXPECT_EQ(a.stamp_s, b.stamp_s);
    EXPECT_EQ(a.T_world_body.matrix(), b.T_world_body.matrix());
    EXPECT_EQ(a.position_covariance_m2, b.position_covariance_m2);
    EXPECT_EQ(a.yaw_variance_rad2, b.yaw_variance_rad2);
    EXPECT_EQ(a.position_yaw_covariance, b.position_yaw_covariance);
    EXPECT_EQ(a.effective_sample_size, b.effective_sample_size);
}

TEST(SurfaceParticleFilter, TheSameSeedGivesBitIdenticalEstimatesAndAnotherSeedDoesNot) {
    Warm a, b, other(6);
    for (int k = 200; k < 1000; ++k) {
        a.feed(a.ticks[k]);
        b.feed(b.ticks[k]);
        other.feed(other.ticks[k]);
    }
    expect_identical(a.pf.estimate(), b.pf.estimate());
    EXPECT_EQ(a.pf.counters().resamples, b.pf.counters().resamples);
    EXPECT_NE(other.pf.estimate().T_world_body.translation(),
              a.pf.estimate().T_world_body.translation());
}

TEST(SurfaceParticleFilter, BadRecordsAreRefusedWithoutChangingTheEstimate) {
    Warm w;
    const SurfaceParticleEstimate before = w.pf.estimate();
    const SurfaceParticleFilterCounters counters = w.pf.counters();
    const double t = w.pf.stamp_s();
    const double nan = std::numeric_limits<double>::quiet_NaN();
    EXPECT_EQ(w.pf.update_uwb({t, 1, nan, false, true}).status, UpdateStatus::kInvalid);
    EXPECT_EQ(w.pf.update_uwb({t, 99, 4.0, true, true}).status, UpdateStatus::kUnknownAnchor);
    EXPECT_THROW(w.pf.update_uwb({t, 1, nan, true, true}), InputError);
    EXPECT_THROW(w.pf.update_uwb({nan, 1, 4.0, true, true}), InputError);
    EXPECT_THROW(w.pf.add_wheel_odometry({t + 0.02, nan, 0.0, false}), InputError);
    EXPECT_THROW(w.pf.add_imu({t + 0.01, Vector3d::Zero(), Vector3d(0.0, 0.0, nan)}), InputError);
    EXPECT_EQ(w.pf.add_wheel_odometry({t, 0.15, 0.0, false}), ImuPredictionStatus::kOutOfOrder);
    EXPECT_EQ(w.pf.add_imu({t - 0.5, Vector3d::Zero(), Vector3d::Zero()}),
              ImuPredictionStatus::kOutOfOrder);
    expect_identical(w.pf.estimate(), before);
    EXPECT_EQ(w.pf.counters().uwb_refused, counters.uwb_refused + 2);
    EXPECT_EQ(w.pf.counters().uwb_applied, counters.uwb_applied);
    EXPECT_EQ(w.pf.counters().predictions, counters.predictions);
    EXPECT_EQ(w.pf.counters().wheel_out_of_order, counters.wheel_out_of_order + 1);
}

TEST(SurfaceParticleFilter, ARangeEveryParticleFindsImpossibleResetsTheWeightsToUniform) {
    Warm w;
    SurfaceParticleFilterConfig c = pf_config(w.scenario);
    c.nlos_probability = c.outlier_probability = 0.0;
    SurfaceParticleFilter pf(c, w.scenario.surface, w.scenario.T_start, 5);
    pf.update_uwb({0.0, 1, 3.0, true, true});                                // not uniform any more
    const UpdateResult result = pf.update_uwb({0.0, 1, 1e200, true, true});  // (e/σ)² = ∞
    EXPECT_EQ(result.status, UpdateStatus::kApplied);
    EXPECT_EQ(pf.counters().weight_resets, 1u);
    const double uniform = -std::log(static_cast<double>(c.num_particles));
    for (const SurfaceParticle& p : pf.particles()) EXPECT_EQ(p.log_weight, uniform);
    EXPECT_TRUE(pf.estimate().T_world_body.matrix().allFinite());
}

TEST(SurfaceParticleFilter, TheRangeLikelihoodForgivesLongRangesNotShortOnes) {
    const SurfaceParticleFilterConfig c;
    const double at_zero = uwb_range_log_likelihood(0.0, c);
    const double long_by_1m = uwb_range_log_likelihood(1.0, c);
    const double short_by_1m = uwb_range_log_likelihood(-1.0, c);
    // Long: the NLOS share's density, log(0.1 / 3) = −3.4; short: only the outliers' floor.
    EXPECT_NEAR(long_by_1m, std::log(0.1 / 3.0), 0.01);
    EXPECT_NEAR(short_by_1m, std::log(0.005 / 50.0), 0.01);
    EXPECT_GT(at_zero, long_by_1m + 5.0);
    EXPECT_TRUE(std::isfinite(uwb_range_log_likelihood(1e200, c)));
}

void expect_config_error(const SurfaceParticleFilterConfig& c, const std::string& field) {
    try {
        c.validate();
        ADD_FAILURE() << "no ConfigError for " << field;
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("particle_filter." + field), std::string::npos)
            << e.what();
    }
}

TEST(SurfaceParticleFilter, ConfigErrorsNameTheField) {
    EXPECT_NO_THROW(SurfaceParticleFilterConfig{}.validate());
    SurfaceParticleFilterConfig c;
    c.num_particles = 0;
    expect_config_error(c, "num_particles");
    c = {};
    c.uwb_range_sigma_m = 0.0;
    expect_config_error(c, "uwb_range_sigma_m");
    c = {};
    c.nlos_probability = 1.0;
    expect_config_error(c, "nlos_probability");
    c = {};
    c.outlier_probability = 0.95;
    expect_config_error(c, "outlier_probability");
    c = {};
    c.slip_correlation_time_s = std::numeric_limits<double>::quiet_NaN();
    expect_config_error(c, "slip_correlation_time_s");
    c = {};
    c.resample_threshold_fraction = 1.5;
    expect_config_error(c, "resample_threshold_fraction");
    c = {};
    c.uwb_anchors_world_m[3] = Vector3d(0.0, std::numeric_limits<double>::infinity(), 0.0);
    expect_config_error(c, "uwb_anchors_world_m[3]");
    c = {};
    c.R_body_imu = 2.0 * Matrix3d::Identity();
    expect_config_error(c, "R_body_imu");
    c = {};
    c.num_particles = 0;
    EXPECT_THROW(SurfaceParticleFilter(c, kPlate, Isometry3d::Identity(), 1), ConfigError);
    Isometry3d bad = Isometry3d::Identity();
    bad.translation().x() = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(SurfaceParticleFilter({}, kPlate, bad, 1), InputError);
}

}  // namespace
}  // namespace scantling::localization
