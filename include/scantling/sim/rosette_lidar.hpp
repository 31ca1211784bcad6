#pragma once
/// @file
/// Non-repetitive rosette-scanning LiDAR (Livox Mid-70 class) by ray casting. SPEC §1, §10.
///
/// Scan pattern: two Risley prisms turning in opposite directions at `prism_a_hz` and
/// `prism_b_hz` deflect the beam by the complex angle
///   z(t) = (fov_rad / 4) · (exp(i 2π f_a t) + exp(−i 2π f_b t)),   |z| ≤ fov_rad / 2,
/// and the beam leaves at polar angle |z| from the boresight (+x) and azimuth arg z about it:
///   d(t) = (cos|z|, sin|z| cos(arg z), sin|z| sin(arg z)).
/// This traces petals through the centre (f_a + f_b of them per second), densest near the
/// centre as on the real sensor. With f_a / f_b near the golden ratio (defaults) consecutive
/// petals turn by the golden angle, the pattern does not repeat for 1 / gcd(f_a, f_b) = 500 s,
/// and the covered fraction of the field of view grows with integration time.
/// The pattern is a function of ABSOLUTE time: point k of a frame stamped t0 fires at
/// t0 + k / point_rate_hz, so consecutive frames continue the pattern.
///
/// Sensor frame: x = boresight (forward), y left, z up (Livox convention).
/// Output (sensor frame, misses and dropped returns removed): points in firing order,
/// `times_s` from `stamp_s`, `intensities` = albedo · cos(incidence) in [0, 1]; no rings.
/// `scan_moving` casts every point from the pose at its own firing time and expresses it in the
/// sensor frame at that time (raw, distorted), as SpinningLidar does.
/// Determinism and thread-safety as SpinningLidar (noise drawn serially in point order).

#include <Eigen/Geometry>
#include <numbers>
#include <span>
#include <string_view>
#include <vector>

#include <scantling/core/parallel.hpp>
#include <scantling/core/point_cloud.hpp>
#include <scantling/core/random.hpp>
#include <scantling/sim/return_model.hpp>
#include <scantling/sim/sensor_mount.hpp>

namespace scantling::sim {

/// Livox Mid-70 datasheet values unless noted.
struct RosetteLidarConfig {
    double fov_rad = 70.4 * std::numbers::pi / 180.0;  ///< full cone angle (circular FOV)
    double point_rate_hz = 100000.0;                   ///< points per second
    double frame_rate_hz = 10.0;                       ///< frames per second (driver default)
    double prism_a_hz = 618.034;  ///< first prism (ours: golden split of 1000 petals/s)
    double prism_b_hz = 381.966;  ///< second prism, turning the other way
    double min_range_m = 0.05;    ///< Mid-70 minimal detection range
    /// Datasheet: 90 m at 10 % reflectivity, 260 m at 80 %; capped at the 10 % figure (painted
    /// steel in a tank or dock is far below 80 %).
    double max_range_m = 90.0;
    /// Datasheet: range precision 2 cm (1σ at 20 m); dropouts as the OS1 model.
    ReturnModel returns{.sigma_m = 0.02,
                        .dropout_probability = 0.001,
                        .weak_reflectivity = 0.02,
                        .weak_dropout_probability = 0.5};
    Eigen::Isometry3d T_body_sensor = Eigen::Isometry3d::Identity();  ///< mounting extrinsic

    /// round(point_rate_hz / frame_rate_hz).
    int points_per_frame() const;

    /// Throws ConfigError naming the field ("rosette_lidar.fov_rad = 4, expected ...").
    void validate(std::string_view prefix = "rosette_lidar") const;
};

/// Livox Mid-70 (the defaults above).
RosetteLidarConfig livox_mid70();

class RosetteLidar {
  public:
    /// Validates the config (ConfigError).
    explicit RosetteLidar(RosetteLidarConfig config = {});

    /// Unit beam direction in the sensor frame at absolute time `time_s`.
    Eigen::Vector3d beam_direction(double time_s) const;

    /// One frame of points_per_frame() beams starting at absolute time `stamp_s`, from a fixed
    /// vehicle pose.
    PointCloud scan(const SceneView& scene, const Eigen::Isometry3d& T_world_body, Rng& rng,
                    double stamp_s, const ParallelConfig& parallel = {}) const;

    /// One frame while moving: point k is cast from T_world_body_at(stamp_s + k/rate) ·
    /// T_body_sensor (the function is called once per point, in order).
    PointCloud scan_moving(const SceneView& scene, const PoseAtTime& T_world_body_at,
                           double stamp_s, Rng& rng, const ParallelConfig& parallel = {}) const;

    const RosetteLidarConfig& config() const { return config_; }

  private:
    struct Frame;
    Frame frame_at(double stamp_s) const;
    PointCloud cast_frame(const SceneView& scene, const Frame& frame,
                          std::span<const Eigen::Isometry3d> poses, Rng& rng, double stamp_s,
                          const ParallelConfig& parallel) const;

    RosetteLidarConfig config_;
};

}  // namespace scantling::sim
