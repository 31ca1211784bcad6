#pragma once
/// @file
/// Ultra-wideband two-way ranging from a tag on the vehicle to fixed anchors, with
/// non-line-of-sight (NLOS) errors. SPEC §6 (crawler localisation fuses UWB ranges), §1 (UWB
/// tag on the drone), §10.
///
/// Geometry: the tag antenna is the origin of the sensor frame, mounted at `T_body_sensor`;
/// the true range is |p_anchor − p_tag|. Line of sight is tested by ray casting
/// (RayCaster::occluded): any surface between tag and anchor makes the range NLOS.
/// Error model per anchor, in this order of draws (fixed: 1 uniform, 1 normal, 3 uniforms):
///   lost with probability dropout_probability (LOS) or nlos_dropout_probability (NLOS), or
///   when the true range exceeds max_range_m;
///   LOS:  r' = r + N(0, range_sigma_m²);
///   NLOS: r' = r + Exp(mean nlos_bias_mean_m) + N(0, nlos_sigma_m²) (the direct path is
///         blocked: the first path through or around the obstacle is longer, never shorter);
///   with probability outlier_probability the reading is replaced by U(0, max_range_m)
///   (multipath lock on a wrong peak).
/// Thread-safety: `measure` is const; one Rng per caller.

#include <Eigen/Geometry>
#include <limits>
#include <string_view>
#include <vector>

#include <scantling/core/random.hpp>
#include <scantling/sim/sensor_mount.hpp>

namespace scantling::sim {

struct UwbAnchor {
    int id = 0;                                                ///< unique among the anchors
    Eigen::Vector3d position_world = Eigen::Vector3d::Zero();  ///< antenna, world frame
};

/// Defaults: Decawave DW1000 class (≈ 5 cm 1σ with line of sight, up to tens of metres).
struct UwbConfig {
    std::vector<UwbAnchor> anchors;         ///< at least one
    double rate_hz = 10.0;                  ///< rounds (all anchors) per second
    double max_range_m = 50.0;              ///< farther anchors give no reading
    double range_sigma_m = 0.05;            ///< LOS 1σ
    double nlos_bias_mean_m = 0.5;          ///< mean of the exponential NLOS excess path
    double nlos_sigma_m = 0.15;             ///< NLOS 1σ on top of the excess
    double dropout_probability = 0.02;      ///< LOS reading lost, in [0, 1]
    double nlos_dropout_probability = 0.3;  ///< NLOS reading lost, in [0, 1]
    double outlier_probability = 0.005;     ///< gross outlier, in [0, 1]
    Eigen::Isometry3d T_body_sensor = Eigen::Isometry3d::Identity();  ///< body ← tag antenna

    /// Throws ConfigError naming the field ("uwb.anchors[2].position_world ...",
    /// "uwb.range_sigma_m = -1, expected >= 0"); anchors must be non-empty with unique ids.
    void validate(std::string_view prefix = "uwb") const;
};

/// The same config with noise, NLOS errors, dropouts and outliers off (ranges are exact).
UwbConfig noiseless(UwbConfig config);

struct UwbRange {
    int anchor_id = 0;
    bool valid = false;
    double range_m = std::numeric_limits<double>::quiet_NaN();  ///< noisy; NaN when invalid
    bool line_of_sight = true;                                  ///< ground truth, for evaluation
    bool outlier = false;                                       ///< ground truth: a gross outlier
};

struct UwbMeasurement {
    double stamp_s = 0.0;
    std::vector<UwbRange> ranges;  ///< one per anchor, in config order
};

class UwbTag {
  public:
    /// Validates the config (ConfigError).
    explicit UwbTag(UwbConfig config);

    /// One round of ranges from the vehicle pose. O(anchors · log triangles).
    UwbMeasurement measure(const SceneView& scene, const Eigen::Isometry3d& T_world_body, Rng& rng,
                           double stamp_s = 0.0) const;

    const UwbConfig& config() const { return config_; }

  private:
    UwbRange range_to(const SceneView& scene, const Eigen::Vector3d& p_tag, const UwbAnchor& anchor,
                      Rng& rng) const;

    UwbConfig config_;
};

}  // namespace scantling::sim
