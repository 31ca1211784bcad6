#pragma once
// Helpers of the mission scenario readers (mission_scenario.cpp, rov_mission_scenario.cpp,
// coverage_spec.cpp) on parsed YAML.
#include <initializer_list>
#include <string>
#include <string_view>

#include <scantling/io/config_node.hpp>

namespace scantling::mission::detail {

/// The map `root` without `keys` (read by their own readers).
io::ConfigNode without(const io::ConfigNode& root, std::initializer_list<std::string_view> keys);

/// The value of `key` in the map `root`; ParseError naming the file and line when absent.
const io::ConfigNode& required(const io::ConfigNode& root, std::string_view key);

/// Applies one "a.b.c=value" override (`scantling mission --set`): the value (YAML: a scalar or
/// a flow collection) replaces or adds the key, creating the maps on its way. ConfigError for a
/// malformed assignment.
void apply_override(io::ConfigNode& root, const std::string& assignment);

}  // namespace scantling::mission::detail
