#pragma once
/// @file
/// Angle wrapping shared by the modules above core. (Older twins remain in sim/trajectory.hpp,
/// control/position_controller.hpp and two registration sources; new code uses this one.)

#include <cmath>
#include <numbers>

namespace scantling {

/// `angle_rad` wrapped to [−π, π] (IEEE remainder: exact, no loop; NaN stays NaN).
inline double wrap_angle_rad(double angle_rad) {
    return std::remainder(angle_rad, 2.0 * std::numbers::pi);
}

}  // namespace scantling
