#include <scantling/io/config_node.hpp>

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <scantling/core/error.hpp>

namespace scantling::io {
namespace {

FileLocation location_of(const YAML::Mark& mark) {
    // yaml-cpp marks are 0-based; a null mark (-1) has no position.
    if (mark.is_null()) return {};
    return FileLocation{
        .byte_offset = std::nullopt, .line = mark.line + 1, .column = mark.column + 1};
}

void set_position(ConfigNode& node, const YAML::Mark& mark) {
    const FileLocation location = location_of(mark);
    node.line = location.line.value_or(0);
    node.column = location.column.value_or(0);
}

/// Deeper than any config; also stops a recursive alias ("a: &x [*x]") from recursing forever.
constexpr int kMaxDepth = 64;

ConfigNode convert(const YAML::Node& yaml, const std::string& file, int depth);

void convert_map(const YAML::Node& yaml, const std::string& file, int depth, ConfigNode& node) {
    for (const auto& entry : yaml) {
        const YAML::Mark key_mark = entry.first.Mark();
        if (!entry.first.IsScalar()) {
            throw ParseError(file, location_of(key_mark), "map keys must be plain scalars");
        }
        const std::string key = entry.first.Scalar();
        if (node.find(key) != nullptr) {
            throw ParseError(file, location_of(key_mark), "duplicate key '" + key + "'");
        }
        ConfigNode value = convert(entry.second, file, depth + 1);
        // The key's position is what a reader looks for, and null values have no mark.
        set_position(value, key_mark);
        node.map.emplace_back(key, std::move(value));
    }
}

ConfigNode convert(const YAML::Node& yaml, const std::string& file, int depth) {
    if (depth > kMaxDepth) {
        throw ParseError(
            file, location_of(yaml.Mark()),
            "nesting deeper than " + std::to_string(kMaxDepth) + " levels (a recursive alias?)");
    }
    ConfigNode node;
    node.file = file;
    set_position(node, yaml.Mark());
    switch (yaml.Type()) {
        case YAML::NodeType::Scalar:
            node.kind = ConfigNode::Kind::kScalar;
            node.scalar = yaml.Scalar();
            break;
        case YAML::NodeType::Sequence:
            node.kind = ConfigNode::Kind::kSequence;
            for (const auto& item : yaml) node.sequence.push_back(convert(item, file, depth + 1));
            break;
        case YAML::NodeType::Map:
            node.kind = ConfigNode::Kind::kMap;
            convert_map(yaml, file, depth, node);
            break;
        default:
            node.kind = ConfigNode::Kind::kNull;
    }
    return node;
}

}  // namespace

const ConfigNode* ConfigNode::find(std::string_view key) const {
    for (const auto& [name, value] : map) {
        if (name == key) return &value;
    }
    return nullptr;
}

std::string describe_kind(const ConfigNode& node) {
    switch (node.kind) {
        case ConfigNode::Kind::kScalar:
            return "'" + node.scalar + "'";
        case ConfigNode::Kind::kSequence:
            return "a sequence";
        case ConfigNode::Kind::kMap:
            return "a map";
        default:
            return "an empty value";
    }
}

ConfigNode parse_yaml_string(const std::string& text, const std::string& name) {
    std::vector<YAML::Node> documents;
    try {
        documents = YAML::LoadAll(text);
    } catch (const YAML::Exception& e) {
        throw ParseError(name, location_of(e.mark), e.msg);
    }
    if (documents.size() > 1) {
        throw ParseError(name, FileLocation{},
                         "expected one YAML document, found " + std::to_string(documents.size()));
    }
    if (documents.empty()) {
        ConfigNode empty;
        empty.file = name;
        return empty;
    }
    return convert(documents.front(), name, 0);
}

ConfigNode parse_yaml_file(const std::string& path) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) {
        throw FileError(path,
                        std::filesystem::exists(path, ec) ? "not a regular file" : "no such file");
    }
    std::ifstream in(path, std::ios::binary);
    if (!in.is_open()) throw FileError(path, "cannot open file for reading");
    std::ostringstream text;
    text << in.rdbuf();
    return parse_yaml_string(text.str(), path);
}

}  // namespace scantling::io
