#pragma once
/// @file
/// The virtual rectangle on a wall that the sweeping and vertical-structure missions cover
/// (SPEC §4; D5.2 §II.1), and the frame the vehicle sees it in.
///
/// Frames: everything in the world frame (z up, metres). The wall is a plane through
/// `corner_world_m` with unit normal n (`normal_world`, pointing out of the wall, towards the
/// vehicle). Seen by a vehicle facing the wall (looking along −n):
///   up    u = world z with its n-component removed, normalised (the wall's "vertical"),
///   right r = u × n (right-handed: with n = +x and u = +z, r = +y),
/// and the rectangle is {corner + a r + b u : a ∈ [0, width], b ∈ [0, height]}, so the corner
/// is its lower-left one. A point at stand-off s in front of it is that point + s n.
/// The wall must not be horizontal (|n_z| ≤ 0.99, i.e. within ~82° of vertical): a ceiling or
/// a floor has no "up" to sweep top to bottom.
///
/// Thread-safety: plain values and pure functions. Cost: O(1).

#include <Eigen/Core>
#include <string_view>

namespace scantling::planning {

struct WallRectangle {
    Eigen::Vector3d corner_world_m = Eigen::Vector3d::Zero();  ///< lower-left, on the wall
    Eigen::Vector3d normal_world = Eigen::Vector3d::UnitX();   ///< out of the wall; normalised
    double width_m = 0.0;   ///< along r, > 0 (0: an empty request, refused)
    double height_m = 0.0;  ///< along u, > 0

    /// Throws ConfigError naming "<prefix>.<field>": non-finite corner or normal, a zero or
    /// horizontal normal, width or height not finite > 0.
    void validate(std::string_view prefix) const;
};

/// The rectangle's in-plane axes and normal, unit vectors (see the file comment).
struct WallAxes {
    Eigen::Vector3d right_world;
    Eigen::Vector3d up_world;
    Eigen::Vector3d normal_world;
};

/// Axes of a validated rectangle.
WallAxes wall_axes(const WallRectangle& rectangle);

/// corner + a r + b u + standoff n.
Eigen::Vector3d point_in_front(const WallRectangle& rectangle, const WallAxes& axes, double a_m,
                               double b_m, double standoff_m);

}  // namespace scantling::planning
