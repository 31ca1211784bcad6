#pragma once
/// @file
/// What a closed-loop run adds to its recording (issue 13, item 1), in DIR/mission/: the
/// robot's estimates, the commands it sent, the mission's events and the intended path, so
/// that every tool reading recordings reads closed-loop runs too.
///
///   mission/estimates.csv     stamp_s,x,y,z,vx,vy,vz,roll,pitch,yaw,sx,sy,sz,syaw,valid
///                             (world frame, m, m/s, rad; s* = 1σ of x, y, z, yaw)
///   mission/estimates.tum     the same poses as a TUM trajectory (for evo, `scantling eval`)
///   mission/commands.csv      stamp_s,vx,vy,vz,yaw_rate,req_vx,req_vy,req_vz,limited
///                             (sent to the vehicle; req_* = the mission's request before the
///                             safety layer; limited = 1 when the safety layer changed it)
///   mission/events.jsonl      one JSON object per line: {"t_s", "type", ...} (state changes,
///                             waypoints reached, refusals, safety interventions, operator
///                             actions, estimator faults)
///   mission/intended_path.csv index,x,y,z,tolerance_m (the mission's waypoints, world frame)
///
/// Readers refuse malformed files with a ParseError naming the file and line, like every
/// recording reader (recording.hpp). Thread-safety: pure functions.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace scantling::io {

namespace recording_layout {
inline constexpr const char* kMissionDir = "mission";
inline constexpr const char* kMissionEstimates = "estimates.csv";
inline constexpr const char* kMissionEstimatesTum = "estimates.tum";
inline constexpr const char* kMissionCommands = "commands.csv";
inline constexpr const char* kMissionEvents = "events.jsonl";
inline constexpr const char* kMissionPath = "intended_path.csv";
inline constexpr const char* kMissionSummary = "summary.json";
/// The ROV's sonar inspection map (mission/rov_mission.hpp): one voxel per line.
inline constexpr const char* kMissionSonarMap = "sonar_map.csv";
/// The exploration's figures (mission/exploration_mission.hpp): the explored-volume curve, one
/// line per planning iteration, and the occupancy map (OctoMap's binary .bt).
inline constexpr const char* kMissionExplorationCurve = "exploration.csv";
inline constexpr const char* kMissionPlans = "plans.csv";
inline constexpr const char* kMissionOccupancyMap = "map.bt";
/// The crawler's texture map (perception/texture_map.hpp): live.png, clean.png, metadata.json.
inline constexpr const char* kMissionTextureDir = "texture";
inline constexpr const char* kMissionEstimatesHeader =
    "stamp_s,x,y,z,vx,vy,vz,roll,pitch,yaw,sx,sy,sz,syaw,valid";
inline constexpr const char* kMissionCommandsHeader =
    "stamp_s,vx,vy,vz,yaw_rate,req_vx,req_vy,req_vz,limited";
inline constexpr const char* kMissionPathHeader = "index,x,y,z,tolerance_m";
}  // namespace recording_layout

struct EstimateRecord {
    double stamp_s = 0.0;
    Eigen::Isometry3d T_world_body = Eigen::Isometry3d::Identity();
    Eigen::Vector3d v_world_mps = Eigen::Vector3d::Zero();
    Eigen::Vector3d position_sigma_m = Eigen::Vector3d::Zero();
    double yaw_sigma_rad = 0.0;
    bool valid = true;
};

struct CommandRecord {
    double stamp_s = 0.0;
    Eigen::Vector3d v_world_mps = Eigen::Vector3d::Zero();  ///< sent to the vehicle
    double yaw_rate_radps = 0.0;
    Eigen::Vector3d v_requested_world_mps = Eigen::Vector3d::Zero();  ///< before safety
    bool limited = false;  ///< the safety layer changed the request
};

/// One event: its time, type and the raw JSON object (for the fields of its type).
struct EventRecord {
    double t_s = 0.0;
    std::string type;
    std::string json;  ///< the whole line
};

struct PathPointRecord {
    Eigen::Vector3d position_world_m = Eigen::Vector3d::Zero();
    double tolerance_m = 0.0;
};

struct MissionLog {
    std::vector<EstimateRecord> estimates;
    std::vector<CommandRecord> commands;
    std::vector<EventRecord> events;
    std::vector<PathPointRecord> intended_path;
};

/// Text of each file (with its header), numbers as the shortest text that reads back exactly.
std::string estimates_csv(std::span<const EstimateRecord> estimates);
std::string commands_csv(std::span<const CommandRecord> commands);
std::string intended_path_csv(std::span<const PathPointRecord> path);
/// One line: {"t_s": t, "type": type, <fields_json members>}; `fields_json` is a JSON object
/// text ("{}" for none). InputError when it is not an object.
std::string event_line(double t_s, const std::string& type, const std::string& fields_json);

std::vector<EstimateRecord> read_estimates_csv(const std::string& path);
std::vector<CommandRecord> read_commands_csv(const std::string& path);
std::vector<PathPointRecord> read_intended_path_csv(const std::string& path);
std::vector<EventRecord> read_events_jsonl(const std::string& path);

/// DIR/mission/ of a recording, or nullopt when the recording has none (an open-loop one).
/// FileError/ParseError for a missing or malformed file inside an existing mission/.
std::optional<MissionLog> read_mission_log(const std::string& recording_directory);

}  // namespace scantling::io
