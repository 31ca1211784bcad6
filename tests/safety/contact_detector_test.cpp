#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include <scantling/core/error.hpp>
#include <scantling/core/random.hpp>
#include <scantling/safety/contact_detector.hpp>

namespace scantling::safety {
namespace {

using Eigen::Quaterniond;
using Eigen::Vector3d;

constexpr double kRateHz = 200.0;
constexpr double kNoiseMps2 = 0.02;     // white accelerometer noise per axis (brief)
constexpr double kBiasMps2 = 0.1;       // constant accelerometer bias per axis (brief)
constexpr double kManoeuvreMps2 = 0.5;  // gentle commanded manoeuvres (brief)
constexpr double kDirectionToleranceDeg = 10.0;
// Normal motion must stay well clear of the 3 m/s² threshold, not just below it: half of it.
// (A reversal of the 0.5 m/s² surge command is a 1 m/s² step when the caller passes no model.)
constexpr double kNormalResidualBoundMps2 = 1.5;

double deg(double d) { return d * std::numbers::pi / 180.0; }
double angle_deg(const Vector3d& a, const Vector3d& b) {
    return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)) * 180.0 /
           std::numbers::pi;
}
Quaterniond rpy(double roll, double pitch, double yaw) {
    return Quaterniond(Eigen::AngleAxisd(yaw, Vector3d::UnitZ()) *
                       Eigen::AngleAxisd(pitch, Vector3d::UnitY()) *
                       Eigen::AngleAxisd(roll, Vector3d::UnitX()));
}

struct Truth {
    Quaterniond q_world_body = Quaterniond::Identity();
    Vector3d a_world_mps2 = Vector3d::Zero();
};

/// Slow yaw, small passive roll/pitch oscillation, surge steps and sway/heave sines.
Truth gentle_manoeuvres(double t) {
    Truth truth;
    truth.q_world_body =
        rpy(deg(2.0) * std::sin(2 * std::numbers::pi * t / 6), deg(2.0) * std::sin(t), 0.1 * t);
    const double surge = std::fmod(t, 4.0) < 2.0 ? kManoeuvreMps2 : -kManoeuvreMps2;
    truth.a_world_mps2 = Vector3d(surge, kManoeuvreMps2 * std::sin(2 * std::numbers::pi * t / 7),
                                  0.6 * kManoeuvreMps2 * std::sin(2 * std::numbers::pi * t / 11));
    return truth;
}

struct Scenario {
    double duration_s = 20.0;
    std::function<Truth(double)> truth = gentle_manoeuvres;
    /// Acceleration from a contact, added to the truth (world).
    std::function<Vector3d(double)> push_world = [](double) -> Vector3d {
        return Vector3d::Zero();
    };
    /// What the caller passes as expected; zero (no model) is the worst case.
    std::function<Vector3d(const Truth&)> expected = [](const Truth&) -> Vector3d {
        return Vector3d::Zero();
    };
    /// The estimator's attitude.
    std::function<Quaterniond(double, const Truth&)> estimate = [](double, const Truth& now) {
        return now.q_world_body;
    };
};

struct RunResult {
    ContactDetector detector;
    std::vector<Contact> contacts;
    double max_residual_mps2 = 0.0;
};

RunResult run(const Scenario& s, const ContactDetectorConfig& config = {},
              std::uint64_t seed = 14) {
    RunResult r{ContactDetector(config), {}, 0.0};
    Rng rng(seed);
    const Vector3d bias_body = Vector3d::Constant(kBiasMps2);
    const Vector3d g_world(0.0, 0.0, -9.81);
    for (int k = 0; k < static_cast<int>(s.duration_s * kRateHz); ++k) {
        const double t = k / kRateHz;
        const Truth truth = s.truth(t);
        const Vector3d a_world = truth.a_world_mps2 + s.push_world(t);
        io::ImuRecord imu;
        imu.stamp_s = t;
        imu.specific_force_mps2 = truth.q_world_body.conjugate() * (a_world - g_world) + bias_body +
                                  rng.normal3(kNoiseMps2);
        if (auto c = r.detector.add(imu, s.estimate(t, truth), s.expected(truth))) {
            r.contacts.push_back(*c);
        }
        r.max_residual_mps2 =
            std::max(r.max_residual_mps2, r.detector.residual_world_mps2().norm());
    }
    return r;
}

