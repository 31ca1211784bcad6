#pragma once
// Angle conversion for the detectors' degree settings (private).
#include <numbers>

namespace scantling::perception::detail {

inline double radians(double degrees) { return degrees * std::numbers::pi / 180.0; }

}  // namespace scantling::perception::detail
