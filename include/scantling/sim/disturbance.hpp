#pragma once
/// @file
/// Seeded random disturbances for the vehicle models (SPEC §10): wind gusts on the MAV, sea
/// currents on the ROV, wheel slip on the crawler.
///
/// Each of the three components is a constant mean plus an Ornstein–Uhlenbeck process
/// (first-order Gauss–Markov, the continuous-time analogue of the first-order Dryden gust
/// filter): dg = −g / T dt + σ sqrt(2 / T) dW, stationary N(0, σ²), autocorrelation
/// σ² exp(−|τ| / T). It is advanced with the exact discretisation
/// g ← g e^(−dt/T) + σ sqrt(1 − e^(−2 dt/T)) n, so its statistics do not depend on the step,
/// and it starts from a stationary draw (no warm-up transient).
///
/// Determinism: the same config, seed and sequence of steps give the same values (exactly
/// three normals per step and three at construction, drawn from an Rng owned by the process).
/// Thread-safety: a GustProcess is mutable; one per vehicle.

#include <Eigen/Core>
#include <cstdint>
#include <string_view>

#include <scantling/core/random.hpp>

namespace scantling::sim {

/// Units are those of the disturbed quantity (m/s for wind and currents, a fraction for slip).
struct GustConfig {
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();   ///< constant part
    Eigen::Vector3d sigma = Eigen::Vector3d::Zero();  ///< stationary 1σ per component (>= 0)
    double correlation_time_s = 2.0;                  ///< T of the OU process (> 0)

    /// Throws ConfigError naming the field ("mav.wind.sigma = (-1, 0, 0), expected >= 0").
    void validate(std::string_view prefix) const;
};

class GustProcess {
  public:
    /// Validates (ConfigError with `prefix`) and draws the stationary initial value.
    GustProcess(const GustConfig& config, std::uint64_t seed, std::string_view prefix = "gust");

    /// Advances the process by `dt_s` (> 0; InputError otherwise).
    void step(double dt_s);

    /// Current value: mean + random part.
    Eigen::Vector3d value() const { return config_.mean + gust_; }

    const GustConfig& config() const { return config_; }

  private:
    GustConfig config_;
    Rng rng_;
    Eigen::Vector3d gust_ = Eigen::Vector3d::Zero();
};

}  // namespace scantling::sim
