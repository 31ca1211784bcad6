#pragma once
/// @file
/// Sparse stereo points (the 3D features of a stereo VIO camera, T265 class) by ray casting.
/// SPEC §1 (confined-space robot), §10.
///
/// Features: the left image is cut into cells of feature_spacing_px × feature_spacing_px and
/// one candidate feature is placed uniformly at random in each cell (the grid bucketing of VIO
/// front ends), i.e. a density of one feature per feature_spacing_px² of image. A candidate
/// becomes a point only when its ray hits a TEXTURED surface (WorldMetadata::surfaces) at a
/// depth in [min_depth_m, max_depth_m] that the right camera (at +baseline_m along x) also sees:
/// inside its image and not occluded.
///
/// Noise: stereo depth from disparity d = f b / z, so a disparity error σ_d gives
///   σ_z = z² σ_d / (f b)       (f = fx in pixels, b = baseline_m),
/// and the point moves along the feature's viewing ray: z' = z + N(0, σ_z²).
/// Frame: the LEFT camera's optical frame (x right, y down, z forward); unorganised cloud of
/// points only, in cell order (row-major).
/// Determinism: two uniforms per cell (cell order), then one normal per kept point (point
/// order); identical for any thread count. Thread-safety: const.

#include <Eigen/Geometry>
#include <string_view>
#include <vector>

#include <scantling/core/parallel.hpp>
#include <scantling/core/point_cloud.hpp>
#include <scantling/core/random.hpp>
#include <scantling/sim/camera_model.hpp>
#include <scantling/sim/sensor_mount.hpp>

namespace scantling::sim {

/// Defaults: Intel RealSense T265 class (848 × 800 images, 64 mm baseline), its fisheye
/// approximated by the central 90° × 86.7° pinhole view (square pixels, fx = 424 px).
struct StereoPointsConfig {
    PinholeIntrinsics intrinsics{
        .width = 848, .height = 800, .fx = 424.0, .fy = 424.0, .cx = 423.5, .cy = 399.5};
    double baseline_m = 0.064;         ///< right camera at +baseline_m along the left's x
    double rate_hz = 30.0;             ///< frames per second
    double feature_spacing_px = 40.0;  ///< one candidate feature per cell of this size
    double disparity_sigma_px = 0.3;   ///< 1σ disparity error (sub-pixel matching)
    double min_depth_m = 0.2;
    double max_depth_m = 10.0;  ///< disparity 2.7 px at 10 m with the defaults
    Eigen::Isometry3d T_body_sensor = Eigen::Isometry3d::Identity();  ///< body ← left optical

    /// Throws ConfigError naming the field ("stereo_points.baseline_m = 0, expected > 0").
    void validate(std::string_view prefix = "stereo_points") const;
};

class StereoPoints {
  public:
    /// Validates the config (ConfigError).
    explicit StereoPoints(StereoPointsConfig config = {});

    /// 1σ depth noise at depth z: z² σ_d / (fx b), metres.
    double depth_sigma_m(double depth_m) const;

    /// One frame of sparse points from the vehicle pose, stamped `stamp_s`.
    PointCloud scan(const SceneView& scene, const Eigen::Isometry3d& T_world_body, Rng& rng,
                    double stamp_s = 0.0, const ParallelConfig& parallel = {}) const;

    const StereoPointsConfig& config() const { return config_; }

  private:
    std::vector<Eigen::Vector2d> candidate_pixels(Rng& rng) const;
    bool seen_by_right(const SceneView& scene, const Eigen::Isometry3d& T_world_camera,
                       const Eigen::Vector3d& p_left, const Eigen::Vector3d& p_world) const;

    StereoPointsConfig config_;
};

}  // namespace scantling::sim
