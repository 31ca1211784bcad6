#include <fmt/format.h>
#include <chrono>
#include <cmath>
#include <scantling/core/error.hpp>
#include <scantling/odometry/liodom.hpp>
#include <string>

namespace scantling::odometry {
namespace {

double elapsed_ms(std::chrono::steady_clock::time_point since) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - since)
        .count();
}

/// The points (sensor frame) moved to the world at T, added to `map` and to `local` around T.
void insert_at(const std::vector<Eigen::Vector3d>& points_sensor, const Eigen::Isometry3d& T,
               mapping::CellMap& map, LocalMap& local) {
    std::vector<Eigen::Vector3d> world(points_sensor.size());
    for (std::size_t i = 0; i < world.size(); ++i) world[i] = T * points_sensor[i];
    map.insert(world);
    local.update(map, T.translation(), std::move(world));
}

LocalMapConfig plane_local_map_config(const LiodomConfig& config) {
    LocalMapConfig c = config.local_map;
    c.num_recent_sweeps = config.plane_recent_sweeps;
    return c;
}

}  // namespace

const char* to_string(FrameStatus status) {
    switch (status) {
        case FrameStatus::kOk:
            return "ok";
        case FrameStatus::kDegenerate:
            return "degenerate";
        case FrameStatus::kFirst:
            return "first";
        case FrameStatus::kNoEdges:
            return "no_edges";
        case FrameStatus::kNotRegistered:
            return "not_registered";
        case FrameStatus::kUnreadable:
            return "unreadable";
    }
    return "unknown";
}

void LiodomConfig::validate(std::string_view prefix) const {
    const std::string p(prefix);
    features.validate(p + ".features");
    registration.validate(p + ".registration");
    map.validate();
    local_map.validate(p + ".local_map");
    if (!(max_time_gap_s > 0.0) || !std::isfinite(max_time_gap_s)) {
        throw ConfigError(fmt::format("{}.max_time_gap_s = {}, expected > 0", p, max_time_gap_s));
    }
    if (!(bootstrap_voxel_m >= 0.0) || !std::isfinite(bootstrap_voxel_m)) {
        throw ConfigError(
            fmt::format("{}.bootstrap_voxel_m = {}, expected >= 0", p, bootstrap_voxel_m));
    }
    if (plane_recent_sweeps < 0) {
        throw ConfigError(
            fmt::format("{}.plane_recent_sweeps = {}, expected >= 0", p, plane_recent_sweeps));
    }
    if (!(max_speed_mps > 0.0) || !std::isfinite(max_speed_mps)) {
        throw ConfigError(fmt::format("{}.max_speed_mps = {}, expected > 0", p, max_speed_mps));
    }
    parallel.validate(p + ".parallel");
}

LidarOdometry::LidarOdometry(const LiodomConfig& config, const Eigen::Isometry3d& T_odom_initial)
    : config_(config),
      map_(config.map),
      local_map_(config.local_map),
      plane_map_(config.map),
      plane_local_map_(plane_local_map_config(config)),
      T_initial_(T_odom_initial) {
    config_.validate();
}

EdgeFeatures LidarOdometry::extract(const PointCloud& sweep) const {
    return extract_edges(sweep, config_.features);
}

Eigen::Isometry3d LidarOdometry::predict(
    double stamp_s, bool& time_gap, const std::optional<Eigen::Isometry3d>& motion_hint) const {
    time_gap = false;
    if (!has_pose_) return T_initial_;
    double dt = stamp_s - last_stamp_s_;
    if (!std::isfinite(dt) || dt <= 0.0 || dt > config_.max_time_gap_s) {
        time_gap = true;
        // Do not extrapolate over a long or backwards gap: the vehicle may have done anything.
        dt = 0.0;
    }
    if (prior_) {
        if (const auto motion = prior_(last_stamp_s_, stamp_s)) return T_last_ * *motion;
    }
    if (motion_hint && !has_velocity_) return T_last_ * *motion_hint;
    return T_last_ * se3_exp(velocity_per_s_ * dt);
}

void LidarOdometry::accept(const Eigen::Isometry3d& T, double stamp_s) {
    if (has_pose_) {
        const double dt = stamp_s - last_stamp_s_;
        if (std::isfinite(dt) && dt > 0.0 && dt <= config_.max_time_gap_s) {
            velocity_per_s_ = se3_log(T_last_.inverse() * T) / dt;
            has_velocity_ = true;
            if (velocity_per_s_.head<3>().norm() > config_.max_speed_mps) {
                velocity_per_s_.setZero();
            }
        }
    }
    T_last_ = T;
    last_stamp_s_ = stamp_s;
    has_pose_ = true;
}

