#pragma once
/// @file
/// Laser-pointer triangulation (SPEC §5, issue 14 item 5): two parallel laser pointers beside
/// the camera draw two spots on the hull; from their pixels follow the distance to the locally
/// planar surface, its pitch relative to the camera (used to tilt the camera) and the image
/// scale in mm per pixel (for overlaying feature sizes on the video).
///
/// Frame: the camera's optical frame (x right, y down, z forward; core/pinhole_intrinsics.hpp).
/// Laser a starts at origin_a_camera, laser b at origin_b_camera, both along direction_camera d.
///
/// Pipeline:
/// 1. Spot pixels: a pixel p (RGB) is split into its grey part and its chroma p − mean(p)·1.
///    Its laser share is w = chroma(p)·chroma(c) / |chroma(c)|² for the spot colour c, and its
///    off-hue residual is |chroma(p) − w·chroma(c)|. A laser spot blended with share α over a
///    grey surface has w = α and no residual, whatever the grey; rust-orange paint has a large
///    residual. A pixel is a spot pixel when w >= min_laser_share and the residual is at most
///    max_off_hue_dn.
/// 2. Blobs: 8-connected components of the spot pixels (OpenCV) with an area in
///    [min_spot_area_px, max_spot_area_px]; each blob's centre is the w-weighted centroid over
///    its box grown by one pixel (the partly covered rim pixels count by their share), to a
///    fraction of a pixel.
/// 3. Association and triangulation: a blob's pixel defines the camera ray; the hit point is
///    the point of the laser line closest to that ray (closest points of two 3-D lines). A
///    (blob, laser) pair is consistent when the closest points lie in front of the camera and
///    ahead of the laser origin and the hit projects within max_reprojection_px of the blob.
///    The assignment of two blobs to (a, b) is the consistent one; with more than two blobs,
///    the single consistent pair is taken (e.g. a red mark away from the laser lines is
///    ignored). Several consistent pairs, or none, is kAmbiguous.
/// 4. From the hits P_a, P_b, with e the unit component of (origin_b − origin_a) normal to d
///    (for lasers displaced vertically, b below a: e = +y) and Δ = P_b − P_a:
///    - distance_m = (P_a.z + P_b.z) / 2, the mean depth. On a planar surface this is the
///      depth along the optical axis where the axis meets the surface when the lasers sit
///      symmetrically about the optical axis and d = +z (the usual mount).
///    - pitch_rad = atan2(Δ·d, Δ·e): the surface's slope in the plane of the two lasers. It is
///      the angle by which rotating the camera about the axis e × d (camera +x for b below a)
///      makes d normal to the surface. For b below a: pitch > 0 when the surface recedes
///      towards the bottom of the image; rotating about +x by pitch turns the optical axis up
///      (towards −y). 0 on a surface facing the camera squarely.
///    - mm_per_px = 1000 · |P_b − P_a| / |pixel_b − pixel_a|: the scale on the surface along
///      the spots' direction, foreshortening included. On a fronto-parallel surface it equals
///      1000 · depth / f (f the focal length along the spots' direction, fy for vertical
///      lasers).
///
/// Cost: O(pixels). Thread-safety: a pure function. @note Deterministic.

#include <Eigen/Core>
#include <array>
#include <string>
#include <string_view>
#include <vector>

#include <scantling/core/pinhole_intrinsics.hpp>
#include <scantling/io/png.hpp>

namespace scantling::perception {

/// Defaults: a 0.2 m vertical baseline (laser a 0.1 m above the optical centre, b 0.1 m below),
/// both along the optical axis, red (650 nm class) spots; set the geometry to the vehicle's.
struct LaserPointerConfig {
    Eigen::Vector3d origin_a_camera = Eigen::Vector3d(0.0, -0.1, 0.0);  ///< laser a, m, finite
    Eigen::Vector3d origin_b_camera = Eigen::Vector3d(0.0, 0.1, 0.0);   ///< laser b, m, finite
    /// Common direction of the parallel lasers (optical frame), normalised on use; non-zero,
    /// with a positive z (the lasers point into the camera's view), and not along b − a.
    Eigen::Vector3d direction_camera = Eigen::Vector3d::UnitZ();
    /// Spot colour (8-bit RGB, each in [0, 255]); not grey (it needs a hue to be found).
    Eigen::Vector3d spot_rgb = Eigen::Vector3d(255.0, 0.0, 0.0);
    /// Laser share w (see the file comment) a spot pixel needs, in (0, 1]. 0.5: the disc's
    /// half-covered rim pixels decide the blob; the weighted centroid uses all rim pixels.
    double min_laser_share = 0.5;
    /// Largest chroma off the spot's hue, 8-bit units, > 0: rejects rust-orange paint (~45 dn
    /// off red) while pixel noise (~3 dn) and the spot over any grey stay well below.
    double max_off_hue_dn = 25.0;
    int min_spot_area_px = 1;       ///< smaller blobs are noise, >= 1
    int max_spot_area_px = 20'000;  ///< larger blobs are not a spot (red paint), >= min
    /// A blob belongs to a laser when the triangulated hit projects this close to it, px, > 0.
    double max_reprojection_px = 2.0;

    /// Throws ConfigError naming "<prefix>.<field>", its value and what was expected.
    void validate(std::string_view prefix = "laser_pointers") const;
};

enum class LaserPointerStatus {
    kOk,         ///< both spots found and triangulated
    kNoSpots,    ///< no spot-coloured blob in the image
    kOneSpot,    ///< a single blob: one laser is off the surface or hidden
    kAmbiguous,  ///< two or more blobs, but not exactly one pair matches the lasers
};

/// The two spots and what follows from them. Geometry fields are 0 unless ok().
struct LaserPointerMeasurement {
    LaserPointerStatus status = LaserPointerStatus::kNoSpots;
    std::string message;  ///< what happened, one line, for logs and events
    /// Centres of every blob within the area bounds, pixels, in OpenCV label order.
    std::vector<Eigen::Vector2d> candidates_px;
    /// Spot centre of laser a and laser b, pixels.
    std::array<Eigen::Vector2d, 2> spots_px{Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()};
    /// Hit points P_a, P_b on the surface, optical frame, m.
    std::array<Eigen::Vector3d, 2> p_camera{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
    double distance_m = 0.0;  ///< mean depth of the hits (see the file comment), m
    double pitch_rad = 0.0;   ///< surface pitch about e × d (see the file comment)
    double mm_per_px = 0.0;   ///< image scale on the surface between the spots

    bool ok() const { return status == LaserPointerStatus::kOk; }
};

/// The laser-pointer measurement of one image. Throws InputError naming the field for a
/// malformed image (pixels.size() != width · height, or a size other than the intrinsics'),
/// and ConfigError for bad intrinsics or config; an image without the spots is a status.
LaserPointerMeasurement measure_laser_pointers(const io::RgbImage& image,
                                               const PinholeIntrinsics& intrinsics,
                                               const LaserPointerConfig& config = {});

/// "ok", "no_spots", "one_spot" or "ambiguous".
std::string_view to_string(LaserPointerStatus status);

}  // namespace scantling::perception
