// PID: step responses with the position controller's gains, anti-windup under saturation, no
// derivative kick on a set-point step, and the input and config contracts.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include <scantling/control/pid.hpp>
#include <scantling/control/position_controller.hpp>
#include <scantling/core/error.hpp>

#include "../planning/expect_error.hpp"
#include "velocity_plant.hpp"

namespace scantling::control {
namespace {

constexpr double kDt = 0.05;  // s: the 20 Hz set-point rate of the FCU link

struct StepResponse {
    double overshoot = 0.0;    // beyond the set-point, in its units
    double settle_s = 0.0;     // last time outside the band
    double final_error = 0.0;  // at the end
};

/// The controller's axis PID closing the loop on the plant's position (x/u = 1/(s(τs + 1))).
StepResponse position_step(const PidConfig& config, double step_m, double band_m) {
    Pid pid(config);
    test::ScalarPlant plant{0.0, 0.0};
    StepResponse response;
    for (int k = 1; k <= 600; ++k) {  // 30 s
        plant.step(pid.update(step_m, plant.p, kDt), kDt, 0.0);
        response.overshoot = std::max(response.overshoot, plant.p - step_m);
        if (std::abs(plant.p - step_m) > band_m) response.settle_s = k * kDt;
    }
    response.final_error = std::abs(plant.p - step_m);
    return response;
}

TEST(Pid, PositionControllerGainsSettleStepsWithBoundedOvershoot) {
    const PidConfig gains = PositionController().axis(0).config();
    // Measured at 20 Hz: overshoot 0.041, 0.056, 0.058 m over 0.3, 1 and 5 m steps (the 5 m
    // one saturated at 1 m/s for ~4 s), within 2 cm after 4.7, 6.2, 10.3 s. Bound 0.10 m:
    // half WP_tol, so a waypoint once reached stays reached.
    constexpr double kMaxOvershootM = 0.10;
    constexpr double kBandM = 0.02;  // "settled": within 2 cm
    for (const double step_m : {0.3, 1.0, 5.0}) {
        const StepResponse response = position_step(gains, step_m, kBandM);
        std::printf("step %.1f m: overshoot %.3f m, settled (2 cm) after %.2f s\n", step_m,
                    response.overshoot, response.settle_s);
        EXPECT_LE(response.overshoot, kMaxOvershootM) << "step " << step_m << " m";
        EXPECT_LE(response.settle_s, 12.0) << "step " << step_m << " m";
        EXPECT_LE(response.final_error, 1e-3) << "step " << step_m << " m";
    }
}

TEST(Pid, PiWithPoleZeroCancellationOnAFirstOrderPlantDoesNotOvershoot) {
    // ki/kp = 1/τ cancels the plant's pole: the loop is first order, time constant τ/kp.
    Pid pid({.kp = 2.0,
             .ki = 2.0 / 0.3,
             .kd = 0.0,
             .derivative_filter_s = 0.0,
             .output_min = -10.0,
             .output_max = 10.0});
    test::ScalarPlant plant{0.0, 0.0};  // the plant's velocity is the first-order output
    double peak = 0.0;
    for (int k = 0; k < 100; ++k) {  // 5 s = 33 closed-loop time constants
        plant.step(pid.update(1.0, plant.v, kDt), kDt, 0.0);
        peak = std::max(peak, plant.v);
    }
    EXPECT_LE(peak, 1.0 + 1e-3);  // discretisation leaves < 0.1 %
    EXPECT_NEAR(plant.v, 1.0, 1e-6);
}

TEST(Pid, AntiWindupBoundsTheIntegralUnderSaturation) {
    const PidConfig config{.kp = 1.0,
                           .ki = 1.0,
                           .kd = 0.0,
                           .derivative_filter_s = 0.0,
                           .output_min = -1.0,
                           .output_max = 1.0};
    Pid pid(config);
    for (int k = 0; k < 2000; ++k) {  // 100 s of an unreachable set-point, output pinned at +1
        EXPECT_EQ(pid.update(10.0, 0.0, kDt), 1.0);
        EXPECT_LE(std::abs(pid.last_terms().i), config.output_max);
        EXPECT_TRUE(pid.last_terms().saturated);
    }
    // A wound-up integrator (100 s · 10) would hold the output at +1 for ~1000 s more; this one
    // follows the error at once.
    EXPECT_EQ(pid.update(-10.0, 0.0, kDt), -1.0);
    EXPECT_EQ(pid.update(0.0, 0.0, kDt), 0.0);  // the integral never grew
    // A pure integrator is clamped at the output limit.
    Pid integrator({.kp = 0.0,
                    .ki = 1.0,
                    .kd = 0.0,
                    .derivative_filter_s = 0.0,
                    .output_min = -1.0,
                    .output_max = 1.0});
    for (int k = 0; k < 200; ++k) integrator.update(1.0, 0.0, kDt);
    EXPECT_EQ(integrator.last_terms().i, 1.0);
}

TEST(Pid, DerivativeOnMeasurementGivesNoKickOnASetPointStep) {
    const PidConfig config{.kp = 0.0,
                           .ki = 0.0,
                           .kd = 1.0,
                           .derivative_filter_s = 0.0,
                           .output_min = -100.0,
                           .output_max = 100.0};
    Pid pid(config);
    EXPECT_EQ(pid.update(0.0, 0.0, kDt), 0.0);
    EXPECT_EQ(pid.update(5.0, 0.0, kDt), 0.0);                // set-point step: no kick
    EXPECT_DOUBLE_EQ(pid.update(5.0, 0.1, kDt), -0.1 / kDt);  // measurement moved: damping
    PidConfig filtered = config;
    filtered.derivative_filter_s = kDt;  // α = dt / (τ_f + dt) = 1/2
    Pid smooth(filtered);
    smooth.update(0.0, 0.0, kDt);
    EXPECT_DOUBLE_EQ(smooth.update(0.0, 0.1, kDt), -0.5 * 0.1 / kDt);
}

TEST(Pid, FirstUpdateAndResetHaveNoDerivativeHistory) {
    Pid pid({.kp = 0.0,
             .ki = 1.0,
             .kd = 1.0,
             .derivative_filter_s = 0.0,
             .output_min = -100.0,
             .output_max = 100.0});
    EXPECT_EQ(pid.update(0.0, 3.0, kDt), -3.0 * kDt);  // I only; D needs a previous sample
    pid.update(0.0, 1.0, kDt);
    pid.reset();
    EXPECT_EQ(pid.update(0.0, 3.0, kDt), -3.0 * kDt);
}

TEST(Pid, NonFiniteInputsAndBadStepsThrowAndLeaveTheStateUnchanged) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    const PidConfig config = PositionController().axis(0).config();
    Pid pid(config);
    Pid reference(config);
    pid.update(1.0, 0.0, kDt);
    reference.update(1.0, 0.0, kDt);
    SCANTLING_EXPECT_ERROR(pid.update(nan, 0.0, kDt), InputError, "setpoint = nan");
    SCANTLING_EXPECT_ERROR(pid.update(1.0, inf, kDt), InputError, "measurement = inf");
    SCANTLING_EXPECT_ERROR(pid.update(1.0, 0.0, 0.0), InputError, "dt_s = 0");
    SCANTLING_EXPECT_ERROR(pid.update(1.0, 0.0, -kDt), InputError, "dt_s = -0.05");
    SCANTLING_EXPECT_ERROR(pid.update(1.0, 0.0, nan), InputError, "dt_s = nan");
    EXPECT_EQ(pid.update(1.0, 0.1, kDt), reference.update(1.0, 0.1, kDt));
}

TEST(Pid, RestoringTheIntegralClampsItAndRefusesNaN) {
    Pid pid({.kp = 1.0, .ki = 2.0, .output_min = -1.0, .output_max = 1.0});
    pid.update(1.0, 0.5, 0.1);
    EXPECT_DOUBLE_EQ(pid.integral(), 0.1);  // ki e dt = 2 · 0.5 · 0.1
    pid.restore_integral(0.0);
    EXPECT_EQ(pid.integral(), 0.0);
    EXPECT_EQ(pid.last_terms().i, 0.0);
    pid.restore_integral(5.0);
    EXPECT_EQ(pid.integral(), 1.0);
    EXPECT_THROW(pid.restore_integral(std::numeric_limits<double>::quiet_NaN()), InputError);
    EXPECT_EQ(pid.integral(), 1.0);
}

TEST(Pid, BadConfigsAreRefusedNamingTheField) {
    SCANTLING_EXPECT_ERROR(Pid({.kp = -1.0,
                                .ki = 0.0,
                                .kd = 0.0,
                                .derivative_filter_s = 0.0,
                                .output_min = -1.0,
                                .output_max = 1.0}),
                           ConfigError, "pid.kp = -1");
    SCANTLING_EXPECT_ERROR(Pid({.kp = 1.0,
                                .ki = 0.0,
                                .kd = 0.0,
                                .derivative_filter_s = -0.1,
                                .output_min = -1.0,
                                .output_max = 1.0},
                               "x"),
                           ConfigError, "x.derivative_filter_s = -0.1");
    SCANTLING_EXPECT_ERROR(Pid({.kp = 1.0,
                                .ki = 0.0,
                                .kd = 0.0,
                                .derivative_filter_s = 0.0,
                                .output_min = 0.0,
                                .output_max = 0.0}),
                           ConfigError, "pid.output_max = 0");
}

}  // namespace
}  // namespace scantling::control
