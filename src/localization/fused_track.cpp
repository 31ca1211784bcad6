#include "scantling/localization/fused_track.hpp"

#include <algorithm>

#include <scantling/core/se3.hpp>

namespace scantling::localization {

std::optional<FusedState> fused_state_at(std::span<const FusedState> track, double stamp_s,
                                         double max_gap_s) {
    const auto after =
        std::lower_bound(track.begin(), track.end(), stamp_s,
                         [](const FusedState& s, double t) { return s.stamp_s < t; });
    if (after == track.end()) return std::nullopt;
    if (after->stamp_s == stamp_s) return *after;
    if (after == track.begin()) return std::nullopt;
    const FusedState& a = *(after - 1);
    const FusedState& b = *after;
    if (b.stamp_s - a.stamp_s > max_gap_s) return std::nullopt;
    const double w = (stamp_s - a.stamp_s) / (b.stamp_s - a.stamp_s);
    FusedState s = w < 0.5 ? a : b;
    s.stamp_s = stamp_s;
    s.T_world_body = interpolate(a.T_world_body, b.T_world_body, w);
    s.v_world_mps = (1.0 - w) * a.v_world_mps + w * b.v_world_mps;
    return s;
}

}  // namespace scantling::localization
