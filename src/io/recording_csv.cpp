// Text files of a simulator recording: stamps, IMU and VIO CSVs (recording.hpp).
#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <limits>

#include <scantling/core/error.hpp>
#include <scantling/core/se3.hpp>
#include <scantling/io/mission_log.hpp>
#include <scantling/io/recording.hpp>

#include "detail/stamp_file.hpp"
#include "detail/text_lines.hpp"

namespace scantling::io {
namespace {

using detail::LineContext;
using detail::StampFile;
using detail::TextLine;

FileLocation at_line(int line) {
    FileLocation location;
    location.line = line;
    return location;
}

std::vector<std::string_view> split_commas(std::string_view text) {
    std::vector<std::string_view> fields;
    std::size_t start = 0;
    while (true) {
        const std::size_t comma = text.find(',', start);
        fields.push_back(detail::trim(text.substr(start, comma - start)));
        if (comma == std::string_view::npos) return fields;
        start = comma + 1;
    }
}

/// The header among `headers` that the first line of `reader` matches (ParseError otherwise).
std::string_view match_header(const std::string& path, detail::LineReader& reader,
                              std::initializer_list<std::string_view> headers) {
    TextLine line;
    if (reader.next(line)) {
        for (std::string_view header : headers) {
            if (detail::trim(line.text) == header) return header;
        }
    }
    throw ParseError(path, at_line(1), fmt::format("expected the header '{}'", *headers.begin()));
}

/// How the stamps (first column) of a file must follow each other. UWB rows share the stamp of
/// their ranging round (one row per anchor); every other stream has one row per sample.
enum class StampOrder { kIncreasing, kNonDecreasing };

/// Where the previous stamp of a file was, so that a stamp going backwards (or repeating) can
/// be refused naming both lines: the readers integrate over stamp differences, and a zero or
/// negative one would be a division by zero or time running backwards, not a sample.
struct StampCheck {
    StampOrder order = StampOrder::kIncreasing;
    double previous_s = 0.0;
    int previous_line = 0;  ///< 0 before the first stamp

