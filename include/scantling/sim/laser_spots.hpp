#pragma once
/// @file
/// Laser pointers on the simulated RGB camera (SPEC §5, issue 14 item 5): the spots that two
/// (or more) lasers mounted beside the camera draw on the surface in view.
///
/// Frame: each laser is given in the camera's optical frame (x right, y down, z forward);
/// `T_world_camera = T_world_body * T_body_sensor` places it in the world.
///
/// A laser's ray is cast into the scene with the camera's ray caster (SceneView). A spot is seen
/// when the ray hits within the camera's max_range_m (measured from the camera), the hit is in
/// front of the camera and projects into the image, and the line of sight from the camera to it
/// is not occluded (SceneView::occluded). It is drawn as a filled disc of the projected spot
/// radius fx · spot_radius_m / depth (at least 1 px), alpha-blended over the rendered image by
/// the share of each pixel it covers (kSpotSubsamples² samples per pixel), so the spot's centre
/// is recoverable to a fraction of a pixel. Spots are drawn unshaded: a laser outshines the lamp.
/// Thread-safety: pure functions. Cost: O(lasers) rays, O(spot area) pixels.

#include <Eigen/Geometry>
#include <string_view>
#include <vector>

#include <scantling/core/pinhole_intrinsics.hpp>
#include <scantling/io/png.hpp>
#include <scantling/sim/sensor_mount.hpp>

namespace scantling::sim {

/// One laser pointer fixed to the camera. Defaults: a red (650 nm class) pointer along the
/// optical axis from the camera centre; set the origin to its place beside the camera.
struct LaserPointer {
    Eigen::Vector3d origin_camera = Eigen::Vector3d::Zero();  ///< beam origin, optical frame, m
    /// Beam direction, optical frame; non-zero, normalised on use.
    Eigen::Vector3d direction_camera = Eigen::Vector3d::UnitZ();
    double spot_radius_m = 0.004;  ///< radius of the spot on the surface, m, > 0
    /// Spot colour, 8-bit RGB, each channel in [0, 255] (default: 650 nm red).
    Eigen::Vector3d rgb = Eigen::Vector3d(255.0, 0.0, 0.0);

    /// Throws ConfigError naming the field ("<prefix>.spot_radius_m = 0, expected > 0").
    void validate(std::string_view prefix = "laser") const;
};

/// Most lasers a camera may carry (a bound for hostile scenarios).
inline constexpr std::size_t kMaxLaserPointers = 16;

/// A laser spot seen by the camera: the ground truth the perception is tested against.
struct LaserSpot {
    int laser = 0;                                       ///< index into the camera's lasers
    Eigen::Vector3d p_camera = Eigen::Vector3d::Zero();  ///< hit point, optical frame, m
    Eigen::Vector2d pixel = Eigen::Vector2d::Zero();     ///< its projection, pixels
    double radius_px = 1.0;  ///< drawn radius, max(1, fx · spot_radius_m / depth)
};

/// Subsamples per pixel side when a spot's coverage is computed.
inline constexpr int kSpotSubsamples = 5;

/// The spots of `lasers` seen from `T_world_camera` (see the file comment), in laser order;
/// lasers without a visible spot are left out. O(lasers) ray casts.
std::vector<LaserSpot> cast_laser_spots(const std::vector<LaserPointer>& lasers,
                                        const PinholeIntrinsics& intrinsics, double max_range_m,
                                        const SceneView& scene,
                                        const Eigen::Isometry3d& T_world_camera);

/// Blends each spot's disc, in the colour of its laser, over `image` (clipped to the image).
void draw_laser_spots(const std::vector<LaserSpot>& spots, const std::vector<LaserPointer>& lasers,
                      io::RgbImage& image);

}  // namespace scantling::sim
