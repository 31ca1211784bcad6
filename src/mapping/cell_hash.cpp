#include <scantling/core/error.hpp>
#include <scantling/mapping/cell_hash.hpp>

#include <algorithm>
#include <array>
#include <utility>
#include <vector>

#include <fmt/format.h>

namespace scantling::mapping {
namespace {

constexpr std::array<std::pair<CellHashKind, std::string_view>, 2> kKindNames{{
    {CellHashKind::kSourceXor, "source_xor"},
    {CellHashKind::kMixed, "mixed"},
}};

}  // namespace

std::string_view to_string(CellHashKind kind) {
    for (const auto& [k, n] : kKindNames) {
        if (k == kind) return n;
    }
    return "unknown";
}

CellHashKind cell_hash_kind_from_string(std::string_view name, std::string_view field) {
    for (const auto& [k, n] : kKindNames) {
        if (n == name) return k;
    }
    throw ConfigError(fmt::format("{} = \"{}\", expected one of source_xor, mixed", field, name));
}

HashStats hash_value_stats(std::span<const CellKey> keys, CellHashKind kind) {
    std::vector<std::uint64_t> hashes(keys.size());
    std::transform(keys.begin(), keys.end(), hashes.begin(),
                   [kind](const CellKey& k) { return hash_cell(k, kind); });
    std::sort(hashes.begin(), hashes.end());
    HashStats stats;
    stats.num_cells = keys.size();
    for (std::size_t i = 0; i < hashes.size();) {
        std::size_t j = i + 1;
        while (j < hashes.size() && hashes[j] == hashes[i]) ++j;
        ++stats.distinct_hashes;
        if (j - i > 1) stats.cells_sharing_hash += j - i;
        stats.largest_hash_group = std::max(stats.largest_hash_group, j - i);
        i = j;
    }
    return stats;
}

}  // namespace scantling::mapping
