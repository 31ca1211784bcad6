#include <gtest/gtest.h>

#include <scantling/core/checked_arithmetic.hpp>

#include <cstdint>
#include <limits>

namespace scantling {
namespace {

constexpr std::uint64_t kMax = std::numeric_limits<std::uint64_t>::max();
constexpr std::uint64_t kTwoTo32 = std::uint64_t{1} << 32;

TEST(CheckedArithmetic, MultiplyReturnsTheProductWhenItFits) {
    EXPECT_EQ(checked_multiply(0, kMax), 0u);
    EXPECT_EQ(checked_multiply(kMax, 1), kMax);
    EXPECT_EQ(checked_multiply(kTwoTo32 - 1, kTwoTo32 + 1), kMax);  // (2^32)^2 - 1
    static_assert(checked_multiply(6, 7) == 42u);
}

TEST(CheckedArithmetic, MultiplyRefusesProductsThatWrap) {
    EXPECT_FALSE(checked_multiply(kTwoTo32, kTwoTo32));  // wraps to 0 unchecked
    EXPECT_FALSE(checked_multiply(4, 4611686018427387904u));
    EXPECT_FALSE(checked_multiply(kMax, 2));
}

TEST(CheckedArithmetic, AddRefusesSumsThatWrap) {
    EXPECT_EQ(checked_add(kMax - 1, 1), kMax);
    EXPECT_FALSE(checked_add(kMax, 1));
    // The PCD header of issue 10: 12 + 4 x (2^62 - 3) is exactly 2^64, i.e. 0 unchecked.
    const auto foo_bytes = checked_multiply(4, 4611686018427387901u);
    ASSERT_TRUE(foo_bytes);
    EXPECT_FALSE(checked_add(12, *foo_bytes));
}

TEST(CheckedArithmetic, MultiplyWithinBoundsTheProductInclusively) {
    EXPECT_EQ(checked_multiply_within(4, 12, 48), 48u);
    EXPECT_FALSE(checked_multiply_within(4, 12, 47));
    EXPECT_EQ(checked_multiply_within(0, kMax, 0), 0u);
    // A product that wraps to a small number must not pass as "fits".
    EXPECT_FALSE(checked_multiply_within(kTwoTo32, kTwoTo32, kMax));
}

}  // namespace
}  // namespace scantling
