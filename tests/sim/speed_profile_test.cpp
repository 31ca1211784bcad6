#include <scantling/core/error.hpp>
#include <scantling/sim/speed_profile.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace scantling::sim {
namespace {

constexpr double kExact = 1e-12;       // closed-form phase boundaries, double round-off
constexpr double kLimitSlack = 1e-12;  // limits hold up to round-off
constexpr double kDiffStepS = 1e-5;
constexpr double kDiffTol = 1e-6;  // central differences of a C² profile, |s| <= 10

TEST(SpeedProfile, LongTrapezoidCruisesAtTheSpeedLimitWithTextbookPhases) {
    const RestToRestProfile p = plan_rest_to_rest(10.0, 2.0, 1.0, ProfileShape::kTrapezoidal);
    EXPECT_NEAR(p.peak_speed, 2.0, kExact);
    EXPECT_NEAR(p.ramp_time_s, 2.0, kExact);    // v / a
    EXPECT_NEAR(p.cruise_time_s, 3.0, kExact);  // (10 − 2 · 2) / 2
    EXPECT_NEAR(p.duration_s(), 7.0, kExact);
    EXPECT_NEAR(sample(p, 1.0).s, 0.5, kExact);
    EXPECT_NEAR(sample(p, 3.5).s, 5.0, kExact);  // symmetric: half way at half time
    EXPECT_NEAR(sample(p, 6.0).dds, -1.0, kExact);
}

TEST(SpeedProfile, ShortDistanceNeverReachesTheSpeedLimit) {
    const RestToRestProfile trap = plan_rest_to_rest(1.0, 5.0, 1.0, ProfileShape::kTrapezoidal);
    EXPECT_NEAR(trap.peak_speed, 1.0, kExact);  // sqrt(D a)
    EXPECT_EQ(trap.cruise_time_s, 0.0);
    const RestToRestProfile smooth = plan_rest_to_rest(1.0, 5.0, 1.0, ProfileShape::kSmooth);
    EXPECT_NEAR(smooth.peak_speed, std::sqrt(0.5), kExact);  // sqrt(D a / 2)
    EXPECT_NEAR(sample(smooth, smooth.duration_s()).s, 1.0, kExact);
}

TEST(SpeedProfile, EndsAtRestOnTheDistanceAndStartsAtRestAtZero) {
    for (const ProfileShape shape : {ProfileShape::kTrapezoidal, ProfileShape::kSmooth}) {
        const RestToRestProfile p = plan_rest_to_rest(7.5, 1.5, 0.8, shape);
        const ProfileSample start = sample(p, -1.0);
        const ProfileSample end = sample(p, p.duration_s() + 1.0);
        EXPECT_EQ(start.s, 0.0);
        EXPECT_EQ(start.ds, 0.0);
        EXPECT_EQ(end.s, 7.5);
        EXPECT_EQ(end.ds, 0.0);
        EXPECT_EQ(end.dds, 0.0);
    }
}

TEST(SpeedProfile, SmoothProfileRespectsLimitsAndIsDifferentiable) {
    const RestToRestProfile p = plan_rest_to_rest(9.0, 1.2, 0.7, ProfileShape::kSmooth);
    double max_ds = 0.0, max_dds = 0.0;
    for (int i = 1; i < 400; ++i) {
        const double t = p.duration_s() * i / 400.0;
        const ProfileSample m = sample(p, t);
        max_ds = std::max(max_ds, m.ds);
        max_dds = std::max(max_dds, std::abs(m.dds));
        const ProfileSample lo = sample(p, t - kDiffStepS), hi = sample(p, t + kDiffStepS);
        EXPECT_NEAR((hi.s - lo.s) / (2 * kDiffStepS), m.ds, kDiffTol) << t;
        EXPECT_NEAR((hi.ds - lo.ds) / (2 * kDiffStepS), m.dds, kDiffTol) << t;
    }
    EXPECT_LE(max_ds, 1.2 + kLimitSlack);
    EXPECT_LE(max_dds, 0.7 + kLimitSlack);
    EXPECT_GT(max_dds, 0.69);  // the limit is used, not just respected
}

TEST(SpeedProfile, ZeroDistanceTakesNoTime) {
    const RestToRestProfile p = plan_rest_to_rest(0.0, 1.0, 1.0);
    EXPECT_EQ(p.duration_s(), 0.0);
    EXPECT_EQ(sample(p, 0.5).s, 0.0);
}

TEST(SpeedProfile, RejectsNegativeDistanceAndNonPositiveLimits) {
    EXPECT_THROW(plan_rest_to_rest(-1.0, 1.0, 1.0), InputError);
    EXPECT_THROW(plan_rest_to_rest(1.0, 0.0, 1.0), InputError);
    EXPECT_THROW(plan_rest_to_rest(1.0, 1.0, -2.0), InputError);
    EXPECT_THROW(plan_rest_to_rest(std::numeric_limits<double>::quiet_NaN(), 1.0, 1.0), InputError);
}

}  // namespace
}  // namespace scantling::sim
