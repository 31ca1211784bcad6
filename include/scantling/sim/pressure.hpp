#pragma once
/// @file
/// Pressure (depth) sensor of an underwater vehicle. SPEC §1 (ROV: pressure for depth), §5
/// (heave is controlled on depth), §10.
///
/// Model: the sensor (origin of the sensor frame, mounted at `T_body_sensor`) at world height z
/// below the water surface at height surface_z_m feels the hydrostatic pressure
///   p = atmospheric_pressure_pa + water_density_kgpm3 · gravity_mps2 · max(0, surface_z_m − z)
/// plus N(0, pressure_sigma_pa²); above the surface it feels the atmosphere alone.
/// The reported depth converts the noisy pressure back with the same constants,
///   depth = (p' − atmospheric_pressure_pa) / (water_density_kgpm3 · gravity_mps2),
/// so it is the true depth plus noise (and ≈ 0 in air).
/// Determinism: one normal per measurement. Thread-safety: `measure` is const.

#include <Eigen/Geometry>
#include <string_view>

#include <scantling/core/random.hpp>

namespace scantling::sim {

/// Defaults: Blue Robotics Bar30 (MS5837-30BA) in sea water: 0.2 mbar resolution; 1σ noise
/// taken as 0.5 mbar (≈ 5 mm of sea water).
struct PressureConfig {
    double rate_hz = 20.0;                      ///< samples per second (caller steps)
    double pressure_sigma_pa = 50.0;            ///< 1σ noise, pascal
    double water_density_kgpm3 = 1025.0;        ///< sea water; 1000 for fresh water
    double gravity_mps2 = 9.81;                 ///< |g|
    double atmospheric_pressure_pa = 101325.0;  ///< at the surface
    double surface_z_m = 0.0;                   ///< world z of the water surface
    Eigen::Isometry3d T_body_sensor = Eigen::Isometry3d::Identity();  ///< body ← sensor

    /// Throws ConfigError naming the field ("pressure.water_density_kgpm3 = 0, expected > 0").
    void validate(std::string_view prefix = "pressure") const;
};

struct PressureSample {
    double stamp_s = 0.0;
    double pressure_pa = 0.0;  ///< absolute, noisy
    double depth_m = 0.0;      ///< below the surface, from the noisy pressure
};

class PressureSensor {
  public:
    /// Validates the config (ConfigError).
    explicit PressureSensor(PressureConfig config = {});

    /// One reading from the vehicle pose. Throws InputError for a non-finite pose.
    PressureSample measure(const Eigen::Isometry3d& T_world_body, Rng& rng,
                           double stamp_s = 0.0) const;

    /// The true depth of the sensor below the surface (negative above it), metres.
    double true_depth_m(const Eigen::Isometry3d& T_world_body) const;

    const PressureConfig& config() const { return config_; }

  private:
    PressureConfig config_;
};

}  // namespace scantling::sim
