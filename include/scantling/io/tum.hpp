#pragma once
/// @file
/// TUM RGB-D benchmark trajectories: "timestamp tx ty tz qx qy qz qw" per line, '#' comments.

#include <Eigen/Geometry>
#include <span>
#include <string>
#include <vector>

namespace scantling::io {

// Thread-safety: the functions keep no shared state; concurrent calls on different files are
// safe. Writers go through AtomicFileWriter, so a reader never sees a partial file.

struct StampedPose {
    double stamp_s = 0.0;  ///< seconds (any epoch)
    Eigen::Isometry3d T_world_body = Eigen::Isometry3d::Identity();
};

/// Reads a TUM trajectory. Quaternions within 1e-3 of unit norm are normalised.
/// Throws FileError, or ParseError naming the line for: no poses, a count of numbers other
/// than 8, a non-number or non-finite value, a quaternion with | |q| − 1 | > 1e-3, or a time
/// stamp not strictly after the previous one.
std::vector<StampedPose> read_tum(const std::string& path);

/// Writes one line per pose (quaternion with qw >= 0), numbers as the shortest text that
/// reads back to the same double. Atomic. Throws InputError for non-finite values or time
/// stamps that do not increase strictly, FileError when the file cannot be written.
void write_tum(const std::string& path, std::span<const StampedPose> poses);

}  // namespace scantling::io
