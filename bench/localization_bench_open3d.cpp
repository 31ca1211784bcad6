// The Open3D 0.16 baseline of the localisation benchmark, on the same frames as ours
// (localization_bench.cpp): the global pipeline of Open3D's examples (voxel 0.05 m, normals,
// FPFH at 0.25 m over <= 100 neighbours, RANSAC on feature matches with the edge-length 0.9 and
// 0.075 m distance checkers, 100 000 iterations / 0.999 confidence, mutual filter off, then
// point-to-plane ICP within 0.05 m) against the map of the frame's compartment, as ours
// searches only that compartment; and point-to-plane ICP from the tracking prediction. The map's
// FPFH are computed once per compartment before the timed loops, from the same cloud and normals
// as our LocalizationMap's region. Threads: omp_set_num_threads (Open3D's loops are OpenMP).
#include <map>
#include <memory>

#include <fmt/format.h>
#include <omp.h>
#include <open3d/geometry/KDTreeSearchParam.h>
#include <open3d/geometry/PointCloud.h>
#include <open3d/pipelines/registration/CorrespondenceChecker.h>
#include <open3d/pipelines/registration/Feature.h>
#include <open3d/pipelines/registration/Registration.h>
#include <open3d/pipelines/registration/TransformationEstimation.h>

#include <scantling/io/structural_map.hpp>

#include "localization_bench.hpp"

