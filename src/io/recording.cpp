// Reader of simulator recordings (recording.hpp).
#include <scantling/io/recording.hpp>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string_view>

#include <scantling/core/error.hpp>
#include <scantling/io/kitti.hpp>
#include <scantling/io/ply.hpp>

#include "detail/stamp_file.hpp"

namespace scantling::io {
namespace fs = std::filesystem;
namespace layout = recording_layout;

namespace {

std::string join(const std::string& a, const std::string& b) { return (fs::path(a) / b).string(); }

FileLocation at_line(int line) { return {.byte_offset = {}, .line = line, .column = {}}; }

/// Extensions of frame files ("NNNNNN.bin"); any of them in a stream's folder needs a stamp.
constexpr std::array<std::string_view, 3> kFrameExtensions{".bin", ".ply", ".png"};
constexpr std::size_t kFrameStemDigits = 6;

/// Frame index of `file` ("000042.bin" → 42; stems of 6 or more digits, as frame_stem writes
/// them), or nullopt for a file that is not a frame. Too many digits for size_t: SIZE_MAX.
std::optional<std::size_t> frame_number(const fs::path& file) {
    const std::string extension = file.extension().string();
    if (std::find(kFrameExtensions.begin(), kFrameExtensions.end(), extension) ==
        kFrameExtensions.end()) {
        return std::nullopt;
    }
    const std::string stem = file.stem().string();
    if (stem.size() < kFrameStemDigits ||
        !std::all_of(stem.begin(), stem.end(), [](char c) { return c >= '0' && c <= '9'; })) {
        return std::nullopt;
    }
    std::size_t index = 0;
    const auto [end, ec] = std::from_chars(stem.data(), stem.data() + stem.size(), index);
    return ec == std::errc() ? index : SIZE_MAX;
}

/// Every stamp of `times` has a frame file with one of `readable` extensions (what the
/// stream's reader opens), and every frame file in the folder has a stamp.
void check_frame_files(const std::string& folder, const std::string& times_path,
                       const detail::StampFile& times,
                       std::initializer_list<std::string_view> readable) {
    const std::size_t count = times.stamps_s.size();
    std::vector<bool> has_file(count, false);
    std::optional<fs::path> first_extra;  // the lowest-numbered frame file without a stamp
    for (const auto& entry : fs::directory_iterator(folder)) {
        const std::optional<std::size_t> i = frame_number(entry.path());
        if (!i || !entry.is_regular_file()) continue;
        if (*i >= count) {
            if (!first_extra || *i < *frame_number(*first_extra)) first_extra = entry.path();
            continue;
        }
        const std::string extension = entry.path().extension().string();
        if (std::find(readable.begin(), readable.end(), extension) != readable.end()) {
            has_file[*i] = true;
        }
    }
    if (first_extra) {
        throw ParseError(times_path, FileLocation{},
                         fmt::format("{} stamps, but the frame file {} has none (expected one "
                                     "stamp per frame file)",
                                     count, first_extra->string()));
    }
    const auto missing = std::find(has_file.begin(), has_file.end(), false);
    if (missing == has_file.end()) return;
    const auto i = static_cast<std::size_t>(missing - has_file.begin());
    throw ParseError(times_path, at_line(times.lines[i]),
                     fmt::format("the stamp of frame {} has no frame file: expected {}{}", i,
                                 join(folder, layout::frame_stem(i)), fmt::join(readable, " or ")));
}

/// The stamps and poses of a frame folder, or an empty index when the folder is absent.
/// `readable`: the extensions of the frame files the stream's reader opens.
FrameIndex read_frame_index(const std::string& directory, const char* folder,
                            std::initializer_list<std::string_view> readable) {
    FrameIndex index;
    const std::string dir = join(directory, folder);
    if (!fs::is_directory(dir)) return index;
    index.directory = dir;
    const std::string times_path = join(dir, layout::kTimes), poses = join(dir, layout::kPoses);
    const detail::StampFile times = detail::read_stamp_file(times_path);
    index.stamps_s = times.stamps_s;
    index.poses_gt = read_kitti_poses(poses);
    if (index.poses_gt.size() != index.stamps_s.size()) {
        throw ParseError(poses, FileLocation{},
                         fmt::format("{} poses but {} has {} stamps", index.poses_gt.size(),
                                     times_path, index.stamps_s.size()));
    }
    check_frame_files(dir, times_path, times, readable);
    return index;
}

/// A mounting extrinsic (lidar/, depth/): exactly one KITTI 3×4 line.
Eigen::Isometry3d read_extrinsic(const std::string& path) {
    const std::vector<Eigen::Isometry3d> poses = read_kitti_poses(path);
    if (poses.size() != 1) {
        throw ParseError(
            path, FileLocation{},
            fmt::format("{} poses, expected exactly one (T_body_sensor)", poses.size()));
    }
    return poses.front();
}

void check_index(std::size_t i, std::size_t size, const char* what, const std::string& directory) {
    if (i >= size) {
        throw InputError(fmt::format("{}: {} index {} out of range (the recording has {})",
                                     directory, what, i, size));
    }
}

std::string frame_path(const FrameIndex& index, std::size_t i, const char* extension) {
    return join(index.directory, layout::frame_stem(i) + extension);
}

}  // namespace

PointCloud Recording::read_sweep(std::size_t i) const {
    check_index(i, lidar_.size(), "sweep", directory_);
    const std::string ply = frame_path(lidar_, i, ".ply");
    // The PLY carries rings and times besides what the .bin holds (same float32 values).
    PointCloud sweep =
        fs::exists(ply) ? read_ply(ply).cloud : read_kitti_bin(frame_path(lidar_, i, ".bin"));
    sweep.stamp_s = lidar_.stamps_s[i];
    return sweep;
}

double Recording::sweep_stamp_s(std::size_t i) const {
    check_index(i, lidar_.size(), "sweep", directory_);
    return lidar_.stamps_s[i];
}

const Eigen::Isometry3d& Recording::sweep_pose_gt(std::size_t i) const {
    check_index(i, lidar_.size(), "sweep", directory_);
    return lidar_.poses_gt[i];
}

PointCloud Recording::read_depth_frame(std::size_t i) const {
    check_index(i, depth_.size(), "depth frame", directory_);
    PointCloud frame = read_ply(frame_path(depth_, i, ".ply")).cloud;
    frame.stamp_s = depth_.stamps_s[i];
    return frame;
}

std::string Recording::image_path(std::size_t i) const {
    check_index(i, images_.size(), "image", directory_);
    return frame_path(images_, i, ".png");
}

PointCloud Recording::read_rosette_frame(std::size_t i) const {
    check_index(i, rosette_.size(), "rosette frame", directory_);
    const std::string bin = frame_path(rosette_, i, ".bin");
    // An empty frame has no .bin (KITTI readers reject it), only a .ply.
    PointCloud frame =
        fs::exists(bin) ? read_kitti_bin(bin) : read_ply(frame_path(rosette_, i, ".ply")).cloud;
    frame.stamp_s = rosette_.stamps_s[i];
    return frame;
}

PointCloud Recording::read_stereo_frame(std::size_t i) const {
    check_index(i, stereo_.size(), "stereo frame", directory_);
    PointCloud frame = read_ply(frame_path(stereo_, i, ".ply")).cloud;
    frame.stamp_s = stereo_.stamps_s[i];
    return frame;
}

std::vector<float> Recording::read_sonar_intensity(std::size_t i) const {
    check_index(i, sonar_.size(), "sonar ping", directory_);
    const std::string path = frame_path(sonar_, i, ".bin");
    std::ifstream in(path, std::ios::binary | std::ios::ate);
    if (!in) throw FileError(path, "cannot open sonar ping");
    const auto bytes = static_cast<std::size_t>(in.tellg());
    if (bytes % sizeof(float) != 0) {
        throw ParseError(path, FileLocation{},
                         fmt::format("size {} bytes is not a multiple of 4 (float32)", bytes));
    }
    std::vector<float> intensity(bytes / sizeof(float));
    in.seekg(0);
    in.read(reinterpret_cast<char*>(intensity.data()), static_cast<std::streamsize>(bytes));
    if (!in)
        throw FileError(path, fmt::format("cannot read the {} bytes of the sonar ping", bytes));
    return intensity;
}

std::string Recording::world_map_path() const {
    return join(join(directory_, layout::kWorldDir), "map.ply");
}

std::string Recording::world_mesh_path() const {
    return join(join(directory_, layout::kWorldDir), "mesh.ply");
}

std::string Recording::world_metadata_path() const {
    return join(join(directory_, layout::kWorldDir), "metadata.json");
}

Recording open_recording(const std::string& directory) {
    if (!fs::is_directory(directory)) throw FileError(directory, "recording directory not found");
    const std::string ground_truth = join(directory, layout::kGroundTruth);
    if (!fs::exists(ground_truth)) {
        throw FileError(ground_truth, "missing: not a scantling recording (no ground truth)");
    }
    Recording recording;
    recording.directory_ = directory;
    recording.ground_truth_ = read_tum(ground_truth);
    // An empty LiDAR sweep or rosette frame is written as .ply alone (KITTI .bin cannot be empty).
    recording.lidar_ = read_frame_index(directory, layout::kLidarDir, {".bin", ".ply"});
    recording.depth_ = read_frame_index(directory, layout::kDepthDir, {".ply"});
    recording.images_ = read_frame_index(directory, layout::kImagesDir, {".png"});
    recording.read_visible_defects();
    recording.read_image_camera();
    const std::string extrinsic = join(join(directory, layout::kLidarDir), layout::kExtrinsic);
    if (fs::exists(extrinsic)) recording.lidar_T_body_sensor_ = read_extrinsic(extrinsic);
    const std::string depth_extrinsic =
        join(join(directory, layout::kDepthDir), layout::kExtrinsic);
    if (fs::exists(depth_extrinsic))
        recording.depth_T_body_sensor_ = read_extrinsic(depth_extrinsic);
    const std::string imu = join(directory, layout::kImu), vio = join(directory, layout::kVio);
    if (fs::exists(imu)) recording.imu_ = read_imu_csv(imu);
    if (fs::exists(vio)) recording.vio_ = read_vio_csv(vio);
    recording.read_extra_streams(directory);
    return recording;
}

void Recording::read_visible_defects() {
    if (images_.directory.empty()) return;
    const std::string path = join(images_.directory, layout::kVisibleDefects);
    if (!fs::exists(path)) return;
    image_visible_defects_ = read_visible_defects_csv(path);
    if (image_visible_defects_.size() != images_.size()) {
        throw ParseError(path, FileLocation{},
                         fmt::format("{} rows but {} has {} stamps", image_visible_defects_.size(),
                                     join(images_.directory, layout::kTimes), images_.size()));
    }
}

void Recording::read_image_camera() {
    if (images_.directory.empty()) return;
    const std::string intrinsics = join(images_.directory, layout::kCameraIntrinsics);
    if (fs::exists(intrinsics)) image_intrinsics_ = read_camera_intrinsics(intrinsics);
    const std::string extrinsic = join(images_.directory, layout::kExtrinsic);
    if (fs::exists(extrinsic)) image_T_body_sensor_ = read_extrinsic(extrinsic);
    const std::string path = join(images_.directory, layout::kDefectSightings);
    if (!fs::exists(path)) return;
    defect_sightings_ = read_defect_sightings_csv(path);
    // A sighting must name an image and carry its stamp (to the microsecond: writers print
    // stamps with different digits): the lifting looks the pose up there.
    for (const DefectSighting& s : defect_sightings_) {
        if (s.image >= images_.size() || std::abs(s.stamp_s - images_.stamps_s[s.image]) > 1e-6) {
            throw ParseError(
                path, FileLocation{},
                fmt::format("sighting of defect {} in image {} at {} s, but {} has {} stamps{}",
                            s.defect_id, s.image, s.stamp_s,
                            join(images_.directory, layout::kTimes), images_.size(),
                            s.image < images_.size()
                                ? fmt::format(" and image {} is at {} s", s.image,
                                              images_.stamps_s[s.image])
                                : std::string()));
        }
    }
}

void Recording::read_extra_streams(const std::string& directory) {
    rosette_ = read_frame_index(directory, layout::kRosetteDir, {".bin", ".ply"});
    stereo_ = read_frame_index(directory, layout::kStereoDir, {".ply"});
    sonar_ = read_frame_index(directory, layout::kSonarDir, {".bin"});
    const auto read_if = [&directory](const char* name, auto reader, auto& out) {
        const std::string path = join(directory, name);
        if (fs::exists(path)) out = reader(path);
    };
    read_if(layout::kRange, &read_range_csv, range_);
    read_if(layout::kUwb, &read_uwb_csv, uwb_);
    read_if(layout::kPressure, &read_pressure_csv, pressure_);
    read_if(layout::kDvl, &read_dvl_csv, dvl_);
    read_if(layout::kWheelOdometry, &read_wheel_odometry_csv, wheel_odometry_);
    read_if(layout::kBarometer, &read_barometer_csv, barometer_);
}

}  // namespace scantling::io
