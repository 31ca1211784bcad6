#include <scantling/safety/height_keeping.hpp>

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>

namespace scantling::safety {
namespace {

void require_above(double value, double bound, std::string_view bound_name, std::string_view prefix,
                   std::string_view field) {
    config_checks::require(std::isfinite(value) && value > bound, prefix, field, value,
                           fmt::format("finite > {} = {}", bound_name, bound));
}

void check_clearance(const std::optional<double>& clearance_m, std::string_view side) {
    // +inf is a range finder's "nothing within range"; NaN or negative is a broken input.
    if (clearance_m && !(*clearance_m >= 0.0)) {
        throw InputError(
            fmt::format("keep_height: {} clearance = {} m, expected >= 0 (+inf: "
                        "nothing within range)",
                        side, *clearance_m));
    }
}

double band_factor(double clearance_m, double min_m, double att_m) {
    return std::clamp((clearance_m - min_m) / (att_m - min_m), 0.0, 1.0);
}

/// λ for the surface the desired speed heads to (1 when it is unknown or the speed is 0).
double vertical_lambda(double v_z_mps, const VerticalClearance& c, const HeightKeepingConfig& k) {
    if (v_z_mps < 0.0 && c.floor_m) return band_factor(*c.floor_m, k.floor_min_m, k.floor_att_m);
    if (v_z_mps > 0.0 && c.ceiling_m) {
        return band_factor(*c.ceiling_m, k.ceiling_min_m, k.ceiling_att_m);
    }
    return 1.0;
}

/// One push per surface inside its minimum, summed, then clamped.
double vertical_push(const VerticalClearance& c, const HeightKeepingConfig& k) {
    double push_mps = 0.0;
    if (c.floor_m) push_mps += k.gain_per_s * std::max(0.0, k.floor_min_m - *c.floor_m);
    if (c.ceiling_m) push_mps -= k.gain_per_s * std::max(0.0, k.ceiling_min_m - *c.ceiling_m);
    return std::clamp(push_mps, -k.max_vertical_speed_mps, k.max_vertical_speed_mps);
}

void keep_nearer(std::optional<double>& nearest_m, double candidate_m) {
    if (!nearest_m || candidate_m < *nearest_m) nearest_m = candidate_m;
}

std::optional<double> min_of(const std::optional<double>& a, const std::optional<double>& b) {
    if (!a) return b;
    if (!b) return a;
    return std::min(*a, *b);
}

}  // namespace

void HeightKeepingConfig::validate(std::string_view prefix) const {
    using namespace config_checks;
    require_positive(floor_min_m, prefix, "floor_min_m");
    require_above(floor_att_m, floor_min_m, "floor_min_m", prefix, "floor_att_m");
    require_positive(ceiling_min_m, prefix, "ceiling_min_m");
    require_above(ceiling_att_m, ceiling_min_m, "ceiling_min_m", prefix, "ceiling_att_m");
    require_positive(gain_per_s, prefix, "gain_per_s");
    require_positive(max_vertical_speed_mps, prefix, "max_vertical_speed_mps");
    require_positive(footprint_radius_m, prefix, "footprint_radius_m");
}

HeightKeepingResult keep_height(double v_z_desired_mps, const VerticalClearance& clearance,
                                const HeightKeepingConfig& config) {
    config.validate();
    if (!std::isfinite(v_z_desired_mps)) {
        throw InputError(
            fmt::format("keep_height: desired vertical speed = {} m/s, expected "
                        "finite",
                        v_z_desired_mps));
    }
    check_clearance(clearance.floor_m, "floor");
    check_clearance(clearance.ceiling_m, "ceiling");
    HeightKeepingResult result;
    result.lambda = vertical_lambda(v_z_desired_mps, clearance, config);
    result.push_mps = vertical_push(clearance, config);
    result.v_z_cmd_mps = result.lambda * v_z_desired_mps + result.push_mps;
    if (clearance.floor_m || clearance.ceiling_m) {
        result.status = result.lambda >= 1.0  ? AttenuationStatus::kClear
                        : result.lambda > 0.0 ? AttenuationStatus::kAttenuated
                                              : AttenuationStatus::kStopped;
    }
    return result;
}

VerticalClearance clearance_from_cloud(const PointCloud& cloud_body,
                                       const HeightKeepingConfig& config) {
    config.validate();
    const double r2 = config.footprint_radius_m * config.footprint_radius_m;
    VerticalClearance clearance;
    for (const Eigen::Vector3d& p : cloud_body.points) {
        if (!p.allFinite() || p.head<2>().squaredNorm() > r2) continue;
        if (p.z() < 0.0) keep_nearer(clearance.floor_m, -p.z());
        if (p.z() > 0.0) keep_nearer(clearance.ceiling_m, p.z());
    }
    return clearance;
}

VerticalClearance nearest(const VerticalClearance& a, const VerticalClearance& b) {
    return {min_of(a.floor_m, b.floor_m), min_of(a.ceiling_m, b.ceiling_m)};
}

}  // namespace scantling::safety
