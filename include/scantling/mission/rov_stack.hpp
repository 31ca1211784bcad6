#pragma once
/// @file
/// The ROV's hull-survey stack as one plain object (issue 14; SPEC §5; D4.2 §III): what runs on
/// the underwater drone, fed with the io types a recording gives and returning the velocity
/// command for the vehicle. It never sees the simulator: the ROV loop (rov_mission.hpp) feeds
/// it from `sim`, a ROS node would feed it from topics.
///
/// Pipeline per measurement:
///   IMU      → local EKF prediction (localization/local_ekf.hpp) and the contact detector
///              (safety/contact_detector.hpp) with the estimate's attitude;
///   DVL      → the EKF's body-velocity update (bottom lock; an invalid sample is skipped);
///   pressure → the EKF's depth update (z = surface z − depth);
///   sonar    → the hull line (perception/sonar_hull_line.hpp), placed in the world from the
///              estimate, adapts the remaining path (planning/hull_relative_adapter.hpp) and,
///              against the surveyed section's direction, measures the heading (the EKF's
///              yaw update: nothing else observes yaw under water near steel); the
///              ping's accepted features go to the sonar inspection map
///              (mapping/sonar_inspection_map.hpp) with their 1σ;
///   camera   → the laser pointers' distance (perception/laser_pointers.hpp) and one view of the
///              estimated camera pose on the surveyed hull rectangle (perception/camera_coverage
///              .hpp at the wanted resolution): the coverage the robot believes it has.
/// Per command tick: operator commands (start, pause, resume, abort) → the target moving along
/// the adapted path at the survey speed → constant-bearing guidance, depth PI and heading
/// (control/rov_guidance.hpp), whose pause (heading or depth off) holds the target → a contact
/// from the IMU overrides the command with the back-off velocity and holds the target too.
/// When the survey path is done, the believed coverage's holes (at least min_hole_area_m2) are
/// re-inspected (planning/hole_reinspection.hpp) on a new adapted path, up to
/// max_reinspection_rounds times; then the mission has completed.
///
/// Safe reactions, each an event: the DVL silent or without bottom lock for longer than
/// max_dvl_age_s pauses the survey (the vehicle holds while its velocity is unaided, resuming
/// when the DVL locks again); the IMU silent for longer than max_imu_age_s invalidates the
/// estimate and the vehicle is commanded to stop; a sonar ping without a hull line (no
/// return, too few features, a failed fit) is an event once per episode, and the path keeps
/// its last adaptation; non-finite samples are dropped (input_rejected).
///
/// Frames: world (z up, the mission's), odom (the EKF's: the start pose's yaw-only frame), body
/// (x forward, z up). Thread-safety: not thread-safe; one stack per vehicle. Deterministic.

#include <Eigen/Geometry>
#include <limits>
#include <numbers>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <scantling/control/mission_manager.hpp>
#include <scantling/control/path_cursor.hpp>
#include <scantling/control/rov_guidance.hpp>
#include <scantling/core/pinhole_intrinsics.hpp>
#include <scantling/io/png.hpp>
#include <scantling/io/recording.hpp>
#include <scantling/io/sonar_ping.hpp>
#include <scantling/localization/local_ekf.hpp>
#include <scantling/mapping/sonar_inspection_map.hpp>
#include <scantling/mission/stack_event.hpp>
#include <scantling/perception/camera_coverage.hpp>
#include <scantling/perception/laser_pointers.hpp>
#include <scantling/perception/sonar_hull_line.hpp>
#include <scantling/planning/hole_reinspection.hpp>
#include <scantling/planning/hull_relative_adapter.hpp>
#include <scantling/planning/hull_survey_plan.hpp>
#include <scantling/safety/contact_detector.hpp>

