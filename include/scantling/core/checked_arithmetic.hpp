#pragma once
/// @file
/// Overflow-checked size arithmetic for everything a file header declares (counts, strides,
/// offsets, products such as SIZE x COUNT or WIDTH x HEIGHT). A header is hostile input: every
/// product is computed here and bounded by the bytes actually present *before* anything is
/// allocated or divided, so a lying header becomes a ParseError instead of a SIGFPE, an
/// out-of-bounds read or a multi-gigabyte allocation.

#include <cstdint>
#include <optional>

namespace scantling {

/// a * b, or nullopt when the product does not fit in 64 bits.
[[nodiscard]] constexpr std::optional<std::uint64_t> checked_multiply(std::uint64_t a,
                                                                      std::uint64_t b) {
    std::uint64_t product = 0;
    if (__builtin_mul_overflow(a, b, &product)) return std::nullopt;
    return product;
}

/// a + b, or nullopt when the sum does not fit in 64 bits.
[[nodiscard]] constexpr std::optional<std::uint64_t> checked_add(std::uint64_t a, std::uint64_t b) {
    std::uint64_t sum = 0;
    if (__builtin_add_overflow(a, b, &sum)) return std::nullopt;
    return sum;
}

/// a * b when it fits and is at most `limit` (typically the bytes left in the file), else
/// nullopt. The one check a reader needs before it trusts "count x stride" bytes exist.
[[nodiscard]] constexpr std::optional<std::uint64_t> checked_multiply_within(std::uint64_t a,
                                                                             std::uint64_t b,
                                                                             std::uint64_t limit) {
    const auto product = checked_multiply(a, b);
    if (!product || *product > limit) return std::nullopt;
    return product;
}

}  // namespace scantling
