#pragma once
/// @file
/// Forward-looking multibeam imaging sonar (Blueprint Oculus M750d class, as on the Blueye X3):
/// a beams × range-bins echo image by ray casting, with elevation ambiguity and speckle.
/// SPEC §1 (ROV sonar, 130° × 20°, configurable range), §5 (hull-relative adaptation and the
/// sonar inspection map read this image), §10.
///
/// Sensor frame: x is the boresight, y left, z up. Beam b looks along the bearing
///   β_b = −horizontal_fov/2 + horizontal_fov · (b + ½) / num_beams   (positive to the left),
/// and is sampled by `rays_per_beam` rays at elevations ε_k = −vertical_fov/2 + vertical_fov ·
/// (k + ½) / rays_per_beam, direction (cos ε cos β, cos ε sin β, sin ε). A sonar cannot tell
/// elevations apart: every ray of a beam adds into the same (beam, range-bin) cell.
/// Bin j covers [min_range + j Δ, min_range + (j + 1) Δ), Δ = (max_range − min_range) / num_bins.
///
/// Echo model: a ray hitting a surface at range r and incidence θ adds the power
///   albedo · cos(θ)^incidence_exponent · (1 m / r)^spreading_exponent · 10^(−absorption · 2r / 10)
/// divided by rays_per_beam (the Surface albedo stands for the acoustic backscatter strength;
/// spreading_exponent 1 leaves the residual of the sonar's time-varied gain). Each cell's
/// power P = signal + noise_floor; the reported intensity is the echo AMPLITUDE
///   gain · √P (speckle off),  gain · √(−P ln(1 − u)), u ~ U(0, 1) (speckle on),
/// i.e. Rayleigh-distributed with E[intensity²] = gain² · P (fully developed speckle: the sum of
/// many random scatterers). Rays that leave the water (above water_surface_z_m) or hit nothing
/// add nothing: such cells show the noise floor only. Rays nearer than min_range_m are dropped.
/// Not modelled: side lobes, the horizontal beam width (one bearing per beam), multipath.
///
/// Cost: num_beams · rays_per_beam ray casts plus num_beams · num_bins cells, both parallel.
/// Determinism: each ping draws one 64-bit value from `rng`, which seeds one sub-stream
/// (Rng::split) per fixed group of 16 beams for their speckle (one uniform per cell, beam-major):
/// identical for any thread count. Thread-safety: `scan` is const; one Rng per caller.

#include <Eigen/Geometry>
#include <cstddef>
#include <limits>
#include <numbers>
#include <string_view>
#include <vector>

#include <scantling/core/parallel.hpp>
#include <scantling/core/random.hpp>
#include <scantling/io/sonar_ping.hpp>
#include <scantling/sim/sensor_mount.hpp>

namespace scantling::sim {

/// Defaults: Oculus M750d low-frequency mode (750 kHz: 130° × 20°, 512 beams) at a 30 m
/// range setting, sea water absorption ≈ 0.2 dB/m at 750 kHz.
struct MultibeamSonarConfig {
    int num_beams = 512;                                           ///< across the horizontal fan
    int num_bins = 512;                                            ///< range bins
    int rays_per_beam = 16;                                        ///< elevation samples
    double horizontal_fov_rad = 130.0 * std::numbers::pi / 180.0;  ///< in (0, π]
    double vertical_fov_rad = 20.0 * std::numbers::pi / 180.0;     ///< in (0, π/2)
    double min_range_m = 0.1;
    double max_range_m = 30.0;         ///< the range setting of the sonar
    double rate_hz = 10.0;             ///< pings per second (caller steps)
    double gain = 1.0;                 ///< amplitude gain
    double noise_floor = 1e-4;         ///< noise power per cell (same unit as the echo power)
    double incidence_exponent = 2.0;   ///< Lambert's law for acoustic backscatter: cos²θ
    double spreading_exponent = 1.0;   ///< residual range loss after time-varied gain
    double absorption_db_per_m = 0.2;  ///< one-way; applied over the two-way path
    bool speckle = true;               ///< Rayleigh speckle on the amplitude
    double water_surface_z_m = std::numeric_limits<double>::infinity();  ///< world z; +inf: none
    Eigen::Isometry3d T_body_sensor = Eigen::Isometry3d::Identity();     ///< body ← sensor (+x)

