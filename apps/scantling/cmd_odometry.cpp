// `scantling odometry INPUT --out TRAJ`: LiODOM over a recording, a KITTI sequence or a folder
// of scans, with per-frame timings beside the trajectory.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <numeric>
#include <span>

#include <scantling/core/error.hpp>
#include <scantling/core/se3.hpp>
#include <scantling/core/text_escape.hpp>
#include <scantling/core/trajectory_metrics.hpp>
#include <scantling/io/atomic_file.hpp>
#include <scantling/io/file_path.hpp>
#include <scantling/io/kitti.hpp>
#include <scantling/io/output_transaction.hpp>
#include <scantling/io/recording.hpp>
#include <scantling/io/sweep_source.hpp>
#include <scantling/io/tum.hpp>
#include <scantling/odometry/icp_odometry.hpp>
#include <scantling/odometry/liodom.hpp>

#include "scantling/commands.hpp"

namespace scantling::app {
namespace {

namespace fs = std::filesystem;
namespace odo = odometry;
using Clock = std::chrono::steady_clock;

std::string resolve_format(const OdometryOptions& options) {
    if (options.format) {
        if (*options.format != "kitti" && *options.format != "tum") {
            throw ConfigError(
                fmt::format("--format = '{}', expected kitti or tum", *options.format));
        }
        return *options.format;
    }
    return io::lower_extension(options.out) == ".tum" ? "tum" : "kitti";
}

odo::LiodomConfig resolve_config(const OdometryOptions& options) {
    odo::LiodomConfig config = options.config_path ? odo::load_liodom_config(*options.config_path)
                                                   : odo::liodom_preset(options.preset);
    if (options.config_path && options.preset_given) {
        throw ConfigError("--preset and --config are exclusive (a config file names its preset)");
    }
    if (options.num_threads != 0) config.set_num_threads(options.num_threads);
    config.validate();
    return config;
}

/// "<dir>/<stem>_frames.csv" beside the trajectory.
std::string sibling(const std::string& out, const std::string& suffix) {
    const fs::path p(out);
    return (p.parent_path() / (p.stem().string() + suffix)).string();
}

/// The trajectory, the per-frame report and the ground truth beside them (when there is one).
struct OutputPaths {
    std::string trajectory, frames_csv, ground_truth;
};

OutputPaths output_paths(const OdometryOptions& options, const std::string& format) {
    return {options.out, sibling(options.out, "_frames.csv"),
            sibling(options.out, format == "tum" ? "_gt.tum" : "_gt.txt")};
}

/// Before the run: every output writable and none of them an input (or inside the input folder).
void check_outputs(const OdometryOptions& options, const OutputPaths& paths) {
    const std::vector<std::string> inputs = {options.input, options.config_path.value_or("")};
    for (const std::string* path : {&paths.trajectory, &paths.frames_csv, &paths.ground_truth}) {
        io::check_output_file(*path);
        io::ensure_output_distinct(*path, inputs);
    }
}

void draw_progress(std::size_t done, std::size_t total, double elapsed_s) {
    const double percent = total > 0 ? 100.0 * static_cast<double>(done) / total : 100.0;
    const int filled = static_cast<int>(percent / 5.0);
    fmt::print(stderr, "\rodometry: [{:<20}] {:5.1f} % {}/{} sweeps, {:.1f} Hz",
               std::string(static_cast<std::size_t>(filled), '#'), percent, done, total,
               elapsed_s > 0 ? static_cast<double>(done) / elapsed_s : 0.0);
    std::fflush(stderr);
}

void write_trajectory(const std::string& path, const std::string& format,
                      const std::vector<double>& stamps,
                      const std::vector<Eigen::Isometry3d>& poses) {
    if (format == "kitti") {
        io::write_kitti_poses(path, poses);
        return;
    }
    std::vector<io::StampedPose> stamped(poses.size());
    for (std::size_t i = 0; i < poses.size(); ++i) stamped[i] = {stamps[i], poses[i]};
    io::write_tum(path, stamped);
}

void write_frames_csv(const std::string& path, const std::vector<odo::FrameReport>& reports) {
    io::AtomicFileWriter writer(path);
    auto& s = writer.stream();
    s << "index,stamp_s,status,points,edges,correspondences,iterations,rmse_m,degenerate,"
         "min_eigen_ratio,local_map_points,extract_ms,register_ms,map_ms,time_gap,message\n";
    for (const auto& r : reports) {
        std::string message = r.message;
        std::replace(message.begin(), message.end(), ',', ';');
        s << fmt::format(
            "{},{:.6f},{},{},{},{},{},{:.5f},{},{:.3e},{},{:.3f},{:.3f},{:.3f},{},{}\n", r.index,
            r.stamp_s, odo::to_string(r.status), r.num_points, r.num_edges, r.num_correspondences,
            r.iterations, r.rmse_m, r.num_degenerate, r.min_eigen_ratio, r.local_map_points,
            r.extract_ms, r.register_ms, r.map_ms, r.time_gap ? 1 : 0, message);
    }
    writer.commit();
}

/// The recording's VIO as a motion prior: the relative sensor motion between two stamps, from
/// the VIO poses interpolated at both (nullopt outside the VIO's span or across a dropout).
odo::MotionPrior vio_prior(const io::Recording& recording) {
    std::vector<io::VioRecord> vio;
    for (const auto& v : recording.vio()) {
        if (v.valid) vio.push_back(v);
    }
    if (vio.size() < 2) {
        throw InputError(recording.directory() + ": --prior vio needs vio.csv with valid samples");
    }
    const Eigen::Isometry3d T_bs = recording.lidar_T_body_sensor();
    auto pose_at = [vio](double t) -> std::optional<Eigen::Isometry3d> {
        const auto it =
            std::lower_bound(vio.begin(), vio.end(), t,
                             [](const io::VioRecord& v, double s) { return v.stamp_s < s; });
        if (it == vio.end() || it == vio.begin()) {
            if (it != vio.end() && it->stamp_s == t) return it->T_odom_body;
            return std::nullopt;
        }
        const auto& a = *(it - 1);
        const auto& b = *it;
        if (b.stamp_s - a.stamp_s > 0.2) return std::nullopt;  // a dropout: no prior
        return interpolate(a.T_odom_body, b.T_odom_body, (t - a.stamp_s) / (b.stamp_s - a.stamp_s));
    };
    return [pose_at, T_bs](double t0, double t1) -> std::optional<Eigen::Isometry3d> {
        const auto a = pose_at(t0);
        const auto b = pose_at(t1);
        if (!a || !b) return std::nullopt;
        return (*a * T_bs).inverse() * (*b * T_bs);
    };
}

double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
}

}  // namespace

