#include <scantling/core/error.hpp>
#include <scantling/mapping/cell_hash.hpp>

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace scantling::mapping {
namespace {

std::vector<CellKey> grid_keys(int nx, int ny, int nz, int offset = 0) {
    std::vector<CellKey> keys;
    for (int x = 0; x < nx; ++x) {
        for (int y = 0; y < ny; ++y) {
            for (int z = 0; z < nz; ++z) keys.push_back({x - offset, y - offset, z - offset});
        }
    }
    return keys;
}

TEST(CellHash, SourceXorIsTheSourceFormulaOnSignExtendedIndices) {
    EXPECT_EQ(hash_cell({3, 5, 7}, CellHashKind::kSourceXor), 3U ^ (5U << 1) ^ (7U << 2));
    // std::hash<int> sign-extends, as the source's code relies on.
    EXPECT_EQ(hash_cell({-1, 0, 0}, CellHashKind::kSourceXor), ~std::uint64_t{0});
    EXPECT_EQ(hash_cell({0, -1, 0}, CellHashKind::kSourceXor), ~std::uint64_t{0} << 1);
}

TEST(CellHash, SourceXorGivesDistinctKeysTheSameHash) {
    EXPECT_EQ(hash_cell({2, 0, 0}, CellHashKind::kSourceXor),
              hash_cell({0, 1, 0}, CellHashKind::kSourceXor));
    EXPECT_EQ(hash_cell({4, 0, 0}, CellHashKind::kSourceXor),
              hash_cell({0, 0, 1}, CellHashKind::kSourceXor));
    EXPECT_EQ(hash_cell({0, 2, 0}, CellHashKind::kSourceXor),
              hash_cell({0, 0, 1}, CellHashKind::kSourceXor));
    EXPECT_NE(hash_cell({2, 0, 0}, CellHashKind::kMixed),
              hash_cell({0, 1, 0}, CellHashKind::kMixed));
}

TEST(CellHash, HashValueStatsCountsSharedValues) {
    const std::vector<CellKey> keys{{2, 0, 0}, {0, 1, 0}, {1, 0, 0},
                                    {4, 0, 0}, {0, 0, 1}, {0, 2, 0}};
    const HashStats s = hash_value_stats(keys, CellHashKind::kSourceXor);
    EXPECT_EQ(s.num_cells, 6U);
    EXPECT_EQ(s.distinct_hashes, 3U);     // {2}, {1}, {4}
    EXPECT_EQ(s.cells_sharing_hash, 5U);  // all but (1, 0, 0)
    EXPECT_EQ(s.largest_hash_group, 3U);  // hash 4
}

TEST(CellHash, SourceXorSpansFewValuesOnADenseGrid) {
    // x < 64, 2y < 128, 4z < 64: every xor is below 128, so 65536 keys share <= 128 values.
    const std::vector<CellKey> keys = grid_keys(64, 64, 16);
    const HashStats s = hash_value_stats(keys, CellHashKind::kSourceXor);
    EXPECT_LE(s.distinct_hashes, 128U);
    EXPECT_EQ(s.cells_sharing_hash, keys.size());
}

TEST(CellHash, MixedGivesEveryCellOfADenseGridItsOwnHash) {
    for (const int offset : {0, 32}) {  // also across negative indices
        const std::vector<CellKey> keys = grid_keys(64, 64, 16, offset);
        const HashStats s = hash_value_stats(keys, CellHashKind::kMixed);
        EXPECT_EQ(s.distinct_hashes, keys.size());
        EXPECT_EQ(s.cells_sharing_hash, 0U);
        EXPECT_EQ(s.largest_hash_group, 1U);
    }
}

TEST(CellHash, MixedSpreadsLowBitsEvenly) {
    // 65536 keys into 1024 buckets by the low bits: mean 64, standard deviation 8. A bucket over
    // 64 + 8 sigma would mean the low bits are not mixed (the xor hash uses only 128 buckets).
    constexpr std::size_t kBuckets = 1024;
    constexpr std::size_t kMaxOccupancy = 64 + 8 * 8;
    const std::vector<CellKey> keys = grid_keys(64, 64, 16, 20);
    for (const CellHashKind kind : {CellHashKind::kMixed, CellHashKind::kSourceXor}) {
        std::vector<std::size_t> occupancy(kBuckets, 0);
        for (const CellKey& k : keys) ++occupancy[hash_cell(k, kind) % kBuckets];
        const std::size_t max = *std::max_element(occupancy.begin(), occupancy.end());
        if (kind == CellHashKind::kMixed) {
            EXPECT_LE(max, kMaxOccupancy);
        } else {
            EXPECT_GT(max, kMaxOccupancy);
        }
    }
}

TEST(CellHash, HasherUsesItsKind) {
    const CellKey key{7, -3, 2};
    EXPECT_EQ(CellKeyHash{CellHashKind::kSourceXor}(key), hash_cell(key, CellHashKind::kSourceXor));
    EXPECT_EQ(CellKeyHash{CellHashKind::kMixed}(key), hash_cell(key, CellHashKind::kMixed));
}

TEST(CellHash, KindNamesRoundTripAndBadNamesNameTheField) {
    for (const CellHashKind kind : {CellHashKind::kSourceXor, CellHashKind::kMixed}) {
        EXPECT_EQ(cell_hash_kind_from_string(to_string(kind)), kind);
    }
    try {
        cell_hash_kind_from_string("xor", "odometry.map.hash");
        FAIL() << "expected ConfigError";
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("odometry.map.hash = \"xor\""), std::string::npos)
            << e.what();
    }
}

TEST(CellKey, OrdersLexicographically) {
    std::vector<CellKey> keys{{1, 0, 0}, {0, 5, -1}, {0, 5, -2}, {-1, 9, 9}};
    std::sort(keys.begin(), keys.end());
    const std::vector<CellKey> expected{{-1, 9, 9}, {0, 5, -2}, {0, 5, -1}, {1, 0, 0}};
    EXPECT_EQ(keys, expected);
}

}  // namespace
}  // namespace scantling::mapping
