// Recording output in the layout of io/recording.hpp (recording_writer.hpp).
#include <scantling/sim/recording_writer.hpp>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <ostream>
#include <system_error>

#include <scantling/core/error.hpp>
#include <scantling/io/atomic_file.hpp>
#include <scantling/io/kitti.hpp>
#include <scantling/io/ply.hpp>
#include <scantling/io/png.hpp>
#include <scantling/io/recording.hpp>

namespace scantling::sim {
namespace fs = std::filesystem;
namespace layout = io::recording_layout;

namespace {

/// An existing non-empty folder: refused without --force, and with it unless a recording.
io::OutputTransaction::ReplaceCheck replace_check(const std::string& directory, bool overwrite) {
    return [directory, overwrite](const std::string&) {
        if (!overwrite) {
            throw FileError(directory,
                            "output directory is not empty (use --force to replace a recording)");
        }
        check_replaceable_recording(directory);
    };
}

void create_folder(const fs::path& dir) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throw FileError(dir.string(), "cannot create directory: " + ec.message());
}

/// `{}` formats doubles as the shortest text that reads back to the same value.
void append_vector(std::string& line, const Eigen::Vector3d& v) {
    line += fmt::format(",{},{},{}", v.x(), v.y(), v.z());
}

void write_text(const std::string& path, const std::string& text) {
    io::write_file_atomically(path, [&](std::ostream& out) { out << text; });
}

}  // namespace

RecordingWriter::RecordingWriter(std::string directory, bool overwrite)
    : directory_(std::move(directory)),
      staging_directory_(
          transaction_.stage_folder(directory_, replace_check(directory_, overwrite))) {
    imu_csv_ = std::string(layout::kImuHeader) + "\n";
    vio_csv_ = std::string(layout::kVioFeatureQualityHeader) + "\n";
    visible_defects_csv_ = std::string(layout::kVisibleDefectsHeader) + "\n";
    defect_sightings_csv_ = std::string(layout::kDefectSightingsHeader) + "\n";
}

std::string RecordingWriter::path(const std::string& relative) const {
    return (fs::path(staging_directory_) / relative).string();
}

void RecordingWriter::write_world(const World& world, const WorldExportConfig& config) {
    sim::write_world(path(layout::kWorldDir), world, config);
}

void RecordingWriter::add_ground_truth(double stamp_s, const Eigen::Isometry3d& T_world_body) {
    ground_truth_.push_back({stamp_s, T_world_body});
    ++counts_.ground_truth;
}

void RecordingWriter::add_lidar_sweep(const PointCloud& sweep,
                                      const Eigen::Isometry3d& T_world_sensor, bool with_ply) {
    if (lidar_.stamps_s.empty()) create_folder(path(layout::kLidarDir));
    const std::string stem =
        path(std::string(layout::kLidarDir) + "/" + layout::frame_stem(lidar_.stamps_s.size()));
    // KITTI readers reject an empty .bin, so a sweep without returns is written as PLY only.
    if (!sweep.empty()) io::write_kitti_bin(stem + ".bin", sweep);
    if (with_ply || sweep.empty()) io::write_ply(stem + ".ply", sweep);
    lidar_.stamps_s.push_back(sweep.stamp_s);
    lidar_.poses.push_back(T_world_sensor);
    ++counts_.lidar_sweeps;
    counts_.lidar_points += static_cast<std::int64_t>(sweep.size());
}

void RecordingWriter::set_lidar_extrinsic(const Eigen::Isometry3d& T_body_sensor) {
    has_lidar_extrinsic_ = true;
    lidar_T_body_sensor_ = T_body_sensor;
}

void RecordingWriter::add_depth_frame(const PointCloud& frame,
                                      const Eigen::Isometry3d& T_world_sensor) {
    if (depth_.stamps_s.empty()) create_folder(path(layout::kDepthDir));
    io::write_ply(path(std::string(layout::kDepthDir) + "/" +
                       layout::frame_stem(depth_.stamps_s.size()) + ".ply"),
                  frame);
    depth_.stamps_s.push_back(frame.stamp_s);
    depth_.poses.push_back(T_world_sensor);
    ++counts_.depth_frames;
}

void RecordingWriter::set_depth_extrinsic(const Eigen::Isometry3d& T_body_sensor) {
    depth_T_body_sensor_ = T_body_sensor;
}

void RecordingWriter::add_image(const RgbImage& image, double stamp_s,
                                const Eigen::Isometry3d& T_world_sensor,
                                std::span<const io::DefectSighting> sightings) {
    if (images_.stamps_s.empty()) create_folder(path(layout::kImagesDir));
    const std::size_t index = images_.stamps_s.size();
    std::vector<int> ids;
    for (const io::DefectSighting& s : sightings) {
        ids.push_back(s.defect_id);
        defect_sightings_csv_ += fmt::format("{},{},{},{},{},{}\n", index, stamp_s, s.defect_id,
                                             s.pixel.x(), s.pixel.y(), s.radius_px);
    }
    visible_defects_csv_ += fmt::format("{},{},{}\n", index, stamp_s, fmt::join(ids, ";"));
    io::write_png(path(std::string(layout::kImagesDir) + "/" +
                       layout::frame_stem(images_.stamps_s.size()) + ".png"),
                  image.width, image.height, image.pixels);
    images_.stamps_s.push_back(stamp_s);
    images_.poses.push_back(T_world_sensor);
    ++counts_.images;
}