/// A rectangular push `a_world_mps2` in [start, start + 50 ms).
std::function<Vector3d(double)> spikes(std::vector<double> starts_s, Vector3d a_world_mps2) {
    return [=](double t) -> Vector3d {
        for (double t0 : starts_s) {
            if (t >= t0 && t < t0 + 0.05) return a_world_mps2;
        }
        return Vector3d::Zero();
    };
}

TEST(ContactDetector, NoFalseAlarmInSixtySecondsOfManoeuvresWithBiasAndTiltError) {
    Scenario s;
    s.duration_s = 60.0;
    // The estimator's attitude is 3° off in pitch (g sin 3° ≈ 0.5 m/s² of false acceleration).
    s.estimate = [](double, const Truth& truth) { return truth.q_world_body * rpy(0, deg(3), 0); };
    for (std::uint64_t seed : {1u, 2u, 3u}) {
        const RunResult r = run(s, {}, seed);
        EXPECT_TRUE(r.contacts.empty()) << "seed " << seed << " at " << r.contacts[0].stamp_s;
        EXPECT_LT(r.max_residual_mps2, kNormalResidualBoundMps2) << "seed " << seed;
        std::printf("[ figures  ] 60 s normal motion, seed %d: max |residual| = %.3f m/s^2\n",
                    static_cast<int>(seed), r.max_residual_mps2);
    }
}

TEST(ContactDetector, SpikeAlongMinusYIsReportedOnceWithDirectionAndBackOff) {
    const ContactDetectorConfig config;
    Scenario s;
    // Obstacle at +y pushes to −y. At 10 s the surge command also reverses (+0.5 → −0.5 m/s²)
    // and the caller passes no model: a 1 m/s² unexplained step along x, the worst case of the
    // manoeuvres, tilts the measured direction by up to atan(1/6) = 9.5°.
    s.push_world = spikes({10.0}, Vector3d(0.0, -6.0, 0.0));
    const RunResult r = run(s, config);
    ASSERT_EQ(r.contacts.size(), 1u);
    const Contact& c = r.contacts[0];
    EXPECT_GE(c.stamp_s, 10.0);
    EXPECT_LT(c.stamp_s, 10.05);  // reported during the spike, not after it
    EXPECT_LT(angle_deg(c.impulse_direction_world, -Vector3d::UnitY()), kDirectionToleranceDeg);
    EXPECT_NEAR(c.impulse_direction_world.norm(), 1.0, 1e-12);
    EXPECT_NEAR(c.peak_residual_mps2, 6.0, 1.0);
    std::printf(
        "[ figures  ] spike: reported %.3f s after onset, direction %.2f deg off -y, "
        "peak %.2f m/s^2\n",
        c.stamp_s - 10.0, angle_deg(c.impulse_direction_world, -Vector3d::UnitY()),
        c.peak_residual_mps2);

    const ContactDetector& d = r.detector;
    EXPECT_FALSE(d.backing_off(c.stamp_s - 0.01));
    for (double dt : {0.0, 1.0, config.back_off_duration_s - 0.01}) {
        ASSERT_TRUE(d.backing_off(c.stamp_s + dt)) << dt;
        const Vector3d v = d.back_off_velocity(c.stamp_s + dt);
        EXPECT_NEAR(v.norm(), config.back_off_speed_mps, 1e-12);
        EXPECT_LT(angle_deg(v, -Vector3d::UnitY()), kDirectionToleranceDeg);
    }
    EXPECT_FALSE(d.backing_off(c.stamp_s + config.back_off_duration_s + 0.01));
    EXPECT_EQ(d.back_off_velocity(c.stamp_s + config.back_off_duration_s + 0.01), Vector3d::Zero());
    EXPECT_EQ(d.num_contacts(), 1u);
}

