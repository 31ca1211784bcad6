#pragma once
/// @file
/// One thing a vehicle's stack reports (the ROV's, the crawler's), written to
/// mission/events.jsonl as `type` with `json`.

#include <string>

namespace scantling::mission {

struct StackEvent {
    double t_s = 0.0;
    std::string type;
    std::string json = "{}";
};

}  // namespace scantling::mission
