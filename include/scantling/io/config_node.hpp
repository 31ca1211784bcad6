#pragma once
/// @file
/// A neutral YAML document tree: config adapters bind it into Config structs without
/// yaml-cpp ever appearing in a public header.

#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace scantling::io {

/// One YAML node with the position it came from (for error messages).
struct ConfigNode {
    enum class Kind { kNull, kScalar, kSequence, kMap };

    Kind kind = Kind::kNull;
    std::string scalar;                                   ///< text of a scalar, unquoted
    std::vector<std::pair<std::string, ConfigNode>> map;  ///< entries in file order
    std::vector<ConfigNode> sequence;                     ///< items in file order
    std::string file;                                     ///< file (or name) it was read from
    int line = 0;    ///< 1-based; for a map entry's value: the line of its key
    int column = 0;  ///< 1-based; for a map entry's value: the column of its key

    bool is_null() const { return kind == Kind::kNull; }
    bool is_scalar() const { return kind == Kind::kScalar; }
    bool is_sequence() const { return kind == Kind::kSequence; }
    bool is_map() const { return kind == Kind::kMap; }

    /// The value of `key` in a map, nullptr when absent (or when this is not a map).
    const ConfigNode* find(std::string_view key) const;
};

/// "'abc'" (a scalar), "a sequence", "a map" or "an empty value": what a node is, for
/// messages such as "expected a number, got 'abc'".
std::string describe_kind(const ConfigNode& node);

/// Parses a YAML file holding one document (an empty file gives a null node).
/// Throws FileError when the file cannot be read, ParseError (file, line, column) on a YAML
/// syntax error, a duplicate map key, a non-scalar key or more than one document.
ConfigNode parse_yaml_file(const std::string& path);

/// Same as parse_yaml_file for text in memory; `name` stands for the file in messages.
ConfigNode parse_yaml_string(const std::string& text, const std::string& name = "<string>");

}  // namespace scantling::io
