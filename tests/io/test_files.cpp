#include "test_files.hpp"

#include <scantling/core/error.hpp>

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <fstream>
#include <random>

namespace scantling::io::test {

TempDir::TempDir() {
    static std::atomic<int> counter{0};
    std::random_device random;
    path_ = std::filesystem::temp_directory_path() /
            ("scantling-io-test-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) +
             "-" + std::to_string(random()));
    std::filesystem::create_directories(path_);
}

TempDir::~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
}

std::vector<std::string> TempDir::list() const {
    std::vector<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(path_)) {
        names.push_back(entry.path().filename().string());
    }
    std::sort(names.begin(), names.end());
    return names;
}

void write_bytes(const std::string& path, std::string_view bytes) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    ASSERT_TRUE(out.good()) << "cannot write test file " << path;
}

std::string read_bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::filesystem::path shared_data_dir() { return SCANTLING_SHARED_DATA_DIR; }

bool shared_data_available() { return std::filesystem::exists(shared_data_dir() / "README.md"); }

PointCloud make_full_cloud(std::size_t n) {
    std::mt19937 rng(42);
    std::uniform_real_distribution<float> coordinate(-100.0f, 100.0f);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    PointCloud cloud;
    cloud.stamp_s = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        cloud.points.emplace_back(coordinate(rng), coordinate(rng), coordinate(rng));
        const Eigen::Vector3f normal =
            Eigen::Vector3f(unit(rng), unit(rng), unit(rng)).normalized();
        cloud.normals.push_back(normal.cast<double>());
        cloud.intensities.push_back(static_cast<float>(i % 256) * 0.5f);
        cloud.rings.push_back(static_cast<std::uint16_t>(i % 64));
        cloud.times_s.push_back(static_cast<float>(i) * 1e-5f);
        cloud.colors.emplace_back(static_cast<std::uint8_t>(i % 256),
                                  static_cast<std::uint8_t>((7 * i) % 256),
                                  static_cast<std::uint8_t>(255 - i % 256));
    }
    return cloud;
}

void expect_same_cloud(const PointCloud& expected, const PointCloud& actual) {
    ASSERT_EQ(expected.size(), actual.size());
    EXPECT_EQ(expected.points, actual.points);
    EXPECT_EQ(expected.normals, actual.normals);
    EXPECT_EQ(expected.intensities, actual.intensities);
    EXPECT_EQ(expected.rings, actual.rings);
    EXPECT_EQ(expected.times_s, actual.times_s);
    EXPECT_EQ(expected.colors, actual.colors);
    EXPECT_EQ(expected.stamp_s, actual.stamp_s);
}

void expect_file_error(const std::function<void()>& call, const std::string& path) {
    try {
        call();
        ADD_FAILURE() << "no error for " << path;
    } catch (const FileError& e) {
        EXPECT_EQ(e.path(), path);
        EXPECT_EQ(std::string(e.what()).rfind(path, 0), 0u) << e.what();
    } catch (const std::exception& e) {
        ADD_FAILURE() << "wrong exception type for " << path << ": " << e.what();
    }
}

}  // namespace scantling::io::test
