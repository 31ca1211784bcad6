// Strict checks of numeric command-line values (option_values.hpp).
#include "scantling/option_values.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <string_view>
#include <system_error>

namespace scantling::app {
namespace {

std::string_view without_plus(std::string_view text) {
    return !text.empty() && text.front() == '+' ? text.substr(1) : text;
}

bool all_digits(std::string_view text) {
    return !text.empty() &&
           std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
}

}  // namespace

std::string check_decimal_integer(std::string& text, std::uint64_t min, std::uint64_t max) {
    const std::string expected =
        fmt::format("expected a whole number in [{}, {}], got '{}'", min, max, text);
    const std::string_view digits = without_plus(text);
    // A sign, a point, an exponent or a base prefix are not digits: "-1", "2.5", "1e3", "0x10".
    if (!all_digits(digits)) return expected;
    std::uint64_t value = 0;
    const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    if (ec != std::errc() || end != digits.data() + digits.size()) return expected;  // overflow
    if (value < min || value > max) return expected;
    text = std::to_string(value);
    return {};
}

std::string check_finite_number(const std::string& text, LowerBound bound) {
    const bool positive = bound == LowerBound::kPositive;
    const std::string expected =
        fmt::format("expected a finite number {} 0, got '{}'", positive ? ">" : ">=", text);
    const std::string_view number = without_plus(text);
    double value = 0.0;
    const auto [end, ec] = std::from_chars(number.data(), number.data() + number.size(), value);
    if (number.empty() || ec != std::errc() || end != number.data() + number.size()) {
        return expected;
    }
    if (!std::isfinite(value) || value < 0.0 || (positive && value == 0.0)) return expected;
    return {};
}

}  // namespace scantling::app
