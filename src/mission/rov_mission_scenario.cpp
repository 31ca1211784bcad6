// ROV mission scenario files (rov_mission.hpp).
#include <scantling/mission/rov_mission.hpp>

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <numbers>

#include <scantling/control/config_yaml.hpp>
#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>
#include <scantling/core/se3.hpp>
#include <scantling/io/config_node.hpp>
#include <scantling/io/config_schema.hpp>
#include <scantling/sim/scenario_schema.hpp>
#include <scantling/sim/sensor_configs.hpp>

#include "detail/config_nodes.hpp"
#include "detail/mission_schemas.hpp"

namespace scantling::mission {
namespace {

using detail::required;
using detail::without;

/// `mission:` of an ROV document.
struct HullSurveyMission {
    std::string type;
    sim::PoseSpec hull{};
    planning::HullSurveyPlanConfig plan{};
    double margin_m = 0.1;
};

const io::ConfigSchema<control::RovGuidanceConfig>& guidance_schema() {
    using S = control::RovGuidanceConfig;
    static const io::ConfigSchema<S> schema = [] {
        io::ConfigSchema<S> s;
        s.field("max_approach_speed_mps", &S::max_approach_speed_mps, "κ, m/s", io::kPositive)
            .field("transient_m", &S::transient_m, "Δ, m", io::kPositive)
            .field("max_speed_mps", &S::max_speed_mps, "horizontal clamp, m/s", io::kPositive)
            .field("yaw_gain_per_s", &S::yaw_gain_per_s, "k_ψ, 1/s", io::kPositive)
            .field("max_yaw_rate_radps", &S::max_yaw_rate_radps, "rad/s", io::kPositive)
            .section("depth", &S::depth, control::pid_schema(), "depth PI, m -> m/s")
            .field("max_heading_error_rad", &S::max_heading_error_rad, "pause above, rad",
                   io::kPositive)
            .field("max_depth_error_m", &S::max_depth_error_m, "pause above, m", io::kPositive)
            .field("resume_fraction", &S::resume_fraction, "resume below this share of the bounds",
                   io::kUnitInterval);
        return s;
    }();
    return schema;
}

const io::ConfigSchema<planning::HullRelativeAdapterConfig>& adapter_schema() {
    using S = planning::HullRelativeAdapterConfig;
    static const io::ConfigSchema<S> schema = [] {
        io::ConfigSchema<S> s;
        s.field("gain", &S::gain, "share of the measured correction per scan", io::kUnitInterval)
            .field("max_shift_per_scan_m", &S::max_shift_per_scan_m, "m", io::kPositive)
            .field("max_turn_per_scan_rad", &S::max_turn_per_scan_rad, "rad", io::kPositive);
        return s;
    }();
    return schema;
}

const io::ConfigSchema<safety::ContactDetectorConfig>& contact_schema() {
    using S = safety::ContactDetectorConfig;
    static const io::ConfigSchema<S> schema = [] {
        io::ConfigSchema<S> s;
        s.field("threshold_mps2", &S::threshold_mps2, "unexplained acceleration, m/s²",
                io::kPositive)
            .field("min_samples_above", &S::min_samples_above, "consecutive samples")
            .field("refractory_s", &S::refractory_s, "s", io::kNonNegative)
            .field("back_off_speed_mps", &S::back_off_speed_mps, "m/s", io::kPositive)
            .field("back_off_duration_s", &S::back_off_duration_s, "s", io::kPositive);
        return s;
    }();
    return schema;
}

const io::ConfigSchema<RovStackConfig>& stack_schema() {
    using S = RovStackConfig;
    static const io::ConfigSchema<S> schema = [] {
        io::ConfigSchema<S> s;
        s.field("dvl_sigma_mps", &S::dvl_sigma_mps, "DVL velocity 1σ, m/s", io::kPositive)
            .field("depth_sigma_m", &S::depth_sigma_m, "pressure depth 1σ, m", io::kPositive)
            .field("sonar_range_sigma_m", &S::sonar_range_sigma_m, "sonar feature 1σ, m",
                   io::kPositive)
            .field("hull_heading_sigma_rad", &S::hull_heading_sigma_rad,
                   "heading from the hull line, 1σ, rad (0: off)", io::kNonNegative)
            .section("guidance", &S::guidance, guidance_schema())
            .section("adapter", &S::adapter, adapter_schema())
            .section("contact", &S::contact, contact_schema())
            .section("coverage", &S::coverage, detail::camera_coverage_config_schema(),
                     "the coverage the robot believes, which decides the re-inspection")
            .field("measure_lasers", &S::measure_lasers, "laser-pointer triangulation per image")
            .field("min_hole_area_m2", &S::min_hole_area_m2, "smaller holes are left, m²",
                   io::kNonNegative)
            .field("max_reinspection_rounds", &S::max_reinspection_rounds, "0: none")
            .field("max_dvl_age_s", &S::max_dvl_age_s, "longer without lock: hold, s",
                   io::kPositive)
            .field("max_imu_age_s", &S::max_imu_age_s, "longer without IMU: stop, s",
                   io::kPositive);
        return s;
    }();
    return schema;
}

const io::ConfigSchema<detail::VehicleDocument<RovStackConfig>>& document_schema() {
    static const auto schema = detail::vehicle_document_schema(stack_schema());
    return schema;
}

const io::ConfigSchema<HullSurveyMission>& mission_schema() {
    using S = HullSurveyMission;
    static const io::ConfigSchema<S> schema = [] {
        io::ConfigSchema<S> s;
        s.field("type", &S::type, "hull_survey")
            .section("hull", &S::hull, sim::detail::pose_spec_schema(),
                     "T_world_hull: the plan's hull frame (y = 0 the hull side, z = 0 the "
                     "water surface)")
            .section("plan", &S::plan, planning::hull_survey_plan_config_schema(),
                     "the section: length, draught, stand-off, slices")
            .field("margin_m", &S::margin_m, "the plan flown reaches beyond the section, m",
                   io::kNonNegative);
        return s;
    }();
    return schema;
}

/// The camera's optical frame in CoverageSpec's mount terms (x forward, y left, z up).
sim::PoseSpec mount_of(const Eigen::Isometry3d& T_body_optical) {
    Eigen::Matrix3d R_mount_optical;
    R_mount_optical << 0.0, 0.0, 1.0, -1.0, 0.0, 0.0, 0.0, -1.0, 0.0;
    const Eigen::Matrix3d R = T_body_optical.linear() * R_mount_optical.transpose();
    sim::PoseSpec mount;
    mount.xyz = T_body_optical.translation();
    mount.rpy_deg = euler_zyx_from_rotation(R) * 180.0 / std::numbers::pi;
    return mount;
}

perception::LaserPointerConfig lasers_of(const std::vector<sim::LaserPointer>& lasers,
                                         perception::LaserPointerConfig config) {
    if (lasers.size() != 2) return config;
    config.origin_a_camera = lasers[0].origin_camera;
    config.origin_b_camera = lasers[1].origin_camera;
    config.direction_camera = lasers[0].direction_camera;
    config.spot_rgb = lasers[0].rgb;
    return config;
}

/// The robot knows its own mounts, its camera and the water's surface; the plan sets the
/// stand-offs, the footprint and the survey speed.
void calibrate(RovMissionScenario& m) {
    RovStackConfig& s = m.stack;
    for (std::size_t i = 0; i < m.simulation.sensors.size(); ++i) {
        const sim::SensorSpec& spec = m.simulation.sensors[i];
        const std::string prefix = fmt::format("simulation.sensors[{}]", i);
        const Eigen::Isometry3d mount = spec.T_body_sensor.to_isometry();
        using T = sim::SensorType;
        if (spec.type == T::kImu) s.local_ekf.T_body_imu = mount;
        if (spec.type == T::kMultibeamSonar) s.T_body_sonar = mount;
        if (spec.type == T::kPressure) s.surface_z_world_m = spec.surface_z_m;
        if (spec.type == T::kDvl) {
            // The DVL reports the transducer's velocity in body axes (sim/dvl.hpp): the EKF's
            // sensor frame is the body's axes at the transducer.
            const sim::DvlConfig dvl = sim::detail::dvl_config(spec, prefix);
            s.local_ekf.T_body_velocity_sensor = Eigen::Isometry3d::Identity();
            s.local_ekf.T_body_velocity_sensor.translation() = dvl.T_body_sensor.translation();
        }
        if (spec.type == T::kCamera) {
            const sim::PinholeCameraConfig camera = sim::detail::camera_config(spec, prefix);
            s.camera = camera.intrinsics;
            s.T_body_camera = camera.T_body_sensor;
            s.lasers = lasers_of(camera.lasers, s.lasers);
            s.measure_lasers = s.measure_lasers && camera.lasers.size() == 2;
        }
    }
    const planning::CameraFootprint footprint = planning::camera_footprint(m.plan);
    // Re-inspection waypoints stay within the depths of the plan's slice centres: a hole along
    // the water line must not send the vehicle to the surface (nor one at the keel below it).
    const double top_z_m = m.T_world_flown_hull().translation().z();
    const double bottom_z_m = top_z_m - m.flown_plan().draught_m;
    s.max_waypoint_z_m = std::max(top_z_m - footprint.height_m / 2.0, bottom_z_m);
    s.min_waypoint_z_m = std::min(bottom_z_m + footprint.height_m / 2.0, s.max_waypoint_z_m);
    s.adapter.stand_off_m = m.plan.stand_off_m;
    s.reinspection.stand_off_m = m.plan.stand_off_m;
    s.reinspection.footprint_width_m = footprint.width_m;
    s.reinspection.waypoint_tolerance_m = m.plan.waypoint_tolerance_m;
    s.survey_speed_mps = m.plan.speed_m_s;
}

RovMissionScenario from_document(const io::ConfigNode& root, const std::string& name) {
    if (!root.is_map()) io::detail::fail(root, "", "expected a map (a mission scenario)");
    detail::VehicleDocument<RovStackConfig> document;
    document_schema().apply(without(root, {"simulation", "mission", "operator", "coverage"}),
                            document);
    HullSurveyMission mission;
    const io::ConfigNode& mission_node = required(root, "mission");
    mission_schema().apply(mission_node, mission, "mission");
    if (mission.type != "hull_survey") {
        io::detail::fail(
            mission_node, "mission.type",
            fmt::format("'{}', expected hull_survey for an ROV mission", mission.type));
    }
    RovMissionScenario m;
    detail::take_common(m, document, root, required(root, "simulation"), name);
    m.hull = mission.hull;
    m.plan = mission.plan;
    m.margin_m = mission.margin_m;
    m.plan.validate("mission.plan");
    calibrate(m);
    if (const io::ConfigNode* coverage = root.find("coverage")) {
        m.coverage = coverage_from_yaml(*coverage, m.section(), "");
        // The figure's camera sits where the robot's does unless the document says otherwise.
        if (coverage->find("mount") == nullptr) m.coverage->mount = mount_of(m.stack.T_body_camera);
    }
    m.validate();
    return m;
}

}  // namespace

planning::WallRectangle RovMissionScenario::section() const {
    const Eigen::Isometry3d T_world_hull = hull.to_isometry();
    return {.corner_world_m = T_world_hull * Eigen::Vector3d(0.0, 0.0, -plan.draught_m),
            .normal_world = T_world_hull.linear() * -Eigen::Vector3d::UnitY(),
            .width_m = plan.length_m,
            .height_m = plan.draught_m};
}

planning::HullSurveyPlanConfig RovMissionScenario::flown_plan() const {
    planning::HullSurveyPlanConfig flown = plan;
    flown.length_m += 2.0 * margin_m;
    flown.draught_m += 2.0 * margin_m;
    return flown;
}

Eigen::Isometry3d RovMissionScenario::T_world_flown_hull() const {
    return hull.to_isometry() * Eigen::Translation3d(-margin_m, 0.0, margin_m);
}

void RovMissionScenario::validate() const {
    simulation.validate("simulation");
    if (simulation.vehicle.type != sim::VehicleType::kRov) {
        throw ConfigError("simulation.vehicle.type: a hull_survey mission needs the rov vehicle");
    }
    config_checks::require(linger_s >= 0.0 && std::isfinite(linger_s), "", "linger_s", linger_s,
                           "finite >= 0");
    plan.validate("mission.plan");
    config_checks::require(margin_m >= 0.0 && std::isfinite(margin_m), "mission", "margin_m",
                           margin_m, "finite >= 0");
    flown_plan().validate("mission.plan (with the margin)");
    stack.validate("stack");
    section().validate("mission.hull");
    for (std::size_t i = 0; i < faults.size(); ++i)
        faults[i].validate(fmt::format("faults[{}]", i));
    if (coverage) coverage->validate("coverage");
}

bool is_rov_mission_file(const std::string& path) {
    return detail::mission_type_of(path) == "hull_survey";
}

RovMissionScenario load_rov_mission_scenario(const std::string& path,
                                             const std::vector<std::string>& overrides) {
    return detail::load_scenario(path, overrides, from_document);
}

RovMissionScenario parse_rov_mission_scenario(const std::string& yaml_text,
                                              const std::string& name) {
    return detail::parse_scenario(yaml_text, name, from_document);
}

}  // namespace scantling::mission
