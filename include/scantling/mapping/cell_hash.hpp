#pragma once
/// @file
/// Keys and hash functions of the LiODOM hashed cell map (SPEC §2, D4.2 §II.2 "Map
/// Representation"), and the statistics that compare them.
///
/// Two hashes of an integer cell index (x, y, z):
/// - kSourceXor: the source's H = (c_x ⊕ (c_y ≪ 1)) ⊕ (c_z ≪ 2), on the indices sign-extended to
///   64 bits (as the source code does through std::hash<int>). It is linear over GF(2) and only
///   spans about max(|x|, 2|y|, 4|z|) values, so distinct cells share full hash values: (2, 0, 0)
///   and (0, 1, 0) both hash to 2. A hash table still finds the right cell (keys are compared),
///   but such cells always share a bucket chain, whatever the bucket count.
/// - kMixed: the packed indices pushed through two rounds of the murmur3/splitmix64 finaliser;
///   every input bit affects every output bit, so equal hashes of distinct map cells are as rare
///   as for a random function (about n² / 2⁶⁵ pairs).
/// docs/benchmarks.md ("Hashed cell map") measures both on real and simulated maps.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

namespace scantling::mapping {

/// Integer index of a cell: floor(x / s_xy), floor(y / s_xy), floor(z / s_z).
struct CellKey {
    std::int32_t x = 0, y = 0, z = 0;
    friend bool operator==(const CellKey&, const CellKey&) = default;
    /// Lexicographic (x, y, z): the deterministic order of every map output.
    friend auto operator<=>(const CellKey&, const CellKey&) = default;
};

enum class CellHashKind {
    kSourceXor,  ///< the source's (c_x ⊕ (c_y ≪ 1)) ⊕ (c_z ≪ 2): collides by construction
    kMixed,      ///< well-mixing 64-bit finaliser of the packed indices
};

/// "source_xor", "mixed".
std::string_view to_string(CellHashKind kind);

/// Inverse of to_string; throws ConfigError naming `field` and listing the accepted names.
CellHashKind cell_hash_kind_from_string(std::string_view name, std::string_view field = "hash");

namespace detail {

/// The murmur3 64-bit finaliser: a bijection in which every input bit flips each output bit
/// with probability about one half.
constexpr std::uint64_t fmix64(std::uint64_t h) {
    h ^= h >> 33;
    h *= 0xff51afd7ed558ccdULL;
    h ^= h >> 33;
    h *= 0xc4ceb9fe1a85ec53ULL;
    h ^= h >> 33;
    return h;
}

}  // namespace detail

/// Full 64-bit hash of a key. Inline because it runs once per table probe. O(1), pure.
constexpr std::uint64_t hash_cell(const CellKey& key, CellHashKind kind) {
    if (kind == CellHashKind::kSourceXor) {
        const auto ext = [](std::int32_t v) { return static_cast<std::uint64_t>(std::int64_t{v}); };
        return (ext(key.x) ^ (ext(key.y) << 1)) ^ (ext(key.z) << 2);
    }
    const std::uint64_t xy = std::uint64_t{static_cast<std::uint32_t>(key.x)} |
                             (std::uint64_t{static_cast<std::uint32_t>(key.y)} << 32);
    // z goes through its own finaliser first so that no xor of (x, y) bits can cancel it
    // systematically; the golden-ratio offset keeps z = 0 from mapping to 0.
    const std::uint64_t z = static_cast<std::uint32_t>(key.z);
    return detail::fmix64(xy ^ detail::fmix64(z + 0x9e3779b97f4a7c15ULL));
}

/// Hasher functor for std::unordered_map<CellKey, ...>: the configured kind is the real table
/// hash, so the source's function can be measured as the table actually uses it.
struct CellKeyHash {
    CellHashKind kind = CellHashKind::kMixed;
    std::size_t operator()(const CellKey& key) const noexcept {
        return static_cast<std::size_t>(hash_cell(key, kind));
    }
};

/// How well a hash spreads a set of keys, and how the table that holds them is loaded.
struct HashStats {
    std::size_t num_cells = 0;           ///< keys in the table
    std::size_t distinct_hashes = 0;     ///< distinct full 64-bit hash values among them
    std::size_t cells_sharing_hash = 0;  ///< keys whose full hash equals another key's
    std::size_t largest_hash_group = 0;  ///< most keys sharing one full hash value
    std::size_t bucket_count = 0;        ///< buckets of the table (0 when not from a table)
    std::size_t empty_buckets = 0;
    std::size_t max_bucket_occupancy = 0;  ///< keys in the fullest bucket
    double mean_bucket_occupancy = 0.0;    ///< keys per non-empty bucket
    /// Mean, over the keys, of the number of keys in the key's bucket (Σ occupancy² / n): what a
    /// successful lookup walks through at worst. 1 for a perfect spread.
    double mean_chain_seen = 0.0;
    double load_factor = 0.0;  ///< keys / buckets
};

/// Fills the hash-value fields (num_cells, distinct_hashes, cells_sharing_hash,
/// largest_hash_group) for `keys` (assumed distinct) under `kind`. O(n log n).
HashStats hash_value_stats(std::span<const CellKey> keys, CellHashKind kind);

}  // namespace scantling::mapping