void run_odometry(const OdometryOptions& options, std::ostream& out) {
    if (options.print_config) {
        out << odo::describe_liodom_config(resolve_config(options));
        return;
    }
    const std::string format = resolve_format(options);
    if (options.prior != "none" && options.prior != "vio") {
        throw ConfigError(fmt::format("--prior = '{}', expected none or vio", options.prior));
    }
    if (options.method != "liodom" && options.method != "icp") {
        throw ConfigError(fmt::format("--method = '{}', expected liodom or icp", options.method));
    }
    const odo::LiodomConfig config = resolve_config(options);
    if (options.out.empty()) throw ConfigError("--out is required");
    if (options.max_frames && *options.max_frames == 0) {
        throw ConfigError("--max-frames = 0, expected >= 1");
    }
    const OutputPaths paths = output_paths(options, format);
    check_outputs(options, paths);
    io::SweepSourceOptions source_options;
    if (options.period_s) source_options.period_s = *options.period_s;
    const std::unique_ptr<io::SweepSource> source =
        io::open_sweep_source(options.input, source_options);
    std::size_t n = source->size();
    if (options.max_frames) n = std::min(n, *options.max_frames);

    // With ground truth the estimate starts at the first true pose, so both share a frame.
    const auto ground_truth = source->ground_truth();
    const Eigen::Isometry3d T_initial = ground_truth && !ground_truth->empty()
                                            ? ground_truth->front()
                                            : Eigen::Isometry3d::Identity();

    const auto start = Clock::now();
    std::size_t done = 0;
    std::map<std::string, std::size_t> warned;
    auto on_frame = [&](const odo::FrameReport& r) {
        ++done;
        if (r.status != odo::FrameStatus::kOk && r.status != odo::FrameStatus::kFirst &&
            r.status != odo::FrameStatus::kDegenerate) {
            if (options.progress) std::fputs("\n", stderr);
            // File names and reader messages quote file bytes: escaped like every message.
            fmt::print(stderr, "warning: sweep {} ({}): {}: {}\n", r.index,
                       escape_control_characters(source->file_of(r.index)),
                       odo::to_string(r.status), escape_control_characters(r.message));
        } else if (r.time_gap) {
            if (options.progress) std::fputs("\n", stderr);
            fmt::print(stderr, "warning: sweep {}: {}\n", r.index,
                       escape_control_characters(r.message));
        }
        if (options.progress && (done % 5 == 0 || done == n)) {
            draw_progress(done, n, std::chrono::duration<double>(Clock::now() - start).count());
        }
    };
    odo::MotionPrior prior;
    if (options.prior == "vio") {
        if (source->kind() != io::SweepSourceKind::kRecording) {
            throw ConfigError("--prior vio needs a simulator recording (it reads vio.csv)");
        }
        prior = vio_prior(io::open_recording(options.input));
    }
    const odo::SweepReader reader = [&](std::size_t i) { return source->read(i); };
    const std::vector<odo::FrameReport> reports =
        options.method == "icp"
            ? odo::run_icp_odometry(n, reader, odo::icp_odometry_config_like(config), on_frame,
                                    T_initial, prior)
            : odo::run_odometry(n, reader, config, on_frame, T_initial, prior);
    const double wall_s = std::chrono::duration<double>(Clock::now() - start).count();
    if (options.progress) std::fputs("\n", stderr);

    std::vector<double> stamps;
    std::vector<Eigen::Isometry3d> poses;
    for (const auto& r : reports) {
        stamps.push_back(r.stamp_s);
        poses.push_back(r.T_odom_sensor);
    }
    // All three files or none: a failure on the last one leaves no trajectory either.
    io::OutputTransaction outputs;
    outputs.write(paths.trajectory,
                  [&](const std::string& p) { write_trajectory(p, format, stamps, poses); });
    outputs.write(paths.frames_csv, [&](const std::string& p) { write_frames_csv(p, reports); });
    if (ground_truth) {
        const std::vector<Eigen::Isometry3d> gt(ground_truth->begin(),
                                                ground_truth->begin() + static_cast<long>(n));
        outputs.write(paths.ground_truth,
                      [&](const std::string& p) { write_trajectory(p, format, stamps, gt); });
    }
    outputs.commit();
    const std::string& frames_path = paths.frames_csv;
    const std::string gt_path = ground_truth ? paths.ground_truth : std::string();

    std::map<std::string, std::size_t> status_counts;
    std::vector<double> extract, reg, map;
    for (const auto& r : reports) {
        ++status_counts[odo::to_string(r.status)];
        extract.push_back(r.extract_ms);
        reg.push_back(r.register_ms);
        map.push_back(r.map_ms);
    }
    out << fmt::format("trajectory: {} ({}, method {}, prior {})\n", options.out, format,
                       options.method, options.prior);
    out << fmt::format("frames_csv: {}\n", frames_path);
    if (!gt_path.empty()) out << fmt::format("ground_truth: {}\n", gt_path);
    out << fmt::format("source: {} ({})\n", source->path(), io::to_string(source->kind()));
    out << fmt::format("sweeps: {}\n", reports.size());
    for (const auto& [status, count] : status_counts) {
        out << fmt::format("status_{}: {}\n", status, count);
    }
    out << fmt::format("median_ms: extract {:.2f}, register {:.2f}, map {:.2f}\n", median(extract),
                       median(reg), median(map));
    out << fmt::format("wall_time_s: {:.3f}\nrate_hz: {:.1f}\n", wall_s,
                       wall_s > 0 ? static_cast<double>(reports.size()) / wall_s : 0.0);
    if (ground_truth && reports.size() >= 2) print_drift(*ground_truth, poses, out);
}

}  // namespace scantling::app

