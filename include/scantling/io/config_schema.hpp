#pragma once
/// @file
/// Table-driven binding of YAML documents into Config structs (CONVENTIONS §3, §4).
///
/// Each field is registered once, by key and member pointer; its default stays where it is
/// written, in the struct's in-class initialiser. `apply` overwrites only the keys the
/// document names, so everything else keeps its default. Every error names the file, the
/// line and the dotted key path: "cfg.yaml: line 7: key 'icp.max_iterations': expected an
/// integer, got 'ten'", or "cfg.yaml: line 3: key 'voxel_size_m' = -0.1, expected > 0".
///
/// Example: `schema.field("voxel_size_m", &VoxelGridConfig::voxel_size_m, "voxel edge, m",
/// Range{.min = 0, .min_exclusive = true}).section("parallel", &VoxelGridConfig::parallel,
/// parallel_schema);` then `auto config = load_config("voxel.yaml", schema);`.
///
/// Thread-safety: a schema is immutable once built; `apply` and `describe` may run
/// concurrently on one schema.

#include <Eigen/Core>
#include <algorithm>
#include <cstddef>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <scantling/core/error.hpp>
#include <scantling/io/config_node.hpp>

namespace scantling::io {

/// Accepted interval of a numeric field (each bound optional; every element of a vector).
struct Range {
    std::optional<double> min{};
    bool min_exclusive = false;
    std::optional<double> max{};
    bool max_exclusive = false;
};

/// Ranges most schemas need: (0, ∞), [0, ∞) and [0, 1].
inline const Range kPositive{.min = 0.0, .min_exclusive = true};
inline const Range kNonNegative{.min = 0.0};
inline const Range kUnitInterval{.min = 0.0, .max = 1.0};

namespace detail {

/// "a.b" + "c" → "a.b.c"; "" + "c" → "c".
std::string join_key(const std::string& prefix, const std::string& key);

/// Throws ParseError "<file>: line L: key '<path>': <what>".
[[noreturn]] void fail(const ConfigNode& node, const std::string& path, const std::string& what);

double parse_real(const ConfigNode& node, const std::string& path, const Range& range);
float parse_float(const ConfigNode& node, const std::string& path, const Range& range);
long long parse_integer(const ConfigNode& node, const std::string& path, const Range& range,
                        long long lowest, long long highest);
bool parse_bool(const ConfigNode& node, const std::string& path);
std::string parse_string(const ConfigNode& node, const std::string& path);
Eigen::Vector3d parse_vector3(const ConfigNode& node, const std::string& path, const Range& range);
std::vector<double> parse_real_list(const ConfigNode& node, const std::string& path,
                                    const Range& range);
/// Index of the node's text in `names`.
std::size_t parse_choice(const ConfigNode& node, const std::string& path,
                         const std::vector<std::string>& names);
/// Items of a sequence node; anything else is an error "expected <expected>, got ...".
const std::vector<ConfigNode>& sequence_items(const ConfigNode& node, const std::string& path,
                                              const std::string& expected);

std::string format_real(double value);
std::string format_real(float value);
std::string format_string(const std::string& value);
std::string format_vector(const Eigen::Vector3d& value);
std::string format_vector(const std::vector<double>& value);
/// "doc (> 0)": the doc with the range appended, for describe().
std::string doc_with_range(const std::string& doc, const Range& range);
std::string join_names(const std::vector<std::string>& names);
/// "doc (one of: a, b)" and "doc; each item has keys: a, b", for describe().
std::string enum_doc(const std::string& doc, const std::vector<std::string>& names);
std::string list_doc(const std::string& doc, const std::vector<std::string>& keys);
/// "sensors" + 2 → "sensors[2]".
std::string index_key(const std::string& path, std::size_t index);

/// Rethrows a validate() error prefixed with the file it was loaded from.
[[noreturn]] void rethrow_validation(const ConfigError& error, const std::string& file);

/// One registered key, type-erased over the struct (`object` points to the struct).
struct SchemaEntry {
    std::string key;
    std::function<void(const ConfigNode& node, void* object, const std::string& path)> apply;
    /// Appends the entry's YAML lines, with the values held by `object`, at `indent` levels.
    std::function<void(const void* object, int indent, std::string& out)> describe;
};

class SchemaTable {
  public:
    /// Throws ConfigError when `entry.key` is already registered (a programming error).
    void add(SchemaEntry entry);
    /// A null node (a section with every key commented out) changes nothing.
    void apply(const ConfigNode& map_node, void* object, const std::string& prefix) const;
    void describe(const void* object, int indent, std::string& out) const;
    std::vector<std::string> keys() const;

