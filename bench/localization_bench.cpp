// Absolute localisation per depth frame (issue 12, item 7): each stage a frame goes through in
// the Localizer, on 20 frames of the simulated mock-up flight on 2 threads, and the whole
// Localizer fed the flight at 10 Hz. The Open3D FPFH + RANSAC + ICP baseline on the same frames
// is in localization_bench_open3d.cpp; the ratio table at the end pairs the cases.
// The re-localisation is reproduced from the public API in localization_bench_relocalization.cpp.
#include <cmath>
#include <optional>

#include <fmt/format.h>

#include <scantling/core/se3.hpp>
#include <scantling/core/voxel_grid.hpp>
#include <scantling/localization/landmark_correction.hpp>
#include <scantling/localization/localizer.hpp>
#include <scantling/registration/icp.hpp>
#include <scantling/registration/quality.hpp>

#include "bench_support.hpp"
#include "localization_bench.hpp"

namespace scantling::bench {
namespace {

namespace loc = scantling::localization;
loc::LocalizerConfig localizer_config() {
    loc::LocalizerConfig config;
    config.set_num_threads(kLocThreads);
    return config;
}

void downsample_ours(benchmark::State& state, const LocalizationData* d) {
    const VoxelGridConfig voxel{d->map->config().voxel_size_m, {.num_threads = kLocThreads}};
    std::vector<double> ms;
    for (auto _ : state) {
        ms.clear();
        for (const LocFrame& f : d->frames) {
            const auto t0 = Clock::now();
            PointCloud scan = voxel_downsample(remove_non_finite(f.raw), voxel);
            ms.push_back(ms_since(t0));
            benchmark::DoNotOptimize(scan.points.data());
        }
    }
    set_rate_counter(state, d->frames.size());
    set_stat_counters(state, ms, "ms");
}

void tracking_ours(benchmark::State& state, const LocalizationData* d) {
    const loc::LocalizerConfig config = localizer_config();
    registration::IcpConfig icp = config.tracking.icp;
    icp.max_correspondence_distance_m = d->tracking_gate_m;
    const loc::MapRegion& map = d->map->whole();
    const double voxel = config.gates.overlap.voxel_size_m;
    std::vector<double> ms, overlap_ms, error_mm;
    int found = 0, degenerate = 0;
    for (auto _ : state) {
        for (auto* v : {&ms, &overlap_ms, &error_mm}) v->clear();
        found = degenerate = 0;
        for (const LocFrame& f : d->frames) {
            const auto t0 = Clock::now();
            const registration::RegistrationResult r = registration::align(
                f.scan, map.cloud, *map.tree, f.T_world_body_predicted * d->T_body_sensor, icp);
            ms.push_back(ms_since(t0));
            // The overlap gate that follows in the Localizer, timed apart (not in "ms").
            const auto t1 = Clock::now();
            benchmark::DoNotOptimize(registration::overlap_ratio(
                transformed(f.scan, r.T_target_source), *map.tree, voxel, config.parallel));
            overlap_ms.push_back(ms_since(t1));
            const Eigen::Isometry3d T = r.T_target_source * d->T_body_sensor.inverse();
            error_mm.push_back(1e3 * pose_error(T, f.T_world_body).translation_m);
            found += r.converged && within_tolerance(T, f.T_world_body) ? 1 : 0;
            degenerate += r.degeneracy.degenerate ? 1 : 0;
        }
    }
    set_rate_counter(state, d->frames.size());
    set_stat_counters(state, ms, "ms");
    set_stat_counters(state, overlap_ms, "overlap_ms");
    set_stat_counters(state, error_mm, "err_mm");
    // Views that leave a direction free (here the end bulkhead seen alone): ICP may slide along
    // it, and the Localizer's covariance leaves that direction to the prediction.
    state.counters["degenerate"] = degenerate;
    set_success_counters(state, found, static_cast<int>(d->frames.size()) - found,
                         d->frames.size());
}

void relocalization_ours(benchmark::State& state, const LocalizationData* d) {
    const loc::LocalizerConfig config = localizer_config();
    std::vector<double> ms, search_ms, verify_ms;
    int found = 0, wrong = 0;
    for (auto _ : state) {
        ms.clear();
        search_ms.clear();
        verify_ms.clear();
        found = wrong = 0;
        for (const LocFrame& f : d->frames) {
            RelocTimes times;
            const auto t0 = Clock::now();
            const auto T = relocalize(f, *d, config, times);
            ms.push_back(ms_since(t0));
            search_ms.push_back(times.search_ms);
            verify_ms.push_back(times.verify_ms);
            if (T) ++(within_tolerance(*T, f.T_world_body) ? found : wrong);
        }
    }
    set_rate_counter(state, d->frames.size());
    set_stat_counters(state, ms, "ms");
    set_stat_counters(state, search_ms, "search_ms");
    set_stat_counters(state, verify_ms, "verify_ms");
    set_success_counters(state, found, wrong, d->frames.size());
}

void landmarks_ours(benchmark::State& state, const LocalizationData* d) {
    const loc::LocalizerConfig config = localizer_config();
    std::vector<double> ms;
    int found = 0, wrong = 0;
    for (auto _ : state) {
        ms.clear();
        found = wrong = 0;
        for (const LocFrame& f : d->frames) {
            const loc::AbsolutePose prediction{d->all_frames[f.index].stamp_s,
                                               f.T_world_body_predicted,
                                               Matrix6d::Identity() * 1e-3};
            const auto t0 = Clock::now();
            const loc::LandmarkCorrection c = loc::correct_with_landmarks(
                f.finite, prediction, d->T_body_sensor, *d->map->structure(), f.compartment,
                config.tracking.landmarks);
            ms.push_back(ms_since(t0));
            if (!c.ok()) continue;  // nothing matched: no correction, not a wrong one
            ++(within_tolerance(c.pose.T_world_body, f.T_world_body) ? found : wrong);
        }
    }
    set_rate_counter(state, d->frames.size());
    set_stat_counters(state, ms, "ms");
    set_success_counters(state, found, wrong, d->frames.size());
}

/// The whole flight through a Localizer from the known start, frames arriving 0.1 s after
/// capture (as in its tests); returns the events.
std::vector<loc::FrameEvent> run_localizer(const LocalizationData& d,
                                           const loc::LocalizerConfig& config) {
    constexpr double kLatencyS = 0.1;
    loc::Localizer localizer(d.map, config);
    const double t_start = d.vio.front().stamp_s;
    localizer.set_initial_pose(
        {t_start, truth_at(d.ground_truth, t_start), Matrix6d::Identity() * 1e-3});
    std::size_t imu = 0, frame = 0;
    for (const io::VioRecord& v : d.vio) {
        for (; imu < d.imu.size() && d.imu[imu].stamp_s <= v.stamp_s; ++imu) {
            localizer.add_imu(d.imu[imu]);
        }
        for (; frame < d.all_frames.size() && d.all_frames[frame].stamp_s + kLatencyS <= v.stamp_s;
             ++frame) {
            localizer.add_depth_frame(frame, d.all_frames[frame], d.T_body_sensor);
        }
        benchmark::DoNotOptimize(localizer.add_vio(v));
    }
    localizer.finish();
    return localizer.take_events();
}

void whole_localizer_ours(benchmark::State& state, const LocalizationData* d) {
    const loc::LocalizerConfig config = localizer_config();
    std::vector<loc::FrameEvent> events;
    double seconds = 0.0;
    for (auto _ : state) {
        const auto t0 = Clock::now();
        events = run_localizer(*d, config);
        seconds += 1e-3 * ms_since(t0);
    }
    std::vector<double> compute_ms;
    int registered = 0, found = 0;
    for (const loc::FrameEvent& e : events) {
        compute_ms.push_back(e.compute_ms);
        if (e.outcome != loc::FrameOutcome::kRegistered || !e.T_world_body) continue;
        ++registered;
        found += within_tolerance(*e.T_world_body, truth_at(d->ground_truth, e.stamp_s)) ? 1 : 0;
    }
    const double runs = static_cast<double>(state.iterations());
    set_rate_counter(state, events.size());  // the last frame has no VIO after it
    state.counters["x_realtime"] = d->duration_s * runs / seconds;
    state.counters["ms_per_frame"] = 1e3 * seconds / (runs * static_cast<double>(events.size()));
    set_stat_counters(state, compute_ms, "event_ms");
    state.counters["registered"] = registered;
    set_success_counters(state, found, registered - found, events.size());
}

template <typename Fn>
void add(const std::string& name, Fn fn, const LocalizationData* d, bool once) {
    auto* b = benchmark::RegisterBenchmark(name.c_str(), fn, d)
                  ->Unit(benchmark::kMillisecond)
                  ->UseRealTime();
    if (once) b->Iterations(1);  // seconds per run: one pass over the frames is enough
}

}  // namespace

void register_localization_benchmarks() {
    const LocalizationData& d = localization_data();
    const std::string thr = fmt::format("{}thr", kLocThreads);
    add("localization_downsample/ours/" + thr, downsample_ours, &d, false);
    add("localization_tracking/ours/" + thr, tracking_ours, &d, false);
    add("localization_relocalization/ours/" + thr, relocalization_ours, &d, true);
    add("localization_landmarks/ours/" + thr, landmarks_ours, &d, false);
    add("localization_whole_flight/ours/" + thr, whole_localizer_ours, &d, true);
    register_open3d_benchmarks(d);
}

}  // namespace scantling::bench

int main(int argc, char** argv) {
    scantling::bench::register_localization_benchmarks();
    return scantling::bench::run_all(argc, argv);
}