namespace scantling::app {

void print_drift(const std::vector<Eigen::Isometry3d>& ground_truth,
                 const std::vector<Eigen::Isometry3d>& estimate, std::ostream& out) {
    const std::size_t n = std::min(ground_truth.size(), estimate.size());
    const std::span<const Eigen::Isometry3d> gt(ground_truth.data(), n);
    const std::span<const Eigen::Isometry3d> est(estimate.data(), n);
    const TrajectoryMetrics m = evaluate_trajectory(gt, est);
    out << fmt::format("path_length_m: {:.2f}\n", m.path_length_m);
    if (m.kitti.num_segments > 0) {
        out << fmt::format("rte_percent: {:.4f}\nrre_deg_per_100m: {:.4f}\n", m.kitti.rte_percent,
                           m.kitti.rre_deg_per_100m);
    } else {
        out << "rte_percent: n/a (path shorter than 100 m)\n";
    }
    out << fmt::format("ate_rmse_m: {:.4f}\nate_percent_of_path: {:.3f}\n", m.ate.rmse_m,
                       m.ate.percent_of_path);
    // Drift without alignment: where the estimate ends up, which is what a pilot sees.
    const Eigen::Isometry3d end_error = gt.back().inverse() * est.back();
    out << fmt::format("final_position_error_m: {:.4f}\n", end_error.translation().norm());
}

}  // namespace scantling::app
