#pragma once
/// @file
/// ConfigError helpers shared by the registration configs (private).

#include <array>
#include <cmath>
#include <cstddef>
#include <string>
#include <string_view>
#include <utility>

#include <fmt/format.h>

#include <scantling/core/error.hpp>

namespace scantling::registration::detail {

/// Throws ConfigError("<prefix>.<field> = <value>, expected finite > 0").
inline void require_positive(double value, std::string_view prefix, std::string_view field) {
    if (!(value > 0.0) || !std::isfinite(value)) {
        throw ConfigError(fmt::format("{}.{} = {}, expected finite > 0", prefix, field, value));
    }
}

/// Throws ConfigError("<prefix>.<field> = <value>, expected >= <minimum>").
inline void require_at_least(int value, int minimum, std::string_view prefix,
                             std::string_view field) {
    if (value < minimum) {
        throw ConfigError(fmt::format("{}.{} = {}, expected >= {}", prefix, field, value, minimum));
    }
}

/// Throws ConfigError unless 0 < value < 1.
inline void require_open_unit(double value, std::string_view prefix, std::string_view field) {
    if (!(value > 0.0 && value < 1.0)) {
        throw ConfigError(fmt::format("{}.{} = {}, expected in (0, 1)", prefix, field, value));
    }
}

/// An enum's names for configs and the CLI: {value, name} pairs.
template <typename Enum, std::size_t N>
using EnumNames = std::array<std::pair<Enum, std::string_view>, N>;

/// The name of `value`, "unknown" when it has none.
template <typename Enum, std::size_t N>
std::string_view enum_name(const EnumNames<Enum, N>& names, Enum value) {
    for (const auto& [v, name] : names) {
        if (v == value) return name;
    }
    return "unknown";
}

/// The value named `name`; throws ConfigError("<field> = \"<name>\", expected one of a, b, c").
template <typename Enum, std::size_t N>
Enum enum_value(const EnumNames<Enum, N>& names, std::string_view name, std::string_view field) {
    std::string accepted;
    for (const auto& [v, n] : names) {
        if (n == name) return v;
        accepted += accepted.empty() ? std::string(n) : ", " + std::string(n);
    }
    throw ConfigError(fmt::format("{} = \"{}\", expected one of {}", field, name, accepted));
}

}  // namespace scantling::registration::detail
