// The ROV's hull-survey stack: construction and the measurements (rov_stack.hpp).
#include <scantling/mission/rov_stack.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include <fmt/format.h>

#include <scantling/core/angles.hpp>
#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>

#include "detail/frames.hpp"

namespace scantling::mission {
namespace {

using namespace scantling::config_checks;

std::string prefixed(std::string_view prefix, std::string_view field) {
    return fmt::format("{}.{}", prefix, field);
}

void require_finite_pose(const Eigen::Isometry3d& T, std::string_view prefix,
                         std::string_view field) {
    if (!T.matrix().allFinite()) {
        throw ConfigError(fmt::format("{}.{} is not finite", prefix, field));
    }
}

/// The sonar's hull line taken to the world's horizontal plane: its foot point from the
/// sonar's position and the unit normal from the sonar towards it. The features lie in the
/// sonar's fan plane (z = 0 of the sonar frame), which a tilted mount leans: the line is
/// mapped as a 3-D line and projected, so a 10° down-tilt does not lengthen the stand-off by
/// 1/cos 10°. Nothing for a line through the sonar (no direction to the hull).
std::optional<planning::HullLineObservation> horizontal_observation(
    const perception::SonarHullLine& line, const Eigen::Isometry3d& T_world_sonar) {
    const Eigen::Vector3d q_sonar(line.distance_m * line.normal_sonar.x(),
                                  line.distance_m * line.normal_sonar.y(), 0.0);
    const Eigen::Vector3d t_sonar(-line.normal_sonar.y(), line.normal_sonar.x(), 0.0);
    const Eigen::Vector2d q = (T_world_sonar * q_sonar).head<2>();
    const Eigen::Vector2d t = (T_world_sonar.linear() * t_sonar).head<2>();
    if (t.norm() < 1e-6) return std::nullopt;
    const Eigen::Vector2d direction = t.normalized();
    const Eigen::Vector2d origin = T_world_sonar.translation().head<2>();
    const Eigen::Vector2d foot = q + (origin - q).dot(direction) * direction;
    const Eigen::Vector2d to_hull = foot - origin;
    if (to_hull.norm() < 1e-6) return std::nullopt;
    return planning::HullLineObservation{.point_world_m = foot,
                                         .normal_world = to_hull.normalized()};
}

}  // namespace

std::string_view to_string(SurveyPhase phase) {
    switch (phase) {
        case SurveyPhase::kSurvey:
            return "survey";
        case SurveyPhase::kReinspection:
            return "reinspection";
        case SurveyPhase::kDone:
            return "done";
    }
    return "unknown";
}

void RovStackConfig::validate(std::string_view prefix) const {
    local_ekf.validate(prefixed(prefix, "local_ekf"));
    require_positive(dvl_sigma_mps, prefix, "dvl_sigma_mps");
    require_positive(depth_sigma_m, prefix, "depth_sigma_m");
    require(std::isfinite(surface_z_world_m), prefix, "surface_z_world_m", surface_z_world_m,
            "finite");
    require_finite_pose(T_body_sonar, prefix, "T_body_sonar");
    require_finite_pose(T_body_camera, prefix, "T_body_camera");
    require_positive(sonar_range_sigma_m, prefix, "sonar_range_sigma_m");
    require_non_negative(hull_heading_sigma_rad, prefix, "hull_heading_sigma_rad");
    hull_line.validate(prefixed(prefix, "hull_line"));
    adapter.validate(prefixed(prefix, "adapter"));
    guidance.validate(prefixed(prefix, "guidance"));
    sonar_map.validate(prefixed(prefix, "sonar_map"));
    contact.validate(prefixed(prefix, "contact"));
    coverage.validate(prefixed(prefix, "coverage"));
    lasers.validate(prefixed(prefix, "lasers"));
    reinspection.validate(prefixed(prefix, "reinspection"));
    require_non_negative(min_hole_area_m2, prefix, "min_hole_area_m2");
    require_at_least(max_reinspection_rounds, 0, prefix, "max_reinspection_rounds");
    require(!std::isnan(min_waypoint_z_m) && !std::isnan(max_waypoint_z_m) &&
                min_waypoint_z_m <= max_waypoint_z_m,
            prefix, "min_waypoint_z_m", min_waypoint_z_m, "<= max_waypoint_z_m, not NaN");
    require_positive(survey_speed_mps, prefix, "survey_speed_mps");
    require_positive(max_dvl_age_s, prefix, "max_dvl_age_s");
    require_positive(max_imu_age_s, prefix, "max_imu_age_s");
}

RovStack::RovStack(RovStackConfig config, planning::WaypointPath survey_world,
                   const perception::InspectionRectangle& inspected,
                   const Eigen::Isometry3d& T_world_body_start, double start_s)
    : config_((config.validate(), std::move(config))),
      inspected_(inspected),
      T_world_odom_(detail::levelled(T_world_body_start, "rov stack")),
      local_(config_.local_ekf),
      contact_(config_.contact),
      adapter_(std::move(survey_world), config_.adapter),
      guidance_(config_.guidance),
      sonar_map_(config_.sonar_map),
      coverage_(inspected, config_.camera, config_.coverage),
      cursor_(T_world_body_start * config_.T_body_camera.translation(),
              detail::yaw_of(T_world_body_start.linear()), config_.survey_speed_mps),
      start_s_(start_s) {
    local_.initialize(start_s, T_world_odom_.inverse() * T_world_body_start);
}

void RovStack::event(double t_s, std::string type, std::string json) {
    pending_.push_back({.t_s = t_s, .type = std::move(type), .json = std::move(json)});
}

void RovStack::reject(std::string_view sensor, double stamp_s) {
    ++counters_.inputs_rejected;
    if (std::find(rejecting_.begin(), rejecting_.end(), sensor) != rejecting_.end()) return;
    rejecting_.emplace_back(sensor);
    event(stamp_s, "input_rejected",
          fmt::format(R"({{"sensor":"{}","reason":"a sample with non-finite values or a )"
                      R"(malformed message was dropped before the estimators"}})",
                      sensor));
}

