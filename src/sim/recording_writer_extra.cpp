// Recording streams of the sonar, rosette LiDAR, stereo and the ranging / odometry sensors
// (recording_writer.hpp).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
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
#include <scantling/sim/recording_writer.hpp>

namespace scantling::sim {
namespace fs = std::filesystem;
namespace layout = io::recording_layout;

namespace {

void create_folder(const std::string& dir) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throw FileError(dir, "cannot create directory: " + ec.message());
}

void write_text(const std::string& path, const std::string& text) {
    io::write_file_atomically(path, [&](std::ostream& out) { out << text; });
}

/// Grey levels scaled by the ping's peak, so a weak echo stays visible in a quiet scene.
std::vector<Rgb8> sonar_pixels(const SonarImage& image) {
    const float peak = image.intensity.empty()
                           ? 0.0f
                           : *std::max_element(image.intensity.begin(), image.intensity.end());
    std::vector<Rgb8> pixels(image.intensity.size(), Rgb8::Zero());
    if (!(peak > 0.0f)) return pixels;
    for (int bin = 0; bin < image.num_bins; ++bin) {
        for (int beam = 0; beam < image.num_beams; ++beam) {
            const float level = std::clamp(image.at(beam, bin) / peak, 0.0f, 1.0f);
            pixels[static_cast<std::size_t>(bin) * image.num_beams + beam] =
                Rgb8::Constant(static_cast<std::uint8_t>(std::lround(255.0f * level)));
        }
    }
    return pixels;
}

std::string frame_file(const std::string& folder, std::size_t index, const char* extension) {
    return folder + "/" + layout::frame_stem(index) + extension;
}

void append_csv(std::string& csv, const char* header, const std::string& line) {
    if (csv.empty()) csv = std::string(header) + "\n";
    csv += line + "\n";
}

}  // namespace

void RecordingWriter::write_sonar_meta(const SonarImage& image) const {
    nlohmann::ordered_json json;
    json["num_beams"] = image.num_beams;
    json["num_bins"] = image.num_bins;
    json["layout"] = "NNNNNN.bin: float32 little-endian, index beam * num_bins + bin";
    json["png"] = "columns = beams, rows = bins (near range at the top), grey scaled by the peak";
    json["min_range_m"] = image.min_range_m;
    json["max_range_m"] = image.max_range_m;
    json["horizontal_fov_rad"] = image.horizontal_fov_rad;
    json["bearings_rad"] = image.bearings_rad;
    json["ranges_m"] = image.ranges_m;
    write_text(path(std::string(layout::kSonarDir) + "/" + layout::kSonarMeta),
               json.dump(2) + "\n");
}

void RecordingWriter::add_sonar(const SonarImage& image, const Eigen::Isometry3d& T_world_sensor) {
    const std::string folder = path(layout::kSonarDir);
    if (sonar_.stamps_s.empty()) {
        create_folder(folder);
        write_sonar_meta(image);
    }
    const std::size_t index = sonar_.stamps_s.size();
    io::write_file_atomically(frame_file(folder, index, ".bin"), [&](std::ostream& out) {
        out.write(reinterpret_cast<const char*>(image.intensity.data()),
                  static_cast<std::streamsize>(image.intensity.size() * sizeof(float)));
    });
    io::write_png(frame_file(folder, index, ".png"), image.num_beams, image.num_bins,
                  sonar_pixels(image));
    sonar_.stamps_s.push_back(image.stamp_s);
    sonar_.poses.push_back(T_world_sensor);
    ++counts_.sonar_pings;
}

void RecordingWriter::add_rosette_frame(const PointCloud& frame,
                                        const Eigen::Isometry3d& T_world_sensor) {
    const std::string folder = path(layout::kRosetteDir);
    if (rosette_.stamps_s.empty()) create_folder(folder);
    const std::size_t index = rosette_.stamps_s.size();
    // KITTI readers reject an empty .bin, so a frame without returns is written as PLY.
    if (frame.empty()) {
        io::write_ply(frame_file(folder, index, ".ply"), frame);
    } else {
        io::write_kitti_bin(frame_file(folder, index, ".bin"), frame);
    }
    rosette_.stamps_s.push_back(frame.stamp_s);
    rosette_.poses.push_back(T_world_sensor);
    ++counts_.rosette_frames;
    counts_.rosette_points += static_cast<std::int64_t>(frame.size());
}

void RecordingWriter::add_stereo_frame(const PointCloud& frame,
                                       const Eigen::Isometry3d& T_world_sensor) {
    const std::string folder = path(layout::kStereoDir);
    if (stereo_.stamps_s.empty()) create_folder(folder);
    io::write_ply(frame_file(folder, stereo_.stamps_s.size(), ".ply"), frame);
    stereo_.stamps_s.push_back(frame.stamp_s);
    stereo_.poses.push_back(T_world_sensor);
    ++counts_.stereo_frames;
    counts_.stereo_points += static_cast<std::int64_t>(frame.size());
}

void RecordingWriter::add_range(const RangeMeasurement& m) {
    append_csv(range_csv_, layout::kRangeHeader,
               fmt::format("{},{},{}", m.stamp_s, m.valid ? 1 : 0, m.range_m));
    ++counts_.ranges;
}

void RecordingWriter::add_uwb(const UwbMeasurement& m) {
    for (const UwbRange& r : m.ranges) {
        append_csv(uwb_csv_, layout::kUwbHeader,
                   fmt::format("{},{},{},{},{}", m.stamp_s, r.anchor_id, r.range_m, r.valid ? 1 : 0,
                               r.line_of_sight ? 1 : 0));
    }
    ++counts_.uwb_rounds;
}

void RecordingWriter::add_pressure(const PressureSample& s) {
    append_csv(pressure_csv_, layout::kPressureHeader,
               fmt::format("{},{},{}", s.stamp_s, s.pressure_pa, s.depth_m));
    ++counts_.pressure;
}

void RecordingWriter::add_dvl(const DvlSample& s) {
    const Eigen::Vector3d& v = s.v_body_mps;
    append_csv(dvl_csv_, layout::kDvlHeader,
               fmt::format("{},{},{},{},{},{}", s.stamp_s, s.valid ? 1 : 0, v.x(), v.y(), v.z(),
                           s.altitude_m));
    ++counts_.dvl;
}

void RecordingWriter::add_wheel_odometry(const WheelOdometrySample& s) {
    append_csv(wheel_odometry_csv_, layout::kWheelOdometryHeader,
               fmt::format("{},{},{},{}", s.stamp_s, s.forward_speed_mps, s.yaw_rate_radps,
                           s.slipping ? 1 : 0));
    ++counts_.wheel_odometry;
}

void RecordingWriter::add_barometer(const BarometerSample& s) {
    append_csv(barometer_csv_, layout::kBarometerHeader,
               fmt::format("{},{}", s.stamp_s, s.altitude_m));
    ++counts_.barometer;
}

void RecordingWriter::finish_extra() const {
    write_stream(layout::kSonarDir, sonar_);
    write_stream(layout::kRosetteDir, rosette_);
    write_stream(layout::kStereoDir, stereo_);
    const std::pair<const char*, const std::string*> csvs[] = {
        {layout::kRange, &range_csv_},
        {layout::kUwb, &uwb_csv_},
        {layout::kPressure, &pressure_csv_},
        {layout::kDvl, &dvl_csv_},
        {layout::kWheelOdometry, &wheel_odometry_csv_},
        {layout::kBarometer, &barometer_csv_}};
    for (const auto& [name, csv] : csvs) {
        if (!csv->empty()) write_text(path(name), *csv);
    }
}

}  // namespace scantling::sim