namespace scantling::mission {

struct RovStackConfig {
    localization::LocalEkfConfig local_ekf{};  ///< IMU and DVL mounts (set from the sensors)
    /// DVL velocity 1σ per axis, m/s, > 0: a Water Linked A50 class DVL (≈ 1 cm/s at 1 m/s).
    double dvl_sigma_mps = 0.01;
    /// Pressure depth 1σ, m, > 0: a 0.1 %-of-full-scale sensor over 20 m of water.
    double depth_sigma_m = 0.02;
    double surface_z_world_m = 0.0;  ///< world z of the water surface (the pressure's datum)
    Eigen::Isometry3d T_body_sonar = Eigen::Isometry3d::Identity();  ///< sonar mount
    /// 1σ of a sonar feature along its beam, m, > 0: a range bin of a 256-bin ping at a 5–10 m
    /// range setting (2–4 cm), the edge's placement within it included.
    double sonar_range_sigma_m = 0.03;
    /// Heading aid, rad, >= 0 (0: off). IMU and DVL leave yaw unobserved (a gyro bias of
    /// 0.01°/s turned the estimate by 10° over a 20-minute survey, and the DVL's velocity with
    /// it: 3 m of drift across the hull); the sonar's hull line, compared with the surveyed
    /// section's direction, measures the heading. The hull is not straight (the parametric
    /// hull's ends bend 2.3°), so the 1σ is wider than the line's own 0.3°.
    double hull_heading_sigma_rad = 3.0 * std::numbers::pi / 180.0;
    perception::SonarHullLineConfig hull_line{};
    planning::HullRelativeAdapterConfig adapter{};  ///< stand_off_m set from the plan
    control::RovGuidanceConfig guidance{};
    mapping::SonarInspectionMapConfig sonar_map{};
    safety::ContactDetectorConfig contact{};
    /// The camera (optical frame: z forward, x right, y down) and its believed coverage.
    PinholeIntrinsics camera{};
    Eigen::Isometry3d T_body_camera = Eigen::Isometry3d::Identity();
    /// A 1080p camera of 77° (f = 1207 px) sees 1000 · r / (f cos i) mm per pixel: 2 mm at
    /// r = 2.0 m square-on, and 1.8 mm at the footprint's edge from a 1.3 m stand-off (r = 1.66
    /// m, i = 38°), the wanted resolution of the survey's figure. The stack's own camera model
    /// may be coarser (a simulated 320-pixel image), so the range stands for the resolution.
    perception::CameraCoverageConfig coverage{.cell_size_m = 0.1, .max_range_m = 2.0};
    perception::LaserPointerConfig lasers{};
    bool measure_lasers = true;  ///< run the laser-pointer triangulation on every image
    planning::HoleReinspectionConfig reinspection{};  ///< stand-off and footprint from the plan
    /// Holes of the believed coverage smaller than this are not re-inspected, m², >= 0: a
    /// single 0.1 m cell at a slice's end is not worth a trip.
    double min_hole_area_m2 = 0.05;
    int max_reinspection_rounds = 1;  ///< >= 0
    /// Re-inspection waypoints are kept within these world heights, m (the plan's slice
    /// centres: a hole at the water line must not send the vehicle to the surface).
    double min_waypoint_z_m = -std::numeric_limits<double>::infinity();
    double max_waypoint_z_m = std::numeric_limits<double>::infinity();
    double survey_speed_mps = 0.25;  ///< the target's speed along the path, m/s, > 0
    double max_dvl_age_s = 1.0;      ///< longer without a locked DVL sample: pause, s, > 0
    double max_imu_age_s = 0.05;     ///< longer without IMU: the estimate is invalid, s, > 0

    /// Throws ConfigError naming "<prefix>.<field>".
    void validate(std::string_view prefix = "stack") const;
};

/// What the stack did with a command tick.
struct RovStackCommand {
    Eigen::Vector3d v_world_mps = Eigen::Vector3d::Zero();  ///< water-relative, to the vehicle
    double yaw_rate_radps = 0.0;
    control::MissionState state = control::MissionState::kIdle;
    bool guidance_paused = false;  ///< heading or depth off: the target is held
    bool backing_off = false;      ///< a contact's back-off overrides the guidance
    double heading_error_rad = 0.0;
    double depth_error_m = 0.0;
    std::vector<StackEvent> events;
};

/// The survey's phase, for the recording and the report.
enum class SurveyPhase { kSurvey, kReinspection, kDone };
std::string_view to_string(SurveyPhase phase);

class RovStack {
  public:
    /// `survey_world`: the survey plan placed in the world (planning::hull_survey_in_world);
    /// `inspected`: the hull rectangle whose coverage decides the re-inspection (its normal
    /// u × v pointing from the hull into the water). ConfigError for a bad config, path or
    /// rectangle; InputError for a non-finite start.
    RovStack(RovStackConfig config, planning::WaypointPath survey_world,
             const perception::InspectionRectangle& inspected,
             const Eigen::Isometry3d& T_world_body_start, double start_s = 0.0);

