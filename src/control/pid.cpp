#include <scantling/control/pid.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include <fmt/format.h>

#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>

namespace scantling::control {
namespace {

void require_finite_input(double value, std::string_view what) {
    if (!std::isfinite(value)) {
        throw InputError(fmt::format("pid.update: {} = {}, expected finite", what, value));
    }
}

}  // namespace

void PidConfig::validate(std::string_view prefix) const {
    using namespace config_checks;
    require_non_negative(kp, prefix, "kp");
    require_non_negative(ki, prefix, "ki");
    require_non_negative(kd, prefix, "kd");
    require_non_negative(derivative_filter_s, prefix, "derivative_filter_s");
    require(!std::isnan(output_min) && output_min <= 0.0, prefix, "output_min", output_min,
            "<= 0 (not NaN)");
    require(!std::isnan(output_max) && output_max >= 0.0 && output_max > output_min, prefix,
            "output_max", output_max, fmt::format(">= 0 and > output_min = {}", output_min));
}

Pid::Pid(const PidConfig& config, std::string_view name) : config_(config) {
    config_.validate(name);
}

void Pid::reset() {
    integral_ = 0.0;
    derivative_ = 0.0;
    has_previous_ = false;
    terms_ = {};
}

void Pid::restore_integral(double integral) {
    require_finite_input(integral, "integral");
    integral_ = std::clamp(integral, config_.output_min, config_.output_max);
    terms_.i = integral_;
}

double Pid::filtered_derivative(double measurement, double dt_s) {
    if (!has_previous_) return 0.0;
    const double raw = (measurement - previous_measurement_) / dt_s;
    return derivative_ + dt_s / (config_.derivative_filter_s + dt_s) * (raw - derivative_);
}

void Pid::integrate(double error, double p_plus_d, double dt_s) {
    const double candidate =
        std::clamp(integral_ + config_.ki * error * dt_s, config_.output_min, config_.output_max);
    // Conditional integration: while saturated, integrate only what pulls back inside.
    const double unsaturated = p_plus_d + candidate;
    const bool pushes_up = unsaturated > config_.output_max && error > 0.0;
    const bool pushes_down = unsaturated < config_.output_min && error < 0.0;
    if (!pushes_up && !pushes_down) integral_ = candidate;
}

double Pid::update(double setpoint, double measurement, double dt_s) {
    require_finite_input(setpoint, "setpoint");
    require_finite_input(measurement, "measurement");
    if (!(std::isfinite(dt_s) && dt_s > 0.0)) {
        throw InputError(fmt::format("pid.update: dt_s = {}, expected finite > 0", dt_s));
    }
    const double error = setpoint - measurement;
    derivative_ = filtered_derivative(measurement, dt_s);
    previous_measurement_ = measurement;
    has_previous_ = true;
    const double p = config_.kp * error;
    const double d = -config_.kd * derivative_;
    integrate(error, p + d, dt_s);
    const double unsaturated = p + integral_ + d;
    const double output = std::clamp(unsaturated, config_.output_min, config_.output_max);
    terms_ = {p, integral_, d, unsaturated, output, unsaturated != output};
    return output;
}

}  // namespace scantling::control
