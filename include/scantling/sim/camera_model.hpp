#pragma once
/// @file
/// The simulated cameras' pinhole model: core's (core/pinhole_intrinsics.hpp), which the readers
/// of their images share.

#include <scantling/core/pinhole_intrinsics.hpp>

namespace scantling::sim {

using PinholeIntrinsics = scantling::PinholeIntrinsics;

}  // namespace scantling::sim
