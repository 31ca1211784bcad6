#pragma once
/// @file
/// Time-of-flight depth camera (Intel L515, Azure Kinect NFOV class) by ray casting: one ray
/// through each pixel centre. SPEC §1 (confined-space robot), §10.
///
/// Frame: the camera optical frame of camera_model.hpp (x right, y down, z forward).
/// Output: an ORGANISED cloud of width × height points, row-major (index v · width + u),
/// `points` NaN where there is no return (nothing within [min_depth_m, max_depth_m] along z,
/// or a dropped return), `intensities` = albedo · cos(incidence) (0 without a return).
///
/// Noise model (ReturnModel applied to the depth z, not to the range): the measured depth is
///   z' = z + N(0, σ(z)²),   σ(z) = sigma_m + sigma_per_m · z + sigma_per_m2 · z²,
/// and the point is z' · (x/z, y/z, 1) on the pixel's viewing ray (depth cameras report depth
/// per pixel, so the noise moves points along the pixel ray).
/// Determinism: noise drawn serially in pixel order (one uniform + one normal per in-window
/// return); identical for any thread count. Thread-safety: const; one Rng per caller.

#include <Eigen/Geometry>
#include <numbers>
#include <string_view>
#include <vector>

#include <scantling/core/parallel.hpp>
#include <scantling/core/point_cloud.hpp>
#include <scantling/core/random.hpp>
#include <scantling/sim/camera_model.hpp>
#include <scantling/sim/return_model.hpp>
#include <scantling/sim/sensor_mount.hpp>

namespace scantling::sim {

/// Defaults: Intel RealSense L515 at 640 × 480 (see intel_l515()).
struct DepthCameraConfig {
    /// Depth intrinsics; L515 depth FOV 70° × 55°.
    PinholeIntrinsics intrinsics = PinholeIntrinsics::from_fov(
        640, 480, 70.0 * std::numbers::pi / 180.0, 55.0 * std::numbers::pi / 180.0);
    double rate_hz = 30.0;      ///< frames per second
    double min_depth_m = 0.25;  ///< L515 minimum depth
    double max_depth_m = 9.0;   ///< L515 maximum depth (95 % reflectivity)
    /// L515 depth noise approximated as 1σ ≈ 2.5 mm at 1 m growing linearly to ≈ 15.5 mm at
    /// 9 m; 0.2 % invalid pixels; dark or grazing pixels (ρ < 0.03) invalid half of the time.
    ReturnModel depth_noise{.sigma_m = 0.000875,
                            .sigma_per_m = 0.001625,
                            .dropout_probability = 0.002,
                            .weak_reflectivity = 0.03,
                            .weak_dropout_probability = 0.5};
    Eigen::Isometry3d T_body_sensor = Eigen::Isometry3d::Identity();  ///< body ← optical frame

    /// Throws ConfigError naming the field ("depth_camera.max_depth_m = 0, expected ...").
    void validate(std::string_view prefix = "depth_camera") const;
};

/// Intel RealSense L515: 70° × 55°, 0.25–9 m, 30 fps, 4:3 depth at width 320, 640 or 1024
/// (else ConfigError "intel_l515.width = ...").
DepthCameraConfig intel_l515(int width = 640);

/// Azure Kinect NFOV (75° × 65°, 30 fps): unbinned 640 × 576, 0.5–3.86 m; binned 320 × 288,
/// 0.5–5.46 m. Noise σ = 1 mm + 1 mm/m² · z², which reaches the datasheet's 17 mm bound on the
/// random error at the far end of the unbinned range.
DepthCameraConfig azure_kinect_nfov(bool binned = false);

/// A depth image: row-major `depth_m` (index v · width + u), 0 where there is no return (the
/// convention of RealSense and Azure Kinect depth images).
struct DepthImage {
    int width = 0;
    int height = 0;
    std::vector<float> depth_m;
};

/// The z of each point of an organised cloud (NaN → 0). Throws InputError unless the cloud
/// has width · height points.
DepthImage to_depth_image(const PointCloud& organised, int width, int height);

class DepthCamera {
  public:
    /// Validates the config (ConfigError) and precomputes the pixel rays.
    explicit DepthCamera(DepthCameraConfig config = {});

    /// One organised frame from the vehicle pose, stamped `stamp_s`.
    PointCloud scan(const SceneView& scene, const Eigen::Isometry3d& T_world_body, Rng& rng,
                    double stamp_s = 0.0, const ParallelConfig& parallel = {}) const;

    /// Convenience: to_depth_image(scan(...)).
    DepthImage depth_image(const SceneView& scene, const Eigen::Isometry3d& T_world_body, Rng& rng,
                           const ParallelConfig& parallel = {}) const;

    const DepthCameraConfig& config() const { return config_; }

  private:
    DepthCameraConfig config_;
    std::vector<Eigen::Vector3d> rays_camera_;  // unit, pixel order
};

}  // namespace scantling::sim
