#pragma once
/// @file
/// The fused state between two of the filter's outputs (pose_filter.hpp emits one per VIO
/// sample): what a camera or a depth frame stamped between VIO samples is placed with.
///
/// The pose is interpolated (position linearly, attitude by slerp), the velocity linearly, the
/// covariances taken from the nearer sample (they change slowly at the VIO rate).
/// Reentrant; O(log n).

#include <optional>
#include <span>

#include <scantling/localization/pose_filter.hpp>

namespace scantling::localization {

/// The state at `stamp_s`, or nullopt when the track does not bracket it or the two samples
/// around it are more than `max_gap_s` apart (a VIO dropout: nothing to interpolate on).
/// `track` must be in increasing stamp order.
std::optional<FusedState> fused_state_at(std::span<const FusedState> track, double stamp_s,
                                         double max_gap_s);

}  // namespace scantling::localization
