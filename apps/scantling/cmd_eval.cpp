// `scantling eval --gt GT --est EST`: trajectory metrics (KITTI RTE/RRE, ATE, RPE) and plots.
#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <scantling/core/error.hpp>
#include <scantling/core/trajectory_metrics.hpp>
#include <scantling/io/file_path.hpp>
#include <scantling/io/kitti.hpp>
#include <scantling/io/output_transaction.hpp>
#include <scantling/io/svg_plot.hpp>
#include <scantling/io/tum.hpp>

#include "scantling/commands.hpp"

namespace scantling::app {
namespace {

namespace fs = std::filesystem;

enum class Format { kKitti, kTum };

constexpr int kKittiNumbers = 12;  // row-major 3×4 per line
constexpr int kTumNumbers = 8;     // stamp tx ty tz qx qy qz qw
constexpr std::array<const char*, 3> kAxisNames = {"x", "y", "z"};

const char* name_of(Format format) { return format == Format::kKitti ? "kitti" : "tum"; }

Format format_from_name(const std::string& name) {
    if (name == "kitti") return Format::kKitti;
    if (name == "tum") return Format::kTum;
    throw ConfigError(fmt::format("--format = '{}', expected kitti or tum", name));
}

/// From the count of numbers on the first line that holds any ('#' starts a comment).
Format detect_format(const std::string& path) {
    if (!fs::exists(path)) throw FileError(path, "no such trajectory file");
    if (fs::is_directory(path)) throw FileError(path, "is a directory, expected a trajectory file");
    std::ifstream in(path);
    if (!in) throw FileError(path, "cannot open the trajectory file");
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
        std::istringstream tokens(line.substr(0, line.find('#')));
        int count = 0;
        for (std::string token; tokens >> token;) ++count;
        if (count == kKittiNumbers) return Format::kKitti;
        if (count == kTumNumbers) return Format::kTum;
        if (count != 0) {
            throw ParseError(path, {std::nullopt, number, std::nullopt},
                             fmt::format("{} numbers, expected 12 (KITTI poses) or 8 (TUM "
                                         "trajectory: stamp tx ty tz qx qy qz qw)",
                                         count));
        }
    }
    throw ParseError(path, {std::nullopt, 1, std::nullopt}, "no poses in the file");
}

/// Ground truth and estimate matched pose by pose.
struct Matched {
    Format format = Format::kKitti;
    std::vector<Eigen::Isometry3d> gt, est;
    std::size_t num_estimated = 0;  // poses in EST, matched or not
};

Matched load_kitti(const EvalOptions& options) {
    Matched m;
    m.gt = io::read_kitti_poses(options.ground_truth);
    m.est = io::read_kitti_poses(options.estimate);
    m.num_estimated = m.est.size();
    if (m.gt.size() != m.est.size()) {
        throw InputError(fmt::format(
            "--gt {} has {} poses but --est {} has {}: KITTI pose files are matched line by line, "
            "expected the same count",
            options.ground_truth, m.gt.size(), options.estimate, m.est.size()));
    }
    return m;
}

Matched load_tum(const EvalOptions& options) {
    const auto split = [](const std::vector<io::StampedPose>& poses) {
        std::pair<std::vector<double>, std::vector<Eigen::Isometry3d>> out;
        for (const io::StampedPose& p : poses) {
            out.first.push_back(p.stamp_s);
            out.second.push_back(p.T_world_body);
        }
        return out;
    };
    const auto [gt_stamps, gt] = split(io::read_tum(options.ground_truth));
    const auto [est_stamps, est] = split(io::read_tum(options.estimate));
    AssociationConfig config;
    config.max_time_difference_s = options.max_time_difference_s;
    AssociatedTrajectories a = associate_by_time(gt_stamps, gt, est_stamps, est, config);
    return {Format::kTum, std::move(a.gt), std::move(a.est), est.size()};
}

Matched load_matched(const EvalOptions& options) {
    Format gt_format = Format::kKitti, est_format = Format::kKitti;
    if (options.format) {
        gt_format = est_format = format_from_name(*options.format);
    } else {
        gt_format = detect_format(options.ground_truth);
        est_format = detect_format(options.estimate);
        if (gt_format != est_format) {
            throw InputError(fmt::format(
                "--gt {} is a {} file but --est {} is a {} file, expected the same format",
                options.ground_truth, name_of(gt_format), options.estimate, name_of(est_format)));
        }
    }
    return gt_format == Format::kKitti ? load_kitti(options) : load_tum(options);
}

/// The two coordinates with the largest ground-truth extent, in axis order (x–z for KITTI's
/// camera frame, x–y for a ground robot or a drone in a z-up world).
std::array<int, 2> top_view_axes(const std::vector<Eigen::Isometry3d>& gt) {
    Eigen::Vector3d lo = gt.front().translation(), hi = lo;
    for (const Eigen::Isometry3d& T : gt) {
        lo = lo.cwiseMin(T.translation());
        hi = hi.cwiseMax(T.translation());
    }
    Eigen::Index smallest = 0;
    (hi - lo).minCoeff(&smallest);
    if (smallest == 0) return {1, 2};
    return smallest == 1 ? std::array<int, 2>{0, 2} : std::array<int, 2>{0, 1};
}

io::SvgPlot top_view(const Matched& m, const TrajectoryMetrics& metrics) {
    const auto [a, b] = top_view_axes(m.gt);
    io::SvgPlot plot;
    plot.title = "Top view (estimate after SE(3) alignment)";
    plot.x_label = fmt::format("{} [m]", kAxisNames[a]);
    plot.y_label = fmt::format("{} [m]", kAxisNames[b]);
    plot.equal_aspect = true;
    io::SvgSeries gt{"ground truth", "", {}}, est{"estimate", "", {}};
    for (std::size_t i = 0; i < m.gt.size(); ++i) {
        const Eigen::Vector3d p_gt = m.gt[i].translation();
        const Eigen::Vector3d p_est = metrics.ate.T_gt_est * m.est[i].translation();
        gt.points.emplace_back(p_gt[a], p_gt[b]);
        est.points.emplace_back(p_est[a], p_est[b]);
    }
    plot.series = {std::move(gt), std::move(est)};
    return plot;
}

io::SvgPlot error_plot(const Matched& m, const TrajectoryMetrics& metrics) {
    io::SvgPlot plot;
    plot.title =
        fmt::format("Position error along the path (ATE RMSE {:.3f} m)", metrics.ate.rmse_m);
    plot.x_label = "distance along the ground truth [m]";
    plot.y_label = "position error after alignment [m]";
    io::SvgSeries errors{"", "", {}};
    const std::vector<double> dist = cumulative_distances_m(m.gt);
    for (std::size_t i = 0; i < dist.size(); ++i) {
        errors.points.emplace_back(dist[i], metrics.ate.errors_m[i]);
    }
    plot.series = {std::move(errors)};
    return plot;
}

struct PlotFile {
    std::string path;
    std::string svg;
};

/// <est-stem>_top.svg and <est-stem>_errors.svg, beside EST or in --plots.
std::array<PlotFile, 2> plot_paths(const EvalOptions& options) {
    const fs::path dir =
        options.plots_dir ? fs::path(*options.plots_dir) : fs::path(options.estimate).parent_path();
    const std::string stem = fs::path(options.estimate).stem().string();
    return {PlotFile{(dir / (stem + "_top.svg")).string(), ""},
            PlotFile{(dir / (stem + "_errors.svg")).string(), ""}};
}

std::array<PlotFile, 2> render_plots(const EvalOptions& options, const Matched& m,
                                     const TrajectoryMetrics& metrics) {
    std::array<PlotFile, 2> plots = plot_paths(options);
    plots[0].svg = io::render_svg(top_view(m, metrics));
    plots[1].svg = io::render_svg(error_plot(m, metrics));
    return plots;
}

/// Both plots or neither (nor a --plots folder created for them).
void write_plots(const EvalOptions& options, const std::array<PlotFile, 2>& plots) {
    io::OutputTransaction outputs;
    if (options.plots_dir) outputs.create_folder(*options.plots_dir);
    for (const PlotFile& plot : plots) {
        outputs.write_stream(plot.path, [&](std::ostream& out) { out << plot.svg; });
    }
    outputs.commit();
}

nlohmann::ordered_json number_or_null(double value) {
    return std::isfinite(value) ? nlohmann::ordered_json(value) : nlohmann::ordered_json(nullptr);
}

std::string json_report(const Matched& m, const TrajectoryMetrics& t,
                        const std::array<PlotFile, 2>* plots) {
    nlohmann::ordered_json per_length = nlohmann::ordered_json::array();
    for (const KittiLengthErrors& l : t.kitti.per_length) {
        per_length.push_back({{"length_m", l.length_m},
                              {"segments", l.num_segments},
                              {"rte_percent", l.rte_percent},
                              {"rre_deg_per_100m", l.rre_deg_per_100m}});
    }
    nlohmann::ordered_json j = {
        {"format", name_of(m.format)},
        {"num_poses", t.num_poses},
        {"num_estimated_poses", m.num_estimated},
        {"path_length_m", t.path_length_m},
        {"rte_percent", number_or_null(t.kitti.rte_percent)},
        {"rre_deg_per_100m", number_or_null(t.kitti.rre_deg_per_100m)},
        {"kitti_segments", t.kitti.num_segments},
        {"kitti_per_length", per_length},
        {"ate_rmse_m", t.ate.rmse_m},
        {"ate_mean_m", t.ate.mean_m},
        {"ate_median_m", t.ate.median_m},
        {"ate_max_m", t.ate.max_m},
        {"ate_percent_of_path", number_or_null(t.ate.percent_of_path)},
        {"rpe_10m_trans_rmse_m", number_or_null(t.rpe.trans_rmse_m)},
        {"rpe_10m_trans_mean_m", number_or_null(t.rpe.trans_mean_m)},
        {"rpe_10m_rot_mean_deg", number_or_null(t.rpe.rot_mean_deg)},
        {"rpe_10m_pairs", t.rpe.num_pairs},
        {"plots",
         plots ? nlohmann::ordered_json{{"top", (*plots)[0].path}, {"errors", (*plots)[1].path}}
               : nlohmann::ordered_json(nullptr)}};
    return j.dump(2) + "\n";
}

std::string text_report(const Matched& m, const TrajectoryMetrics& t,
                        const std::array<PlotFile, 2>* plots) {
    std::string text = fmt::format("format: {}\n", name_of(m.format));
    if (m.format == Format::kTum) {
        text += fmt::format("matched: {} of {} estimated poses\n", t.num_poses, m.num_estimated);
    }
    text += fmt::format("num_poses: {}\npath_length_m: {:.3f}\n", t.num_poses, t.path_length_m);
    if (t.kitti.num_segments > 0) {
        text += fmt::format("rte_percent: {:.4f}\nrre_deg_per_100m: {:.4f}\nkitti_segments: {}\n",
                            t.kitti.rte_percent, t.kitti.rre_deg_per_100m, t.kitti.num_segments);
        for (const KittiLengthErrors& l : t.kitti.per_length) {
            text +=
                fmt::format("kitti_{:g}m: rte_percent {:.4f} rre_deg_per_100m {:.4f} segments {}\n",
                            l.length_m, l.rte_percent, l.rre_deg_per_100m, l.num_segments);
        }
    } else {
        text +=
            "rte_percent: n/a (path shorter than 100 m)\n"
            "rre_deg_per_100m: n/a (path shorter than 100 m)\n";
    }
    text += fmt::format(
        "ate_rmse_m: {:.4f}\nate_mean_m: {:.4f}\nate_median_m: {:.4f}\nate_max_m: {:.4f}\n"
        "ate_percent_of_path: {:.4f}\n",
        t.ate.rmse_m, t.ate.mean_m, t.ate.median_m, t.ate.max_m, t.ate.percent_of_path);
    if (t.rpe.num_pairs > 0) {
        text += fmt::format(
            "rpe_10m_trans_rmse_m: {:.4f}\nrpe_10m_trans_mean_m: {:.4f}\nrpe_10m_rot_mean_deg: "
            "{:.4f}\nrpe_10m_pairs: {}\n",
            t.rpe.trans_rmse_m, t.rpe.trans_mean_m, t.rpe.rot_mean_deg, t.rpe.num_pairs);
    } else {
        text +=
            "rpe_10m_trans_rmse_m: n/a (path shorter than 10 m)\n"
            "rpe_10m_rot_mean_deg: n/a (path shorter than 10 m)\n";
    }
    if (plots)
        text += fmt::format("plot_top: {}\nplot_errors: {}\n", (*plots)[0].path, (*plots)[1].path);
    return text;
}

}  // namespace

void run_eval(const EvalOptions& options, std::ostream& out) {
    if (!(options.max_time_difference_s >= 0.0) || !std::isfinite(options.max_time_difference_s)) {
        throw ConfigError(fmt::format("--max-dt = {}, expected a finite number of seconds >= 0",
                                      options.max_time_difference_s));
    }
    // Before anything is read: no plot may overwrite GT or EST (a GT named <est-stem>_top.svg).
    for (const PlotFile& plot : plot_paths(options)) {
        if (options.plots)
            io::ensure_output_distinct(plot.path, {options.ground_truth, options.estimate});
    }
    const Matched matched = load_matched(options);
    const TrajectoryMetrics metrics = evaluate_trajectory(matched.gt, matched.est);
    std::array<PlotFile, 2> plots;
    if (options.plots) {
        plots = render_plots(options, matched, metrics);
        write_plots(options, plots);
    }
    const std::array<PlotFile, 2>* written = options.plots ? &plots : nullptr;
    out << (options.json ? json_report(matched, metrics, written)
                         : text_report(matched, metrics, written));
}

}  // namespace scantling::app