    void next(double stamp_s, const std::string& path, int line) {
        if (!std::isfinite(stamp_s)) {
            throw ParseError(path, at_line(line),
                             fmt::format("stamp {} is not a finite number of seconds", stamp_s));
        }
        const bool in_order =
            order == StampOrder::kIncreasing ? stamp_s > previous_s : stamp_s >= previous_s;
        if (previous_line > 0 && !in_order) {
            throw ParseError(path, at_line(line),
                             fmt::format("stamp {} s is not after the previous one ({} s, line "
                                         "{}), expected stamps that {}",
                                         stamp_s, previous_s, previous_line,
                                         order == StampOrder::kIncreasing ? "increase strictly"
                                                                          : "never decrease"));
        }
        previous_s = stamp_s;
        previous_line = line;
    }
};

/// Every non-blank line after the header as parsed numbers, one per column of the header
/// found (any of `headers`); the first column is the stamp, in `order`.
template <class Row>
std::vector<Row> read_csv(const std::string& path, std::initializer_list<std::string_view> headers,
                          Row (*make)(const std::vector<double>&),
                          detail::NonFinite non_finite = detail::NonFinite::kReject,
                          StampOrder order = StampOrder::kIncreasing) {
    const std::string text = detail::read_whole_file(path);
    detail::LineReader reader(text);
    const std::size_t columns = split_commas(match_header(path, reader, headers)).size();
    std::vector<Row> rows;
    std::vector<double> values(columns);
    StampCheck stamps{.order = order};
    TextLine line;
    while (reader.next(line)) {
        if (detail::trim(line.text).empty()) continue;
        const std::vector<std::string_view> fields = split_commas(line.text);
        const LineContext where{path, line};
        if (fields.size() != columns) {
            throw ParseError(
                path, at_line(line.number),
                fmt::format("expected {} comma-separated values, got {}", columns, fields.size()));
        }
        for (std::size_t c = 0; c < columns; ++c)
            values[c] = detail::parse_double(fields[c], where, non_finite);
        stamps.next(values[0], path, line.number);
        rows.push_back(make(values));
    }
    return rows;
}

ImuRecord make_imu(const std::vector<double>& v) {
    return ImuRecord{v[0], Eigen::Vector3d(v[1], v[2], v[3]), Eigen::Vector3d(v[4], v[5], v[6])};
}

VioRecord make_vio(const std::vector<double>& v) {
    VioRecord record;
    record.stamp_s = v[0];
    record.valid = v[1] != 0.0;
    const Eigen::Quaterniond q(v[8], v[5], v[6], v[7]);  // w, x, y, z
    record.T_odom_body.linear() = q.normalized().toRotationMatrix();
    record.T_odom_body.translation() = Eigen::Vector3d(v[2], v[3], v[4]);
    record.v_body_mps = Eigen::Vector3d(v[9], v[10], v[11]);
    for (int k = 0; k < 6; ++k) record.variances[k] = v[12 + static_cast<std::size_t>(k)];
    if (v.size() > 18) record.feature_quality = v[18];
    return record;
}

/// "3;7;12" → {3, 7, 12}; "" → {}.
std::vector<int> parse_ids(std::string_view field, const LineContext& where) {
    std::vector<int> ids;
    if (field.empty()) return ids;
    std::size_t start = 0;
    while (true) {
        const std::size_t semicolon = field.find(';', start);
        const std::string_view token = detail::trim(field.substr(start, semicolon - start));
        ids.push_back(static_cast<int>(detail::parse_int(token, where)));
        if (semicolon == std::string_view::npos) return ids;
        start = semicolon + 1;
    }
}

RangeRecord make_range(const std::vector<double>& v) { return {v[0], v[1] != 0.0, v[2]}; }

UwbRecord make_uwb(const std::vector<double>& v) {
    return {v[0], static_cast<int>(v[1]), v[2], v[3] != 0.0, v[4] != 0.0};
}

PressureRecord make_pressure(const std::vector<double>& v) { return {v[0], v[1], v[2]}; }

DvlRecord make_dvl(const std::vector<double>& v) {
    return {v[0], v[1] != 0.0, Eigen::Vector3d(v[2], v[3], v[4]), v[5]};
}

WheelOdometryRecord make_wheel(const std::vector<double>& v) {
    return {v[0], v[1], v[2], v[3] != 0.0};
}

BarometerRecord make_barometer(const std::vector<double>& v) { return {v[0], v[1]}; }

// Invalid readings are written as "nan", so these files allow non-finite numbers.
constexpr detail::NonFinite kAllowNan = detail::NonFinite::kAllow;

}  // namespace

std::vector<RangeRecord> read_range_csv(const std::string& path) {
    return read_csv<RangeRecord>(path, {recording_layout::kRangeHeader}, &make_range, kAllowNan);
}

std::vector<UwbRecord> read_uwb_csv(const std::string& path) {
    return read_csv<UwbRecord>(path, {recording_layout::kUwbHeader}, &make_uwb, kAllowNan,
                               StampOrder::kNonDecreasing);
}

std::vector<PressureRecord> read_pressure_csv(const std::string& path) {
    return read_csv<PressureRecord>(path, {recording_layout::kPressureHeader}, &make_pressure);
}

std::vector<DvlRecord> read_dvl_csv(const std::string& path) {
    return read_csv<DvlRecord>(path, {recording_layout::kDvlHeader}, &make_dvl, kAllowNan);
}

std::vector<WheelOdometryRecord> read_wheel_odometry_csv(const std::string& path) {
    return read_csv<WheelOdometryRecord>(path, {recording_layout::kWheelOdometryHeader},
                                         &make_wheel);
}

std::vector<BarometerRecord> read_barometer_csv(const std::string& path) {
    return read_csv<BarometerRecord>(path, {recording_layout::kBarometerHeader}, &make_barometer);
}

std::string recording_layout::frame_stem(std::size_t index) { return fmt::format("{:06d}", index); }

std::vector<ImuRecord> read_imu_csv(const std::string& path) {
    return read_csv<ImuRecord>(path, {recording_layout::kImuHeader}, &make_imu);
}

std::vector<VioRecord> read_vio_csv(const std::string& path) {
    return read_csv<VioRecord>(
        path, {recording_layout::kVioFeatureQualityHeader, recording_layout::kVioHeader},
        &make_vio);
}

std::vector<std::vector<int>> read_visible_defects_csv(const std::string& path) {
    const std::string text = detail::read_whole_file(path);
    detail::LineReader reader(text);
    match_header(path, reader, {recording_layout::kVisibleDefectsHeader});
    std::vector<std::vector<int>> rows;
    StampCheck stamps;
    TextLine line;
    while (reader.next(line)) {
        if (detail::trim(line.text).empty()) continue;
        const std::vector<std::string_view> fields = split_commas(line.text);
        const LineContext where{path, line};
        if (fields.size() != 3) {
            throw ParseError(
                path, at_line(line.number),
                fmt::format("expected 3 comma-separated values, got {}", fields.size()));
        }
        if (detail::parse_int(fields[0], where) != static_cast<std::int64_t>(rows.size())) {
            throw ParseError(path, at_line(line.number),
                             fmt::format("expected image index {}", rows.size()));
        }
        stamps.next(detail::parse_double(fields[1], where), path, line.number);
        rows.push_back(parse_ids(fields[2], where));
    }
    return rows;
}

namespace {

DefectSighting parse_sighting(const std::vector<std::string_view>& fields, const LineContext& where,
                              std::size_t previous_image) {
    const auto fail = [&where](const std::string& what) {
        throw ParseError(where.path, at_line(where.line.number), what);
    };
    const std::int64_t image = detail::parse_int(fields[0], where);
    if (image < static_cast<std::int64_t>(previous_image)) {
        fail(fmt::format("image index {} after {}, expected indices that never decrease", image,
                         previous_image));
    }
    DefectSighting sighting;
    sighting.image = static_cast<std::size_t>(image);
    sighting.stamp_s = detail::parse_double(fields[1], where);
    const std::int64_t id = detail::parse_int(fields[2], where);
    if (id < 0 || id > std::numeric_limits<int>::max()) {
        fail(fmt::format("defect_id {}, expected an id >= 0", id));
    }
    sighting.defect_id = static_cast<int>(id);
    sighting.pixel = {detail::parse_double(fields[3], where),
                      detail::parse_double(fields[4], where)};
    sighting.radius_px = detail::parse_double(fields[5], where);
    if (!(sighting.radius_px >= 0.0)) {
        fail(fmt::format("radius_px {}, expected >= 0", sighting.radius_px));
    }
    return sighting;
}

}  // namespace

std::vector<DefectSighting> read_defect_sightings_csv(const std::string& path) {
    const std::string text = detail::read_whole_file(path);
    detail::LineReader reader(text);
    match_header(path, reader, {recording_layout::kDefectSightingsHeader});
    std::vector<DefectSighting> rows;
    TextLine line;
    while (reader.next(line)) {
        if (detail::trim(line.text).empty()) continue;
        const std::vector<std::string_view> fields = split_commas(line.text);
        if (fields.size() != 6) {
            throw ParseError(
                path, at_line(line.number),
                fmt::format("expected 6 comma-separated values, got {}", fields.size()));
        }
        rows.push_back(
            parse_sighting(fields, LineContext{path, line}, rows.empty() ? 0 : rows.back().image));
    }
    return rows;
}

detail::StampFile detail::read_stamp_file(const std::string& path) {
    const std::string text = detail::read_whole_file(path);
    detail::LineReader reader(text);
    TextLine line;
    StampFile file;
    StampCheck check;
    while (reader.next(line)) {
        const std::string_view token = detail::trim(line.text);
        if (token.empty()) continue;
        const double stamp_s = detail::parse_double(token, LineContext{path, line});
        check.next(stamp_s, path, line.number);
        file.stamps_s.push_back(stamp_s);
        file.lines.push_back(line.number);
    }
    return file;
}

std::vector<double> read_stamps(const std::string& path) {
    return detail::read_stamp_file(path).stamps_s;
}

}  // namespace scantling::io

