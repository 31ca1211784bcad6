#include <scantling/core/error.hpp>
#include <scantling/sim/sensor_mount.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace scantling::sim {

const Surface& surface_of(const WorldMetadata& metadata, int tag) {
    static const Surface kDefault{};
    if (tag < 0 || static_cast<std::size_t>(tag) >= metadata.surfaces.size()) return kDefault;
    return metadata.surfaces[static_cast<std::size_t>(tag)];
}

double lambertian_reflectivity(double albedo, const Eigen::Vector3d& unit_direction,
                               const Eigen::Vector3d& normal) {
    const double cos_incidence = std::clamp(-unit_direction.dot(normal), 0.0, 1.0);
    return std::clamp(albedo, 0.0, 1.0) * cos_incidence;
}

void validate_mount(const Eigen::Isometry3d& T_body_sensor, std::string_view prefix) {
    // Tolerance matches RayCaster's unit-direction check: rotated unit rays must stay unit.
    constexpr double kRigidTolerance = 1e-6;
    if (!T_body_sensor.matrix().allFinite()) {
        throw ConfigError(
            fmt::format("{}.T_body_sensor is not finite, expected a rigid transform", prefix));
    }
    const Eigen::Matrix3d R = T_body_sensor.linear();
    const double orthonormality_error = (R.transpose() * R - Eigen::Matrix3d::Identity()).norm();
    if (orthonormality_error > kRigidTolerance || R.determinant() < 0.0) {
        throw ConfigError(fmt::format(
            "{}.T_body_sensor rotation has |R^T R - I| = {:.3g} and det = {:.3g}, expected a "
            "rotation (orthonormal to 1e-6, det +1)",
            prefix, orthonormality_error, R.determinant()));
    }
}

}  // namespace scantling::sim
