// Vehicle, trajectory and pose sections of the scenario schema (scenario_schema.hpp).
#include <scantling/sim/scenario_schema.hpp>

namespace scantling::sim::detail {
namespace {

using io::ConfigSchema;
using io::kNonNegative;
using io::kPositive;
using io::Range;

/// A member of a base config seen as a member of the derived spec (schemas are keyed on it).
template <class Derived, class M, class Base>
M Derived::*as_derived(M Base::*member) {
    return static_cast<M Derived::*>(member);
}

const std::vector<std::pair<std::string, ProfileShape>> kShapes{
    {"smooth", ProfileShape::kSmooth}, {"trapezoidal", ProfileShape::kTrapezoidal}};

ConfigSchema<Waypoint> waypoint_schema() {
    ConfigSchema<Waypoint> s;
    s.field("position_m", &Waypoint::position_m, "world frame", kCoordinate)
        .field("yaw_rad", &Waypoint::yaw_rad, "heading at the waypoint")
        .field("dwell_s", &Waypoint::dwell_s, "rest on arrival", up_to(limits::kMaxDuration_s));
    return s;
}

ConfigSchema<WaypointTrajectoryConfig> waypoints_schema() {
    using C = WaypointTrajectoryConfig;
    ConfigSchema<C> s;
    s.list("waypoints", &C::waypoints, waypoint_schema(), "at least one, at most 1e4")
        .field("max_speed_mps", &C::max_speed_mps, "", kPositive)
        .field("max_accel_mps2", &C::max_accel_mps2, "", kPositive)
        .field("max_yaw_rate_radps", &C::max_yaw_rate_radps, "", kPositive)
        .field("max_yaw_accel_radps2", &C::max_yaw_accel_radps2, "", kPositive)
        .enum_field("shape", &C::shape, kShapes, "speed profile of each leg")
        .enum_field("yaw_mode", &C::yaw_mode,
                    {{"waypoint", YawMode::kWaypoint}, {"face_travel", YawMode::kFaceTravel}},
                    "heading from the waypoints or the direction of travel");
    return s;
}

ConfigSchema<HelixTrajectoryConfig> helix_schema() {
    using C = HelixTrajectoryConfig;
    ConfigSchema<C> s;
    s.field("x0_m", &C::x0_m, "axis x", kCoordinate)
        .field("y0_m", &C::y0_m, "axis y", kCoordinate)
        .field("z0_m", &C::z0_m, "start height", kCoordinate)
        .field("radius_m", &C::radius_m, "", kExtent)
        .field("omega_radps", &C::omega_radps, "angular rate")
        .field("v_z_mps", &C::v_z_mps, "climb rate")
        .field("yaw0_rad", &C::yaw0_rad, "0 faces the axis")
        .field("rotations", &C::rotations, "", positive_up_to(limits::kMaxTurns));
    return s;
}

ConfigSchema<OrbitTrajectoryConfig> orbit_schema() {
    using C = OrbitTrajectoryConfig;
    ConfigSchema<C> s;
    s.field("centre_m", &C::centre_m, "axis point at the start height", kCoordinate)
        .field("radius_m", &C::radius_m, "", kExtent)
        .field("angular_rate_radps", &C::angular_rate_radps, "> 0 counter-clockwise from above")
        .field("start_angle_rad", &C::start_angle_rad)
        .field("climb_rate_mps", &C::climb_rate_mps)
        .field("turns", &C::turns, "", positive_up_to(limits::kMaxTurns))
        .enum_field("heading", &C::heading,
                    {{"face_centre", OrbitHeading::kFaceCentre},
                     {"face_travel", OrbitHeading::kFaceTravel}})
        .field("yaw_offset_rad", &C::yaw_offset_rad);
    return s;
}

ConfigSchema<LawnmowerSpec> lawnmower_schema() {
    using C = LawnmowerTrajectoryConfig;
    using S = LawnmowerSpec;
    ConfigSchema<S> s;
    s.section("T_world_wall", &S::wall, pose_spec_schema(), "wall frame: z towards the vehicle")
        .field("width_m", as_derived<S>(&C::width_m), "along wall x", kExtent)
        .field("height_m", as_derived<S>(&C::height_m), "along wall y", kExtent)
        .field("standoff_m", as_derived<S>(&C::standoff_m), "", kExtent)
        .field("slice_spacing_m", as_derived<S>(&C::slice_spacing_m), "", kExtent)
        .enum_field(
            "slices", as_derived<S>(&C::slices),
            {{"horizontal", SliceDirection::kHorizontal}, {"vertical", SliceDirection::kVertical}})
        .field("start_at_top", as_derived<S>(&C::start_at_top))
        .field("face_wall", as_derived<S>(&C::face_wall))
        .field("yaw_rad", as_derived<S>(&C::yaw_rad), "heading when not facing the wall")
        .field("max_speed_mps", as_derived<S>(&C::max_speed_mps), "", kPositive)
        .field("max_accel_mps2", as_derived<S>(&C::max_accel_mps2), "", kPositive)
        .enum_field("shape", as_derived<S>(&C::shape), kShapes);
    return s;
}

ConfigSchema<TrajectorySpec> trajectory_schema() {
    ConfigSchema<TrajectorySpec> s;
    s.enum_field("type", &TrajectorySpec::type,
                 {{"waypoints", TrajectoryType::kWaypoints},
                  {"helix", TrajectoryType::kHelix},
                  {"lawnmower", TrajectoryType::kLawnmower},
                  {"orbit", TrajectoryType::kOrbit}},
                 "its parameters go in the section of the same name")
        .section("waypoints", &TrajectorySpec::waypoints, waypoints_schema())
        .section("helix", &TrajectorySpec::helix, helix_schema())
        .section("lawnmower", &TrajectorySpec::lawnmower, lawnmower_schema())
        .section("orbit", &TrajectorySpec::orbit, orbit_schema());
    return s;
}

ConfigSchema<GustConfig> gust_schema() {
    ConfigSchema<GustConfig> s;
    s.field("mean", &GustConfig::mean, "constant wind, m/s, world")
        .field("sigma", &GustConfig::sigma, "gust 1 sigma per axis, m/s", kNonNegative)
        .field("correlation_time_s", &GustConfig::correlation_time_s, "", kPositive);
    return s;
}

ConfigSchema<MavDynamicsConfig> mav_schema() {
    using C = MavDynamicsConfig;
    ConfigSchema<C> s;
    s.field("velocity_time_constant_s", &C::velocity_time_constant_s, "", kPositive)
        .field("yaw_rate_time_constant_s", &C::yaw_rate_time_constant_s, "", kNonNegative)
        .field("max_speed_mps", &C::max_speed_mps, "", kPositive)
        .field("max_accel_mps2", &C::max_accel_mps2, "", kPositive)
        .field("max_yaw_rate_radps", &C::max_yaw_rate_radps, "", kPositive)
        .field("drag_coefficient_per_s", &C::drag_coefficient_per_s, "", kNonNegative)
        .field("attitude_time_constant_s", &C::attitude_time_constant_s, "", kNonNegative)
        .section("wind", &C::wind, gust_schema());
    return s;
}

ConfigSchema<RovPush> rov_push_schema() {
    using C = RovPush;
    ConfigSchema<C> s;
    s.field("start_s", &C::start_s, "simulated time, s", kNonNegative)
        .field("duration_s", &C::duration_s, "s", kPositive)
        .field("acceleration_world_mps2", &C::acceleration_world_mps2, "m/s², world frame");
    return s;
}

ConfigSchema<RovDynamicsConfig> rov_schema() {
    using C = RovDynamicsConfig;
    ConfigSchema<C> s;
    // Damping and command limits (4-vectors) keep the model's defaults.
    s.field("thrust_time_constant_s", &C::thrust_time_constant_s, "", kNonNegative)
        .section("current", &C::current, gust_schema())
        .list("pushes", &C::pushes, rov_push_schema(), "out-of-view contacts");
    return s;
}

ConfigSchema<CrawlerDynamicsConfig> crawler_schema() {
    using C = CrawlerDynamicsConfig;
    ConfigSchema<C> s;
    s.field("velocity_time_constant_s", &C::velocity_time_constant_s, "", kNonNegative)
        .field("max_speed_mps", &C::max_speed_mps, "", kPositive)
        .field("max_yaw_rate_radps", &C::max_yaw_rate_radps, "", kPositive)
        .field("slip_mean", &C::slip_mean, "mean longitudinal slip fraction")
        .field("slip_sigma", &C::slip_sigma, "", kNonNegative)
        .field("lateral_slip_sigma", &C::lateral_slip_sigma, "", kNonNegative)
        .field("yaw_slip_sigma", &C::yaw_slip_sigma, "", kNonNegative)
        .field("slip_correlation_time_s", &C::slip_correlation_time_s, "", kPositive);
    return s;
}

ConfigSchema<LeggedBaseConfig> legged_schema() {
    using C = LeggedBaseConfig;
    ConfigSchema<C> s;
    s.field("velocity_time_constant_s", &C::velocity_time_constant_s, "", kNonNegative)
        .field("max_speed_mps", &C::max_speed_mps, "", kPositive)
        .field("max_accel_mps2", &C::max_accel_mps2, "", kPositive)
        .field("max_yaw_rate_radps", &C::max_yaw_rate_radps, "", kPositive)
        .field("bounce_amplitude_m", &C::bounce_amplitude_m, "", kNonNegative)
        .field("step_frequency_hz", &C::step_frequency_hz, "", kPositive);
    return s;
}

}  // namespace

const ConfigSchema<PoseSpec>& pose_spec_schema() {
    static const ConfigSchema<PoseSpec> schema = [] {
        ConfigSchema<PoseSpec> s;
        s.field("xyz", &PoseSpec::xyz, "translation, m", kCoordinate)
            .field("rpy_deg", &PoseSpec::rpy_deg, "roll, pitch, yaw, degrees");
        return s;
    }();
    return schema;
}

const ConfigSchema<VehicleSpec>& vehicle_spec_schema() {
    static const ConfigSchema<VehicleSpec> schema = [] {
        ConfigSchema<VehicleSpec> s;
        s.enum_field("type", &VehicleSpec::type,
                     {{"scripted", VehicleType::kScripted},
                      {"mav", VehicleType::kMav},
                      {"rov", VehicleType::kRov},
                      {"crawler", VehicleType::kCrawler},
                      {"legged", VehicleType::kLegged}},
                     "scripted: moves exactly along the trajectory; others track it")
            .section("trajectory", &VehicleSpec::trajectory, trajectory_schema())
            .section("mav", &VehicleSpec::mav, mav_schema(), "type mav only")
            .section("rov", &VehicleSpec::rov, rov_schema(), "type rov only")
            .section("crawler", &VehicleSpec::crawler, crawler_schema(), "type crawler only")
            .section("legged", &VehicleSpec::legged, legged_schema(), "type legged only")
            .field("position_gain_per_s", &VehicleSpec::position_gain_per_s, "tracking", kPositive)
            .field("yaw_gain_per_s", &VehicleSpec::yaw_gain_per_s, "tracking", kPositive);
        return s;
    }();
    return schema;
}

}  // namespace scantling::sim::detail
