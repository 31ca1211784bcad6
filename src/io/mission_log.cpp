// The closed loop's files in a recording (mission_log.hpp): writers and the events' reader.
#include <scantling/io/mission_log.hpp>

#include <fmt/format.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include <scantling/core/error.hpp>
#include <scantling/core/se3.hpp>

#include "detail/text_lines.hpp"

namespace scantling::io {
namespace {

namespace layout = recording_layout;

std::string with_header(const char* header) { return std::string(header) + "\n"; }

}  // namespace

std::string estimates_csv(std::span<const EstimateRecord> estimates) {
    std::string text = with_header(layout::kMissionEstimatesHeader);
    for (const EstimateRecord& e : estimates) {
        const Eigen::Vector3d p = e.T_world_body.translation();
        const Eigen::Vector3d rpy = euler_zyx_from_rotation(e.T_world_body.linear());
        const Eigen::Vector3d& v = e.v_world_mps;
        const Eigen::Vector3d& s = e.position_sigma_m;
        text += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", e.stamp_s, p.x(),
                            p.y(), p.z(), v.x(), v.y(), v.z(), rpy.x(), rpy.y(), rpy.z(), s.x(),
                            s.y(), s.z(), e.yaw_sigma_rad, e.valid ? 1 : 0);
    }
    return text;
}

std::string commands_csv(std::span<const CommandRecord> commands) {
    std::string text = with_header(layout::kMissionCommandsHeader);
    for (const CommandRecord& c : commands) {
        const Eigen::Vector3d& v = c.v_world_mps;
        const Eigen::Vector3d& r = c.v_requested_world_mps;
        text += fmt::format("{},{},{},{},{},{},{},{},{}\n", c.stamp_s, v.x(), v.y(), v.z(),
                            c.yaw_rate_radps, r.x(), r.y(), r.z(), c.limited ? 1 : 0);
    }
    return text;
}

std::string intended_path_csv(std::span<const PathPointRecord> path) {
    std::string text = with_header(layout::kMissionPathHeader);
    for (std::size_t i = 0; i < path.size(); ++i) {
        const Eigen::Vector3d& p = path[i].position_world_m;
        text += fmt::format("{},{},{},{},{}\n", i, p.x(), p.y(), p.z(), path[i].tolerance_m);
    }
    return text;
}

std::string event_line(double t_s, const std::string& type, const std::string& fields_json) {
    nlohmann::ordered_json fields = nlohmann::ordered_json::parse(fields_json, nullptr, false);
    if (!fields.is_object()) throw InputError("event_line: fields are not a JSON object");
    nlohmann::ordered_json line{{"t_s", t_s}, {"type", type}};
    line.update(fields);
    return line.dump() + "\n";
}

std::vector<EventRecord> read_events_jsonl(const std::string& path) {
    const std::string text = detail::read_whole_file(path);
    detail::LineReader reader(text);
    std::vector<EventRecord> events;
    detail::TextLine line;
    while (reader.next(line)) {
        if (detail::trim(line.text).empty()) continue;
        const auto json = nlohmann::json::parse(line.text, nullptr, false);
        const bool ok = json.is_object() && json.contains("t_s") && json["t_s"].is_number() &&
                        json.contains("type") && json["type"].is_string();
        if (!ok) {
            FileLocation at;
            at.line = line.number;
            throw ParseError(path, at,
                             "expected a JSON object with a number 't_s' and a "
                             "string 'type'");
        }
        events.push_back(
            {json["t_s"].get<double>(), json["type"].get<std::string>(), std::string(line.text)});
    }
    return events;
}

std::optional<MissionLog> read_mission_log(const std::string& recording_directory) {
    const std::filesystem::path dir =
        std::filesystem::path(recording_directory) / layout::kMissionDir;
    if (!std::filesystem::is_directory(dir)) return std::nullopt;
    const auto file = [&dir](const char* name) { return (dir / name).string(); };
    MissionLog log;
    log.estimates = read_estimates_csv(file(layout::kMissionEstimates));
    log.commands = read_commands_csv(file(layout::kMissionCommands));
    log.events = read_events_jsonl(file(layout::kMissionEvents));
    log.intended_path = read_intended_path_csv(file(layout::kMissionPath));
    return log;
}

}  // namespace scantling::io
