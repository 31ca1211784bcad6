#pragma once
// Shared helpers for the io tests: scoped temporary directories, raw byte files, a cloud with
// every field, and the path to the real recordings (tests skip when they are absent).

#include <gtest/gtest.h>

#include <bit>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include <scantling/core/point_cloud.hpp>

namespace scantling::io::test {

/// A fresh directory under the system temp dir, removed with everything in it on destruction.
class TempDir {
  public:
    TempDir();
    ~TempDir();
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;

    const std::filesystem::path& path() const { return path_; }
    /// Path of `name` inside the directory (not created).
    std::string file(const std::string& name) const { return (path_ / name).string(); }
    /// Names of the entries in the directory, sorted.
    std::vector<std::string> list() const;

  private:
    std::filesystem::path path_;
};

void write_bytes(const std::string& path, std::string_view bytes);
std::string read_bytes(const std::string& path);

/// SCANTLING_SHARED_DATA_DIR (the real recordings; see its README.md).
std::filesystem::path shared_data_dir();
bool shared_data_available();

/// A cloud with every field the formats can hold, values exactly representable as float32
/// (so lossless formats must return them bit for bit): points, normals, intensities, rings,
/// times, colours; `n` points.
PointCloud make_full_cloud(std::size_t n);

/// Expects equality of every field (positions compared exactly).
void expect_same_cloud(const PointCloud& expected, const PointCloud& actual);

/// Expects `call` to throw FileError whose path() is `path` and whose message starts with it.
void expect_file_error(const std::function<void()>& call, const std::string& path);

/// Appends the little-endian bytes of `value`.
template <typename T>
void put(std::string& out, T value) {
    static_assert(std::endian::native == std::endian::little, "tests assume a little-endian host");
    out.append(reinterpret_cast<const char*>(&value), sizeof(T));
}

/// Appends the big-endian bytes of `value`.
template <typename T>
void put_be(std::string& out, T value) {
    const char* bytes = reinterpret_cast<const char*>(&value);
    for (std::size_t i = sizeof(T); i-- > 0;) out.push_back(bytes[i]);
}

}  // namespace scantling::io::test

#define SCANTLING_SKIP_WITHOUT_SHARED_DATA()                                                \
    do {                                                                                    \
        if (!::scantling::io::test::shared_data_available()) {                              \
            GTEST_SKIP() << "real data folder " << ::scantling::io::test::shared_data_dir() \
                         << " is absent (set SCANTLING_SHARED_DATA_DIR); skipping";         \
        }                                                                                   \
    } while (0)
