#pragma once
// `mission:` of a crawler document (crawler_mission.hpp): the tasks it lists, or the one
// rectangle of `type: surface_rectangle`. Defined in crawler_task_document.cpp.
#include <vector>

#include <scantling/io/config_node.hpp>
#include <scantling/planning/surface_tasks.hpp>

namespace scantling::mission::detail {

struct CrawlerMissionDocument {
    std::vector<planning::SurfaceTask> tasks;
    double swath_width_m = 0.5;
};

/// ParseError naming the file, line and key: an unknown mission type or task type, a key the
/// task's type does not take, a bad value.
CrawlerMissionDocument crawler_mission_from(const io::ConfigNode& mission_node);

/// The mission types the crawler reader takes.
bool is_crawler_mission_type(const std::string& type);

}  // namespace scantling::mission::detail
