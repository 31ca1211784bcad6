#pragma once
/// @file
/// What a reader promises about what it returns (its header's contract), checked on every input
/// the reader accepts: a violation is a silent wrong answer and is reported as a finding.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <span>
#include <string_view>

#include <scantling/core/point_cloud.hpp>

namespace scantling::fuzz {

/// Every optional field is empty or as long as `points` (point_cloud.hpp).
void require_consistent_cloud(const PointCloud& cloud, std::string_view reader);

/// Every face indexes a vertex of a cloud of `num_vertices` (ply.hpp: out of range is an error).
void require_faces_in_range(std::span<const Eigen::Vector3i> faces, std::size_t num_vertices,
                            std::string_view reader);

/// Finite, with a proper rotation: max |RᵀR − I| <= `tolerance` and det R > 0 (kitti.hpp,
/// tum.hpp reject anything else).
void require_valid_pose(const Eigen::Isometry3d& T, double tolerance, std::string_view reader);

}  // namespace scantling::fuzz
