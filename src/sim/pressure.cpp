#include <scantling/sim/pressure.hpp>

#include <scantling/core/error.hpp>
#include <scantling/sim/sensor_mount.hpp>

#include "detail/sensor_checks.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace scantling::sim {

void PressureConfig::validate(std::string_view prefix) const {
    detail::require_positive(prefix, "rate_hz", rate_hz);
    detail::require_non_negative(prefix, "pressure_sigma_pa", pressure_sigma_pa);
    detail::require_positive(prefix, "water_density_kgpm3", water_density_kgpm3);
    detail::require_positive(prefix, "gravity_mps2", gravity_mps2);
    detail::require_non_negative(prefix, "atmospheric_pressure_pa", atmospheric_pressure_pa);
    detail::require(std::isfinite(surface_z_m), prefix, "surface_z_m", surface_z_m, "finite");
    validate_mount(T_body_sensor, prefix);
}

PressureSensor::PressureSensor(PressureConfig config) : config_(std::move(config)) {
    config_.validate();
}

double PressureSensor::true_depth_m(const Eigen::Isometry3d& T_world_body) const {
    return config_.surface_z_m - (T_world_body * config_.T_body_sensor).translation().z();
}

PressureSample PressureSensor::measure(const Eigen::Isometry3d& T_world_body, Rng& rng,
                                       double stamp_s) const {
    if (!T_world_body.matrix().allFinite()) {
        throw InputError(fmt::format("pressure: vehicle pose at t = {} s is not finite", stamp_s));
    }
    const double rho_g = config_.water_density_kgpm3 * config_.gravity_mps2;
    const double water_column_m = std::max(0.0, true_depth_m(T_world_body));
    PressureSample sample;
    sample.stamp_s = stamp_s;
    sample.pressure_pa = config_.atmospheric_pressure_pa + rho_g * water_column_m +
                         rng.normal(0.0, config_.pressure_sigma_pa);
    sample.depth_m = (sample.pressure_pa - config_.atmospheric_pressure_pa) / rho_g;
    return sample;
}

}  // namespace scantling::sim
