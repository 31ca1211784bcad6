#pragma once
// Synthetic scenes for the registration tests: surfaces sampled at random, seeded.

#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>

#include <scantling/core/point_cloud.hpp>

namespace scantling::registration::test {

/// A room corner centred on the origin (floor and two walls of a 6 × 4 × 3 m room) with two
/// boxes on the floor: every degree of freedom is constrained. Points uniform over the area,
/// Gaussian noise of `noise_sigma_m` per coordinate.
PointCloud sample_room_corner(std::size_t n, std::uint64_t seed, double noise_sigma_m);

/// The floor and the two walls of sample_room_corner (no boxes) as a CAD map models them: plates
/// of `thickness_m` whose room-side faces lie where sample_room_corner's surfaces are. With
/// `hidden_faces`, the outer faces too (a map sampled over the whole mesh); without, only the
/// faces a sensor inside the room sees. Normals point out of the plates (into the room on the
/// visible faces). Without noise.
PointCloud sample_plated_room_corner(std::size_t n, std::uint64_t seed, double thickness_m,
                                     bool hidden_faces);

/// The square z = 0, |x|, |y| <= half_size_m, without noise: constrains z, roll and pitch only.
PointCloud sample_plane(std::size_t n, std::uint64_t seed, double half_size_m);

/// `n` points uniform in the box |x| <= 3, |y| <= 2, |z| <= 1.5 (clutter / outliers).
PointCloud sample_clutter(std::size_t n, std::uint64_t seed);

/// T from Z-Y-X Euler angles (radians) and a translation (metres).
Eigen::Isometry3d make_pose(double roll_rad, double pitch_rad, double yaw_rad,
                            const Eigen::Vector3d& t_m);

}  // namespace scantling::registration::test
