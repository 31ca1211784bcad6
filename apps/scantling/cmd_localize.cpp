// `scantling localize RECORDING --out DIR`: absolute localisation over a recording.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>

#include <scantling/core/error.hpp>
#include <scantling/io/atomic_file.hpp>
#include <scantling/io/cloud_io.hpp>
#include <scantling/io/file_path.hpp>
#include <scantling/io/output_transaction.hpp>
#include <scantling/io/recording.hpp>
#include <scantling/io/structural_map.hpp>
#include <scantling/localization/localizer.hpp>

#include "scantling/commands.hpp"
#include "scantling/interrupt.hpp"
#include "scantling/localize_defects.hpp"
#include "scantling/localize_report.hpp"

namespace scantling::app {
namespace {

namespace fs = std::filesystem;
namespace loc = localization;
using Clock = std::chrono::steady_clock;

constexpr const char* kOutputs[] = {"trajectory.tum", "events.csv",  "summary.json",
                                    "defects.json",   "defects.csv", "defects"};

loc::LocalizerConfig resolve_config(const LocalizeOptions& o) {
    loc::LocalizerConfig c =
        o.config_path ? loc::load_localizer_config(*o.config_path) : loc::LocalizerConfig{};
    if (o.filter) c.filter.kind = loc::filter_kind_from_string(*o.filter, "--filter");
    if (o.method) c.tracking.method = loc::tracking_method_from_string(*o.method, "--method");
    if (o.vio) c.odometry_input = loc::odometry_input_from_string(*o.vio, "--vio");
    if (o.rate_hz) {
        if (!(std::isfinite(*o.rate_hz) && *o.rate_hz >= 0)) {
            throw ConfigError(
                fmt::format("--rate = {}, expected >= 0 (0 = every frame)", *o.rate_hz));
        }
        c.registration_period_s = *o.rate_hz > 0 ? 1.0 / *o.rate_hz : 0.0;
    }
    if (o.num_threads != 0) c.set_num_threads(o.num_threads);
    c.validate();
    return c;
}

/// The structural map, or none (with a warning on stderr) when the file is absent.
std::optional<io::StructuralMap> read_metadata(const LocalizeOptions& o,
                                               const io::Recording& recording) {
    const std::string path = o.metadata_path.value_or(recording.world_metadata_path());
    if (!o.metadata_path && !fs::exists(path)) {
        fmt::print(stderr,
                   "scantling: warning: {} is missing: no compartments, every re-localisation "
                   "searches the whole map\n",
                   path);
        return std::nullopt;
    }
    return io::read_structural_map(path);
}

std::shared_ptr<const loc::LocalizationMap> build_map(const LocalizeOptions& o,
                                                      const io::Recording& recording,
                                                      const loc::LocalizerConfig& config) {
    const std::string map_path = o.map_path.value_or(recording.world_map_path());
    if (!fs::exists(map_path)) {
        throw FileError(map_path, "no map (record with export.world, or pass --map)");
    }
    std::optional<io::StructuralMap> structure = read_metadata(o, recording);
    const std::string cache =
        o.no_descriptor_cache ? "" : o.descriptor_cache.value_or(map_path + ".fpfh");
    auto map = std::make_shared<loc::LocalizationMap>(loc::LocalizationMap::build(
        io::read_cloud(map_path), std::move(structure), config.map, cache));
    if (!map->cache_message().empty()) {
        fmt::print(stderr, "scantling: warning: descriptor cache: {}\n", map->cache_message());
    }
    return map;
}

/// The depth camera's mounting: depth/T_body_sensor.txt, or (older recordings) the first
/// frame's pose relative to the true body pose at its stamp.
Eigen::Isometry3d depth_extrinsic(const io::Recording& recording, const GroundTruth& truth) {
    if (const auto T = recording.depth_T_body_sensor()) return *T;
    fmt::print(stderr,
               "scantling: warning: {}: no depth/T_body_sensor.txt, the camera mounting is "
               "taken from the first frame's true pose\n",
               recording.directory());
    const auto& frames = recording.depth_frames();
    return truth.at(frames.stamps_s.front()).inverse() * frames.poses_gt.front();
}

/// One input of the merged stream: its time (frames: capture + latency), kind and index.
struct Item {
    double time_s;
    int kind;  // 0 IMU, 1 VIO, 2 depth (same time: the IMU and VIO first)
    std::size_t index;
    bool operator<(const Item& o) const {
        return time_s != o.time_s ? time_s < o.time_s
               : kind != o.kind   ? kind < o.kind
                                  : index < o.index;
    }
};

std::vector<Item> merged_inputs(const io::Recording& r, std::size_t num_frames, double latency_s) {
    std::vector<Item> items;
    for (std::size_t i = 0; i < r.imu().size(); ++i) items.push_back({r.imu()[i].stamp_s, 0, i});
    for (std::size_t i = 0; i < r.vio().size(); ++i) items.push_back({r.vio()[i].stamp_s, 1, i});
    for (std::size_t i = 0; i < num_frames; ++i) {
        items.push_back({r.depth_frames().stamps_s[i] + latency_s, 2, i});
    }
    std::sort(items.begin(), items.end());
    return items;
}

void draw_progress(std::size_t done, std::size_t total) {
    const double percent = total > 0 ? 100.0 * static_cast<double>(done) / total : 100.0;
    fmt::print(stderr, "\rlocalize: [{:<20}] {:5.1f} % {}/{} frames",
               std::string(static_cast<std::size_t>(percent / 5.0), '#'), percent, done, total);
    std::fflush(stderr);
}

void check_inputs(const io::Recording& r) {
    if (r.num_depth_frames() == 0) {
        throw InputError(r.directory() + ": no depth frames (depth/): nothing to localise with");
    }
    if (r.vio().empty()) throw InputError(r.directory() + ": no vio.csv: the localiser fuses VIO");
}

LocalizeRun localize(const io::Recording& r, const LocalizeOptions& o, loc::Localizer& localizer,
                     const GroundTruth& truth, const Eigen::Isometry3d& T_body_sensor) {
    const std::size_t num_frames =
        std::min(r.num_depth_frames(), o.max_frames.value_or(r.num_depth_frames()));
    LocalizeRun run;
    const io::VioRecord& first = r.vio().front();
    const Eigen::Isometry3d T_world_odom = truth.at(first.stamp_s) * first.T_odom_body.inverse();
    if (o.start == "known") {
        Matrix6d P = Matrix6d::Zero();  // 5 cm, 3°: a launch point measured by hand
        P.diagonal() << 0.0025, 0.0025, 0.0025, 0.0027, 0.0027, 0.0027;
        const Eigen::Isometry3d T0 = truth.at(first.stamp_s);
        localizer.set_initial_pose({first.stamp_s, T0, loc::twist_covariance(P, T0.translation())});
    }
    const InterruptScope interrupt;
    std::size_t frames_done = 0;
    const auto start = Clock::now();
    for (const Item& item : merged_inputs(r, num_frames, o.latency_s)) {
        if (interrupt.requested())
            exit_interrupted("localize stopped; nothing written", interrupt.signal_number());
        if (item.kind == 0) {
            localizer.add_imu(r.imu()[item.index]);
        } else if (item.kind == 1) {
            const io::VioRecord& v = r.vio()[item.index];
            if (auto s = localizer.add_vio(v)) run.fused.push_back(*s);
            run.vio_alone.push_back({v.stamp_s, T_world_odom * v.T_odom_body});
        } else {
            localizer.add_depth_frame(item.index, r.read_depth_frame(item.index), T_body_sensor);
            if (o.progress && ++frames_done % 10 == 0) draw_progress(frames_done, num_frames);
        }
    }
    localizer.finish();
    if (o.progress) {
        draw_progress(num_frames, num_frames);
        std::fputs("\n", stderr);
    }
    run.wall_s = std::chrono::duration<double>(Clock::now() - start).count();
    run.duration_s = r.vio().back().stamp_s - r.vio().front().stamp_s;
    run.events = localizer.take_events();
    run.warnings = localizer.take_warnings();
    return run;
}

/// An existing output folder is replaced only when it holds nothing but our outputs.
void check_replaceable(const std::string& folder) {
    for (const auto& entry : fs::directory_iterator(folder)) {
        const std::string name = entry.path().filename().string();
        if (std::find(std::begin(kOutputs), std::end(kOutputs), name) == std::end(kOutputs)) {
            throw FileError(folder, fmt::format("holds '{}', which `scantling localize` did not "
                                                "write: choose another --out",
                                                name));
        }
    }
}

void write_outputs(const LocalizeOptions& o, const LocalizeRun& run, const GroundTruth& truth,
                   const std::string& summary, const DefectSurvey& defects,
                   const io::Recording& recording) {
    // The folder is staged and renamed into place at commit: all outputs or none.
    io::OutputTransaction outputs;
    const fs::path dir = outputs.stage_folder(o.out, check_replaceable);
    io::write_file_atomically((dir / "trajectory.tum").string(), [&](std::ostream& s) {
        s << "# timestamp tx ty tz qx qy qz qw (fused T_world_body at the VIO rate)\n";
        for (const loc::FusedState& f : run.fused) {
            const Eigen::Quaterniond q(f.T_world_body.linear());
            const Eigen::Vector3d p = f.T_world_body.translation();
            s << fmt::format("{:.6f} {:.6f} {:.6f} {:.6f} {:.9f} {:.9f} {:.9f} {:.9f}\n", f.stamp_s,
                             p.x(), p.y(), p.z(), q.x(), q.y(), q.z(), q.w());
        }
    });
    io::write_file_atomically((dir / "events.csv").string(),
                              [&](std::ostream& s) { write_events_csv(s, run, truth); });
    io::write_file_atomically((dir / "summary.json").string(),
                              [&](std::ostream& s) { s << summary; });
    write_defects(dir, defects, recording);
    outputs.commit();
}

}  // namespace

void run_localize(const LocalizeOptions& o, std::ostream& out) {
    const loc::LocalizerConfig config = resolve_config(o);
    if (o.print_config) {
        out << loc::describe_localizer_config(config);
        return;
    }
    if (o.start != "known" && o.start != "unknown") {
        throw ConfigError(fmt::format("--start = '{}', expected known or unknown", o.start));
    }
    if (o.out.empty()) throw ConfigError("--out is required");
    if (!(std::isfinite(o.latency_s) && o.latency_s >= 0)) {
        throw ConfigError(fmt::format("--latency = {}, expected >= 0", o.latency_s));
    }
    io::ensure_output_distinct(o.out, {o.recording, o.config_path.value_or(""),
                                       o.map_path.value_or(""), o.metadata_path.value_or("")});
    const io::Recording recording = io::open_recording(o.recording);
    check_inputs(recording);
    const GroundTruth truth(recording.ground_truth());
    const auto map = build_map(o, recording, config);
    loc::Localizer localizer(map, config);
    const Eigen::Isometry3d T_body_depth = depth_extrinsic(recording, truth);
    const LocalizeRun run = localize(recording, o, localizer, truth, T_body_depth);
    const DefectSurvey defects =
        survey_defects(recording, run, T_body_depth, map->structure(), config.defects);
    const LocalizeMetrics metrics = measure(run, truth);
    const std::map<std::string, std::string> settings = {
        {"recording", o.recording},
        {"filter", std::string(loc::to_string(config.filter.kind))},
        {"method", std::string(loc::to_string(config.tracking.method))},
        {"vio", std::string(loc::to_string(config.odometry_input))},
        {"start", o.start},
        {"registration_period_s", fmt::format("{}", config.registration_period_s)},
        {"latency_s", fmt::format("{}", o.latency_s)}};
    write_outputs(o, run, truth, summary_json(metrics, run, settings), defects, recording);
    print_summary(out, metrics, run);
    print_defects(out, defects);
}

}  // namespace scantling::app