    /// Throws ConfigError naming the field ("multibeam_sonar.num_beams = 0, expected ...").
    void validate(std::string_view prefix = "multibeam_sonar") const;
};

/// A polar sonar image.
struct SonarImage {
    double stamp_s = 0.0;
    int num_beams = 0;
    int num_bins = 0;
    std::vector<float> intensity;      ///< beam-major: index beam · num_bins + bin
    std::vector<double> bearings_rad;  ///< per beam, sensor frame, positive to the left
    std::vector<double> ranges_m;      ///< per bin, centre of the bin
    double min_range_m = 0.0;          ///< near edge of bin 0
    double max_range_m = 0.0;          ///< far edge of the last bin
    double horizontal_fov_rad = 0.0;   ///< width of the fan (beams tile it evenly)

    float at(int beam, int bin) const {
        return intensity[static_cast<std::size_t>(beam) * num_bins + bin];
    }
    /// Bin containing `range_m`, or −1 outside [min_range_m, max_range_m).
    int bin_of(double range_m) const;
    /// Beam whose bearing is nearest `bearing_rad`, or −1 outside the fan (half a beam
    /// spacing beyond the outer beams).
    int beam_of(double bearing_rad) const;
};

/// The fan seen from above, for display and edge detection (SPEC §5): row 0 is the far end
/// (x = max_range), rows go towards the sonar; column 0 is the left end (+y). Pixel (u, v)
/// centre: x = max_range − (v + ½) · resolution, y = y_max − (u + ½) · resolution, with
/// y_max = max_range · sin(min(horizontal_fov / 2, π / 2)).
struct CartesianSonarImage {
    int width = 0;
    int height = 0;
    double resolution_m = 0.0;
    double y_max_m = 0.0;
    double x_max_m = 0.0;
    std::vector<float> intensity;  ///< row-major (v · width + u); 0 outside the fan
};

/// Nearest-neighbour resampling of the polar image onto the Cartesian grid. Throws InputError
/// for a non-positive resolution, an image whose arrays disagree with its sizes, or a grid over
/// 2²⁶ pixels. O(pixels).
CartesianSonarImage to_cartesian(const SonarImage& image, double resolution_m);

/// The image as the robot receives it (io::SonarPing, what perception reads): the same fields,
/// copied. Does not validate; SonarPing::validate does. O(num_beams · num_bins).
io::SonarPing to_sonar_ping(const SonarImage& image);

class MultibeamSonar {
  public:
    /// Validates the config (ConfigError) and precomputes the rays.
    explicit MultibeamSonar(MultibeamSonarConfig config = {});

    /// One ping from the vehicle pose.
    SonarImage scan(const SceneView& scene, const Eigen::Isometry3d& T_world_body, Rng& rng,
                    double stamp_s = 0.0, const ParallelConfig& parallel = {}) const;

    /// Unit ray directions, sensor frame, beam-major (beam · rays_per_beam + k).
    const std::vector<Eigen::Vector3d>& rays_sensor() const { return rays_sensor_; }

    /// Echo power of one ray hitting at `range_m` with cos(incidence) `cos_incidence` on a
    /// surface of `albedo` (before the division by rays_per_beam).
    double echo_power(double albedo, double cos_incidence, double range_m) const;

    const MultibeamSonarConfig& config() const { return config_; }

  private:
    std::vector<double> signal_power(const SceneView& scene,
                                     const Eigen::Isometry3d& T_world_sensor,
                                     const ParallelConfig& parallel) const;
    SonarImage empty_image(double stamp_s) const;
    float amplitude(double signal_power, double speckle) const;

    MultibeamSonarConfig config_;
    std::vector<Eigen::Vector3d> rays_sensor_;
};

}  // namespace scantling::sim
