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

#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>

namespace scantling::registration::detail {

using config_checks::require_open_unit;
using config_checks::require_positive;

/// Throws ConfigError("<prefix>.<field> = <value>, expected >= <minimum>").
inline void require_at_least(int value, int minimum, std::string_view prefix,
                             std::string_view field) {
    config_checks::require_at_least(value, minimum, prefix, field);
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
