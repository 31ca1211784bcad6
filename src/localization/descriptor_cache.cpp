// The binary FPFH cache beside a map (localization_map.hpp):
//   8 bytes magic "SCTLFPFH", u32 version, u32 rows, u64 key, u64 columns, rows × columns
//   float32 (column-major), little-endian as the machines we build for.
#include <fmt/format.h>

#include <cstring>
#include <filesystem>
#include <fstream>

#include <scantling/core/error.hpp>
#include <scantling/io/atomic_file.hpp>
#include <scantling/localization/localization_map.hpp>

namespace scantling::localization {
namespace {

constexpr char kMagic[8] = {'S', 'C', 'T', 'L', 'F', 'P', 'F', 'H'};
constexpr std::uint32_t kVersion = 1;
constexpr std::size_t kHeaderBytes = 8 + 4 + 4 + 8 + 8;

struct Fnv1a {
    std::uint64_t hash = 1469598103934665603ull;
    void add(const void* data, std::size_t n) {
        const auto* bytes = static_cast<const unsigned char*>(data);
        for (std::size_t i = 0; i < n; ++i) {
            hash ^= bytes[i];
            hash *= 1099511628211ull;
        }
    }
    void add(double v) { add(&v, sizeof v); }
};

template <class T>
bool read_value(std::istream& in, T& value) {
    return static_cast<bool>(in.read(reinterpret_cast<char*>(&value), sizeof value));
}

}  // namespace

std::uint64_t descriptor_cache_key(const PointCloud& cloud, const LocalizationMapConfig& config) {
    Fnv1a h;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        h.add(cloud.points[i].data(), 3 * sizeof(double));
        if (cloud.has_normals()) h.add(cloud.normals[i].data(), 3 * sizeof(double));
    }
    h.add(config.voxel_size_m);
    h.add(config.fpfh.radius_m);
    h.add(static_cast<double>(config.fpfh.max_neighbors));
    h.add(static_cast<double>(config.fpfh.weighting));
    h.add(static_cast<double>(config.normal_neighbors));
    return h.hash;
}

std::optional<registration::FeatureMatrix> read_descriptor_cache(const std::string& path,
                                                                 std::uint64_t key,
                                                                 std::size_t num_points,
                                                                 std::string& why) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (!fs::exists(path, ec)) return std::nullopt;  // first use: no message
    const auto bytes = fs::file_size(path, ec);
    std::ifstream in(path, std::ios::binary);
    char magic[8];
    std::uint32_t version = 0, rows = 0;
    std::uint64_t stored_key = 0, cols = 0;
    if (ec || !in || !in.read(magic, 8) || !read_value(in, version) || !read_value(in, rows) ||
        !read_value(in, stored_key) || !read_value(in, cols)) {
        why = fmt::format("{}: unreadable or shorter than its header, recomputed", path);
        return std::nullopt;
    }
    if (std::memcmp(magic, kMagic, 8) != 0 || version != kVersion ||
        rows != static_cast<std::uint32_t>(registration::kFpfhDimension)) {
        why = fmt::format("{}: not a version-{} FPFH cache, recomputed", path, kVersion);
        return std::nullopt;
    }
    if (stored_key != key || cols != num_points) {
        why = fmt::format("{}: made for another map or settings, recomputed", path);
        return std::nullopt;
    }
    if (bytes != kHeaderBytes + static_cast<std::uint64_t>(rows) * cols * sizeof(float)) {
        why = fmt::format("{}: {} bytes, expected {}, recomputed", path, bytes,
                          kHeaderBytes + static_cast<std::uint64_t>(rows) * cols * sizeof(float));
        return std::nullopt;
    }
    registration::FeatureMatrix m(rows, static_cast<Eigen::Index>(cols));
    in.read(reinterpret_cast<char*>(m.data()),
            static_cast<std::streamsize>(m.size() * sizeof(float)));
    if (!in || !m.allFinite()) {
        why = fmt::format("{}: corrupt descriptors, recomputed", path);
        return std::nullopt;
    }
    return m;
}

void write_descriptor_cache(const std::string& path, std::uint64_t key,
                            const registration::FeatureMatrix& descriptors) {
    io::write_file_atomically(path, [&](std::ostream& out) {
        const auto rows = static_cast<std::uint32_t>(descriptors.rows());
        const auto cols = static_cast<std::uint64_t>(descriptors.cols());
        out.write(kMagic, 8);
        out.write(reinterpret_cast<const char*>(&kVersion), sizeof kVersion);
        out.write(reinterpret_cast<const char*>(&rows), sizeof rows);
        out.write(reinterpret_cast<const char*>(&key), sizeof key);
        out.write(reinterpret_cast<const char*>(&cols), sizeof cols);
        out.write(reinterpret_cast<const char*>(descriptors.data()),
                  static_cast<std::streamsize>(descriptors.size() * sizeof(float)));
    });
}

}  // namespace scantling::localization
