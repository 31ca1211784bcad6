#pragma once
/// @file
/// The point cloud that flows between every module, whether it was simulated or recorded.
/// Struct of arrays: `points` is always present; every other field is optional and is either
/// empty (absent) or exactly `points.size()` long.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <scantling/core/bounds.hpp>

namespace scantling {

using Rgb8 = Eigen::Matrix<std::uint8_t, 3, 1>;

struct PointCloud {
    /// Positions in metres, in the frame the producer states (sensor frame for raw sweeps).
    std::vector<Eigen::Vector3d> points;
    /// Unit surface normals (optional).
    std::vector<Eigen::Vector3d> normals;
    /// Per-point 3×3 position covariances in m² (optional; GICP-style local shape).
    std::vector<Eigen::Matrix3d> covariances;
    /// Return intensity / reflectivity, sensor units (optional).
    std::vector<float> intensities;
    /// LiDAR ring (laser) index, 0 = lowest elevation (optional).
    std::vector<std::uint16_t> rings;
    /// Per-point time offset from `stamp_s`, in seconds (optional; motion distortion).
    std::vector<float> times_s;
    /// 8-bit RGB colour (optional).
    std::vector<Rgb8> colors;
    /// Acquisition time of the cloud (sweep start), seconds.
    double stamp_s = 0.0;

    std::size_t size() const { return points.size(); }
    bool empty() const { return points.empty(); }
    bool has_normals() const { return !normals.empty(); }
    bool has_covariances() const { return !covariances.empty(); }
    bool has_intensities() const { return !intensities.empty(); }
    bool has_rings() const { return !rings.empty(); }
    bool has_times() const { return !times_s.empty(); }
    bool has_colors() const { return !colors.empty(); }

    /// Reserves capacity in `points` and in every present optional field.
    void reserve(std::size_t n);
};

/// Throws InputError naming `what` and the field when an optional field is neither empty nor
/// as long as `points`.
void check_consistent(const PointCloud& cloud, std::string_view what);

/// Throws InputError naming `what` and the first index whose position is NaN or infinite.
void check_finite(const PointCloud& cloud, std::string_view what);

/// Throws InputError when the cloud is empty, inconsistent or holds a non-finite position.
void check_usable(const PointCloud& cloud, std::string_view what);

/// Names of the fields present, in a fixed order: x y z [normal_x normal_y normal_z]
/// [intensity] [ring] [time] [rgb] [covariance].
std::vector<std::string> field_names(const PointCloud& cloud);

/// The points at `indices` (every present field is carried). Indices must be < size().
PointCloud select(const PointCloud& cloud, std::span<const std::size_t> indices);

/// Keeps only points with finite positions (and finite normals when present).
PointCloud remove_non_finite(const PointCloud& cloud);

/// Appends `src` to `dst`; both must carry the same optional fields (or `dst` be empty).
void append(PointCloud& dst, const PointCloud& src);

/// Maps the cloud from frame `from` into frame `to`: points by T, normals and covariances by
/// its rotation. Name the argument `T_to_from` at the call site.
void transform_in_place(PointCloud& cloud, const Eigen::Isometry3d& T_to_from);
PointCloud transformed(const PointCloud& cloud, const Eigen::Isometry3d& T_to_from);

/// Bounds of the positions (empty box for an empty cloud).
Aabb compute_bounds(const PointCloud& cloud);

}  // namespace scantling
