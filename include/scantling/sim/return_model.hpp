#pragma once
/// @file
/// Noise and dropout of an active range measurement (LiDAR return, ToF pixel, range finder).
///
/// Model, per return at distance d (the range along the ray for LiDARs, the depth z for depth
/// cameras):
///   measured = d + N(0, σ(d)²),  σ(d) = sigma_m + sigma_per_m · d + sigma_per_m2 · d²;
///   reflectivity ρ = albedo · cos(incidence)  (see lambertian_reflectivity);
///   the return is lost with probability weak_dropout_probability when ρ < weak_reflectivity
///   (grazing incidence, dark surface), else with probability dropout_probability.
///
/// Determinism: every return consumes exactly one uniform and then one normal from the Rng,
/// in the order the sensor documents (its point order), whatever the outcome.

#include <string_view>

#include <scantling/core/random.hpp>

namespace scantling::sim {

struct ReturnModel {
    double sigma_m = 0.0;                   ///< constant part of the 1σ noise, metres
    double sigma_per_m = 0.0;               ///< linear growth of σ with distance, metres per metre
    double sigma_per_m2 = 0.0;              ///< quadratic growth of σ with distance, 1/metre
    double dropout_probability = 0.0;       ///< loss of any return, in [0, 1]
    double weak_reflectivity = 0.0;         ///< ρ below this is a weak return, in [0, 1]
    double weak_dropout_probability = 0.0;  ///< loss of a weak return, in [0, 1]

    /// 1σ noise at distance `distance_m`, metres.
    double sigma_at(double distance_m) const;

    /// Throws ConfigError naming the field ("<prefix>.sigma_m = -1, expected >= 0").
    void validate(std::string_view prefix) const;
};

/// Outcome of one return.
struct ReturnSample {
    bool kept = false;        ///< false: the return was dropped
    double distance_m = 0.0;  ///< noisy distance (meaningful when kept)
};

/// Applies the model to a true distance and reflectivity, drawing one uniform then one normal.
ReturnSample sample_return(const ReturnModel& model, double distance_m, double reflectivity,
                           Rng& rng);

}  // namespace scantling::sim
