// Art. F's 3-DoF registration in the column (SPEC §7; column_registration.hpp).
#include <scantling/localization/column_registration.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>
#include <scantling/core/se3.hpp>
#include <scantling/core/voxel_grid.hpp>

namespace scantling::localization {
namespace {

using config_checks::require;
using config_checks::require_non_negative;
using config_checks::require_open_unit;
using config_checks::require_positive;

constexpr double kPi = std::numbers::pi;
constexpr double kRadPerDeg = kPi / 180.0;
// The DoFs the registration measures, in the (δp, δθ) order of FusedState::covariance.
constexpr int kMeasured[] = {0, 1, 5};
constexpr int kFree[] = {2, 3, 4};  // z is measured too when the floor is seen

double wrap_rad(double angle_rad) { return std::remainder(angle_rad, 2.0 * kPi); }

double yaw_of(const Eigen::Matrix3d& R) { return euler_zyx_from_rotation(R).z(); }

/// The levelled frame G of a frame: origin at the sensor, z up, the body's yaw left out.
struct Levelled {
    Eigen::Isometry3d T_G_sensor = Eigen::Isometry3d::Identity();  ///< rotation only
    Eigen::Isometry3d T_G_body = Eigen::Isometry3d::Identity();
};

Levelled levelled(const Eigen::Matrix3d& R_world_body_imu, const Eigen::Isometry3d& T_body_sensor) {
    // R = R_z(yaw) R_y(pitch) R_x(roll): taking R_z(yaw) off leaves the IMU's roll and pitch.
    const Eigen::Matrix3d R_G_body =
        Eigen::AngleAxisd(-yaw_of(R_world_body_imu), Eigen::Vector3d::UnitZ()) * R_world_body_imu;
    Levelled g;
    g.T_G_sensor.linear() = R_G_body * T_body_sensor.linear();
    g.T_G_body = g.T_G_sensor * T_body_sensor.inverse();
    return g;
}

PointCloud downsampled(const PointCloud& cloud, double voxel_m) {
    return voxel_m > 0.0 ? voxel_downsample(cloud, voxel_m) : cloud;
}

/// The sensor's z from the seen floor: the map's floor under the sensor plus the height above
/// it (nullopt without a floor in view or in the map near where the prediction puts it).
std::optional<double> sensor_z_from_floor(const perception::ColumnStructure& structure_G,
                                          const Eigen::Vector2d& p_world_sensor_xy,
                                          double predicted_z_m, const PointCloud& map,
                                          const KdTree& map_tree,
                                          const ColumnRegistrationConfig& config) {
    if (!structure_G.floor || !map.has_normals()) return std::nullopt;
    const perception::Plane& floor = *structure_G.floor;
    if (!(std::abs(floor.normal.z()) > 0.0)) return std::nullopt;
    const double height_m =
        std::abs(floor.signed_distance(Eigen::Vector3d::Zero()) / floor.normal.z());
    const auto hit = map_tree.nearest(
        Eigen::Vector3d(p_world_sensor_xy.x(), p_world_sensor_xy.y(), predicted_z_m - height_m));
    const double cos_tolerance = std::cos(config.structure.vertical_tolerance_deg * kRadPerDeg);
    if (!hit || hit->distance_sq_m2 > config.max_floor_snap_m * config.max_floor_snap_m ||
        std::abs(map.normals[hit->index].z()) < cos_tolerance) {
        return std::nullopt;
    }
    return map.points[hit->index].z() + height_m;
}

/// (δp, δθ) covariance at the body of the particles about the chosen pose, the measured block
/// only, with the floors; roll, pitch (and z without a floor) free. As the filter's left twist.
Matrix6d measurement_covariance(const registration::SteinIcpResult& r,
                                const Eigen::Isometry3d& T_G_body,
                                const Eigen::Isometry3d& T_world_body, bool z_from_floor,
                                const ColumnRegistrationConfig& config) {
    Matrix6d spread = Matrix6d::Zero();
    for (const Vector6d& particle : r.particles) {
        const Vector6d e = position_attitude_error(
            T_world_body, registration::isometry_from_pose_params(particle) * T_G_body);
        spread += e * e.transpose();
    }
    spread /= static_cast<double>(std::max<std::size_t>(r.particles.size(), 2) - 1);
    Matrix6d C = Matrix6d::Zero();
    for (const int i : kMeasured) {
        for (const int j : kMeasured) C(i, j) = spread(i, j);
    }
    const double yaw_floor_rad = config.min_yaw_sigma_deg * kRadPerDeg;
    C(0, 0) += config.min_position_sigma_m * config.min_position_sigma_m;
    C(1, 1) += config.min_position_sigma_m * config.min_position_sigma_m;
    C(5, 5) += yaw_floor_rad * yaw_floor_rad;
    for (const int i : kFree) C(i, i) = config.free_sigma * config.free_sigma;
    if (z_from_floor) C(2, 2) = config.floor_z_sigma_m * config.floor_z_sigma_m;
    return twist_covariance(C, T_world_body.translation());
}

void check_inputs(const PointCloud& frame_sensor, const AbsolutePose& predicted,
                  const Eigen::Matrix3d& R_world_body_imu) {
    check_consistent(frame_sensor, "register_column");
    check_finite(frame_sensor, "register_column");
    if (!predicted.T_world_body.matrix().allFinite() || !R_world_body_imu.allFinite()) {
        throw InputError("register_column: the prediction and the IMU attitude must be finite");
    }
}

}  // namespace

void ColumnRegistrationConfig::validate(std::string_view prefix) const {
    structure.validate(fmt::format("{}.structure", prefix));
    require_non_negative(detection_voxel_m, prefix, "detection_voxel_m");
    require_positive(registration_voxel_m, prefix, "registration_voxel_m");
    require(axis_xy_m.allFinite(), prefix, "axis_xy_m", axis_xy_m.x(), "finite");
    require(std::isfinite(downcomer_azimuth_deg), prefix, "downcomer_azimuth_deg",
            downcomer_azimuth_deg, "finite");
    const std::string stein_prefix = fmt::format("{}.stein", prefix);
    stein.validate(stein_prefix);
    require(stein.reduced_3dof, stein_prefix, "reduced_3dof", 0.0, "true (x, y, yaw only)");
    require_positive(max_floor_snap_m, prefix, "max_floor_snap_m");
    require_positive(floor_z_sigma_m, prefix, "floor_z_sigma_m");
    require_positive(max_rmse_m, prefix, "max_rmse_m");
    require_open_unit(min_fitness, prefix, "min_fitness");
    require_non_negative(min_position_sigma_m, prefix, "min_position_sigma_m");
    require_non_negative(min_yaw_sigma_deg, prefix, "min_yaw_sigma_deg");
    require_positive(free_sigma, prefix, "free_sigma");
}

std::optional<ColumnSeed> column_seed(const perception::ColumnStructure& structure_G,
                                      double predicted_yaw_rad,
                                      const ColumnRegistrationConfig& config) {
    if (!structure_G.registrable() || !structure_G.axis_point) return std::nullopt;
    const Eigen::Vector3d seen = structure_G.downcomer_direction();
    // R_z(yaw) turns the seen direction onto the map's line, on one side or the other.
    double yaw_rad =
        wrap_rad(config.downcomer_azimuth_deg * kRadPerDeg - std::atan2(seen.y(), seen.x()));
    if (std::abs(wrap_rad(yaw_rad - predicted_yaw_rad)) > 0.5 * kPi) {
        yaw_rad = wrap_rad(yaw_rad + kPi);
    }
    ColumnSeed seed;
    seed.yaw_rad = yaw_rad;
    seed.p_world_sensor_xy =
        config.axis_xy_m - Eigen::Rotation2Dd(yaw_rad) * structure_G.axis_point->head<2>();
    return seed;
}

ColumnRegistration register_column(const PointCloud& frame_sensor,
                                   const Eigen::Isometry3d& T_body_sensor,
                                   const Eigen::Matrix3d& R_world_body_imu,
                                   const AbsolutePose& predicted, const PointCloud& map,
                                   const KdTree& map_tree, const ColumnRegistrationConfig& config,
                                   std::uint64_t seed_offset) {
    config.validate();
    check_inputs(frame_sensor, predicted, R_world_body_imu);
    const Levelled g = levelled(R_world_body_imu, T_body_sensor);
    const PointCloud frame_G = transformed(frame_sensor, g.T_G_sensor);
    ColumnRegistration out;
    out.structure = perception::detect_column_structure(
        downsampled(frame_G, config.detection_voxel_m), Eigen::Vector3d::UnitZ(),
        Eigen::Vector3d::Zero(), config.structure);
    out.seed = column_seed(out.structure, yaw_of(predicted.T_world_body.linear()), config);
    if (!out.seed) {
        out.failure = "not_registrable";
        out.reason = out.structure.status;
        return out;
    }
    // z from the floor, or from the prediction (a drifted z would add to every residual of
    // the floor and the downcomer's lower edge); roll and pitch are those of G: zero.
    const double predicted_z_m = (predicted.T_world_body * T_body_sensor).translation().z();
    const std::optional<double> floor_z_m = sensor_z_from_floor(
        out.structure, out.seed->p_world_sensor_xy, predicted_z_m, map, map_tree, config);
    out.z_from_floor = floor_z_m.has_value();
    Vector6d guess;
    guess << out.seed->p_world_sensor_xy, floor_z_m.value_or(predicted_z_m), 0.0, 0.0,
        out.seed->yaw_rad;
    registration::SteinIcpConfig stein = config.stein;
    stein.seed += seed_offset;  // every frame its own particles, reproducibly
    const registration::SteinIcpResult r =
        registration::stein_icp(downsampled(frame_G, config.registration_voxel_m), map, map_tree,
                                registration::isometry_from_pose_params(guess), stein);
    const Eigen::Isometry3d T_world_body = r.T_target_source * g.T_G_body;
    out.T_world_body = T_world_body;
    out.rmse_m = r.rmse_m;
    out.fitness = r.fitness;
    out.num_modes = r.num_modes;
    if (!(r.rmse_m <= config.max_rmse_m) || !(r.fitness >= config.min_fitness)) {
        out.failure = "registration";
        out.reason = fmt::format("rmse {:.3f} m (max {}), fitness {:.2f} (min {})", r.rmse_m,
                                 config.max_rmse_m, r.fitness, config.min_fitness);
        return out;
    }
    out.pose =
        AbsolutePose{predicted.stamp_s, T_world_body,
                     measurement_covariance(r, g.T_G_body, T_world_body, out.z_from_floor, config)};
    out.reason = fmt::format("{} KDE modes, rmse {:.3f} m, z from the {}", r.num_modes, r.rmse_m,
                             out.z_from_floor ? "floor" : "prediction");
    return out;
}

}  // namespace scantling::localization
