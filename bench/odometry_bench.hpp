#pragma once
/// @file Pieces shared by the LiODOM speed benchmark's files (bench/odometry_bench*.cpp).

#include <Eigen/Geometry>
#include <chrono>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include <scantling/core/point_cloud.hpp>
#include <scantling/odometry/liodom.hpp>

namespace scantling::bench {

inline constexpr int kOdometryThreadCounts[] = {1, 2};

/// Sweeps held in memory, so that reading them is not timed. They are loaded on first use
/// (before a benchmark's timed loop), so a filtered-out sequence costs nothing.
class SweepSequence {
  public:
    struct Data {
        std::vector<PointCloud> sweeps;
        /// Ground truth T_world_sensor per sweep when the source has it.
        std::optional<std::vector<Eigen::Isometry3d>> ground_truth;
    };

    SweepSequence(std::string name, std::string preset, std::function<Data()> load)
        : name_(std::move(name)), preset_(std::move(preset)), load_(std::move(load)) {}

    /// Benchmark case name, e.g. "liodom_kitti16".
    const std::string& name() const { return name_; }
    /// The LiODOM preset for this sensor.
    const std::string& preset() const { return preset_; }
    /// Loads on the first call (prints what it loaded). A load that throws scantling::Error
    /// leaves the data empty and error() set.
    const Data& data() const;
    /// Why the sequence could not be loaded (empty when it could, or before data()).
    const std::string& error() const { return error_; }

  private:
    std::string name_;
    std::string preset_;
    std::function<Data()> load_;
    mutable std::optional<Data> data_;
    mutable std::string error_;
};

/// The preset with every thread count (pipeline, extraction, registration) set to `threads`.
odometry::LiodomConfig liodom_config(const std::string& preset, int threads);

/// Length of the path through the positions of `poses`, metres.
double path_length_m(const std::vector<Eigen::Isometry3d>& poses);

/// Median of `values` (0 when empty).
double median(std::vector<double> values);

/// Frames completed per second once started: over the frames after `kSteadyFromFrame`, from
/// the completion time of each frame (`done_at`). Frames 0 and 1 are left out: the first starts
/// the map, the second runs LiODOM's one-off GICP bootstrap. 0 when there are too few frames.
inline constexpr std::size_t kSteadyFromFrame = 2;
double steady_fps(const std::vector<std::chrono::steady_clock::time_point>& done_at);

/// Frames per second, distance travelled and, with ground truth, the end-point error, as
/// counters: `fps` (frames × runs / seconds), `path_m` (estimated), `gt_path_m` and `end_err_m`
/// (final position relative to the first frame against the truth: the accumulated drift).
void set_trajectory_counters(benchmark::State& state, const SweepSequence::Data& data,
                             const std::vector<Eigen::Isometry3d>& T_odom_sensor, double seconds);

/// Registers "<sequence>/open3d_icp/<n>thr": Open3D 0.16 scan-to-scan point-to-plane ICP
/// odometry over the same sweeps (odometry_bench_open3d.cpp).
void register_open3d_icp_odometry(const SweepSequence* sequence);

}  // namespace scantling::bench