FrameReport LidarOdometry::register_and_map(const EdgeFeatures& edges, double stamp_s,
                                            std::size_t num_points,
                                            const std::optional<Eigen::Isometry3d>& motion_hint) {
    FrameReport report;
    report.index = num_frames_++;
    report.stamp_s = stamp_s;
    report.num_points = num_points;
    report.num_edges = edges.points.size();
    const Eigen::Isometry3d T_pred = predict(stamp_s, report.time_gap, motion_hint);
    if (report.time_gap) {
        report.message = has_pose_ ? fmt::format(
                                         "time gap of {:.3f} s to the previous sweep "
                                         "(max {:.3f} s): motion not extrapolated",
                                         stamp_s - last_stamp_s_, config_.max_time_gap_s)
                                   : std::string();
    }
    const auto min_edges = static_cast<std::size_t>(config_.registration.min_correspondences);
    auto carry = [&](FrameStatus status, const std::string& why) {
        report.status = status;
        report.message = report.message.empty() ? why : report.message + "; " + why;
        report.T_odom_sensor = T_pred;
        accept(T_pred, stamp_s);
        return report;
    };
    if (edges.points.size() < min_edges) {
        return carry(FrameStatus::kNoEdges,
                     fmt::format("{} edges (of {} points), need {}: pose from the motion model",
                                 edges.points.size(), num_points, min_edges));
    }
    Eigen::Isometry3d T = T_pred;
    if (!map_started_) {
        report.status = FrameStatus::kFirst;
    } else {
        const auto t0 = std::chrono::steady_clock::now();
        EdgeRegistrationConfig registration = config_.registration;
        registration.remap_degenerate = static_cast<bool>(prior_);
        const EdgeRegistrationResult result =
            register_edges(edges, local_map_, T_pred, config_.features.min_range_m,
                           config_.features.max_range_m, registration, &plane_local_map_);
        report.register_ms = elapsed_ms(t0);
        report.iterations = result.iterations;
        report.num_correspondences = result.num_correspondences;
        report.rmse_m = result.rmse_m;
        report.num_degenerate = result.num_degenerate;
        report.min_eigen_ratio = result.min_eigen_ratio;
        if (!result.registered) {
            return carry(
                FrameStatus::kNotRegistered,
                fmt::format("{} line correspondences, need {}: pose from the motion "
                            "model",
                            result.num_correspondences, config_.registration.min_correspondences));
        }
        T = result.T_world_sensor;
        report.information = result.information;
        report.status = result.num_degenerate > 0 ? FrameStatus::kDegenerate : FrameStatus::kOk;
        if (result.num_degenerate > 0) {
            report.message =
                fmt::format("{} weakly observed direction(s) (eigenvalue ratio {:.1e}){}",
                            result.num_degenerate, result.min_eigen_ratio,
                            prior_ ? ": kept the motion prior along them" : "");
        }
    }
    const auto t1 = std::chrono::steady_clock::now();
    update_maps(edges, T);
    map_started_ = true;
    report.map_ms = elapsed_ms(t1);
    report.local_map_points = local_map_.size();
    report.T_odom_sensor = T;
    accept(T, stamp_s);
    return report;
}

void LidarOdometry::update_maps(const EdgeFeatures& edges, const Eigen::Isometry3d& T) {
    // The two maps share nothing: with two threads their inserts and k-d tree rebuilds overlap
    // (the mapping stage is on the pipeline's critical path; the extraction stage waits on it).
    parallel_for(config_.parallel, 2, 1, [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) {
            if (i == 0) insert_at(edges.points, T, map_, local_map_);
            if (i == 1 && !edges.plane_points.empty())
                insert_at(edges.plane_points, T, plane_map_, plane_local_map_);
        }
    });
}

FrameReport LidarOdometry::skip_unreadable(double stamp_s, const std::string& message) {
    FrameReport report;
    report.index = num_frames_++;
    report.stamp_s = stamp_s;
    report.status = FrameStatus::kUnreadable;
    report.message = message + ": pose from the motion model";
    report.T_odom_sensor = predict(stamp_s, report.time_gap);
    accept(report.T_odom_sensor, stamp_s);
    return report;
}

FrameReport LidarOdometry::process(const PointCloud& sweep) {
    const auto t0 = std::chrono::steady_clock::now();
    const EdgeFeatures edges = extract(sweep);
    const double extract_ms = elapsed_ms(t0);
    FrameReport report = register_and_map(edges, sweep.stamp_s, sweep.size());
    report.extract_ms = extract_ms;
    return report;
}

std::size_t LidarOdometry::memory_bytes() const {
    // The local map's two trees hold ~70 bytes a point (core/kdtree.hpp).
    return map_.memory_bytes() + plane_map_.memory_bytes() +
           (local_map_.size() + plane_local_map_.size()) * 70 + sizeof(*this);
}

}  // namespace scantling::odometry
