#pragma once
/// @file
/// Strict checks of numeric command-line values, applied before CLI11 converts them. CLI11 2.1
/// reads integers with strtoull/strtoll in base 0 and floats with strtold, so on its own
/// "--seed -1" becomes 2^64 − 1, an overflowing value saturates, "010" is octal 8 and "nan" or
/// "inf" pass as numbers. Pure functions (no CLI11 here: main.cpp wraps them as validators).

#include <cstdint>
#include <string>

namespace scantling::app {

/// Empty when `text` is a decimal integer (digits only, an optional leading '+') in
/// [min, max]; `text` is then rewritten without sign or leading zeros, so that CLI11's base-0
/// conversion reads the same number. Otherwise what was expected, quoting `text`.
std::string check_decimal_integer(std::string& text, std::uint64_t min, std::uint64_t max);

enum class LowerBound {
    kPositive,     ///< > 0
    kNonNegative,  ///< >= 0
};

/// Empty when `text` is a finite decimal number (std::from_chars, an optional leading '+';
/// no hexadecimal) above `bound`; otherwise what was expected, quoting `text`.
std::string check_finite_number(const std::string& text, LowerBound bound);

}  // namespace scantling::app