Eigen::Isometry3d RovStack::T_world_body() const {
    return T_world_odom_ * local_.state().T_odom_body;
}

localization::DroneState RovStack::estimate() const {
    localization::DroneState s = local_.state();
    const Eigen::Matrix3d R = T_world_odom_.linear();
    s.T_odom_body = T_world_odom_ * s.T_odom_body;
    s.v_odom_mps = R * s.v_odom_mps;
    s.a_odom_mps2 = R * s.a_odom_mps2;
    localization::Matrix9d rotation = localization::Matrix9d::Zero();
    for (int block = 0; block < 3; ++block) rotation.block<3, 3>(3 * block, 3 * block) = R;
    s.covariance = rotation * s.covariance * rotation.transpose();
    return s;
}

bool RovStack::estimate_valid(double t_s) const {
    return last_imu_s_ && t_s - *last_imu_s_ <= config_.max_imu_age_s;
}

void RovStack::add_imu(const io::ImuRecord& sample) {
    if (!std::isfinite(sample.stamp_s) || !sample.specific_force_mps2.allFinite() ||
        !sample.angular_rate_radps.allFinite()) {
        return reject("imu", sample.stamp_s);
    }
    std::erase(rejecting_, "imu");
    if (local_.add_imu(sample) == localization::ImuPredictionStatus::kOutOfOrder) return;
    last_imu_s_ = sample.stamp_s;
    // The detector works in the body frame; the IMU's lever arm is neglected (its file comment).
    const Eigen::Matrix3d R_body_imu = config_.local_ekf.T_body_imu.linear();
    const io::ImuRecord body{sample.stamp_s, R_body_imu * sample.specific_force_mps2,
                             R_body_imu * sample.angular_rate_radps};
    const Eigen::Quaterniond q_world_body(T_world_body().linear());
    if (const auto contact = contact_.add(body, q_world_body)) {
        const Eigen::Vector3d& d = contact->impulse_direction_world;
        event(contact->stamp_s, "contact",
              fmt::format(R"({{"impulse_direction_world":[{:.3f},{:.3f},{:.3f}],)"
                          R"("peak_residual_mps2":{:.2f},"back_off_s":{}}})",
                          d.x(), d.y(), d.z(), contact->peak_residual_mps2,
                          config_.contact.back_off_duration_s));
    }
}

void RovStack::add_dvl(const io::DvlRecord& sample) {
    if (!std::isfinite(sample.stamp_s)) return reject("dvl", sample.stamp_s);
    if (!sample.valid) {
        ++counters_.dvl_invalid;
        return;
    }
    if (!sample.v_body_mps.allFinite()) return reject("dvl", sample.stamp_s);
    std::erase(rejecting_, "dvl");
    const double variance = config_.dvl_sigma_mps * config_.dvl_sigma_mps;
    const localization::UpdateResult result =
        local_.update_body_velocity({.stamp_s = sample.stamp_s,
                                     .v_sensor_mps = sample.v_body_mps,
                                     .covariance_mps2 = Eigen::Matrix3d::Identity() * variance});
    if (result.status == localization::UpdateStatus::kApplied) last_dvl_lock_s_ = sample.stamp_s;
}

void RovStack::add_pressure(const io::PressureRecord& sample) {
    if (!std::isfinite(sample.stamp_s) || !std::isfinite(sample.depth_m)) {
        return reject("pressure", sample.stamp_s);
    }
    std::erase(rejecting_, "pressure");
    const double z_world_m = config_.surface_z_world_m - sample.depth_m;
    local_.update_depth({.stamp_s = sample.stamp_s,
                         .z_odom_m = z_world_m - T_world_odom_.translation().z(),
                         .sigma_m = config_.depth_sigma_m});
}