namespace scantling::bench {
namespace {

namespace o3reg = open3d::pipelines::registration;
using O3dCloud = open3d::geometry::PointCloud;

constexpr double kVoxelM = 0.05;
constexpr double kNormalRadiusM = 2.0 * kVoxelM;  // Open3D's example: 2 voxels, 30 neighbours
constexpr int kNormalNeighbors = 30;
constexpr double kFpfhRadiusM = 0.25;
constexpr int kFpfhNeighbors = 100;
constexpr double kRansacDistanceM = 0.075;
constexpr double kEdgeLengthRatio = 0.9;
constexpr int kRansacIterations = 100000;
constexpr double kRansacConfidence = 0.999;
constexpr double kIcpDistanceM = 0.05;

/// A compartment's map with its FPFH.
struct O3dMap {
    std::shared_ptr<O3dCloud> cloud;
    std::shared_ptr<o3reg::Feature> fpfh;
};

/// The inputs in Open3D's types, converted before any timed loop.
struct O3dInputs {
    const LocalizationData* data = nullptr;
    std::vector<std::shared_ptr<O3dCloud>> raw;    ///< organised frames, NaN included
    std::vector<std::shared_ptr<O3dCloud>> scans;  ///< our downsampled scans (for tracking)
    std::map<int, O3dMap> maps;                    ///< by compartment
    std::shared_ptr<O3dCloud> whole;               ///< the whole map (for tracking)
};

std::shared_ptr<O3dCloud> to_open3d(const PointCloud& cloud) {
    auto out = std::make_shared<O3dCloud>(cloud.points);
    out->normals_ = cloud.normals;
    return out;
}

open3d::geometry::KDTreeSearchParamHybrid fpfh_param() { return {kFpfhRadiusM, kFpfhNeighbors}; }

struct O3dTimes {
    double prepare_ms = 0.0;
    double fpfh_ms = 0.0;
    double ransac_ms = 0.0;
    double icp_ms = 0.0;
};

/// Finite points, voxel, normals turned towards the camera (the map's point to the free side).
std::shared_ptr<O3dCloud> prepare(const O3dCloud& raw) {
    O3dCloud finite(raw.points_);
    finite.RemoveNonFinitePoints();
    auto down = finite.VoxelDownSample(kVoxelM);
    down->EstimateNormals(
        open3d::geometry::KDTreeSearchParamHybrid(kNormalRadiusM, kNormalNeighbors));
    down->OrientNormalsTowardsCameraLocation(Eigen::Vector3d::Zero());
    return down;
}

/// The whole pipeline on one frame: T_world_sensor.
Eigen::Isometry3d global_pipeline(const O3dCloud& raw, const O3dMap& map, O3dTimes& times) {
    auto t = Clock::now();
    const auto scan = prepare(raw);
    times.prepare_ms = ms_since(t);
    t = Clock::now();
    const auto fpfh = o3reg::ComputeFPFHFeature(*scan, fpfh_param());
    times.fpfh_ms = ms_since(t);
    t = Clock::now();
    const o3reg::CorrespondenceCheckerBasedOnEdgeLength edge(kEdgeLengthRatio);
    const o3reg::CorrespondenceCheckerBasedOnDistance distance(kRansacDistanceM);
    const auto ransac = o3reg::RegistrationRANSACBasedOnFeatureMatching(
        *scan, *map.cloud, *fpfh, *map.fpfh, false, kRansacDistanceM,
        o3reg::TransformationEstimationPointToPoint(false), 3, {edge, distance},
        o3reg::RANSACConvergenceCriteria(kRansacIterations, kRansacConfidence));
    times.ransac_ms = ms_since(t);
    t = Clock::now();
    const auto icp =
        o3reg::RegistrationICP(*scan, *map.cloud, kIcpDistanceM, ransac.transformation_,
                               o3reg::TransformationEstimationPointToPlane());
    times.icp_ms = ms_since(t);
    return Eigen::Isometry3d(icp.transformation_);
}

void downsample_open3d(benchmark::State& state, const O3dInputs* in) {
    omp_set_num_threads(kLocThreads);
    std::vector<double> ms;
    for (auto _ : state) {
        ms.clear();
        for (const auto& raw : in->raw) {
            const auto t0 = Clock::now();
            O3dCloud finite(raw->points_);
            finite.RemoveNonFinitePoints();
            const auto down = finite.VoxelDownSample(kVoxelM);
            ms.push_back(ms_since(t0));
            benchmark::DoNotOptimize(down->points_.data());
        }
    }
    set_rate_counter(state, in->raw.size());
    set_stat_counters(state, ms, "ms");
}

void tracking_open3d(benchmark::State& state, const O3dInputs* in) {
    omp_set_num_threads(kLocThreads);
    const LocalizationData& d = *in->data;
    std::vector<double> ms, error_mm;
    int found = 0;
    for (auto _ : state) {
        ms.clear();
        error_mm.clear();
        found = 0;
        for (std::size_t i = 0; i < d.frames.size(); ++i) {
            const LocFrame& f = d.frames[i];
            const Eigen::Matrix4d guess = (f.T_world_body_predicted * d.T_body_sensor).matrix();
            const auto t0 = Clock::now();
            const auto r =
                o3reg::RegistrationICP(*in->scans[i], *in->whole, d.tracking_gate_m, guess,
                                       o3reg::TransformationEstimationPointToPlane());
            ms.push_back(ms_since(t0));
            const Eigen::Isometry3d T =
                Eigen::Isometry3d(r.transformation_) * d.T_body_sensor.inverse();
            error_mm.push_back(1e3 * (T.translation() - f.T_world_body.translation()).norm());
            found += within_tolerance(T, f.T_world_body) ? 1 : 0;
        }
    }
    set_rate_counter(state, d.frames.size());
    set_stat_counters(state, ms, "ms");
    set_stat_counters(state, error_mm, "err_mm");
    set_success_counters(state, found, static_cast<int>(d.frames.size()) - found, d.frames.size());
}

void global_open3d(benchmark::State& state, const O3dInputs* in) {
    omp_set_num_threads(kLocThreads);
    const LocalizationData& d = *in->data;
    std::vector<double> ms, prepare_ms, fpfh_ms, ransac_ms, icp_ms;
    int found = 0, outside = 0;
    for (auto _ : state) {
        for (auto* v : {&ms, &prepare_ms, &fpfh_ms, &ransac_ms, &icp_ms}) v->clear();
        found = outside = 0;
        for (std::size_t i = 0; i < d.frames.size(); ++i) {
            const LocFrame& f = d.frames[i];
            O3dTimes times;
            const auto t0 = Clock::now();
            const Eigen::Isometry3d T_world_sensor =
                global_pipeline(*in->raw[i], in->maps.at(f.compartment), times);
            ms.push_back(ms_since(t0));
            prepare_ms.push_back(times.prepare_ms);
            fpfh_ms.push_back(times.fpfh_ms);
            ransac_ms.push_back(times.ransac_ms);
            icp_ms.push_back(times.icp_ms);
            const Eigen::Isometry3d T = T_world_sensor * d.T_body_sensor.inverse();
            found += within_tolerance(T, f.T_world_body) ? 1 : 0;
            outside += io::compartment_at(*d.map->structure(), T.translation()) ? 0 : 1;
        }
    }
    set_rate_counter(state, d.frames.size());
    set_stat_counters(state, ms, "ms");
    set_stat_counters(state, prepare_ms, "prepare_ms");
    set_stat_counters(state, fpfh_ms, "fpfh_ms");
    set_stat_counters(state, ransac_ms, "ransac_ms");
    set_stat_counters(state, icp_ms, "icp_ms");
    // It always answers: every frame not found is a wrong pose; "outside" of them put the body
    // outside every compartment (outside the tank).
    state.counters["outside"] = outside;
    set_success_counters(state, found, static_cast<int>(d.frames.size()) - found, d.frames.size());
}

/// Converts the frames and maps and computes the maps' FPFH (untimed).
const O3dInputs* convert(const LocalizationData& d) {
    auto* in = new O3dInputs;  // lives until exit: the benchmarks point to it
    in->data = &d;
    omp_set_num_threads(kLocThreads);
    for (const LocFrame& f : d.frames) {
        in->raw.push_back(std::make_shared<O3dCloud>(f.raw.points));
        in->scans.push_back(to_open3d(f.scan));
        if (in->maps.count(f.compartment) != 0) continue;
        O3dMap& m = in->maps[f.compartment];
        m.cloud = to_open3d(d.map->region(f.compartment).cloud);
        m.fpfh = o3reg::ComputeFPFHFeature(*m.cloud, fpfh_param());
        std::printf("open3d map of compartment %d: %zu points with FPFH\n", f.compartment,
                    m.cloud->points_.size());
    }
    in->whole = to_open3d(d.map->whole().cloud);
    return in;
}

template <typename Fn>
void add(const std::string& name, Fn fn, const O3dInputs* in, bool once) {
    auto* b = benchmark::RegisterBenchmark(name.c_str(), fn, in)
                  ->Unit(benchmark::kMillisecond)
                  ->UseRealTime();
    if (once) b->Iterations(1);  // seconds per run: one pass over the frames is enough
}

}  // namespace

void register_open3d_benchmarks(const LocalizationData& data) {
    const O3dInputs* in = convert(data);
    const std::string thr = fmt::format("{}thr", kLocThreads);
    add("localization_downsample/open3d/" + thr, downsample_open3d, in, false);
    add("localization_tracking/open3d_icp/" + thr, tracking_open3d, in, false);
    add("localization_relocalization/open3d_fpfh_ransac_icp/" + thr, global_open3d, in, true);
}

}  // namespace scantling::bench