// The closed loop's CSVs (mission_log.hpp), read with the same checks as the sensor CSVs.
namespace scantling::io {
namespace {

EstimateRecord make_estimate(const std::vector<double>& v) {
    EstimateRecord record;
    record.stamp_s = v[0];
    record.T_world_body.translation() = Eigen::Vector3d(v[1], v[2], v[3]);
    record.v_world_mps = Eigen::Vector3d(v[4], v[5], v[6]);
    record.T_world_body.linear() = rotation_from_euler_zyx(v[7], v[8], v[9]);
    record.position_sigma_m = Eigen::Vector3d(v[10], v[11], v[12]);
    record.yaw_sigma_rad = v[13];
    record.valid = v[14] != 0.0;
    return record;
}

CommandRecord make_command(const std::vector<double>& v) {
    return {v[0], Eigen::Vector3d(v[1], v[2], v[3]), v[4], Eigen::Vector3d(v[5], v[6], v[7]),
            v[8] != 0.0};
}

PathPointRecord make_path_point(const std::vector<double>& v) {
    return {Eigen::Vector3d(v[1], v[2], v[3]), v[4]};
}

}  // namespace

std::vector<EstimateRecord> read_estimates_csv(const std::string& path) {
    // An estimate lost by the estimator is written as NaN with valid = 0.
    return read_csv<EstimateRecord>(path, {recording_layout::kMissionEstimatesHeader},
                                    &make_estimate, kAllowNan);
}

std::vector<CommandRecord> read_commands_csv(const std::string& path) {
    return read_csv<CommandRecord>(path, {recording_layout::kMissionCommandsHeader}, &make_command);
}

std::vector<PathPointRecord> read_intended_path_csv(const std::string& path) {
    return read_csv<PathPointRecord>(path, {recording_layout::kMissionPathHeader},
                                     &make_path_point);
}

}  // namespace scantling::io
