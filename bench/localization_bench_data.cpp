// The localisation benchmark's inputs: the short mock-up flight simulated into a temporary
// recording, read back into memory, and the benchmarked frames prepared (localization_bench.hpp).
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include <fmt/format.h>

#include <scantling/core/random.hpp>
#include <scantling/core/se3.hpp>
#include <scantling/core/voxel_grid.hpp>
#include <scantling/io/cloud_io.hpp>
#include <scantling/io/structural_map.hpp>
#include <scantling/localization/attitude_estimator.hpp>
#include <scantling/localization/localizer_config.hpp>
#include <scantling/sim/scenario.hpp>
#include <scantling/sim/scenario_runner.hpp>

#include "localization_bench.hpp"

namespace scantling::bench {
namespace {

namespace fs = std::filesystem;

constexpr std::size_t kBenchFrames = 20;  // spread evenly over the flight
constexpr std::uint64_t kPerturbationSeed = 12;

Eigen::Vector3d random_unit(Rng& rng) { return rng.normal3(1.0).normalized(); }

/// `T` moved by exactly kPredictionOffsetM and turned by kPredictionTurnDeg, each in a random
/// direction: every frame the same size of error, so the tracking times are comparable.
Eigen::Isometry3d predicted(const Eigen::Isometry3d& T, Rng& rng) {
    Eigen::Isometry3d out = T;
    out.translation() += kPredictionOffsetM * random_unit(rng);
    out.linear() = so3_exp(kPredictionTurnDeg * M_PI / 180.0 * random_unit(rng)) * T.linear();
    return out;
}

/// The scenario run into a fresh temporary folder, opened (the caller deletes the folder).
io::Recording simulate(const fs::path& dir) {
    const sim::Scenario scenario =
        sim::load_scenario(std::string(SCANTLING_SCENARIO_DIR) + "/ballast_mockup_l515.yaml");
    fs::remove_all(dir);
    const sim::ScenarioRunResult run = sim::run_scenario(scenario, dir.string());
    std::printf("simulated %s: %.1f s of flight, %lld depth frames, in %.1f s\n",
                scenario.name.c_str(), run.duration_s,
                static_cast<long long>(run.counts.depth_frames), run.wall_time_s);
    return io::open_recording(dir.string());
}

std::shared_ptr<const localization::LocalizationMap> build_map(const io::Recording& r) {
    localization::LocalizationMapConfig config;
    config.parallel.num_threads = kLocThreads;
    config.likelihood.parallel.num_threads = kLocThreads;
    return std::make_shared<const localization::LocalizationMap>(
        localization::LocalizationMap::build(io::read_cloud(r.world_map_path()),
                                             io::read_structural_map(r.world_metadata_path()),
                                             config));
}

double tracking_gate_m(const localization::LocalizerConfig& c) {
    const localization::TrackingConfig& tc = c.tracking;
    return std::clamp(tc.correspondence_sigmas * kPredictionOffsetM + c.map.voxel_size_m,
                      tc.min_correspondence_distance_m, tc.max_correspondence_distance_m);
}

/// The IMU attitude at each benchmarked frame's stamp, the IMU fed in time order up to it.
void add_imu_attitudes(LocalizationData& d) {
    localization::AttitudeEstimator attitude;
    std::size_t next = 0;
    for (LocFrame& f : d.frames) {
        const double t = d.all_frames[f.index].stamp_s;
        for (; next < d.imu.size() && d.imu[next].stamp_s <= t; ++next) attitude.add(d.imu[next]);
        f.R_world_body_imu = attitude.attitude_at(t).value_or(f.T_world_body.linear());
    }
}

LocFrame prepare_frame(const LocalizationData& d, const io::Recording& r, std::size_t index,
                       Rng& rng) {
    LocFrame f;
    f.index = index;
    f.raw = d.all_frames[index];
    f.finite = remove_non_finite(f.raw);
    f.scan = voxel_downsample(f.finite, d.map->config().voxel_size_m);
    f.T_world_body = r.depth_frames().poses_gt[index] * d.T_body_sensor.inverse();
    f.T_world_body_predicted = predicted(f.T_world_body, rng);
    f.compartment =
        io::compartment_at(*d.map->structure(), f.T_world_body.translation()).value_or(-1);
    return f;
}

LocalizationData load(const io::Recording& r) {
    LocalizationData d;
    d.map = build_map(r);
    d.T_body_sensor = r.depth_T_body_sensor().value();
    for (std::size_t i = 0; i < r.num_depth_frames(); ++i) {
        d.all_frames.push_back(r.read_depth_frame(i));
    }
    d.imu = r.imu();
    d.vio = r.vio();
    d.ground_truth = r.ground_truth();
    d.duration_s = d.ground_truth.back().stamp_s - d.ground_truth.front().stamp_s;
    d.tracking_gate_m = tracking_gate_m(localization::LocalizerConfig{});
    Rng rng(kPerturbationSeed);
    const std::size_t n = d.all_frames.size();
    for (std::size_t k = 0; k < kBenchFrames && n > 0; ++k) {
        d.frames.push_back(prepare_frame(d, r, k * (n - 1) / (kBenchFrames - 1), rng));
    }
    add_imu_attitudes(d);
    return d;
}

void print_summary(const LocalizationData& d) {
    std::size_t points = 0;
    for (const LocFrame& f : d.frames) points += f.scan.size();
    std::printf(
        "map: %zu points at %.2f m; %zu of %zu frames benchmarked, %zu points each after "
        "the voxel (mean)\n",
        d.map->whole().cloud.size(), d.map->config().voxel_size_m, d.frames.size(),
        d.all_frames.size(), d.frames.empty() ? 0 : points / d.frames.size());
}

}  // namespace

const LocalizationData& localization_data() {
    static const LocalizationData data = [] {
        const fs::path dir =
            fs::temp_directory_path() / fmt::format("scantling_bench_localization_{}", ::getpid());
        LocalizationData d;
        try {
            d = load(simulate(dir));
        } catch (...) {
            fs::remove_all(dir);
            throw;
        }
        fs::remove_all(dir);  // everything is in memory now
        print_summary(d);
        return d;
    }();
    return data;
}

Eigen::Isometry3d truth_at(const std::vector<io::StampedPose>& ground_truth, double stamp_s) {
    const auto after =
        std::lower_bound(ground_truth.begin(), ground_truth.end(), stamp_s,
                         [](const io::StampedPose& p, double s) { return p.stamp_s < s; });
    if (after == ground_truth.begin()) return after->T_world_body;
    if (after == ground_truth.end()) return ground_truth.back().T_world_body;
    const auto before = std::prev(after);
    const double span = after->stamp_s - before->stamp_s;
    const double t = span > 0.0 ? (stamp_s - before->stamp_s) / span : 0.0;
    return interpolate(before->T_world_body, after->T_world_body, t);
}

bool within_tolerance(const Eigen::Isometry3d& T, const Eigen::Isometry3d& T_ref) {
    const PoseError e = pose_error(T, T_ref);
    return e.translation_m <= kSuccessTranslationM &&
           e.rotation_rad <= kSuccessRotationDeg * M_PI / 180.0;
}

void set_stat_counters(benchmark::State& state, std::vector<double> values,
                       const std::string& name) {
    if (values.empty()) return;
    double sum = 0.0;
    for (const double v : values) sum += v;
    std::sort(values.begin(), values.end());
    state.counters[name + "_mean"] = sum / static_cast<double>(values.size());
    state.counters[name + "_p50"] = values[values.size() / 2];
    state.counters[name + "_max"] = values.back();
}

void set_rate_counter(benchmark::State& state, std::size_t frames) {
    // kIsRate divides by the real time: every benchmark here uses UseRealTime.
    const auto runs = static_cast<double>(state.iterations());
    state.counters["frames/s"] =
        benchmark::Counter(static_cast<double>(frames) * runs, benchmark::Counter::kIsRate);
}

void set_success_counters(benchmark::State& state, int found, int wrong, std::size_t frames) {
    state.counters["found"] = found;
    state.counters["wrong"] = wrong;
    state.counters["frames"] = static_cast<double>(frames);
}

}  // namespace scantling::bench