std::optional<perception::SonarHullLine> RovStack::add_sonar(const io::SonarPing& ping) {
    try {
        ping.validate("sonar_ping");
    } catch (const InputError&) {
        reject("sonar", ping.stamp_s);
        return std::nullopt;
    }
    std::erase(rejecting_, "sonar");
    ++counters_.pings;
    perception::SonarHullLine line = perception::detect_hull_line(ping, config_.hull_line);
    const Eigen::Isometry3d T_world_sonar = T_world_body() * config_.T_body_sonar;
    add_features(line, T_world_sonar, ping.stamp_s);
    if (!line.ok()) {
        if (!hull_line_lost_) {
            event(ping.stamp_s, "hull_line_lost",
                  fmt::format(R"({{"status":"{}","features":{}}})",
                              perception::to_string(line.status), line.features.size()));
        }
        hull_line_lost_ = true;
        return line;
    }
    if (hull_line_lost_) event(ping.stamp_s, "hull_line_restored");
    hull_line_lost_ = false;
    ++counters_.hull_lines;
    const auto observation = horizontal_observation(line, T_world_sonar);
    if (observation) aid_heading(*observation, ping.stamp_s);
    if (observation && state_ == control::MissionState::kRunning) {
        // After the heading aid: the pose it has just corrected.
        const Eigen::Vector3d p_camera = T_world_body() * config_.T_body_camera.translation();
        // From the current leg's start on: the target runs along the leg, so both of its ends
        // must lie on the adapted line (both are on one line parallel to the planned hull, so
        // the start's heading and pivot are the goal's). Moving only the goal tilted the leg
        // and left the target up to the whole correction off the line near the leg's start.
        const std::size_t next = cursor_.next_index();
        const planning::AdaptationStep step =
            adapter_.adapt(*observation, p_camera, next > 0 ? next - 1 : 0);
        counters_.last_stand_off_measured_m = step.stand_off_measured_m;
        if (step.clamped) ++counters_.adaptations_clamped;
    }
    return line;
}

void RovStack::aid_heading(const planning::HullLineObservation& observation, double stamp_s) {
    if (config_.hull_heading_sigma_rad <= 0.0) return;
    // The measured line's normal turns with the estimate's yaw error: a yaw too large by ε
    // puts it ε further counter-clockwise than the section's own (its inward normal, −n).
    const Eigen::Vector2d inward = -inspected_.normal_world().head<2>();
    const double correction_rad =
        wrap_angle_rad(std::atan2(inward.y(), inward.x()) -
                       std::atan2(observation.normal_world.y(), observation.normal_world.x()));
    const double yaw_odom_rad = detail::yaw_of(local_.state().T_odom_body.linear());
    local_.update_yaw({.stamp_s = stamp_s,
                       .yaw_odom_rad = yaw_odom_rad + correction_rad,
                       .sigma_rad = config_.hull_heading_sigma_rad});
}

void RovStack::add_features(const perception::SonarHullLine& line,
                            const Eigen::Isometry3d& T_world_sonar, double stamp_s) {
    const Eigen::Matrix3d P = estimate().covariance.topLeftCorner<3, 3>();
    const double pose_variance = P.trace() / 3.0;
    std::vector<Eigen::Vector3d> points;
    std::vector<double> sigmas;
    for (const perception::SonarFeature& f : line.features) {
        if (f.outlier) continue;
        points.push_back(T_world_sonar * Eigen::Vector3d(f.p_sonar.x(), f.p_sonar.y(), 0.0));
        sigmas.push_back(
            std::sqrt(config_.sonar_range_sigma_m * config_.sonar_range_sigma_m + pose_variance));
    }
    if (!points.empty()) sonar_map_.add(points, sigmas, stamp_s);
}

std::optional<perception::LaserPointerMeasurement> RovStack::add_image(const io::RgbImage& image,
                                                                       double stamp_s) {
    if (!std::isfinite(stamp_s)) {
        reject("camera", stamp_s);
        return std::nullopt;
    }
    ++counters_.images;
    if (state_ == control::MissionState::kRunning) {
        coverage_.add_view(T_world_body() * config_.T_body_camera);
    }
    if (!config_.measure_lasers) return std::nullopt;
    try {
        perception::LaserPointerMeasurement m =
            perception::measure_laser_pointers(image, config_.camera, config_.lasers);
        if (m.ok()) {
            ++counters_.laser_measurements;
            counters_.last_laser_distance_m = m.distance_m;
        }
        std::erase(rejecting_, "camera");
        return m;
    } catch (const InputError&) {
        reject("camera", stamp_s);
        return std::nullopt;
    }
}

std::size_t RovStack::next_waypoint() const { return cursor_.next_index(); }

}  // namespace scantling::mission
