#include "motion_checks.hpp"

#include <scantling/core/error.hpp>

#include <fmt/format.h>

#include <cmath>

namespace scantling::sim::detail {

void check_motion(const MotionState& truth, std::string_view who) {
    const bool finite = std::isfinite(truth.stamp_s) && truth.T_world_body.matrix().allFinite() &&
                        truth.v_world_mps.allFinite() && truth.a_world_mps2.allFinite() &&
                        truth.omega_body_radps.allFinite();
    if (!finite) {
        throw InputError(
            fmt::format("{}: motion state at t = {} s is not finite", who, truth.stamp_s));
    }
}

void check_stamp_order(double stamp_s, double previous_stamp_s, std::string_view who) {
    if (stamp_s < previous_stamp_s) {
        throw InputError(fmt::format("{}: stamp {} s is earlier than the previous sample's {} s",
                                     who, stamp_s, previous_stamp_s));
    }
}

}  // namespace scantling::sim::detail
