#pragma once
/// @file
/// A discrete PID controller, the building block of the MAV position controller (SPEC §4:
/// "three independent PIDs, one per axis"; D5.2 §II.1).
///
///   e = r − y
///   P = kp e
///   I ← I + ki e dt, unless the output is saturated and e pushes it further (conditional
///       integration), and always clamped to [output_min, output_max]: the integral never
///       winds up beyond what the output can use (anti-windup by clamping)
///   D = −kd ẏ_f, ẏ_f ← ẏ_f + dt / (τ_f + dt) · ((y − y_prev)/dt − ẏ_f)
///       (derivative on the measurement, not the error, so a set-point step gives no "kick";
///       a first-order low-pass of time constant τ_f, backward Euler, so any dt > 0 is stable)
///   u = clamp(P + I + D, output_min, output_max)
/// The first update after construction or reset() has no previous measurement: D = 0.
///
/// Units: whatever r and y are in (e.g. metres) and u in (e.g. m/s); kp in u/e, ki in u/(e·s),
/// kd in u·s/e. Input contract: r, y finite and dt finite > 0, else InputError (the state is
/// left unchanged, so a NaN never reaches the output). Thread-safety: mutable state, one
/// instance per loop. Cost: O(1). Deterministic.

#include <limits>
#include <string_view>

namespace scantling::control {

/// No defaults for a generic loop: the gains here give a pure P controller with unit gain;
/// the position controller sets its own (position_controller.hpp).
struct PidConfig {
    double kp = 1.0;  ///< proportional gain, ≥ 0
    double ki = 0.0;  ///< integral gain, 1/s · kp's units, ≥ 0
    double kd = 0.0;  ///< derivative gain (on the measurement), s · kp's units, ≥ 0
    double derivative_filter_s = 0.0;  ///< τ_f of the derivative's low-pass, ≥ 0 (0: none)
    double output_min = -std::numeric_limits<double>::infinity();  ///< < output_max
    double output_max = std::numeric_limits<double>::infinity();   ///< may be ±∞: no limit

    /// Throws ConfigError naming "<prefix>.<field>": finite gains ≥ 0, τ_f ≥ 0, limits not NaN
    /// and output_min < output_max, with 0 in [output_min, output_max] (so reset's zero
    /// integral is within them).
    void validate(std::string_view prefix = "pid") const;
};

/// The terms of the last update, for logs and tests.
struct PidTerms {
    double p = 0.0;
    double i = 0.0;  ///< the integrator's state after the update
    double d = 0.0;
    double unsaturated = 0.0;  ///< P + I + D before the output clamp
    double output = 0.0;       ///< clamp(P + I + D, output_min, output_max)
    bool saturated = false;    ///< P + I + D was outside the limits
};

class Pid {
  public:
    /// Validates the config (ConfigError).
    explicit Pid(const PidConfig& config = {}, std::string_view name = "pid");

    /// One step: the output for set-point `setpoint` and measurement `measurement`, `dt_s` after
    /// the previous update. Throws InputError for non-finite inputs or dt ≤ 0.
    double update(double setpoint, double measurement, double dt_s);
    /// Forgets the integral and the derivative's history.
    void reset();
    /// The integrator's state (I), in the output's units.
    double integral() const { return integral_; }
    /// Sets the integrator back to `integral` (clamped to the output limits): anti-windup for
    /// a caller whose own limit acts on several PIDs at once (position_controller.hpp's vector
    /// clamp). InputError if not finite.
    void restore_integral(double integral);

    const PidTerms& last_terms() const { return terms_; }
    const PidConfig& config() const { return config_; }

  private:
    double filtered_derivative(double measurement, double dt_s);
    void integrate(double error, double p_plus_d, double dt_s);

    PidConfig config_;
    double integral_ = 0.0;
    double previous_measurement_ = 0.0;
    double derivative_ = 0.0;  // ẏ_f
    bool has_previous_ = false;
    PidTerms terms_;
};

}  // namespace scantling::control
