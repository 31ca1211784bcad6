#include <scantling/sim/return_model.hpp>

#include "detail/sensor_checks.hpp"

namespace scantling::sim {

double ReturnModel::sigma_at(double distance_m) const {
    return sigma_m + distance_m * (sigma_per_m + distance_m * sigma_per_m2);
}

void ReturnModel::validate(std::string_view prefix) const {
    detail::require_non_negative(prefix, "sigma_m", sigma_m);
    detail::require_non_negative(prefix, "sigma_per_m", sigma_per_m);
    detail::require_non_negative(prefix, "sigma_per_m2", sigma_per_m2);
    detail::require_probability(prefix, "dropout_probability", dropout_probability);
    detail::require_probability(prefix, "weak_reflectivity", weak_reflectivity);
    detail::require_probability(prefix, "weak_dropout_probability", weak_dropout_probability);
}

ReturnSample sample_return(const ReturnModel& model, double distance_m, double reflectivity,
                           Rng& rng) {
    const double u = rng.uniform();
    const double n = rng.normal();
    const double p_drop = reflectivity < model.weak_reflectivity ? model.weak_dropout_probability
                                                                 : model.dropout_probability;
    if (u < p_drop) return {};
    return {true, distance_m + model.sigma_at(distance_m) * n};
}

}  // namespace scantling::sim
