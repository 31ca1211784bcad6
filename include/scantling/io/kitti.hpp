#pragma once
/// @file
/// KITTI odometry files: velodyne scans (.bin) and pose lists.

#include <Eigen/Geometry>
#include <span>
#include <string>
#include <vector>

#include <scantling/core/point_cloud.hpp>

namespace scantling::io {

// Thread-safety: the functions keep no shared state; concurrent calls on different files are
// safe. Writers go through AtomicFileWriter, so a reader never sees a partial file.

/// Velodyne scan: consecutive little-endian float32 records (x, y, z, reflectance), 16 bytes
/// each, in the sensor frame (metres). Returns points and intensities (= reflectance).
/// Throws FileError (missing, unreadable, directory) or ParseError for an empty file or a
/// size that is not a multiple of 16 (naming the byte offset of the incomplete record).
PointCloud read_kitti_bin(const std::string& path);

/// Writes points (rounded to float32) and intensities (0 when absent); other fields are
/// dropped. Atomic. Throws InputError for an empty or inconsistent cloud (an empty file would
/// be rejected on read), FileError when the file cannot be written.
void write_kitti_bin(const std::string& path, const PointCloud& cloud);

/// Pose file: one pose per line, 12 numbers = row-major 3×4 [R | t] (KITTI ground truth is
/// T_cam0_camN, i.e. T_world_body with the first camera frame as world). Blank lines are
/// skipped. Throws FileError, or ParseError naming the line for: no poses, a count of numbers
/// other than 12, a non-number, or a rotation that is not orthonormal (max |RᵀR − I| > 1e-3,
/// or det R < 0). Values are used as read (no re-orthonormalisation).
std::vector<Eigen::Isometry3d> read_kitti_poses(const std::string& path);

/// Writes 12 numbers per line with the shortest text that reads back to the same double
/// (exact round trip). Atomic. Throws InputError for a non-finite pose, FileError when the
/// file cannot be written.
void write_kitti_poses(const std::string& path, std::span<const Eigen::Isometry3d> poses);

}  // namespace scantling::io
