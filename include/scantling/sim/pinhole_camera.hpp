#pragma once
/// @file
/// Pinhole RGB camera by ray casting: a shaded image of the world and the ids of the defects it
/// sees. SPEC §1 (ROV camera ~77° × 48°, drone camera), §5, §9 (UAV3D camera 66° × 49.5°), §10.
///
/// Frame: the optical frame of camera_model.hpp (x right, y down, z forward);
/// `T_world_camera = T_world_body * T_body_sensor`.
///
/// Rendering: one ray through each pixel centre. The light is a lamp at the camera (vehicles in
/// tanks and under water carry their own), so a hit at incidence θ has brightness
///   b = albedo · (ambient + (1 − ambient) · cos θ) · texture,
/// where `texture` is 1 on untextured surfaces and on textured ones a deterministic pattern of
/// world-fixed cubes of `texture_cell_m` whose brightness varies by ± texture_contrast.
/// Surfaces are grey; corrosion is drawn rust-orange and cracks near-black-red (scaled by the
/// same b / albedo shading); misses are `background`. Optional Gaussian pixel noise
/// (`pixel_noise_dn`, drawn serially in pixel order, R then G then B), added after the spots of
/// the optional laser pointers (laser_spots.hpp) are blended in; without lasers the image is the
/// same as before they existed.
/// Determinism: identical images for any thread count. Thread-safety: const.

#include <Eigen/Geometry>
#include <numbers>
#include <string_view>
#include <vector>

#include <scantling/core/parallel.hpp>
#include <scantling/core/point_cloud.hpp>
#include <scantling/core/random.hpp>
#include <scantling/io/png.hpp>
#include <scantling/io/recording.hpp>
#include <scantling/sim/camera_model.hpp>
#include <scantling/sim/laser_spots.hpp>
#include <scantling/sim/sensor_mount.hpp>

namespace scantling::sim {

/// An 8-bit RGB image, row-major (index v · width + u): the type recordings store as PNG.
using RgbImage = io::RgbImage;

/// Defaults: the UAV3D camera (640 × 480, HFOV 66°, VFOV 49.5°).
struct PinholeCameraConfig {
    PinholeIntrinsics intrinsics = PinholeIntrinsics::from_fov(
        640, 480, 66.0 * std::numbers::pi / 180.0, 49.5 * std::numbers::pi / 180.0);
    double rate_hz = 30.0;           ///< frames per second
    double max_range_m = 50.0;       ///< farther surfaces are not seen (lamp range, turbidity)
    double ambient = 0.2;            ///< share of light independent of incidence, [0, 1]
    double texture_cell_m = 0.05;    ///< size of the procedural texture cubes
    double texture_contrast = 0.35;  ///< texture brightness varies by ± this, [0, 1)
    double pixel_noise_dn = 2.0;     ///< 1σ Gaussian noise per channel, 8-bit units (0 = off)
    /// A defect counts as visible only when seen at incidence below this (cos > cos(angle)).
    double max_defect_view_angle_rad = 80.0 * std::numbers::pi / 180.0;
    Rgb8 background = Rgb8(0, 0, 0);  ///< colour of pixels without a hit
    Eigen::Isometry3d T_body_sensor = Eigen::Isometry3d::Identity();  ///< body ← optical frame
    /// Laser pointers beside the camera (SPEC §5), at most kMaxLaserPointers; none by default.
    std::vector<LaserPointer> lasers;

    /// Throws ConfigError naming the field ("pinhole_camera.ambient = 2, expected in [0, 1]").
    void validate(std::string_view prefix = "pinhole_camera") const;
};

/// UAV3D camera (SPEC §9): 640 × 480, HFOV 66°, VFOV 49.5°.
PinholeCameraConfig uav3d_camera();

/// ROV camera (SPEC §1, Blueye X3 class): 77° × 48° at 16:9, `width` × round(width · 9 / 16)
/// (1920 × 1080 full HD by default), 20 m visibility. Throws ConfigError for width < 16.
PinholeCameraConfig rov_camera(int width = 1920);

class PinholeCamera {
  public:
    /// Validates the config (ConfigError) and precomputes the pixel rays.
    explicit PinholeCamera(PinholeCameraConfig config = {});

    /// Renders the view from the vehicle pose (see the file comment). `rng` is used only when
    /// pixel_noise_dn > 0 (3 normals per pixel).
    RgbImage render(const SceneView& scene, const Eigen::Isometry3d& T_world_body, Rng& rng,
                    const ParallelConfig& parallel = {}) const;

    /// Ids of the defects of `scene.metadata` in view, ascending: the defect centre is in front
    /// of the camera, projects into the image, lies within max_range_m, faces the camera at an
    /// incidence below max_defect_view_angle_rad, and the line of sight to it is not occluded
    /// (RayCaster::occluded). O(defects) occlusion rays.
    std::vector<int> visible_defects(const SceneView& scene,
                                     const Eigen::Isometry3d& T_world_body) const;
    /// The visible defects (as visible_defects) with the pixel their centre projects to and
    /// their apparent radius (fx · radius_m / depth): what a fiducial-tag detector reports, the
    /// stand-in for the tags of the sources (SPEC §7). `image` and `stamp_s` are left 0.
    std::vector<io::DefectSighting> sight_defects(const SceneView& scene,
                                                  const Eigen::Isometry3d& T_world_body) const;

    /// The spots of the config's lasers seen from the vehicle pose, in laser order (ground
    /// truth; laser_spots.hpp). Empty without lasers. O(lasers) ray casts.
    std::vector<LaserSpot> laser_spots(const SceneView& scene,
                                       const Eigen::Isometry3d& T_world_body) const;

    const PinholeCameraConfig& config() const { return config_; }

  private:
    PinholeCameraConfig config_;
    std::vector<Eigen::Vector3d> rays_camera_;  // unit, pixel order
};

/// Colours defects are drawn in (before shading).
inline const Rgb8 kCorrosionRgb(200, 90, 25);
inline const Rgb8 kCrackRgb(60, 10, 10);

}  // namespace scantling::sim
