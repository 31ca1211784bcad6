#pragma once
/// @file
/// Pinhole projection shared by the simulated cameras (RGB, ToF depth, stereo) and by what
/// reads their images back (a recording's images/camera.json, the defect lifting).
///
/// Camera (optical) frame: x right, y down, z forward along the optical axis (OpenCV/ROS
/// optical convention). Pixel coordinates (u, v) follow OpenCV: the centre of pixel (i, j)
/// (column i, row j) is at (i, j), so the image spans [−0.5, width − 0.5) × [−0.5, height − 0.5)
/// and a centred principal point is ((width − 1)/2, (height − 1)/2). No lens distortion.
///   u = fx · x / z + cx,   v = fy · y / z + cy.

#include <Eigen/Core>
#include <optional>
#include <string_view>

namespace scantling {

struct PinholeIntrinsics {
    int width = 640;    ///< pixels
    int height = 480;   ///< pixels
    double fx = 500.0;  ///< focal length, pixels
    double fy = 500.0;
    double cx = 319.5;  ///< principal point, pixels
    double cy = 239.5;

    /// Intrinsics with the given full fields of view across the image edges:
    /// fx = (width / 2) / tan(hfov / 2), fy likewise, principal point centred. Throws
    /// ConfigError ("pinhole.hfov_rad = ...") unless sizes >= 1 and FOVs in (0, π).
    static PinholeIntrinsics from_fov(int width, int height, double hfov_rad, double vfov_rad);

    /// Full horizontal / vertical field of view across the image edges, radians.
    double hfov_rad() const;
    double vfov_rad() const;

    /// Pixel of a camera-frame point, or nullopt when it is not in front (z <= 0) or falls
    /// outside the image.
    std::optional<Eigen::Vector2d> project(const Eigen::Vector3d& p_camera) const;

    /// The camera-frame point at depth `depth_m` (its z) seen at `pixel`; inverts project().
    Eigen::Vector3d unproject(const Eigen::Vector2d& pixel, double depth_m) const;

    /// Unit direction of the viewing ray through `pixel`, camera frame.
    Eigen::Vector3d ray_direction(const Eigen::Vector2d& pixel) const;

    /// True when the pixel lies in [−0.5, width − 0.5) × [−0.5, height − 0.5).
    bool contains(const Eigen::Vector2d& pixel) const;

    /// Throws ConfigError naming the field ("<prefix>.fx = 0, expected > 0").
    void validate(std::string_view prefix) const;
};

}  // namespace scantling
