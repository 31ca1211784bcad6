// Checked JSON field access (detail/json_fields.hpp).
#include "detail/json_fields.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <set>
#include <vector>

#include <scantling/core/error.hpp>

namespace scantling::io::detail {
namespace {

constexpr std::size_t kMaxQuotedBytes = 64;
// Writers normalise in double precision; 1e-6 still refuses a vector someone forgot to scale.
constexpr double kUnitTolerance = 1e-6;

/// "[json.exception.parse_error.101] parse error at ...": the text after the bracketed tag.
std::string without_tag(const char* what) {
    const std::string_view text(what);
    const std::size_t end = text.find("] ");
    return std::string(end == std::string_view::npos ? text : text.substr(end + 2));
}

/// A first pass over the text that builds nothing: counts values, limits depth and refuses a
/// key twice in one object, so that the DOM parse after it stays within the limits. (Not
/// nlohmann's parser callback: its DOM builder scans the parent at every object's end, which
/// is quadratic in the siblings, minutes for a million of them.)
class LimitCheck : public nlohmann::json_sax<Json> {
  public:
    LimitCheck(const std::string& name, const JsonLimits& limits) : name_(name), limits_(limits) {}

    bool null() override { return count(); }
    bool boolean(bool) override { return count(); }
    bool number_integer(number_integer_t) override { return count(); }
    bool number_unsigned(number_unsigned_t) override { return count(); }
    bool number_float(number_float_t, const string_t&) override { return count(); }
    bool string(string_t&) override { return count(); }
    bool binary(binary_t&) override { return count(); }
    bool start_object(std::size_t) override {
        keys_.emplace_back();
        return open();
    }
    bool key(string_t& key) override {
        if (!keys_.back().insert(key).second) {
            refuse("the key \"" + shortened(key) + "\" appears twice in one object");
        }
        return count();
    }
    bool end_object() override {
        keys_.pop_back();
        --depth_;
        return true;
    }
    bool start_array(std::size_t) override { return open(); }
    bool end_array() override {
        --depth_;
        return true;
    }
    bool parse_error(std::size_t, const std::string&,
                     const nlohmann::detail::exception& e) override {
        // Syntax errors and number overflow ("1e999": JSON's only way to a non-finite number).
        refuse("malformed JSON: " + without_tag(e.what()));
    }

  private:
    bool count() {
        if (++values_ > limits_.max_values) {
            refuse(fmt::format("more than {} JSON values", limits_.max_values));
        }
        return true;
    }
    bool open() {
        if (++depth_ > limits_.max_depth) {
            refuse(fmt::format("nesting deeper than {} levels", limits_.max_depth));
        }
        return count();
    }
    [[noreturn]] void refuse(const std::string& what) const {
        throw ParseError(name_, FileLocation{}, what);
    }