    void add_imu(const io::ImuRecord& sample);
    void add_dvl(const io::DvlRecord& sample);
    void add_pressure(const io::PressureRecord& sample);
    /// Returns the ping's hull line (status and features), or nothing when the ping was
    /// refused (malformed, or before the estimate exists).
    std::optional<perception::SonarHullLine> add_sonar(const io::SonarPing& ping);
    std::optional<perception::LaserPointerMeasurement> add_image(const io::RgbImage& image,
                                                                 double stamp_s);

    RovStackCommand command(double t_s, std::span<const control::OperatorCommand> commands);

    /// The estimate in the world at the last IMU sample (covariance rotated into the world).
    localization::DroneState estimate() const;
    bool estimate_valid(double t_s) const;
    SurveyPhase phase() const { return phase_; }
    control::MissionState state() const { return state_; }
    /// The path flown now (survey or re-inspection), as adapted so far.
    const planning::WaypointPath& path() const { return adapter_.path(); }
    std::size_t next_waypoint() const;
    const mapping::SonarInspectionMap& sonar_map() const { return sonar_map_; }
    const perception::CameraCoverage& believed_coverage() const { return coverage_; }
    const perception::InspectionRectangle& inspected() const { return inspected_; }
    const safety::ContactDetector& contacts() const { return contact_; }
    const localization::LocalEkf& local_ekf() const { return local_; }
    const RovStackConfig& config() const { return config_; }

    /// Counters for the run's figures.
    struct Counters {
        std::size_t pings = 0;
        std::size_t hull_lines = 0;  ///< pings with a fitted hull line
        std::size_t adaptations_clamped = 0;
        std::size_t laser_measurements = 0;  ///< images with both spots triangulated
        std::size_t images = 0;
        std::size_t dvl_invalid = 0;  ///< samples without bottom lock
        std::size_t inputs_rejected = 0;
        std::size_t holes_found = 0;  ///< holes handed to the re-inspection, all rounds
        std::size_t reinspection_rounds = 0;
        double last_stand_off_measured_m = 0.0;  ///< from the latest hull line
        double last_laser_distance_m = 0.0;
    };
    const Counters& counters() const { return counters_; }

  private:
    void reject(std::string_view sensor, double stamp_s);
    void apply_operator(const control::OperatorCommand& c, double t_s);
    void set_state(control::MissionState to, double t_s, std::string_view reason);
    void watch_dvl(double t_s);
    void finish_path(double t_s);
    void add_features(const perception::SonarHullLine& line, const Eigen::Isometry3d& T_world_sonar,
                      double stamp_s);
    void aid_heading(const planning::HullLineObservation& observation, double stamp_s);
    Eigen::Isometry3d T_world_body() const;
    RovStackCommand guide(double t_s, double dt_s);
    void event(double t_s, std::string type, std::string json = "{}");

    RovStackConfig config_;
    perception::InspectionRectangle inspected_;
    Eigen::Isometry3d T_world_odom_;
    localization::LocalEkf local_;
    safety::ContactDetector contact_;
    planning::HullRelativeAdapter adapter_;
    control::RovGuidance guidance_;
    mapping::SonarInspectionMap sonar_map_;
    perception::CameraCoverage coverage_;
    control::PathCursor cursor_;  ///< the moving target along path()
    control::MissionState state_ = control::MissionState::kIdle;
    SurveyPhase phase_ = SurveyPhase::kSurvey;
    std::optional<double> last_command_s_;
    std::optional<double> last_imu_s_;
    std::optional<double> last_dvl_lock_s_;
    double start_s_ = 0.0;
    bool dvl_lost_ = false;
    bool hull_line_lost_ = false;
    bool estimate_lost_ = false;
    std::vector<std::string> rejecting_;
    std::vector<StackEvent> pending_;
    Counters counters_;
};

}  // namespace scantling::mission