  private:
    std::vector<SchemaEntry> entries_;
};

void describe_line(const std::string& key, const std::string& value, const std::string& doc,
                   int indent, std::string& out);

template <class M>
M parse_value(const ConfigNode& node, const std::string& path, const Range& range) {
    if constexpr (std::is_same_v<M, bool>) {
        return parse_bool(node, path);
    } else if constexpr (std::is_integral_v<M>) {
        constexpr auto kHigh = std::numeric_limits<M>::max();  // may exceed long long
        constexpr long long kHighest =
            std::in_range<long long>(kHigh) ? kHigh : std::numeric_limits<long long>::max();
        return static_cast<M>(
            parse_integer(node, path, range, std::numeric_limits<M>::lowest(), kHighest));
    } else if constexpr (std::is_same_v<M, float>) {
        return parse_float(node, path, range);
    } else if constexpr (std::is_same_v<M, double>) {
        return parse_real(node, path, range);
    } else if constexpr (std::is_same_v<M, std::string>) {
        return parse_string(node, path);
    } else if constexpr (std::is_same_v<M, Eigen::Vector3d>) {
        return parse_vector3(node, path, range);
    } else if constexpr (std::is_same_v<M, std::vector<double>>) {
        return parse_real_list(node, path, range);
    } else {
        static_assert(!sizeof(M), "unsupported field type: use enum_field, section or list");
    }
}

template <class M>
std::string format_value(const M& value) {
    if constexpr (std::is_same_v<M, bool>) {
        return value ? "true" : "false";
    } else if constexpr (std::is_integral_v<M>) {
        return std::to_string(value);
    } else if constexpr (std::is_floating_point_v<M>) {
        return format_real(value);
    } else if constexpr (std::is_same_v<M, std::string>) {
        return format_string(value);
    } else {
        return format_vector(value);
    }
}

}  // namespace detail

/// The keys of one Config struct `T`. Build it once (e.g. a function-local static) and reuse.
template <class T>
class ConfigSchema {
  public:
    /// Registers a double, float, integer, bool, std::string, Eigen::Vector3d (a sequence of
    /// 3 numbers) or std::vector<double> member. `range` bounds numbers (every element for
    /// vectors). Non-finite numbers are always rejected.
    template <class M>
    ConfigSchema& field(const std::string& key, M T::*member, const std::string& doc = "",
                        Range range = {}) {
        static_assert(!std::is_enum_v<M>, "register enums with enum_field");
        add(
            key,
            [member, range](const ConfigNode& node, void* object, const std::string& path) {
                static_cast<T*>(object)->*member = detail::parse_value<M>(node, path, range);
            },
            [key, member, text = detail::doc_with_range(doc, range)](const void* object, int indent,
                                                                     std::string& out) {
                const M& value = static_cast<const T*>(object)->*member;
                detail::describe_line(key, detail::format_value(value), text, indent, out);
            });
        return *this;
    }

    /// Registers an enum member spelled in YAML by the names of `choices`.
    template <class E>
    ConfigSchema& enum_field(const std::string& key, E T::*member,
                             const std::vector<std::pair<std::string, E>>& choices,
                             const std::string& doc = "") {
        static_assert(std::is_enum_v<E>, "enum_field needs an enum member");
        std::vector<std::string> names;
        for (const auto& choice : choices) names.push_back(choice.first);
        add(
            key,
            [member, names, choices](const ConfigNode& node, void* object,
                                     const std::string& path) {
                static_cast<T*>(object)->*member =
                    choices[detail::parse_choice(node, path, names)].second;
            },
            [key, member, choices, text = detail::enum_doc(doc, names)](
                const void* object, int indent, std::string& out) {
                const auto it = std::find_if(choices.begin(), choices.end(), [&](const auto& c) {
                    return c.second == static_cast<const T*>(object)->*member;
                });
                detail::describe_line(key, it == choices.end() ? "?" : it->first, text, indent,
                                      out);
            });
        return *this;
    }

