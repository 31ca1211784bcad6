#pragma once
// Checked access to the fields of a JSON document (the structural map reader): every failure
// is a ParseError naming the file and the field path ("compartments[1].min").

#include <Eigen/Core>
#include <cstddef>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <utility>

#include <scantling/io/structural_map.hpp>

namespace scantling::io::detail {

using Json = nlohmann::json;

struct JsonLimits {
    std::size_t max_values = 0;  ///< objects, arrays, keys and scalars built
    int max_depth = 0;           ///< nesting levels
};

/// Parses `text` within `limits` (checked by a first pass that builds nothing, so memory stays
/// bounded by them), refusing malformed JSON and a key repeated in one object (ParseError naming
/// `name`). Linear in the text.
Json parse_bounded_json(std::string_view text, const std::string& name, const JsonLimits& limits);

/// At most 64 bytes of `text`, for messages (hostile keys and names can be megabytes long).
std::string shortened(std::string_view text);

/// "an integer", "a string", ...: what a value is, for "expected X, found Y".
std::string describe(const Json& value);

/// One JSON object being read. `where` is its path ("" for the root, "surfaces[2]").
class Fields {
  public:
    /// ParseError unless `object` is an object.
    Fields(const std::string& file, const Json& object, std::string where);

    /// ParseError for a missing `required` key or a key in neither list.
    void require(std::initializer_list<std::string_view> required,
                 std::initializer_list<std::string_view> optional = {}) const;
    /// "<file>: <where>.<key> = 3, ..." when `what` starts with "= ", "<where>.<key>[..." when it
    /// starts with '[', else "<where>.<key>: <what>".
    [[noreturn]] void fail(std::string_view key, const std::string& what) const;

    const Json* find(std::string_view key) const;
    const Json& array(std::string_view key) const;
    /// Element i of the array `key`, which must be an object.
    Fields item(std::string_view key, std::size_t i) const;
    int integer(std::string_view key) const;
    double number(std::string_view key) const;  ///< finite
    double non_negative(std::string_view key) const;
    bool boolean(std::string_view key) const;
    std::string text(std::string_view key) const;
    Eigen::Vector3d vector(std::string_view key) const;       ///< 3 finite numbers
    Eigen::Vector3d unit_vector(std::string_view key) const;  ///< norm within 1e-6 of 1
    /// Element i of the array `key` as a pair of integers.
    std::pair<int, int> int_pair(std::string_view key, std::size_t i) const;

    /// The kind among `kinds` whose to_string is the string at `key`.
    template <typename Kind>
    Kind kind(std::string_view key, std::initializer_list<Kind> kinds) const {
        const std::string name = text(key);
        for (const Kind k : kinds) {
            if (to_string(k) == name) return k;
        }
        std::string names;
        for (const Kind k : kinds) names += (names.empty() ? "" : ", ") + std::string(to_string(k));
        fail(key, "= \"" + shortened(name) + "\", expected one of: " + names);
    }

  private:
    const Json& at(std::string_view key) const;
    std::string field(std::string_view key) const;

    const std::string& file_;
    const Json& object_;
    std::string where_;
};

}  // namespace scantling::io::detail