    const std::string& name_;
    const JsonLimits& limits_;
    std::size_t values_ = 0;
    int depth_ = 0;
    std::vector<std::set<std::string>> keys_;  // keys of each open object, innermost last
};

/// `value` as an int, or nullopt when it is not an integer or out of int range.
std::optional<int> as_int(const Json& value) {
    if (!value.is_number_integer()) return std::nullopt;
    constexpr auto kMin = std::numeric_limits<int>::min(), kMax = std::numeric_limits<int>::max();
    // An unsigned above INT64_MAX would wrap in get<int64_t>: compare it as unsigned.
    if (value.is_number_unsigned()) {
        const auto x = value.get<std::uint64_t>();
        return x <= static_cast<std::uint64_t>(kMax) ? std::optional<int>(static_cast<int>(x))
                                                     : std::nullopt;
    }
    const auto x = value.get<std::int64_t>();
    return x >= kMin && x <= kMax ? std::optional<int>(static_cast<int>(x)) : std::nullopt;
}

}  // namespace

Json parse_bounded_json(std::string_view text, const std::string& name, const JsonLimits& limits) {
    LimitCheck check(name, limits);
    // The check throws on malformed JSON or past the limits; it never returns false itself.
    if (!Json::sax_parse(text, &check)) {
        throw ParseError(name, FileLocation{}, "malformed JSON");
    }
    try {
        return Json::parse(text);
    } catch (const Json::exception& e) {  // not expected after the check, but never a crash
        throw ParseError(name, FileLocation{}, "malformed JSON: " + without_tag(e.what()));
    }
}

std::string shortened(std::string_view text) {
    if (text.size() <= kMaxQuotedBytes) return std::string(text);
    return std::string(text.substr(0, kMaxQuotedBytes)) + "...";
}

std::string describe(const Json& value) {
    switch (value.type()) {
        case Json::value_t::null:
            return "null";
        case Json::value_t::boolean:
            return "a boolean";
        case Json::value_t::number_integer:
        case Json::value_t::number_unsigned:
            return "an integer";
        case Json::value_t::number_float:
            return "a fractional number";
        case Json::value_t::string:
            return "a string";
        case Json::value_t::array:
            return "an array";
        case Json::value_t::object:
            return "an object";
        default:
            return "an unsupported value";
    }
}

Fields::Fields(const std::string& file, const Json& object, std::string where)
    : file_(file), object_(object), where_(std::move(where)) {
    if (!object_.is_object()) {
        const std::string what = "expected an object, found " + describe(object_);
        throw ParseError(file_, FileLocation{}, where_.empty() ? what : where_ + ": " + what);
    }
}

void Fields::require(std::initializer_list<std::string_view> required,
                     std::initializer_list<std::string_view> optional) const {
    for (const std::string_view key : required) {
        if (!find(key)) fail(key, "missing (a required key)");
    }
    // Not a structured binding: clang 14 (the fuzz build) cannot capture one in a lambda.
    for (const auto& entry : object_.items()) {
        const std::string& key = entry.key();
        const auto is = [&key](std::string_view k) { return k == key; };
        if (std::none_of(required.begin(), required.end(), is) &&
            std::none_of(optional.begin(), optional.end(), is)) {
            fail(shortened(key), "unknown key");
        }
    }
}

void Fields::fail(std::string_view key, const std::string& what) const {
    const std::string separator = what.starts_with("= ") ? " " : what.starts_with("[") ? "" : ": ";
    throw ParseError(file_, FileLocation{}, field(key) + separator + what);
}

std::string Fields::field(std::string_view key) const {
    return where_.empty() ? std::string(key) : where_ + "." + std::string(key);
}

const Json* Fields::find(std::string_view key) const {
    const auto it = object_.find(key);
    return it == object_.end() ? nullptr : &*it;
}

const Json& Fields::at(std::string_view key) const {
    const Json* value = find(key);
    if (!value) fail(key, "missing (a required key)");
    return *value;
}

const Json& Fields::array(std::string_view key) const {
    const Json& value = at(key);
    if (!value.is_array()) fail(key, "expected an array, found " + describe(value));
    return value;
}

Fields Fields::item(std::string_view key, std::size_t i) const {
    return Fields(file_, array(key)[i], field(key) + fmt::format("[{}]", i));
}

int Fields::integer(std::string_view key) const {
    const Json& value = at(key);
    if (!value.is_number_integer()) fail(key, "expected an integer, found " + describe(value));
    const std::optional<int> x = as_int(value);
    if (!x) {
        fail(key, fmt::format("expected an integer in [{}, {}]", std::numeric_limits<int>::min(),
                              std::numeric_limits<int>::max()));
    }
    return *x;
}

double Fields::number(std::string_view key) const {
    const Json& value = at(key);
    if (!value.is_number()) fail(key, "expected a number, found " + describe(value));
    const double x = value.get<double>();
    if (!std::isfinite(x)) fail(key, "expected a finite number");
    return x;
}

double Fields::non_negative(std::string_view key) const {
    const double x = number(key);
    if (x < 0.0) fail(key, fmt::format("= {}, expected >= 0", x));
    return x;
}

bool Fields::boolean(std::string_view key) const {
    const Json& value = at(key);
    if (!value.is_boolean()) fail(key, "expected true or false, found " + describe(value));
    return value.get<bool>();
}

std::string Fields::text(std::string_view key) const {
    const Json& value = at(key);
    if (!value.is_string()) fail(key, "expected a string, found " + describe(value));
    return value.get<std::string>();
}

Eigen::Vector3d Fields::vector(std::string_view key) const {
    const Json& value = at(key);
    const auto is_number = [](const Json& x) { return x.is_number(); };
    if (!value.is_array() || value.size() != 3 ||
        !std::all_of(value.begin(), value.end(), is_number)) {
        fail(key, "expected 3 numbers");
    }
    Eigen::Vector3d v(value[0].get<double>(), value[1].get<double>(), value[2].get<double>());
    if (!v.allFinite()) fail(key, "expected 3 finite numbers");
    return v;
}

Eigen::Vector3d Fields::unit_vector(std::string_view key) const {
    Eigen::Vector3d v = vector(key);
    if (std::abs(v.norm() - 1.0) > kUnitTolerance) {
        fail(key, fmt::format("has norm {}, expected a unit vector", v.norm()));
    }
    return v;
}

std::pair<int, int> Fields::int_pair(std::string_view key, std::size_t i) const {
    const Json& pair = array(key)[i];
    const bool two = pair.is_array() && pair.size() == 2;
    const std::optional<int> first = two ? as_int(pair[0]) : std::nullopt;
    const std::optional<int> second = two ? as_int(pair[1]) : std::nullopt;
    if (!first || !second) fail(key, fmt::format("[{}]: expected [tag, count], two integers", i));
    return {*first, *second};
}

}  // namespace scantling::io::detail