    /// Registers a nested struct read from a nested map with `schema` (copied).
    template <class U>
    ConfigSchema& section(const std::string& key, U T::*member, const ConfigSchema<U>& schema,
                          const std::string& doc = "") {
        auto sub = std::make_shared<const ConfigSchema<U>>(schema);
        add(
            key,
            [member, sub](const ConfigNode& node, void* object, const std::string& path) {
                sub->table_.apply(node, &(static_cast<T*>(object)->*member), path);
            },
            [key, member, sub, doc](const void* object, int indent, std::string& out) {
                detail::describe_line(key, "", doc, indent, out);
                sub->table_.describe(&(static_cast<const T*>(object)->*member), indent + 1, out);
            });
        return *this;
    }

    /// Registers a list of structs: a YAML sequence of maps, each read with `schema` starting
    /// from `U{}`. A list in the document replaces the default list entirely.
    template <class U>
    ConfigSchema& list(const std::string& key, std::vector<U> T::*member,
                       const ConfigSchema<U>& schema, const std::string& doc = "") {
        auto sub = std::make_shared<const ConfigSchema<U>>(schema);
        add(
            key,
            [member, sub](const ConfigNode& node, void* object, const std::string& path) {
                std::vector<U> items;
                for (const ConfigNode& item :
                     detail::sequence_items(node, path, "a list of maps")) {
                    const std::string item_path = detail::index_key(path, items.size());
                    sub->table_.apply(item, &items.emplace_back(), item_path);
                }
                static_cast<T*>(object)->*member = std::move(items);
            },
            [key, member, text = detail::list_doc(doc, sub->keys())](const void* object, int indent,
                                                                     std::string& out) {
                const auto& items = static_cast<const T*>(object)->*member;
                detail::describe_line(key, items.empty() ? "[]" : "[...]", text, indent, out);
            });
        return *this;
    }

    /// Overwrites the members of `config` named in `map_node` (others keep their values),
    /// then calls `config.validate(prefix)` when T has one (ConfigError, prefixed with the
    /// file name). `prefix` is prepended to key paths in messages ("icp" → "icp.max_iterations").
    /// Throws ParseError naming file, line and key path for an unknown key (listing the valid
    /// ones), a wrong type, a value out of range, a non-finite number, a wrong sequence length
    /// or a node that is not a map.
    void apply(const ConfigNode& map_node, T& config, const std::string& prefix = "") const {
        table_.apply(map_node, &config, prefix);
        try {
            validate(config, prefix);
        } catch (const ConfigError& e) {
            detail::rethrow_validation(e, map_node.file);
        }
    }

    /// The schema as a commented YAML document holding the values of `values`.
    std::string describe(const T& values = T{}) const {
        std::string out;
        table_.describe(&values, 0, out);
        return out;
    }

    /// Registered keys, in registration order.
    std::vector<std::string> keys() const { return table_.keys(); }

  private:
    template <class>
    friend class ConfigSchema;

    template <class Apply, class Describe>
    void add(const std::string& key, Apply&& apply_fn, Describe&& describe_fn) {
        table_.add(detail::SchemaEntry{key, std::forward<Apply>(apply_fn),
                                       std::forward<Describe>(describe_fn)});
    }

    static void validate(const T& config, const std::string& prefix) {
        if constexpr (requires(const T& c) { c.validate(); }) {
            if (prefix.empty()) return config.validate();
        }
        if constexpr (requires(const T& c, const std::string& p) { c.validate(p); }) {
            config.validate(prefix);
        }
    }

    detail::SchemaTable table_;
};

/// Reads `yaml_path` into a `T{}` (the struct's own defaults) with `schema`; see apply().
/// Throws FileError for a missing file, ParseError for malformed YAML or a bad value.
template <class T>
T load_config(const std::string& yaml_path, const ConfigSchema<T>& schema,
              const std::string& prefix = "") {
    T config{};
    schema.apply(parse_yaml_file(yaml_path), config, prefix);
    return config;
}

}  // namespace scantling::io
