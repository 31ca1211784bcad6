#pragma once
/// @file
/// Doppler velocity log: four Janus beams ray-cast against the world for bottom lock, the
/// velocity over ground from the beams' radial velocities. SPEC §1 (ROV: DVL), §10.
///
/// Sensor frame: the transducer face looks along +z; beam i (i = 0..3) points at
/// azimuth 45° + 90° i about z, tilted beam_angle_rad from z:
///   b_i = (sin a cos φ_i, sin a sin φ_i, cos a).
/// The default mount looks straight down from a body with z up: sensor x = body x,
/// sensor z = body −z (a rotation of π about x).
/// Per beam: the first surface along b_i within [min_altitude_m, max_altitude_m] / cos a gives
/// bottom lock on that beam; the beam measures its radial velocity u_i = b_i · v_sensor +
/// N(0, σ_i²), σ_i = hypot(beam_velocity_sigma_mps, beam_velocity_sigma_fraction · |b_i · v|),
/// and its range + N(0, range_sigma_m²). v_sensor is the velocity of the transducer over
/// the (static) world, v_world + R_world_body (ω_body × r), r the lever arm.
/// With at least 3 locked beams the velocity is the weighted least-squares solution of
/// B v = u (weights 1/σ_i² from the measured u_i, covariance (Bᵀ W B)⁻¹) and the sample is
/// valid; otherwise bottom lock is lost.
/// The output velocity is that of the transducer expressed in body axes (add −ω × r with
/// the gyro to move it to the body origin); altitude = mean over locked beams of range · cos a.
/// Determinism: 2 normals per beam (velocity, range), beams in order, always drawn.
/// Thread-safety: `measure` is const; one Rng per caller.

#include <Eigen/Geometry>
#include <array>
#include <limits>
#include <string_view>

#include <scantling/core/random.hpp>
#include <scantling/sim/motion_state.hpp>
#include <scantling/sim/sensor_mount.hpp>

namespace scantling::sim {

/// Defaults: Water Linked DVL A50 class (beams 22.5° from the axis, 0.05–50 m altitude, up to
/// 15 Hz), looking down.
struct DvlConfig {
    double rate_hz = 10.0;                             ///< samples per second (caller steps)
    double beam_angle_rad = 0.39269908169872414;       ///< 22.5°, each beam from the sensor z
    double min_altitude_m = 0.05;                      ///< nearer bottoms give no lock
    double max_altitude_m = 50.0;                      ///< farther bottoms give no lock
    double beam_velocity_sigma_mps = 0.002;            ///< 1σ floor of a beam's radial velocity
    double beam_velocity_sigma_fraction = 0.01;        ///< 1σ as a fraction of the radial speed
    double range_sigma_m = 0.01;                       ///< 1σ of a beam's range
    Eigen::Isometry3d T_body_sensor = looking_down();  ///< body ← sensor (+z along the axis)

    /// Rotation of π about x: sensor z = body −z.
    static Eigen::Isometry3d looking_down();

    /// Throws ConfigError naming the field ("dvl.max_altitude_m = 0, expected ...").
    void validate(std::string_view prefix = "dvl") const;
};

/// The same config with velocity and range noise off.
DvlConfig noiseless(DvlConfig config);

struct DvlBeam {
    bool locked = false;  ///< bottom found within the altitude window
    double range_m = std::numeric_limits<double>::quiet_NaN();       ///< noisy slant range
    double velocity_mps = std::numeric_limits<double>::quiet_NaN();  ///< noisy radial velocity
};

struct DvlSample {
    double stamp_s = 0.0;
    bool valid = false;  ///< bottom lock: at least 3 beams locked
    Eigen::Vector3d v_body_mps =
        Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
    Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();          ///< of v_body_mps, body axes
    double altitude_m = std::numeric_limits<double>::quiet_NaN();  ///< along the sensor z
    std::array<DvlBeam, 4> beams{};
};

class Dvl {
  public:
    /// Validates the config (ConfigError) and precomputes the beam directions.
    explicit Dvl(DvlConfig config = {});

    /// One sample from the true motion. Throws InputError for non-finite truth.
    DvlSample measure(const SceneView& scene, const MotionState& truth, Rng& rng) const;

    /// Unit beam directions, sensor frame.
    const std::array<Eigen::Vector3d, 4>& beams_sensor() const { return beams_sensor_; }

    const DvlConfig& config() const { return config_; }

  private:
    DvlBeam measure_beam(const SceneView& scene, const Eigen::Isometry3d& T_world_sensor, int i,
                         const Eigen::Vector3d& v_sensor_mps, Rng& rng) const;
    double beam_sigma_mps(double radial_velocity_mps) const;
    void fit_velocity(DvlSample& sample) const;

    DvlConfig config_;
    std::array<Eigen::Vector3d, 4> beams_sensor_;
};

}  // namespace scantling::sim
