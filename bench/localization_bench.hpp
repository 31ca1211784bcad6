#pragma once
/// @file Inputs of the absolute-localisation benchmark (issue 12, item 7): the short mock-up
/// flight (scenarios/ballast_mockup_l515.yaml) simulated in-process, its LocalizationMap, and
/// 20 depth frames spread over the flight with their truth, shared by our stages
/// (localization_bench.cpp, localization_bench_relocalization.cpp) and the Open3D FPFH + RANSAC +
/// ICP baseline (localization_bench_open3d.cpp).

#include <Eigen/Geometry>
#include <chrono>
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include <scantling/core/point_cloud.hpp>
#include <scantling/io/recording.hpp>
#include <scantling/localization/localization_map.hpp>
#include <scantling/localization/localizer_config.hpp>

namespace scantling::bench {

/// Item 7 states its targets on 2 threads.
inline constexpr int kLocThreads = 2;
/// A pose counts as found within these of the truth (the success criterion).
inline constexpr double kSuccessTranslationM = 0.1;
inline constexpr double kSuccessRotationDeg = 5.0;
/// The tracking prediction's error: the truth moved by this much and turned by this much, each
/// in a random direction (fixed seed).
inline constexpr double kPredictionOffsetM = 0.05;
inline constexpr double kPredictionTurnDeg = 2.0;

/// One benchmarked depth frame with everything derived from it outside the timed loops.
struct LocFrame {
    std::size_t index = 0;  ///< in the recording
    PointCloud raw;         ///< organised sensor frame, NaN where no return
    PointCloud finite;      ///< raw without the NaNs (the landmark detector's input)
    PointCloud scan;        ///< finite at the map voxel (the registrations' input)
    Eigen::Isometry3d T_world_body = Eigen::Isometry3d::Identity();  ///< truth
    /// The truth moved by kPredictionOffsetM and turned by kPredictionTurnDeg: the tracking
    /// prediction.
    Eigen::Isometry3d T_world_body_predicted = Eigen::Isometry3d::Identity();
    /// The IMU's attitude at the capture time (AttitudeEstimator over the recording's IMU): the
    /// re-localisation takes roll and pitch from it, as the Localizer does.
    Eigen::Matrix3d R_world_body_imu = Eigen::Matrix3d::Identity();
    int compartment = -1;  ///< the compartment the truth is in
};

/// The whole flight in memory (the temporary recording is deleted once read).
struct LocalizationData {
    std::shared_ptr<const localization::LocalizationMap> map;
    Eigen::Isometry3d T_body_sensor = Eigen::Isometry3d::Identity();
    std::vector<LocFrame> frames;        ///< the benchmarked frames
    std::vector<PointCloud> all_frames;  ///< every depth frame, for the whole Localizer
    std::vector<io::ImuRecord> imu;
    std::vector<io::VioRecord> vio;
    std::vector<io::StampedPose> ground_truth;
    double duration_s = 0.0;  ///< simulated flight
    /// The ICP correspondence distance the Localizer sets for a prediction whose σ is
    /// kPredictionOffsetM (3 σ plus one voxel, clamped), metres: ours and Open3D's tracking.
    double tracking_gate_m = 0.0;
};

using Clock = std::chrono::steady_clock;

inline double ms_since(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

/// Simulates the flight and prepares the inputs (once; seconds).
const LocalizationData& localization_data();

/// The truth at `stamp_s`, interpolated between the ground-truth samples around it.
Eigen::Isometry3d truth_at(const std::vector<io::StampedPose>& ground_truth, double stamp_s);

/// Whether `T` is within kSuccessTranslationM and kSuccessRotationDeg of `T_ref`.
bool within_tolerance(const Eigen::Isometry3d& T, const Eigen::Isometry3d& T_ref);

/// Counters <name>_mean, <name>_p50 and <name>_max of per-frame values (times, errors).
void set_stat_counters(benchmark::State& state, std::vector<double> values,
                       const std::string& name);

/// Counter "frames/s": `frames` per iteration over the wall-clock time.
void set_rate_counter(benchmark::State& state, std::size_t frames);

/// Frames found within tolerance and frames answered wrongly (a pose outside it), as counters
/// "found" and "wrong", with the frame count.
void set_success_counters(benchmark::State& state, int found, int wrong, std::size_t frames);

/// Wall time of the re-localisation's two parts, milliseconds (added to).
struct RelocTimes {
    double search_ms = 0.0;  ///< correlative search
    double verify_ms = 0.0;  ///< ICP and gates of every candidate
};

/// Our re-localisation of `f` in its compartment, as the Localizer's at a start without a prior
/// (localization_bench_relocalization.cpp): T_world_body, or nullopt when it gives no answer.
std::optional<Eigen::Isometry3d> relocalize(const LocFrame& f, const LocalizationData& d,
                                            const localization::LocalizerConfig& c,
                                            RelocTimes& times);

/// The Open3D baseline (localization_bench_open3d.cpp).
void register_open3d_benchmarks(const LocalizationData& data);

}  // namespace scantling::bench