TEST(ContactDetector, SecondSpikeWithinRefractoryIsNotReportedButOneAfterItIs) {
    Scenario s;
    // A rebound 0.4 s after the impact (inside the 1 s refractory), then a new bump at 12 s.
    s.push_world = spikes({10.0, 10.4, 12.0}, Vector3d(0.0, -6.0, 0.0));
    const RunResult r = run(s);
    ASSERT_EQ(r.contacts.size(), 2u);
    EXPECT_NEAR(r.contacts[0].stamp_s, 10.0, 0.05);
    EXPECT_NEAR(r.contacts[1].stamp_s, 12.0, 0.05);
}

/// Level until 5 s, then a roll to 20° within 0.1 s (smoothstep; a wave or tether kick), held.
/// Fast, so that a gravity removal done wrong cannot hide in the running mean.
Truth rolled(double t) {
    Truth truth;
    const double x = std::clamp((t - 5.0) / 0.1, 0.0, 1.0);
    truth.q_world_body = rpy(deg(20.0) * x * x * (3 - 2 * x), 0.0, 0.0);
    return truth;
}

TEST(ContactDetector, TwentyDegreeRollKnownToTheEstimatorDoesNotTrigger) {
    Scenario s;
    s.truth = rolled;
    const RunResult r = run(s);
    EXPECT_TRUE(r.contacts.empty());
    EXPECT_LT(r.max_residual_mps2, kNormalResidualBoundMps2);
    EXPECT_EQ(r.detector.num_baseline_restarts(), 0u);
    std::printf("[ figures  ] 20 deg roll in 0.1 s, known: max |residual| = %.3f m/s^2\n",
                r.max_residual_mps2);

    // The same roll hidden from the estimator is 2 g sin 10° ≈ 3.4 m/s² of unexplained force: it
    // is reported (so the test above can fail), once, then absorbed as an offset step.
    s.estimate = [](double, const Truth&) { return Quaterniond::Identity(); };
    const RunResult blind = run(s);
    EXPECT_EQ(blind.contacts.size(), 1u);
    EXPECT_EQ(blind.detector.num_baseline_restarts(), 1u);
    std::printf("[ figures  ] same roll hidden: max |residual| = %.3f m/s^2, %zu contact(s)\n",
                blind.max_residual_mps2, blind.contacts.size());
}

TEST(ContactDetector, SustainedCommandedAccelerationPassedAsExpectedDoesNotTrigger) {
    Scenario s;
    // 4 m/s² for 1.5 s: more than the threshold, so only the subtraction keeps it quiet.
    s.truth = [](double t) {
        Truth truth;
        if (t >= 5.0 && t < 6.5) truth.a_world_mps2 = Vector3d(4.0, 0.0, 0.0);
        return truth;
    };
    s.expected = [](const Truth& truth) { return truth.a_world_mps2; };
    const RunResult r = run(s);
    EXPECT_TRUE(r.contacts.empty());
    EXPECT_LT(r.max_residual_mps2, kNormalResidualBoundMps2);
    std::printf("[ figures  ] 4 m/s^2 for 1.5 s passed as expected: max |residual| = %.3f m/s^2\n",
                r.max_residual_mps2);

    s.expected = [](const Truth&) -> Vector3d { return Vector3d::Zero(); };
    EXPECT_FALSE(run(s).contacts.empty());
}

TEST(ContactDetector, SpikeDuringWarmUpIsNotReported) {
    Scenario s;
    s.push_world = spikes({0.5}, Vector3d(0.0, -6.0, 0.0));
    EXPECT_TRUE(run(s).contacts.empty());
}