void RecordingWriter::set_image_camera(const PinholeIntrinsics& intrinsics,
                                       const Eigen::Isometry3d& T_body_sensor) {
    image_intrinsics_ = intrinsics;
    image_T_body_sensor_ = T_body_sensor;
}

void RecordingWriter::add_imu(const ImuSample& sample) {
    std::string line = fmt::format("{}", sample.stamp_s);
    append_vector(line, sample.specific_force_mps2);
    append_vector(line, sample.angular_rate_radps);
    imu_csv_ += line + "\n";
    ++counts_.imu;
}

void RecordingWriter::add_vio(const VioSample& sample) {
    const Eigen::Quaterniond q(sample.T_odom_body.rotation());
    std::string line = fmt::format("{},{}", sample.stamp_s, sample.valid ? 1 : 0);
    append_vector(line, sample.T_odom_body.translation());
    line += fmt::format(",{},{},{},{}", q.x(), q.y(), q.z(), q.w());
    append_vector(line, sample.v_body_mps);
    for (int k = 0; k < 6; ++k) line += fmt::format(",{}", sample.covariance(k, k));
    line += fmt::format(",{}", sample.feature_quality);
    vio_csv_ += line + "\n";
    ++counts_.vio;
}

void RecordingWriter::write_stream(const std::string& folder, const Stream& stream) const {
    if (stream.stamps_s.empty()) return;
    std::string times;
    for (double t : stream.stamps_s) times += fmt::format("{}\n", t);
    write_text(path(folder + "/" + layout::kTimes), times);
    io::write_kitti_poses(path(folder + "/" + layout::kPoses), stream.poses);
}

void RecordingWriter::write_extrinsic(const std::string& folder,
                                      const Eigen::Isometry3d& T_body_sensor) const {
    const Eigen::Isometry3d extrinsic[] = {T_body_sensor};
    io::write_kitti_poses(path(folder + "/" + layout::kExtrinsic), extrinsic);
}

void RecordingWriter::finish(const RecordingSummary& summary) {
    if (!ground_truth_.empty()) io::write_tum(path(layout::kGroundTruth), ground_truth_);
    write_stream(layout::kLidarDir, lidar_);
    if (has_lidar_extrinsic_ && !lidar_.stamps_s.empty()) {
        write_extrinsic(layout::kLidarDir, lidar_T_body_sensor_);
    }
    write_stream(layout::kDepthDir, depth_);
    if (depth_T_body_sensor_ && !depth_.stamps_s.empty()) {
        write_extrinsic(layout::kDepthDir, *depth_T_body_sensor_);
    }
    write_stream(layout::kImagesDir, images_);
    if (counts_.images > 0) {
        const std::string images = std::string(layout::kImagesDir) + "/";
        write_text(path(images + layout::kVisibleDefects), visible_defects_csv_);
        write_text(path(images + layout::kDefectSightings), defect_sightings_csv_);
        if (image_intrinsics_) {
            write_text(path(images + layout::kCameraIntrinsics),
                       io::camera_intrinsics_json(*image_intrinsics_));
            write_extrinsic(layout::kImagesDir, image_T_body_sensor_);
        }
    }
    if (counts_.imu > 0) write_text(path(layout::kImu), imu_csv_);
    if (counts_.vio > 0) write_text(path(layout::kVio), vio_csv_);
    finish_extra();
    write_text(path(layout::kSummary), summary_json(summary));
}

std::string RecordingWriter::summary_json(const RecordingSummary& summary) const {
    nlohmann::ordered_json json;
    json["scenario"] = summary.scenario;
    json["description"] = summary.description;
    json["world"] = summary.world;
    json["duration_s"] = summary.duration_s;
    json["dt_s"] = summary.dt_s;
    json["seed"] = summary.seed;
    nlohmann::ordered_json sensors = nlohmann::ordered_json::array();
    for (const auto& [name, rate_hz] : summary.sensors) {
        sensors.push_back({{"type", name}, {"rate_hz", rate_hz}});
    }
    json["sensors"] = sensors;
    json["counts"] = {{"ground_truth", counts_.ground_truth},
                      {"lidar_sweeps", counts_.lidar_sweeps},
                      {"lidar_points", counts_.lidar_points},
                      {"depth_frames", counts_.depth_frames},
                      {"images", counts_.images},
                      {"imu", counts_.imu},
                      {"vio", counts_.vio},
                      {"sonar_pings", counts_.sonar_pings},
                      {"rosette_frames", counts_.rosette_frames},
                      {"rosette_points", counts_.rosette_points},
                      {"stereo_frames", counts_.stereo_frames},
                      {"stereo_points", counts_.stereo_points},
                      {"ranges", counts_.ranges},
                      {"uwb_rounds", counts_.uwb_rounds},
                      {"pressure", counts_.pressure},
                      {"dvl", counts_.dvl},
                      {"wheel_odometry", counts_.wheel_odometry}};
    return json.dump(2) + "\n";
}

void RecordingWriter::write_timing(double wall_time_s, double real_time_factor) const {
    nlohmann::ordered_json json;
    json["wall_time_s"] = wall_time_s;
    json["real_time_factor"] = real_time_factor;
    write_text(path(layout::kTiming), json.dump(2) + "\n");
}

void RecordingWriter::commit() { transaction_.commit(); }

}  // namespace scantling::sim
