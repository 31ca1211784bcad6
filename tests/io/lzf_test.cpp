#include <gtest/gtest.h>

#include <scantling/core/error.hpp>

#include <random>

#include "../../src/io/detail/lzf.hpp"

namespace scantling::io {
namespace {

TEST(Lzf, CompressesAndDecompressesRandomAndRepetitiveData) {
    std::mt19937 rng(7);
    for (const std::size_t size : {0u, 1u, 2u, 3u, 31u, 32u, 33u, 300u, 70000u}) {
        std::vector<std::uint8_t> data(size);
        for (std::size_t i = 0; i < size; ++i) {
            data[i] =
                (i / 100) % 2 ? static_cast<std::uint8_t>(rng()) : static_cast<std::uint8_t>(i % 7);
        }
        const auto packed = detail::lzf_compress(data);
        std::vector<std::uint8_t> unpacked(size);
        detail::lzf_decompress(packed, unpacked, "mem", 0);
        EXPECT_EQ(unpacked, data) << "size " << size;
    }
}

TEST(Lzf, CompressesLongRunsWellBelowTheirSize) {
    const std::vector<std::uint8_t> zeros(100000, 0);
    const auto packed = detail::lzf_compress(zeros);
    EXPECT_LT(packed.size(), zeros.size() / 50);
}

TEST(Lzf, NeverWritesOutOfBoundsOnCorruptStreams) {
    std::vector<std::uint8_t> data(4000);
    for (std::size_t i = 0; i < data.size(); ++i) data[i] = static_cast<std::uint8_t>((i * i) % 13);
    const auto packed = detail::lzf_compress(data);
    std::mt19937 rng(3);
    int rejected = 0;
    for (int trial = 0; trial < 2000; ++trial) {
        auto corrupt = packed;
        corrupt[rng() % corrupt.size()] = static_cast<std::uint8_t>(rng());
        corrupt.resize(corrupt.size() - (trial % 3 == 0 ? rng() % 8 : 0));
        std::vector<std::uint8_t> out(data.size());
        try {
            detail::lzf_decompress(corrupt, out, "mem", 0);
        } catch (const ParseError&) {
            ++rejected;
        }
    }
    EXPECT_GT(rejected, 1000);  // most corruptions change the decoded length
}

}  // namespace
}  // namespace scantling::io
