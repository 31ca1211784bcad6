#pragma once
// Helpers of the mission scenario readers (mission_scenario.cpp, rov_mission_scenario.cpp,
// crawler_mission_scenario.cpp, coverage_spec.cpp) on parsed YAML.
#include <filesystem>
#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

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

/// `mission.type` of the document at `path`, empty when it has none (the CLI picks the reader
/// by it). FileError / ParseError as the readers.
std::string mission_type_of(const std::string& path);

/// The scenario `from_document(root, path)` reads from the file at `path` with the `--set`
/// overrides applied first; its simulation's files are relative to the file and its name is
/// the scenario's unless the simulation names itself.
template <class FromDocument>
auto load_scenario(const std::string& path, const std::vector<std::string>& overrides,
                   FromDocument from_document) {
    io::ConfigNode root = io::parse_yaml_file(path);
    for (const std::string& assignment : overrides) apply_override(root, assignment);
    auto m = from_document(root, path);
    m.simulation.base_directory = std::filesystem::path(path).parent_path().string();
    if (m.simulation.name.empty()) m.simulation.name = m.name;
    return m;
}

/// The same from YAML text (`name` stands for the file in errors).
template <class FromDocument>
auto parse_scenario(const std::string& yaml_text, const std::string& name,
                    FromDocument from_document) {
    auto m = from_document(io::parse_yaml_string(yaml_text, name), name);
    if (m.simulation.name.empty()) m.simulation.name = m.name;
    return m;
}

}  // namespace scantling::mission::detail
