// `mission:` of a crawler document (detail/crawler_task_document.hpp).
#include "detail/crawler_task_document.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <map>
#include <string>

#include <scantling/io/config_schema.hpp>

namespace scantling::mission::detail {
namespace {

using planning::SurfaceTaskType;

/// One task of `mission.tasks`, every key any type takes; a type takes only its own.
struct TaskDocument {
    std::string type;
    Eigen::Vector3d goal_m = Eigen::Vector3d::Zero();
    Eigen::Vector3d start_m = Eigen::Vector3d::Zero();
    double width_m = 1.0;
    double height_m = 1.0;
    double max_step_m = 0.4;
    Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
    double length_m = 1.0;
    bool reverse = false;
};

/// `mission:` itself; the rectangle keys are `type: surface_rectangle`'s.
struct MissionDocument {
    std::string type;
    double swath_width_m = 0.5;
};

const io::ConfigSchema<TaskDocument>& task_schema() {
    using S = TaskDocument;
    static const io::ConfigSchema<S> schema = [] {
        io::ConfigSchema<S> s;
        s.field("type", &S::type, planning::surface_task_type_names())
            .field("goal_m", &S::goal_m, "go_to: the goal on the surface, world, m")
            .field("start_m", &S::start_m, "rectangle: lower-left corner, world, m")
            .field("width_m", &S::width_m, "rectangle: W, across, m", io::kPositive)
            .field("height_m", &S::height_m, "rectangle: H, up, m", io::kPositive)
            .field("max_step_m", &S::max_step_m, "rectangle: largest transect spacing, m",
                   io::kPositive)
            .field("up", &S::up, "rectangle, transects: the world's up direction")
            .field("length_m", &S::length_m, "transects and stiffener drives, m", io::kPositive)
            .field("reverse", &S::reverse, "transects: down, or to the left");
        return s;
    }();
    return schema;
}

/// The keys each task type takes besides `type`.
const std::map<SurfaceTaskType, std::vector<std::string>>& keys_by_type() {
    static const std::map<SurfaceTaskType, std::vector<std::string>> keys{
        {SurfaceTaskType::kGoTo, {"goal_m"}},
        {SurfaceTaskType::kRectangle, {"start_m", "width_m", "height_m", "max_step_m", "up"}},
        {SurfaceTaskType::kVerticalTransect, {"length_m", "reverse", "up"}},
        {SurfaceTaskType::kHorizontalTransect, {"length_m", "reverse", "up"}},
        {SurfaceTaskType::kDriveBetweenStiffeners, {"length_m"}},
        {SurfaceTaskType::kDriveOnStiffener, {"length_m"}},
        {SurfaceTaskType::kDriveOnStiffenerSide, {"length_m"}},
    };
    return keys;
}

planning::SurfaceTask to_task(const TaskDocument& d, SurfaceTaskType type) {
    planning::SurfaceTask t;
    t.type = type;
    t.goal_world_m = d.goal_m;
    t.rectangle = {.start_world_m = d.start_m,
                   .width_m = d.width_m,
                   .height_m = d.height_m,
                   .max_step_m = d.max_step_m,
                   .up_world = d.up};
    t.length_m = d.length_m;
    t.reverse = d.reverse;
    t.up_world = d.up;
    return t;
}

planning::SurfaceTask task_from(const io::ConfigNode& node, const std::string& path) {
    TaskDocument d;
    task_schema().apply(node, d, path);
    const auto type = planning::surface_task_type_from(d.type);
    if (!type) {
        io::detail::fail(
            *node.find("type"), path + ".type",
            fmt::format("'{}', expected one of: {}", d.type, planning::surface_task_type_names()));
    }
    const std::vector<std::string>& allowed = keys_by_type().at(*type);
    for (const auto& [key, value] : node.map) {
        if (key == "type" || std::find(allowed.begin(), allowed.end(), key) != allowed.end())
            continue;
        io::detail::fail(
            value, path + "." + key,
            fmt::format("not a key of a {} task (it takes: {})", d.type, fmt::join(allowed, ", ")));
    }
    return to_task(d, *type);
}

const io::ConfigSchema<MissionDocument>& rectangle_mission_schema() {
    using S = MissionDocument;
    static const io::ConfigSchema<S> schema = [] {
        io::ConfigSchema<S> s;
        s.field("type", &S::type, "surface_rectangle or surface_tasks")
            .field("swath_width_m", &S::swath_width_m, "one transect's inspected width, m",
                   io::kPositive);
        return s;
    }();
    return schema;
}

}  // namespace

bool is_crawler_mission_type(const std::string& type) {
    return type == "surface_rectangle" || type == "surface_tasks";
}

CrawlerMissionDocument crawler_mission_from(const io::ConfigNode& mission_node) {
    if (!mission_node.is_map()) io::detail::fail(mission_node, "mission", "expected a map");
    const io::ConfigNode* type_node = mission_node.find("type");
    const std::string type = type_node && type_node->is_scalar() ? type_node->scalar : "";
    if (!is_crawler_mission_type(type)) {
        io::detail::fail(type_node ? *type_node : mission_node, "mission.type",
                         fmt::format("'{}', expected surface_rectangle or surface_tasks for a "
                                     "crawler mission",
                                     type));
    }
    MissionDocument d;
    CrawlerMissionDocument out;
    if (type == "surface_rectangle") {
        // The rectangle's keys sit beside `type`: the one-task form of the mission.
        io::ConfigNode task_node = mission_node;
        std::erase_if(task_node.map, [](const auto& e) { return e.first == "swath_width_m"; });
        for (auto& [key, value] : task_node.map) {
            if (key == "type") value.scalar = "rectangle";
        }
        out.tasks.push_back(task_from(task_node, "mission"));
    } else {
        for (const auto& [key, value] : mission_node.map) {
            if (key != "type" && key != "swath_width_m" && key != "tasks") {
                io::detail::fail(value, "mission." + key,
                                 "not a key of a surface_tasks mission (it takes: type, "
                                 "swath_width_m, tasks)");
            }
        }
        const io::ConfigNode* tasks = mission_node.find("tasks");
        if (!tasks) io::detail::fail(mission_node, "mission.tasks", "missing: the task list");
        const auto& items = io::detail::sequence_items(*tasks, "mission.tasks", "a list of tasks");
        for (std::size_t i = 0; i < items.size(); ++i) {
            out.tasks.push_back(task_from(items[i], io::detail::index_key("mission.tasks", i)));
        }
        if (out.tasks.empty()) io::detail::fail(*tasks, "mission.tasks", "expected a task");
    }
    io::ConfigNode rest = mission_node;
    std::erase_if(rest.map,
                  [&](const auto& e) { return e.first != "type" && e.first != "swath_width_m"; });
    rectangle_mission_schema().apply(rest, d, "mission");
    out.swath_width_m = d.swath_width_m;
    return out;
}

}  // namespace scantling::mission::detail
