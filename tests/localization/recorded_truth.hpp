#pragma once
// The true body pose of a recording at a stamp, for the tests that run the localiser on one.
#include <Eigen/Geometry>
#include <algorithm>
#include <vector>

#include <scantling/io/tum.hpp>

namespace scantling::localization::test {

/// The first ground-truth pose at or after `t` (the last one past the end): the simulator's
/// ground truth is at every clock step, finer than any sensor stamp.
inline Eigen::Isometry3d truth_at(const std::vector<io::StampedPose>& ground_truth, double t) {
    const auto it =
        std::lower_bound(ground_truth.begin(), ground_truth.end(), t,
                         [](const io::StampedPose& p, double s) { return p.stamp_s < s; });
    return it == ground_truth.end() ? ground_truth.back().T_world_body : it->T_world_body;
}

}  // namespace scantling::localization::test
