#pragma once
// Input checks shared by the motion-based sensor models (IMU, VIO, wheel odometry, DVL,
// pressure): each throws InputError naming the sensor.

#include <string_view>

#include <scantling/sim/motion_state.hpp>

namespace scantling::sim::detail {

/// Throws InputError "<who>: motion state at t = ... s is not finite" unless every field is.
void check_motion(const MotionState& truth, std::string_view who);

/// Throws InputError unless stamp_s >= previous_stamp_s (sensors never go back in time).
void check_stamp_order(double stamp_s, double previous_stamp_s, std::string_view who);

}  // namespace scantling::sim::detail
