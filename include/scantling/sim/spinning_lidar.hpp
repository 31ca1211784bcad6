#pragma once
/// @file
/// Spinning multi-beam LiDAR (Ouster OS1-64, OS0-64, Velodyne HDL-64E) by ray casting. SPEC §1,
/// §10.
///
/// Sensor frame: x forward, y left, z up, origin on the rotation axis at the optical centre
/// (Ouster's "sensor coordinate frame"). Beam (ring r, column c) has elevation
/// `ring_elevations_rad[r]` above the xy plane and azimuth
///   φ_c = start_azimuth_rad − 2π c / columns      (from +x towards +y),
/// i.e. the head turns clockwise seen from above, as Ouster and Velodyne heads do, and the
/// sweep starts (and ends) at `start_azimuth_rad` (default π: behind the sensor, where Ouster
/// splits its frames). All rings of a column fire together at
///   t_c = c / (columns · rate_hz)  ∈ [0, 1/rate_hz)   from the sweep start.
///
/// Output cloud (sensor frame, misses and dropped returns removed, no NaN): points in firing
/// order (column 0 rings 0..R−1, column 1, ...), `rings` (0 = lowest elevation), `times_s`
/// (t_c, relative to `stamp_s` = sweep start), `intensities` (calibrated reflectivity
/// albedo · cos(incidence) in [0, 1], before dropout, noise-free).
///
/// Motion distortion (`scan_moving`): each column is cast from the pose at its own firing
/// time, and each point is expressed in the sensor frame AT ITS OWN FIRING TIME (raw, distorted
/// data, as the hardware delivers it); de-skewing needs the trajectory and `times_s`.
///
/// Determinism: the same config, poses and Rng state give bit-identical clouds for any thread
/// count; noise is drawn from `rng` serially in point order (one uniform and one normal per
/// in-range return). Thread-safety: scans are const; give each concurrent caller its own Rng.
/// Cost: one ray per beam, cast in parallel (see RayCaster::cast_batch).

#include <Eigen/Geometry>
#include <cstdint>
#include <numbers>
#include <string_view>
#include <vector>

#include <scantling/core/parallel.hpp>
#include <scantling/core/point_cloud.hpp>
#include <scantling/core/random.hpp>
#include <scantling/sim/return_model.hpp>
#include <scantling/sim/sensor_mount.hpp>

namespace scantling::sim {

/// `rings` elevations evenly spread from `lowest_rad` to `highest_rad` (both included),
/// ascending. Throws ConfigError unless rings >= 2 and lowest < highest (finite).
std::vector<double> uniform_ring_elevations(int rings, double lowest_rad, double highest_rad);

/// Return model of the Ouster OS1 (datasheet: range repeatability 1σ ±1.5 cm at high SNR,
/// ±3 cm at SNR 100): σ = 1.5 cm + 0.2 mm/m · r (3.5 cm at 100 m, where SNR is low); 0.1 %
/// random dropouts; returns with reflectivity < 0.02 (grazing or dark) lost half of the time.
ReturnModel ouster_os1_returns();

struct SpinningLidarConfig {
    /// Elevation of each ring, radians, strictly ascending (ring 0 = lowest). Default: the
    /// OS1-64 of SPEC §1, 64 rings uniform over ±22.5°.
    std::vector<double> ring_elevations_rad = uniform_ring_elevations(
        64, -22.5 * std::numbers::pi / 180.0, 22.5 * std::numbers::pi / 180.0);
    int columns = 1024;     ///< azimuth steps per revolution (OS1: 512, 1024 or 2048)
    double rate_hz = 10.0;  ///< revolutions per second (OS1: 10 or 20)
    double start_azimuth_rad = std::numbers::pi;  ///< azimuth of column 0 (sweep boundary)
    double min_range_m = 0.3;    ///< nearer returns are dropped (OS1 rev 6+: 0.3 m)
    double max_range_m = 100.0;  ///< SPEC §1 (OS1: 100 m on 80 % targets)
    ReturnModel returns = ouster_os1_returns();
    Eigen::Isometry3d T_body_sensor = Eigen::Isometry3d::Identity();  ///< mounting extrinsic

    /// Number of rings.
    int rings() const { return static_cast<int>(ring_elevations_rad.size()); }

    /// Throws ConfigError naming the field ("spinning_lidar.columns = 0, expected >= 1").
    void validate(std::string_view prefix = "spinning_lidar") const;
};

/// Ouster OS1-64 (SPEC §1): 64 rings uniform over ±22.5° (rev 6+ "wide" OS1-64), 0.3–100 m.
/// Lidar modes: columns × rate_hz ∈ {512×10, 512×20, 1024×10, 1024×20, 2048×10}; anything
/// else throws ConfigError ("ouster_os1_64.columns = ...").
SpinningLidarConfig ouster_os1_64(int columns = 1024, double rate_hz = 10.0);

/// Ouster OS0-64-like ultra-wide LiDAR for confined spaces: 64 rings uniform over ±45° (the
/// OS0's 90° vertical field of view), the OS1's lidar modes (columns × rate_hz as
/// ouster_os1_64, else ConfigError "ouster_os0_64.columns = ..."), 0.3–50 m, and the OS1's
/// return model (ouster_os1_returns). Provenance: the ±45° field of view and the modes are
/// Ouster's; the range window and the noise are approximate (shorter range than the OS1, as
/// for the OS0, not datasheet figures).
SpinningLidarConfig ouster_os0_64(int columns = 1024, double rate_hz = 10.0);

/// Velodyne HDL-64E (S2/S3 datasheet): 64 lasers from +2.0° to −24.8° (26.8° vertical FOV) in
/// two blocks, approximated as upper 32 lasers every 1/3° from +2.0° to −8.33° and lower 32
/// evenly from −8.83° to −24.8° (~0.515°); 10 Hz; 0.1728° azimuth resolution at 600 rpm
/// → 2083 columns (≈1.33 M points/s); 120 m range (80 % targets), 0.9 m minimum; range
/// accuracy < 2 cm (1σ) → σ = 2 cm; dropouts as the OS1.
SpinningLidarConfig velodyne_hdl64e();

class SpinningLidar {
  public:
    /// Validates the config (ConfigError) and precomputes the beam directions.
    explicit SpinningLidar(SpinningLidarConfig config = {});

    /// One full sweep from a fixed vehicle pose, stamped `stamp_s` (sweep start).
    PointCloud scan(const SceneView& scene, const Eigen::Isometry3d& T_world_body, Rng& rng,
                    double stamp_s = 0.0, const ParallelConfig& parallel = {}) const;

    /// One sweep starting at `sweep_start_s` while the vehicle moves: column c is cast from
    /// T_world_body_at(sweep_start_s + t_c) · T_body_sensor and its points are in that
    /// firing-time sensor frame (see the file comment). Calls the pose function once per
    /// column, in column order. Throws InputError when the function is empty or returns a
    /// non-finite pose.
    PointCloud scan_moving(const SceneView& scene, const PoseAtTime& T_world_body_at,
                           double sweep_start_s, Rng& rng,
                           const ParallelConfig& parallel = {}) const;

    /// Firing time of each column from the sweep start, seconds.
    const std::vector<double>& column_times_s() const;

    const SpinningLidarConfig& config() const { return config_; }

  private:
    SpinningLidarConfig config_;
    std::vector<Eigen::Vector3d> directions_sensor_;  // column-major: c * rings + r
    std::vector<double> column_times_s_;
    std::vector<std::uint16_t> rings_;
};

}  // namespace scantling::sim
