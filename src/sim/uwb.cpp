#include <scantling/sim/uwb.hpp>

#include <scantling/core/error.hpp>

#include "detail/sensor_checks.hpp"

#include <fmt/format.h>

#include <cmath>
#include <set>

namespace scantling::sim {

void UwbConfig::validate(std::string_view prefix) const {
    if (anchors.empty()) {
        throw ConfigError(fmt::format("{}.anchors is empty, expected at least one anchor", prefix));
    }
    std::set<int> ids;
    for (std::size_t i = 0; i < anchors.size(); ++i) {
        if (!anchors[i].position_world.allFinite()) {
            throw ConfigError(
                fmt::format("{}.anchors[{}].position_world is not finite", prefix, i));
        }
        if (!ids.insert(anchors[i].id).second) {
            throw ConfigError(fmt::format("{}.anchors[{}].id = {}, expected a unique id", prefix, i,
                                          anchors[i].id));
        }
    }
    detail::require_positive(prefix, "rate_hz", rate_hz);
    detail::require_positive(prefix, "max_range_m", max_range_m);
    detail::require_non_negative(prefix, "range_sigma_m", range_sigma_m);
    detail::require_non_negative(prefix, "nlos_bias_mean_m", nlos_bias_mean_m);
    detail::require_non_negative(prefix, "nlos_sigma_m", nlos_sigma_m);
    detail::require_probability(prefix, "dropout_probability", dropout_probability);
    detail::require_probability(prefix, "nlos_dropout_probability", nlos_dropout_probability);
    detail::require_probability(prefix, "outlier_probability", outlier_probability);
    validate_mount(T_body_sensor, prefix);
}

UwbConfig noiseless(UwbConfig config) {
    config.range_sigma_m = config.nlos_bias_mean_m = config.nlos_sigma_m = 0.0;
    config.dropout_probability = config.nlos_dropout_probability = 0.0;
    config.outlier_probability = 0.0;
    return config;
}

UwbTag::UwbTag(UwbConfig config) : config_(std::move(config)) { config_.validate(); }

UwbRange UwbTag::range_to(const SceneView& scene, const Eigen::Vector3d& p_tag,
                          const UwbAnchor& anchor, Rng& rng) const {
    const double true_range_m = (anchor.position_world - p_tag).norm();
    UwbRange range;
    range.anchor_id = anchor.id;
    range.line_of_sight = !scene.occluded(p_tag, anchor.position_world);
    const double lost_u = rng.uniform();
    const double noise = rng.normal();
    const double excess_u = rng.uniform();
    const double outlier_u = rng.uniform();
    const double outlier_value_u = rng.uniform();
    const double p_lost =
        range.line_of_sight ? config_.dropout_probability : config_.nlos_dropout_probability;
    if (lost_u < p_lost || true_range_m > config_.max_range_m) return range;
    range.valid = true;
    if (range.line_of_sight) {
        range.range_m = true_range_m + config_.range_sigma_m * noise;
    } else {
        // Exponential excess path by inversion; 1 − u is in (0, 1], so the log is finite.
        const double excess_m = -config_.nlos_bias_mean_m * std::log(1.0 - excess_u);
        range.range_m = true_range_m + excess_m + config_.nlos_sigma_m * noise;
    }
    range.outlier = outlier_u < config_.outlier_probability;
    if (range.outlier) range.range_m = config_.max_range_m * outlier_value_u;
    return range;
}

UwbMeasurement UwbTag::measure(const SceneView& scene, const Eigen::Isometry3d& T_world_body,
                               Rng& rng, double stamp_s) const {
    if (!T_world_body.matrix().allFinite()) {
        throw InputError(fmt::format("uwb: vehicle pose at t = {} s is not finite", stamp_s));
    }
    const Eigen::Vector3d p_tag = (T_world_body * config_.T_body_sensor).translation();
    UwbMeasurement measurement;
    measurement.stamp_s = stamp_s;
    measurement.ranges.reserve(config_.anchors.size());
    for (const UwbAnchor& anchor : config_.anchors) {
        measurement.ranges.push_back(range_to(scene, p_tag, anchor, rng));
    }
    return measurement;
}

}  // namespace scantling::sim
