#pragma once
/// @file
/// A neutral YAML document tree: config adapters bind it into Config structs without
/// yaml-cpp ever appearing in a public header.

#include <cstddef>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace scantling::io {

/// One YAML node with the position it came from (for error messages).
struct ConfigNode {
    enum class Kind { kNull, kScalar, kSequence, kMap };

    /// Out of line: clang (14-16) with libstdc++ 12 rejects the implicit one of this recursive
    /// type (std::pair's conditionally explicit default constructor asks about ConfigNode while
    /// it is being defined); the fuzz targets are built with clang.
    ConfigNode();

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

/// What one YAML document may cost (a config or scenario is a few kilobytes and a few hundred
/// nodes). A YAML file is hostile input: without these bounds a 400-byte file of nested
/// aliases ("billion laughs": `a: &a [x, x, ...]`, `b: &b [*a, *a, ...]`, ...) expands to
/// tens of gigabytes, and a large file makes yaml-cpp build a tree of several hundred bytes
/// per node before any check can run.
struct YamlLimits {
    /// Largest file or text accepted, checked before yaml-cpp reads it: 1 MiB (real configs
    /// and scenarios are a few kB). yaml-cpp takes ~470 bytes and ~5 µs per node, so the worst
    /// 1 MiB document (`[0,0,0,...]`) costs it ~250 MB and ~3 s.
    std::size_t max_bytes = std::size_t{1} << 20;
    /// Most nodes (scalars, sequences, maps) the document may expand to, counted over the
    /// whole conversion; an alias counts its whole subtree each time it is used. 1e6 nodes
    /// take about 300 MB (measured: a 378-byte alias bomb is refused at a 296 MB peak).
    std::size_t max_nodes = 1'000'000;
    /// Deepest nesting of sequences and maps (also stops a recursive alias "a: &x [*x]").
    /// Deeper documents (up to 2000 levels, where yaml-cpp's own guard stops its recursive
    /// parser) are parsed by yaml-cpp, then refused here.
    int max_depth = 64;
};

/// Parses a YAML file holding one document (an empty file gives a null node).
/// Throws FileError when the file cannot be read, ParseError (file, line, column) on a YAML
/// syntax error, a duplicate map key, a non-scalar key, more than one document, or a document
/// over `limits` (the message names the limit; the file size is checked before reading).
ConfigNode parse_yaml_file(const std::string& path, const YamlLimits& limits = {});

/// Same as parse_yaml_file for text in memory; `name` stands for the file in messages.
ConfigNode parse_yaml_string(const std::string& text, const std::string& name = "<string>",
                             const YamlLimits& limits = {});

}  // namespace scantling::io
