#pragma once
/// @file
/// Single-beam range finders (LiDAR / ToF point sensors, ultrasonic rangers) by ray casting.
/// SPEC §1: down-looking range finder (40 m) and up-looking ToF (60 m) on the drone,
/// ultrasonic rangers on the crawler.
///
/// Sensor frame: the beam axis is +x. A beam with a cone (beam_half_angle_rad > 0 and
/// cone_rings > 0) casts the axis ray plus `cone_rings` rings of `rays_per_ring` rays at
/// polar angles k / cone_rings · beam_half_angle_rad (k = 1..cone_rings, alternate rings
/// turned by half a step) and reports the NEAREST hit, as a first-echo sensor does.
/// Noise: measured = r + N(0, σ²), σ = max(range_sigma_m, range_sigma_fraction · r).
/// A reading is invalid when nothing lies within [min_range_m, max_range_m] (nearest hit
/// nearer than min_range_m also gives no reading: the sensor is blind there).
/// Determinism: exactly one normal is drawn per call (even for an invalid reading).

#include <Eigen/Geometry>
#include <limits>
#include <string_view>
#include <vector>

#include <scantling/core/random.hpp>
#include <scantling/sim/sensor_mount.hpp>

namespace scantling::sim {

/// Defaults: Garmin LIDAR-Lite v3 (datasheet: 5 cm – 40 m, ±2.5 cm accuracy above 1 m taken as
/// 1σ, 8 mrad beam divergence), looking along +x of its frame.
struct RangeFinderConfig {
    double min_range_m = 0.05;
    double max_range_m = 40.0;
    double rate_hz = 50.0;               ///< readings per second
    double range_sigma_m = 0.025;        ///< 1σ floor, metres
    double range_sigma_fraction = 0.0;   ///< 1σ as a fraction of the range (when larger)
    double beam_half_angle_rad = 0.004;  ///< half the beam divergence / cone angle
    int cone_rings = 0;                  ///< 0 = the axis ray only
    int rays_per_ring = 8;
    Eigen::Isometry3d T_body_sensor = Eigen::Isometry3d::Identity();  ///< body ← sensor (+x beam)

    /// Throws ConfigError naming the field ("range_finder.max_range_m = 0, expected ...").
    void validate(std::string_view prefix = "range_finder") const;
};

/// Garmin LIDAR-Lite v3 mounted looking down: sensor +x = body −z (T_body_sensor rotation
/// only). Place it with T_body_sensor.translation() as needed.
RangeFinderConfig down_looking_lidar_lite_v3();

/// TeraRanger Evo 60m mounted looking up (sensor +x = body +z): 0.5–60 m, ±4 cm up to 14 m and
/// 1.5 % beyond (taken as 1σ), 2° field of view (one ring of 6 rays at 1°), 100 Hz.
RangeFinderConfig up_looking_teraranger_evo_60m();

/// HC-SR04-class ultrasonic ranger looking forward (+x): 0.02–4 m, 15° measuring cone
/// (two rings of 8 rays out to 7.5°), 3 mm resolution taken as 1σ, 20 Hz.
RangeFinderConfig ultrasonic_hc_sr04();

struct RangeMeasurement {
    bool valid = false;
    double range_m = std::numeric_limits<double>::quiet_NaN();  ///< noisy; NaN when invalid
    double stamp_s = 0.0;
};

class RangeFinder {
  public:
    /// Validates the config (ConfigError) and precomputes the cone rays.
    explicit RangeFinder(RangeFinderConfig config = {});

    /// One reading from the vehicle pose.
    RangeMeasurement measure(const SceneView& scene, const Eigen::Isometry3d& T_world_body,
                             Rng& rng, double stamp_s = 0.0) const;

    /// The cone's unit ray directions, sensor frame (the axis first).
    const std::vector<Eigen::Vector3d>& rays_sensor() const { return rays_sensor_; }

    const RangeFinderConfig& config() const { return config_; }

  private:
    RangeFinderConfig config_;
    std::vector<Eigen::Vector3d> rays_sensor_;
};

}  // namespace scantling::sim
