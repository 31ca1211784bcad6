// Helpers of the mission scenario readers (config_nodes.hpp).
#include "config_nodes.hpp"

#include <algorithm>

#include <scantling/core/error.hpp>
#include <scantling/io/config_schema.hpp>

namespace scantling::mission::detail {
namespace {

/// The entry `key` of the map `node`, created (null) when absent.
io::ConfigNode& entry(io::ConfigNode& node, const std::string& key) {
    for (auto& [k, value] : node.map) {
        if (k == key) return value;
    }
    return node.map.emplace_back(key, io::ConfigNode{}).second;
}

}  // namespace

io::ConfigNode without(const io::ConfigNode& root, std::initializer_list<std::string_view> keys) {
    io::ConfigNode rest = root;
    std::erase_if(rest.map, [&keys](const auto& entry) {
        return std::find(keys.begin(), keys.end(), entry.first) != keys.end();
    });
    return rest;
}

const io::ConfigNode& required(const io::ConfigNode& root, std::string_view key) {
    const io::ConfigNode* node = root.find(key);
    if (node == nullptr) {
        io::detail::fail(root, "", "missing key '" + std::string(key) + "'");
    }
    return *node;
}

void apply_override(io::ConfigNode& root, const std::string& assignment) {
    const std::size_t eq = assignment.find('=');
    if (eq == std::string::npos || eq == 0) {
        throw ConfigError("--set " + assignment +
                          ": expected KEY=VALUE (KEY dotted, e.g. "
                          "stack.manager.tracking.use_vtp=false)");
    }
    const std::string key = assignment.substr(0, eq);
    io::ConfigNode* node = &root;
    std::size_t begin = 0;
    while (true) {
        const std::size_t dot = key.find('.', begin);
        const std::string part = key.substr(begin, dot == std::string::npos ? dot : dot - begin);
        if (part.empty()) throw ConfigError("--set " + assignment + ": empty key component");
        if (node->is_null()) node->kind = io::ConfigNode::Kind::kMap;
        if (!node->is_map()) {
            throw ConfigError("--set " + assignment + ": '" + key.substr(0, begin - 1) +
                              "' is not a map");
        }
        node = &entry(*node, part);
        if (dot == std::string::npos) break;
        begin = dot + 1;
    }
    *node = io::parse_yaml_string(assignment.substr(eq + 1), "--set " + key);
}

std::string mission_type_of(const std::string& path) {
    const io::ConfigNode root = io::parse_yaml_file(path);
    const io::ConfigNode* mission = root.is_map() ? root.find("mission") : nullptr;
    const io::ConfigNode* type =
        mission != nullptr && mission->is_map() ? mission->find("type") : nullptr;
    return type != nullptr && type->is_scalar() ? type->scalar : std::string();
}

}  // namespace scantling::mission::detail
