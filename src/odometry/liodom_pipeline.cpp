#include <tbb/parallel_pipeline.h>
#include <chrono>
#include <optional>
#include <scantling/core/error.hpp>
#include <scantling/core/voxel_grid.hpp>
#include <scantling/odometry/liodom.hpp>
#include <scantling/registration/icp.hpp>
#include <string>
#include <thread>

namespace scantling::odometry {
namespace {

/// What stage 1 hands to stage 2.
struct Extracted {
    std::size_t index = 0;
    double stamp_s = 0.0;
    std::size_t num_points = 0;
    EdgeFeatures edges;
    double extract_ms = 0.0;
    std::optional<std::string> error;              ///< the sweep could not be read
    std::optional<Eigen::Isometry3d> motion_hint;  ///< bootstrap: T_prev_this by dense GICP
};

/// Stage-1 state of the bootstrap: the first readable sweep, downsampled.
struct Bootstrap {
    double voxel_m = 0.0;
    int sweeps_seen = 0;
    PointCloud first;
};

/// GICP of the second readable sweep onto the first (nullopt when it does not converge).
std::optional<Eigen::Isometry3d> bootstrap_motion(Bootstrap& boot, const PointCloud& sweep,
                                                  const LiodomConfig& config) {
    if (boot.voxel_m <= 0.0 || boot.sweeps_seen >= 2 || sweep.empty()) return std::nullopt;
    PointCloud gated;
    for (const auto& p : sweep.points) {
        const double r = p.norm();
        if (p.allFinite() && r >= config.features.min_range_m && r <= config.features.max_range_m) {
            gated.points.push_back(p);
        }
    }
    PointCloud down = voxel_downsample(gated, boot.voxel_m);
    if (down.size() < 50) return std::nullopt;
    ++boot.sweeps_seen;
    if (boot.sweeps_seen == 1) {
        boot.first = std::move(down);
        return std::nullopt;
    }
    registration::IcpConfig icp;
    icp.method = registration::IcpMethod::kGeneralized;
    icp.max_correspondence_distance_m = 1.0;
    icp.covariance = registration::IcpCovariance::kHessian;  // only the pose is used
    icp.parallel = config.parallel;
    const auto result = registration::align(down, boot.first, Eigen::Isometry3d::Identity(), icp);
    boot.first = PointCloud{};
    if (!result.converged) return std::nullopt;
    return result.T_target_source;
}

Extracted read_and_extract(const LidarOdometry& odometry, const SweepReader& read_sweep,
                           std::size_t index, double fallback_stamp_s, Bootstrap& boot) {
    Extracted out;
    out.index = index;
    out.stamp_s = fallback_stamp_s;
    PointCloud sweep;
    try {
        sweep = read_sweep(index);
    } catch (const Error& e) {
        out.error = e.what();
        return out;
    }
    out.stamp_s = sweep.stamp_s;
    out.num_points = sweep.size();
    const auto t0 = std::chrono::steady_clock::now();
    out.edges = odometry.extract(sweep);
    out.motion_hint = bootstrap_motion(boot, sweep, odometry.config());
    out.extract_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return out;
}

FrameReport register_extracted(LidarOdometry& odometry, const Extracted& in) {
    if (in.error) return odometry.skip_unreadable(in.stamp_s, *in.error);
    FrameReport report =
        odometry.register_and_map(in.edges, in.stamp_s, in.num_points, in.motion_hint);
    report.extract_ms = in.extract_ms;
    return report;
}

int resolve_threads(const ParallelConfig& parallel) {
    if (parallel.num_threads > 0) return parallel.num_threads;
    return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

}  // namespace

std::vector<FrameReport> run_odometry(std::size_t num_sweeps, const SweepReader& read_sweep,
                                      const LiodomConfig& config, const FrameCallback& on_frame,
                                      const Eigen::Isometry3d& T_odom_initial,
                                      const MotionPrior& prior) {
    LidarOdometry odometry(config, T_odom_initial);
    odometry.set_motion_prior(prior);
    std::vector<FrameReport> reports;
    reports.reserve(num_sweeps);
    // An unreadable sweep gets the stamp one nominal period after the previous one.
    double last_stamp_s = 0.0;
    auto finish = [&](const Extracted& in) {
        Extracted item = in;
        if (item.error) item.stamp_s = reports.empty() ? 0.0 : last_stamp_s + 0.1;
        reports.push_back(register_extracted(odometry, item));
        last_stamp_s = reports.back().stamp_s;
        if (on_frame) on_frame(reports.back());
    };
    Bootstrap boot;
    boot.voxel_m = config.bootstrap_voxel_m;
    const int threads = resolve_threads(config.parallel);
    if (threads <= 1) {
        for (std::size_t i = 0; i < num_sweeps; ++i) {
            finish(read_and_extract(odometry, read_sweep, i, 0.0, boot));
        }
        return reports;
    }
    // Two tokens: sweep i+1 is read and its edges extracted while sweep i is registered and
    // mapped. Both filters are serial_in_order, so stage 2 sees the sweeps in order and the
    // result equals the sequential run.
    // The stages' own parallel loops (rings, edges) run in the pipeline's arena: with an arena
    // of their own they could not get the second thread while the pipeline holds it.
    std::size_t next = 0;
    ParallelConfig pipeline;
    pipeline.num_threads = threads;
    with_threads(pipeline, [&] {
        tbb::parallel_pipeline(
            2, tbb::make_filter<void, std::shared_ptr<Extracted>>(
                   tbb::filter_mode::serial_in_order,
                   [&](tbb::flow_control& fc) -> std::shared_ptr<Extracted> {
                       if (next >= num_sweeps) {
                           fc.stop();
                           return nullptr;
                       }
                       return std::make_shared<Extracted>(
                           read_and_extract(odometry, read_sweep, next++, 0.0, boot));
                   }) &
                   tbb::make_filter<std::shared_ptr<Extracted>, void>(
                       tbb::filter_mode::serial_in_order,
                       [&](const std::shared_ptr<Extracted>& in) { finish(*in); }));
    });
    return reports;
}

}  // namespace scantling::odometry