TEST(ContactDetector, OutOfOrderStampsAreIgnoredAndCounted) {
    ContactDetector d;
    io::ImuRecord imu;
    imu.specific_force_mps2 = Vector3d(0.0, 0.0, 9.81);
    for (int k = 0; k <= 400; ++k) {
        imu.stamp_s = k / kRateHz;
        d.add(imu, Quaterniond::Identity());
    }
    imu.specific_force_mps2 = Vector3d(0.0, -20.0, 9.81);  // a huge spike, but stale
    for (double t : {1.0, 1.5, 2.0, 2.0}) {
        imu.stamp_s = t;
        EXPECT_FALSE(d.add(imu, Quaterniond::Identity()).has_value());
    }
    EXPECT_EQ(d.num_out_of_order(), 4u);
    EXPECT_EQ(d.residual_world_mps2(), Vector3d::Zero());
}

void expect_config_error(const std::function<void(ContactDetectorConfig&)>& spoil,
                         const std::string& field) {
    ContactDetectorConfig config;
    spoil(config);
    try {
        config.validate();
        ADD_FAILURE() << field << " accepted";
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("contact_detector." + field), std::string::npos)
            << e.what();
    }
    EXPECT_THROW(ContactDetector{config}, ConfigError) << field;
}

TEST(ContactDetector, BadConfigIsRefusedNamingTheField) {
    EXPECT_NO_THROW(ContactDetectorConfig{}.validate());
    const double nan = std::numeric_limits<double>::quiet_NaN();
    expect_config_error([](auto& c) { c.threshold_mps2 = 0.0; }, "threshold_mps2");
    expect_config_error([&](auto& c) { c.threshold_mps2 = nan; }, "threshold_mps2");
    expect_config_error([](auto& c) { c.min_samples_above = 0; }, "min_samples_above");
    expect_config_error([](auto& c) { c.refractory_s = -1.0; }, "refractory_s");
    expect_config_error([](auto& c) { c.baseline_time_constant_s = 0.0; },
                        "baseline_time_constant_s");
    expect_config_error([](auto& c) { c.max_spike_duration_s = -0.1; }, "max_spike_duration_s");
    expect_config_error([](auto& c) { c.gravity_mps2 = 0.0; }, "gravity_mps2");
    expect_config_error([](auto& c) { c.back_off_speed_mps = 0.0; }, "back_off_speed_mps");
    expect_config_error([&](auto& c) { c.back_off_duration_s = nan; }, "back_off_duration_s");
}

void expect_input_error(const std::function<void(io::ImuRecord&, Quaterniond&, Vector3d&)>& spoil,
                        const std::string& field) {
    ContactDetector d;
    io::ImuRecord imu;
    imu.stamp_s = 1.0;
    Quaterniond q = Quaterniond::Identity();
    Vector3d a = Vector3d::Zero();
    spoil(imu, q, a);
    try {
        d.add(imu, q, a);
        ADD_FAILURE() << field << " accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
}

TEST(ContactDetector, NonFiniteInputIsRefusedNamingTheField) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    expect_input_error([&](auto& imu, auto&, auto&) { imu.stamp_s = nan; }, "imu.stamp_s");
    expect_input_error([&](auto& imu, auto&, auto&) { imu.specific_force_mps2.y() = nan; },
                       "imu.specific_force_mps2");
    expect_input_error([&](auto& imu, auto&, auto&) { imu.angular_rate_radps.z() = inf; },
                       "imu.angular_rate_radps");
    expect_input_error([&](auto&, auto& q, auto&) { q.w() = nan; }, "q_world_body");
    expect_input_error([&](auto&, auto& q, auto&) { q.coeffs().setZero(); }, "q_world_body");
    expect_input_error([&](auto&, auto&, auto& a) { a.x() = nan; }, "a_expected_world_mps2");
}

}  // namespace
}  // namespace scantling::safety
