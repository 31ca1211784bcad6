#include <scantling/io/config_schema.hpp>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <limits>
#include <string_view>
#include <system_error>

namespace scantling::io::detail {
namespace {

constexpr int kIndentSpaces = 2;

std::string file_name(const ConfigNode& node) { return node.file.empty() ? "<string>" : node.file; }

FileLocation line_of(const ConfigNode& node) {
    FileLocation location;
    if (node.line > 0) location.line = node.line;
    return location;
}

/// Scalar text of `node`, or an error naming what was expected instead.
const std::string& scalar_text(const ConfigNode& node, const std::string& path,
                               const std::string& expected) {
    if (!node.is_scalar())
        fail(node, path, "expected " + expected + ", got " + describe_kind(node));
    return node.scalar;
}

/// from_chars rejects a leading '+', which YAML allows.
std::string_view without_plus(std::string_view text) {
    return (text.size() > 1 && text.front() == '+') ? text.substr(1) : text;
}

/// Shortest text that reads back to the same value.
template <class Real>
std::string shortest_text(Real value) {
    std::array<char, 32> buffer{};
    const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
    return std::string(buffer.data(), result.ptr);
}

/// Keeps reals recognisable as reals in the YAML dump ("1.0", not "1").
std::string as_yaml_real(std::string text) {
    if (text.find_first_of(".en") == std::string::npos) text += ".0";
    return text;
}

bool is_yaml_non_finite(std::string_view text) {
    static constexpr std::array<std::string_view, 9> kSpellings = {
        ".nan", ".NaN", ".NAN", ".inf", ".Inf", ".INF", "-.inf", "-.Inf", "-.INF"};
    text = without_plus(text);
    return std::find(kSpellings.begin(), kSpellings.end(), text) != kSpellings.end();
}

std::string bound_text(double bound, bool exclusive, const char* strict, const char* loose) {
    return std::string(exclusive ? strict : loose) + " " + shortest_text(bound);
}

std::string range_text(const Range& range) {
    if (range.min && range.max) {
        return std::string("in ") + (range.min_exclusive ? "(" : "[") + shortest_text(*range.min) +
               ", " + shortest_text(*range.max) + (range.max_exclusive ? ")" : "]");
    }
    if (range.min) return bound_text(*range.min, range.min_exclusive, ">", ">=");
    if (range.max) return bound_text(*range.max, range.max_exclusive, "<", "<=");
    return "";
}

bool in_range(double value, const Range& range) {
    if (range.min && (range.min_exclusive ? value <= *range.min : value < *range.min)) return false;
    if (range.max && (range.max_exclusive ? value >= *range.max : value > *range.max)) return false;
    return true;
}

[[noreturn]] void fail_value(const ConfigNode& node, const std::string& path,
                             const std::string& value, const std::string& expected) {
    throw ParseError(file_name(node), line_of(node),
                     "key '" + path + "' = " + value + ", expected " + expected);
}

void check_range(const ConfigNode& node, const std::string& path, double value,
                 const Range& range) {
    if (!in_range(value, range)) fail_value(node, path, node.scalar, range_text(range));
}

}  // namespace

std::string join_key(const std::string& prefix, const std::string& key) {
    return prefix.empty() ? key : prefix + "." + key;
}

void fail(const ConfigNode& node, const std::string& path, const std::string& what) {
    const std::string subject = path.empty() ? "document" : "key '" + path + "'";
    throw ParseError(file_name(node), line_of(node), subject + ": " + what);
}

double parse_real(const ConfigNode& node, const std::string& path, const Range& range) {
    const std::string& text = scalar_text(node, path, "a number");
    if (is_yaml_non_finite(text)) fail(node, path, "expected a finite number, got '" + text + "'");
    const std::string_view digits = without_plus(text);
    double value = 0.0;
    const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    if (ec == std::errc::result_out_of_range || (ec == std::errc() && !std::isfinite(value))) {
        fail(node, path, "expected a finite number, got '" + text + "'");
    }
    if (ec != std::errc() || end != digits.data() + digits.size() || digits.empty()) {
        fail(node, path, "expected a number, got '" + text + "'");
    }
    check_range(node, path, value, range);
    return value;
}

float parse_float(const ConfigNode& node, const std::string& path, const Range& range) {
    const double value = parse_real(node, path, range);
    if (std::abs(value) > std::numeric_limits<float>::max()) {
        fail(node, path, "expected a number within single precision, got '" + node.scalar + "'");
    }
    return static_cast<float>(value);
}

long long parse_integer(const ConfigNode& node, const std::string& path, const Range& range,
                        long long lowest, long long highest) {
    const std::string& text = scalar_text(node, path, "an integer");
    const std::string_view digits = without_plus(text);
    long long value = 0;
    const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    if (ec == std::errc::result_out_of_range) {
        fail_value(
            node, path, text,
            "an integer in [" + std::to_string(lowest) + ", " + std::to_string(highest) + "]");
    }
    if (ec != std::errc() || end != digits.data() + digits.size() || digits.empty()) {
        fail(node, path, "expected an integer, got '" + text + "'");
    }
    if (value < lowest) fail_value(node, path, text, ">= " + std::to_string(lowest));
    if (value > highest) fail_value(node, path, text, "<= " + std::to_string(highest));
    check_range(node, path, static_cast<double>(value), range);
    return value;
}

bool parse_bool(const ConfigNode& node, const std::string& path) {
    // YAML 1.2 core schema spellings plus the YAML 1.1 yes/no/on/off that yaml-cpp accepts.
    static constexpr std::array<std::string_view, 9> kTrue = {"true", "True", "TRUE", "yes", "Yes",
                                                              "YES",  "on",   "On",   "ON"};
    static constexpr std::array<std::string_view, 9> kFalse = {
        "false", "False", "FALSE", "no", "No", "NO", "off", "Off", "OFF"};
    const std::string& text = scalar_text(node, path, "true or false");
    if (std::find(kTrue.begin(), kTrue.end(), text) != kTrue.end()) return true;
    if (std::find(kFalse.begin(), kFalse.end(), text) != kFalse.end()) return false;
    fail(node, path, "expected true or false, got '" + text + "'");
}

std::string parse_string(const ConfigNode& node, const std::string& path) {
    return scalar_text(node, path, "a string");
}

Eigen::Vector3d parse_vector3(const ConfigNode& node, const std::string& path, const Range& range) {
    const std::vector<ConfigNode>& items = sequence_items(node, path, "a sequence of 3 numbers");
    if (items.size() != 3) {
        fail(node, path,
             "expected a sequence of 3 numbers, got " + std::to_string(items.size()) + " items");
    }
    Eigen::Vector3d value;
    for (int i = 0; i < 3; ++i) {
        value[i] = parse_real(items[i], index_key(path, static_cast<std::size_t>(i)), range);
    }
    return value;
}

std::vector<double> parse_real_list(const ConfigNode& node, const std::string& path,
                                    const Range& range) {
    std::vector<double> values;
    for (const ConfigNode& item : sequence_items(node, path, "a sequence of numbers")) {
        values.push_back(parse_real(item, index_key(path, values.size()), range));
    }
    return values;
}

std::size_t parse_choice(const ConfigNode& node, const std::string& path,
                         const std::vector<std::string>& names) {
    const std::string expected = "one of " + join_names(names);
    const std::string& text = scalar_text(node, path, expected);
    const auto it = std::find(names.begin(), names.end(), text);
    if (it == names.end()) fail(node, path, "expected " + expected + ", got '" + text + "'");
    return static_cast<std::size_t>(it - names.begin());
}

const std::vector<ConfigNode>& sequence_items(const ConfigNode& node, const std::string& path,
                                              const std::string& expected) {
    if (!node.is_sequence())
        fail(node, path, "expected " + expected + ", got " + describe_kind(node));
    return node.sequence;
}

std::string format_real(double value) { return as_yaml_real(shortest_text(value)); }

std::string format_real(float value) { return as_yaml_real(shortest_text(value)); }

std::string format_string(const std::string& value) {
    std::string text = "\"";
    for (const char c : value) {
        if (c == '"' || c == '\\') text += '\\';
        text += c;
    }
    return text + "\"";
}

std::string format_vector(const Eigen::Vector3d& value) {
    return format_vector(std::vector<double>(value.data(), value.data() + 3));
}

std::string format_vector(const std::vector<double>& value) {
    std::string text = "[";
    for (std::size_t i = 0; i < value.size(); ++i) {
        text += (i > 0 ? ", " : "") + format_real(value[i]);
    }
    return text + "]";
}

std::string doc_with_range(const std::string& doc, const Range& range) {
    const std::string bounds = range_text(range);
    if (bounds.empty()) return doc;
    return doc + (doc.empty() ? "(" : " (") + bounds + ")";
}

std::string join_names(const std::vector<std::string>& names) {
    std::string text;
    for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
    return text;
}

std::string enum_doc(const std::string& doc, const std::vector<std::string>& names) {
    return doc + (doc.empty() ? "" : " ") + "(one of: " + join_names(names) + ")";
}

std::string list_doc(const std::string& doc, const std::vector<std::string>& keys) {
    return doc + (doc.empty() ? "" : "; ") + "each item has keys: " + join_names(keys);
}

std::string index_key(const std::string& path, std::size_t index) {
    return path + "[" + std::to_string(index) + "]";
}

void rethrow_validation(const ConfigError& error, const std::string& file) {
    if (file.empty()) throw error;
    throw ConfigError(file + ": " + error.what());
}

void SchemaTable::add(SchemaEntry entry) {
    for (const SchemaEntry& existing : entries_) {
        if (existing.key == entry.key) {
            throw ConfigError("config schema: key '" + entry.key + "' is registered twice");
        }
    }
    entries_.push_back(std::move(entry));
}

void SchemaTable::apply(const ConfigNode& map_node, void* object, const std::string& prefix) const {
    if (map_node.is_null()) return;
    if (!map_node.is_map()) {
        fail(map_node, prefix,
             "expected a map with keys " + join_names(keys()) + ", got " + describe_kind(map_node));
    }
    for (const auto& entry : map_node.map) {
        const std::string path = join_key(prefix, entry.first);
        const auto it = std::find_if(entries_.begin(), entries_.end(),
                                     [&](const SchemaEntry& e) { return e.key == entry.first; });
        if (it == entries_.end()) {
            fail(entry.second, path, "unknown key; valid keys: " + join_names(keys()));
        }
        it->apply(entry.second, object, path);
    }
}

void SchemaTable::describe(const void* object, int indent, std::string& out) const {
    for (const SchemaEntry& entry : entries_) entry.describe(object, indent, out);
}

std::vector<std::string> SchemaTable::keys() const {
    std::vector<std::string> names;
    for (const SchemaEntry& entry : entries_) names.push_back(entry.key);
    return names;
}

void describe_line(const std::string& key, const std::string& value, const std::string& doc,
                   int indent, std::string& out) {
    out += std::string(static_cast<std::size_t>(indent * kIndentSpaces), ' ') + key + ":";
    if (!value.empty()) out += " " + value;
    if (!doc.empty()) out += "  # " + doc;
    out += "\n";
}

}  // namespace scantling::io::detail
