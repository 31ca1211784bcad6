// Shared pieces of the LiODOM benchmarks: sequences held in memory, configs, counters.
#include <algorithm>
#include <chrono>
#include <cstdio>

#include <scantling/core/error.hpp>

#include "odometry_bench.hpp"

namespace scantling::bench {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

double ms_to_copy(const PointCloud& sweep) {
    constexpr int kCopies = 20;
    const auto t0 = Clock::now();
    for (int i = 0; i < kCopies; ++i) {
        PointCloud copy = sweep;
        benchmark::DoNotOptimize(copy.points.data());
    }
    return 1e3 * seconds_since(t0) / kCopies;
}

}  // namespace

const SweepSequence::Data& SweepSequence::data() const {
    if (!data_) {
        const auto t0 = Clock::now();
        try {
            data_ = load_();
        } catch (const Error& e) {
            data_ = Data{};
            error_ = e.what();
            std::printf("SKIP: %s: %s\n", name_.c_str(), e.what());
            return *data_;
        }
        std::size_t points = 0;
        for (const PointCloud& sweep : data_->sweeps) points += sweep.size();
        const double per_sweep =
            static_cast<double>(points) / std::max<std::size_t>(1, data_->sweeps.size());
        std::printf(
            "%s: %zu sweeps, %.0f points per sweep on average, loaded in %.1f s (not timed); "
            "copying one sweep (as the reader does each frame) takes %.2f ms\n",
            name_.c_str(), data_->sweeps.size(), per_sweep, seconds_since(t0),
            data_->sweeps.empty() ? 0.0 : ms_to_copy(data_->sweeps.front()));
        std::fflush(stdout);
    }
    return *data_;
}

odometry::LiodomConfig liodom_config(const std::string& preset, int threads) {
    odometry::LiodomConfig config = odometry::liodom_preset(preset);
    config.set_num_threads(threads);
    return config;
}

double path_length_m(const std::vector<Eigen::Isometry3d>& poses) {
    double length_m = 0.0;
    for (std::size_t i = 1; i < poses.size(); ++i) {
        length_m += (poses[i].translation() - poses[i - 1].translation()).norm();
    }
    return length_m;
}

double steady_fps(const std::vector<Clock::time_point>& done_at) {
    if (done_at.size() < kSteadyFromFrame + 2) return 0.0;
    const double frames = static_cast<double>(done_at.size() - 1 - kSteadyFromFrame);
    return frames /
           std::chrono::duration<double>(done_at.back() - done_at[kSteadyFromFrame]).count();
}

double median(std::vector<double> values) {
    if (values.empty()) return 0.0;
    const auto mid = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
    std::nth_element(values.begin(), mid, values.end());
    return *mid;
}

void set_trajectory_counters(benchmark::State& state, const SweepSequence::Data& data,
                             const std::vector<Eigen::Isometry3d>& T_odom_sensor, double seconds) {
    const double frames = static_cast<double>(T_odom_sensor.size());
    state.counters["fps"] = frames * static_cast<double>(state.iterations()) / seconds;
    state.counters["path_m"] = path_length_m(T_odom_sensor);
    const auto& truth = data.ground_truth;
    if (truth && truth->size() == T_odom_sensor.size() && !truth->empty()) {
        state.counters["gt_path_m"] = path_length_m(*truth);
        const Eigen::Isometry3d gt = truth->front().inverse() * truth->back();
        const Eigen::Isometry3d est = T_odom_sensor.front().inverse() * T_odom_sensor.back();
        state.counters["end_err_m"] = (gt.translation() - est.translation()).norm();
    }
}

}  // namespace scantling::bench
