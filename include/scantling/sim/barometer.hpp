#pragma once
/// @file
/// Barometric altimeter of an aerial vehicle (SPEC §4: the local EKF fuses "a barometer").
///
/// Model: the altitude of the sensor (origin of the sensor frame, mounted at `T_body_sensor`)
/// above the world's z = 0, plus a slowly wandering bias and white noise:
///   altitude' = z_sensor + bias + N(0, altitude_sigma_m²),
///   bias_0 ~ N(0, initial_bias_sigma_m²),  bias_k = bias_{k−1} + N(0, walk² · Δt).
/// The bias stands for what a barometer cannot tell from altitude: the weather, the
/// temperature of the die, the propellers' downwash. Reported as an altitude (what a flight
/// controller's driver gives after the standard-atmosphere conversion), not as pascals.
/// Determinism: the constructor draws 1 normal (initial bias); each measure draws 2 (walk,
/// noise), whatever the configuration. Thread-safety: mutable (the bias); one per sensor.

#include <Eigen/Geometry>
#include <string_view>

#include <scantling/core/random.hpp>

namespace scantling::sim {

/// Defaults: a Bosch BMP388 / TE MS5611 on a small multirotor: ≈ 0.1 m of noise once the
/// downwash is filtered, a turn-on offset of a few decimetres and ≈ 1 cm/√s of drift.
struct BarometerConfig {
    double rate_hz = 50.0;                                            ///< samples per second
    double altitude_sigma_m = 0.1;                                    ///< white noise, 1σ
    double initial_bias_sigma_m = 0.3;                                ///< turn-on offset, 1σ
    double bias_random_walk_m_per_sqrt_s = 0.01;                      ///< drift of the offset
    Eigen::Isometry3d T_body_sensor = Eigen::Isometry3d::Identity();  ///< body ← sensor

    /// Throws ConfigError naming the field ("barometer.rate_hz = 0, expected > 0").
    void validate(std::string_view prefix = "barometer") const;
};

/// The same config with no noise, offset or drift.
BarometerConfig noiseless(BarometerConfig config);

struct BarometerSample {
    double stamp_s = 0.0;
    double altitude_m = 0.0;  ///< noisy, biased, world z of the sensor
};

class Barometer {
  public:
    /// Validates the config (ConfigError) and draws the turn-on offset from `rng`.
    Barometer(BarometerConfig config, Rng& rng);

    /// One sample at `stamp_s` (InputError for a non-finite pose or a stamp going back).
    BarometerSample measure(const Eigen::Isometry3d& T_world_body, Rng& rng, double stamp_s);

    double bias_m() const { return bias_m_; }  ///< offset of the last sample
    const BarometerConfig& config() const { return config_; }

  private:
    BarometerConfig config_;
    double bias_m_ = 0.0;
    double previous_stamp_s_ = 0.0;
    bool has_previous_ = false;
};

}  // namespace scantling::sim
