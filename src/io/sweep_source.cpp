#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <scantling/core/error.hpp>
#include <scantling/io/cloud_io.hpp>
#include <scantling/io/file_path.hpp>
#include <scantling/io/recording.hpp>
#include <scantling/io/sweep_source.hpp>
#include <set>
#include <string>

namespace scantling::io {
namespace {

namespace fs = std::filesystem;

void check_index(std::size_t i, std::size_t size, const std::string& path) {
    if (i >= size) {
        throw InputError(path + ": sweep " + std::to_string(i) + " out of range (" +
                         std::to_string(size) + " sweeps)");
    }
}

class RecordingSource final : public SweepSource {
  public:
    explicit RecordingSource(const std::string& path)
        : path_(path), recording_(open_recording(path)) {
        if (recording_.num_sweeps() == 0) {
            throw FileError(path, "the recording has no LiDAR sweeps (lidar/ is missing or empty)");
        }
    }
    SweepSourceKind kind() const override { return SweepSourceKind::kRecording; }
    const std::string& path() const override { return path_; }
    std::size_t size() const override { return recording_.num_sweeps(); }
    PointCloud read(std::size_t i) const override {
        check_index(i, size(), path_);
        return recording_.read_sweep(i);
    }
    double stamp_s(std::size_t i) const override {
        check_index(i, size(), path_);
        return recording_.sweep_stamp_s(i);
    }
    std::string file_of(std::size_t i) const override {
        return recording_.lidar_sweeps().directory + "/" + recording_layout::frame_stem(i) + ".bin";
    }
    std::optional<std::vector<Eigen::Isometry3d>> ground_truth() const override {
        return recording_.lidar_sweeps().poses_gt;
    }

  private:
    std::string path_;
    Recording recording_;
};

/// Clouds in a folder, one format, file-name order.
class FileListSource final : public SweepSource {
  public:
    FileListSource(SweepSourceKind kind, std::string path, std::vector<std::string> files,
                   std::vector<double> stamps_s)
        : kind_(kind),
          path_(std::move(path)),
          files_(std::move(files)),
          stamps_s_(std::move(stamps_s)) {}
    SweepSourceKind kind() const override { return kind_; }
    const std::string& path() const override { return path_; }
    std::size_t size() const override { return files_.size(); }
    PointCloud read(std::size_t i) const override {
        check_index(i, size(), path_);
        PointCloud cloud = read_cloud(files_[i]);
        cloud.stamp_s = stamps_s_[i];
        return cloud;
    }
    double stamp_s(std::size_t i) const override {
        check_index(i, size(), path_);
        return stamps_s_[i];
    }
    std::string file_of(std::size_t i) const override {
        check_index(i, size(), path_);
        return files_[i];
    }
    std::optional<std::vector<Eigen::Isometry3d>> ground_truth() const override {
        return std::nullopt;
    }

  private:
    SweepSourceKind kind_;
    std::string path_;
    std::vector<std::string> files_;
    std::vector<double> stamps_s_;
};

std::vector<std::string> cloud_files(const fs::path& folder) {
    static const std::set<std::string> kExtensions = {".pcd", ".ply", ".bin"};
    std::vector<std::string> files;
    std::set<std::string> extensions;
    for (const auto& entry : fs::directory_iterator(folder)) {
        if (!entry.is_regular_file()) continue;
        const std::string ext = lower_extension(entry.path().string());
        if (kExtensions.count(ext) == 0) continue;
        files.push_back(entry.path().string());
        extensions.insert(ext);
    }
    if (files.empty()) {
        throw FileError(folder.string(),
                        "no .pcd, .ply or .bin files (expected a folder of "
                        "sweeps, a KITTI sequence or a simulator recording)");
    }
    if (extensions.size() > 1) {
        throw FileError(folder.string(), "mixes cloud formats (" +
                                             std::to_string(extensions.size()) +
                                             " extensions); expected one format per folder");
    }
    std::sort(files.begin(), files.end());
    return files;
}

std::vector<double> regular_stamps(std::size_t n, double period_s) {
    std::vector<double> stamps(n);
    for (std::size_t i = 0; i < n; ++i) stamps[i] = static_cast<double>(i) * period_s;
    return stamps;
}

std::vector<double> kitti_stamps(const fs::path& sequence, std::size_t n, double period_s) {
    const fs::path times = sequence / "times.txt";
    if (!fs::exists(times)) return regular_stamps(n, period_s);
    std::vector<double> stamps = read_stamps(times.string());
    if (stamps.size() != n) {
        throw ParseError(times.string(), FileLocation{},
                         std::to_string(stamps.size()) + " stamps but velodyne/ has " +
                             std::to_string(n) + " sweeps");
    }
    return stamps;
}

}  // namespace

const char* to_string(SweepSourceKind kind) {
    switch (kind) {
        case SweepSourceKind::kRecording:
            return "recording";
        case SweepSourceKind::kKittiSequence:
            return "kitti";
        case SweepSourceKind::kCloudFolder:
            return "folder";
    }
    return "unknown";
}

std::unique_ptr<SweepSource> open_sweep_source(const std::string& path,
                                               const SweepSourceOptions& options) {
    if (!(options.period_s > 0.0) || !std::isfinite(options.period_s)) {
        throw ConfigError("period_s = " + std::to_string(options.period_s) + ", expected > 0");
    }
    const fs::path folder(path);
    std::error_code ec;
    if (!fs::exists(folder, ec)) throw FileError(path, "does not exist");
    if (!fs::is_directory(folder, ec)) {
        throw FileError(path,
                        "is not a folder (expected a simulator recording, a KITTI "
                        "sequence folder with velodyne/, or a folder of .pcd/.ply/.bin)");
    }
    if (fs::exists(folder / recording_layout::kGroundTruth)) {
        return std::make_unique<RecordingSource>(path);
    }
    if (fs::is_directory(folder / "velodyne")) {
        std::vector<std::string> files = cloud_files(folder / "velodyne");
        std::vector<double> stamps = kitti_stamps(folder, files.size(), options.period_s);
        return std::make_unique<FileListSource>(SweepSourceKind::kKittiSequence, path,
                                                std::move(files), std::move(stamps));
    }
    std::vector<std::string> files = cloud_files(folder);
    std::vector<double> stamps = regular_stamps(files.size(), options.period_s);
    return std::make_unique<FileListSource>(SweepSourceKind::kCloudFolder, path, std::move(files),
                                            std::move(stamps));
}

}  // namespace scantling::io
