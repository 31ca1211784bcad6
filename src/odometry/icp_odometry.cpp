#include <fmt/format.h>
#include <chrono>
#include <cmath>
#include <scantling/core/error.hpp>
#include <scantling/core/normals.hpp>
#include <scantling/core/se3.hpp>
#include <scantling/core/voxel_grid.hpp>
#include <scantling/odometry/icp_odometry.hpp>

namespace scantling::odometry {
namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

/// Range-gated, downsampled, with normals (the next sweep's target).
PointCloud prepare(const PointCloud& sweep, const IcpOdometryConfig& config) {
    std::vector<std::size_t> keep;
    keep.reserve(sweep.size());
    for (std::size_t i = 0; i < sweep.size(); ++i) {
        const Eigen::Vector3d& p = sweep.points[i];
        if (!p.allFinite()) continue;
        const double r = p.norm();
        if (r >= config.min_range_m && r <= config.max_range_m) keep.push_back(i);
    }
    PointCloud gated;
    gated.points.reserve(keep.size());
    for (std::size_t i : keep) gated.points.push_back(sweep.points[i]);
    PointCloud down = voxel_downsample(gated, config.voxel_size_m);
    if (down.size() >= 10) {
        NormalEstimationConfig nc;
        nc.num_neighbors = config.icp.num_neighbors;
        nc.parallel = config.parallel;
        estimate_normals(down, nc);
    }
    return down;
}

}  // namespace

void IcpOdometryConfig::validate(std::string_view prefix) const {
    const std::string p(prefix);
    if (!(min_range_m >= 0.0) || !(max_range_m > min_range_m) || !std::isfinite(max_range_m)) {
        throw ConfigError(
            fmt::format("{}.min_range_m = {}, max_range_m = {}: expected 0 <= min < "
                        "max",
                        p, min_range_m, max_range_m));
    }
    if (!(voxel_size_m > 0.0) || !std::isfinite(voxel_size_m)) {
        throw ConfigError(fmt::format("{}.voxel_size_m = {}, expected > 0", p, voxel_size_m));
    }
    if (!(max_speed_mps > 0.0)) {
        throw ConfigError(fmt::format("{}.max_speed_mps = {}, expected > 0", p, max_speed_mps));
    }
    if (!(max_time_gap_s > 0.0)) {
        throw ConfigError(fmt::format("{}.max_time_gap_s = {}, expected > 0", p, max_time_gap_s));
    }
    icp.validate(p + ".icp");
    parallel.validate(p + ".parallel");
}

IcpOdometryConfig icp_odometry_config_like(const LiodomConfig& liodom) {
    IcpOdometryConfig c;
    c.min_range_m = liodom.features.min_range_m;
    c.max_range_m = liodom.features.max_range_m;
    // The map's thinning voxel: the density LiODOM keeps its edges at.
    c.voxel_size_m = std::max(0.05, liodom.map.thinning_voxel_m);
    c.icp.max_correspondence_distance_m = liodom.registration.max_neighbor_distance_m;
    c.max_time_gap_s = liodom.max_time_gap_s;
    c.max_speed_mps = liodom.max_speed_mps;
    c.parallel = liodom.parallel;
    c.icp.parallel = liodom.parallel;
    return c;
}

std::vector<FrameReport> run_icp_odometry(std::size_t num_sweeps, const SweepReader& read_sweep,
                                          const IcpOdometryConfig& config,
                                          const FrameCallback& on_frame,
                                          const Eigen::Isometry3d& T_odom_initial,
                                          const MotionPrior& prior) {
    config.validate();
    std::vector<FrameReport> reports;
    reports.reserve(num_sweeps);
    PointCloud previous;
    Eigen::Isometry3d T = T_odom_initial;
    Eigen::Isometry3d delta = Eigen::Isometry3d::Identity();  // last relative motion
    double last_stamp_s = 0.0;
    for (std::size_t i = 0; i < num_sweeps; ++i) {
        FrameReport r;
        r.index = i;
        PointCloud sweep;
        bool readable = true;
        try {
            sweep = read_sweep(i);
        } catch (const Error& e) {
            readable = false;
            r.message = std::string(e.what()) + ": pose from the motion model";
            sweep.stamp_s = last_stamp_s + 0.1;
        }
        r.stamp_s = sweep.stamp_s;
        r.num_points = sweep.size();
        const double dt = sweep.stamp_s - last_stamp_s;
        r.time_gap = i > 0 && (!(dt > 0.0) || dt > config.max_time_gap_s);
        Eigen::Isometry3d T_pred =
            i == 0 ? T : T * (r.time_gap ? Eigen::Isometry3d::Identity() : delta);
        if (i > 0 && prior) {
            if (const auto motion = prior(last_stamp_s, sweep.stamp_s)) T_pred = T * *motion;
        }
        const auto t0 = Clock::now();
        PointCloud current = readable ? prepare(sweep, config) : PointCloud{};
        r.extract_ms = ms_since(t0);
        r.num_edges = current.size();
        Eigen::Isometry3d T_new = T_pred;
        if (!readable) {
            r.status = FrameStatus::kUnreadable;
        } else if (current.size() < 10) {
            r.status = FrameStatus::kNoEdges;
            r.message = fmt::format("{} points after downsampling: pose from the motion model",
                                    current.size());
        } else if (previous.size() < 10) {
            r.status = i == 0 ? FrameStatus::kFirst : FrameStatus::kOk;
        } else {
            const auto t1 = Clock::now();
            // Source = current sweep, target = previous: T_prev_cur.
            const auto result =
                registration::align(current, previous, T.inverse() * T_pred, config.icp);
            r.register_ms = ms_since(t1);
            r.iterations = result.iterations;
            r.num_correspondences = result.num_inliers;
            r.rmse_m = result.rmse_m;
            const double step_m = result.T_target_source.translation().norm();
            const double limit_m = config.max_speed_mps * std::max(dt, 1e-3);
            if (result.num_inliers < 10) {
                r.status = FrameStatus::kNotRegistered;
                r.message = "ICP: " + result.status + ": pose from the motion model";
            } else if (step_m > limit_m) {
                r.status = FrameStatus::kNotRegistered;
                r.message = fmt::format(
                    "ICP moved {:.2f} m in {:.3f} s (limit {:.2f} m): pose "
                    "from the motion model",
                    step_m, dt, limit_m);
            } else {
                T_new = T * result.T_target_source;
                // Chained products drift off SO(3); writers and readers check orthonormality.
                T_new.linear() = orthonormalize(T_new.linear());
                r.status = FrameStatus::kOk;
            }
        }
        if (r.status == FrameStatus::kNotRegistered) {
            delta = Eigen::Isometry3d::Identity();  // the velocity is unknown: do not extrapolate
        } else if (i > 0 && !r.time_gap) {
            delta = T.inverse() * T_new;
        }
        T = T_new;
        if (current.size() >= 10) previous = std::move(current);
        r.T_odom_sensor = T;
        last_stamp_s = r.stamp_s;
        reports.push_back(r);
        if (on_frame) on_frame(reports.back());
    }
    return reports;
}

}  // namespace scantling::odometry
