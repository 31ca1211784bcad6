// FPFH and global registration on the 3DMatch RGB-D pair (0.05 m voxels) against Open3D 0.16:
// ComputeFPFHFeature, and RegistrationRANSACBasedOnFeatureMatching with the settings of its
// examples (0.075 m, edge-length 0.9 and distance checkers, RANSACConvergenceCriteria(100000,
// 0.999)) against our mutual matching + TEASER-style robust registration. Both sides get the
// same downsampled points and normals (ours, k = 30 as in our FPFH pipeline).
#include <fmt/format.h>
#include <omp.h>
#include <open3d/pipelines/registration/CorrespondenceChecker.h>
#include <open3d/pipelines/registration/Feature.h>
#include <open3d/pipelines/registration/Registration.h>

#include <scantling/core/normals.hpp>
#include <scantling/core/voxel_grid.hpp>
#include <scantling/registration/feature_matching.hpp>
#include <scantling/registration/fpfh.hpp>
#include <scantling/registration/robust_registration.hpp>

#include "registration_bench.hpp"

namespace scantling::bench {
namespace {

namespace o3reg = open3d::pipelines::registration;

/// The downsampled pair with normals and both libraries' features (computed once, untimed).
struct GlobalInputs {
    RegistrationPair pair;
    registration::FeatureMatrix source_fpfh, target_fpfh;
    std::shared_ptr<o3reg::Feature> o3d_source_fpfh, o3d_target_fpfh;
};

void fpfh_ours(benchmark::State& state, const GlobalInputs* in, int threads) {
    for (auto _ : state) {
        auto s = registration::compute_fpfh(in->pair.source, fpfh_config(threads));
        auto t = registration::compute_fpfh(in->pair.target, fpfh_config(threads));
        benchmark::DoNotOptimize(s.data());
        benchmark::DoNotOptimize(t.data());
    }
}

void fpfh_open3d(benchmark::State& state, const GlobalInputs* in, int threads) {
    omp_set_num_threads(threads);
    for (auto _ : state) {
        auto s = o3reg::ComputeFPFHFeature(*in->pair.o3d_source, open3d_fpfh_param());
        auto t = o3reg::ComputeFPFHFeature(*in->pair.o3d_target, open3d_fpfh_param());
        benchmark::DoNotOptimize(s->data_.data());
        benchmark::DoNotOptimize(t->data_.data());
    }
}

void count_success(benchmark::State& state, int successes, int runs, const Eigen::Isometry3d& T,
                   const Eigen::Isometry3d& T_ref) {
    set_error_counters(state, T, T_ref);
    state.counters["success_rate"] = runs > 0 ? static_cast<double>(successes) / runs : 0.0;
}

/// Matching + robust registration on precomputed features (the part RANSAC replaces).
void global_ours(benchmark::State& state, const GlobalInputs* in, int threads) {
    registration::MatchConfig match;
    match.parallel = threads_config(threads);
    registration::RobustRegistrationConfig robust;
    robust.noise_bound_m = kGlobalVoxelM;
    robust.parallel = threads_config(threads);
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    int successes = 0, runs = 0;
    for (auto _ : state) {
        const auto matches = registration::match_features(in->source_fpfh, in->target_fpfh, match);
        const auto r =
            registration::robust_register(in->pair.source, in->pair.target, matches, robust);
        T = r.registration.T_target_source;
        successes += is_3dmatch_success(T, in->pair.T_target_source_ref) ? 1 : 0;
        ++runs;
        state.counters["correspondences"] = static_cast<double>(matches.size());
        // Which verified candidate won (0 = the maximum clique's pose).
        state.counters["winning_hypothesis"] = static_cast<double>(r.winning_hypothesis);
    }
    count_success(state, successes, runs, T, in->pair.T_target_source_ref);
}

void global_open3d(benchmark::State& state, const GlobalInputs* in, bool mutual, int threads) {
    omp_set_num_threads(threads);
    const o3reg::CorrespondenceCheckerBasedOnEdgeLength edge(0.9);
    const o3reg::CorrespondenceCheckerBasedOnDistance distance(kRansacDistanceM);
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    int successes = 0, runs = 0;
    for (auto _ : state) {
        const auto r = o3reg::RegistrationRANSACBasedOnFeatureMatching(
            *in->pair.o3d_source, *in->pair.o3d_target, *in->o3d_source_fpfh, *in->o3d_target_fpfh,
            mutual, kRansacDistanceM, o3reg::TransformationEstimationPointToPoint(false), 3,
            {edge, distance}, o3reg::RANSACConvergenceCriteria(100000, 0.999));
        T.matrix() = r.transformation_;
        successes += is_3dmatch_success(T, in->pair.T_target_source_ref) ? 1 : 0;
        ++runs;
    }
    count_success(state, successes, runs, T, in->pair.T_target_source_ref);
}

PointCloud prepare(const PointCloud& cloud) {
    PointCloud down = voxel_downsample(remove_non_finite(cloud), kGlobalVoxelM);
    down.normals.clear();
    NormalEstimationConfig normals;
    normals.num_neighbors = 30;
    estimate_normals(down, normals);
    return down;
}

}  // namespace

void register_global_benchmarks(const RegistrationPair& raw) {
    auto* in = new GlobalInputs;  // lives until exit: the benchmarks point to it
    in->pair.source = prepare(raw.source);
    in->pair.target = prepare(raw.target);
    in->pair.T_target_source_ref = raw.T_target_source_ref;
    in->pair.o3d_source = to_open3d(in->pair.source);
    in->pair.o3d_target = to_open3d(in->pair.target);
    in->source_fpfh = registration::compute_fpfh(in->pair.source, fpfh_config(0));
    in->target_fpfh = registration::compute_fpfh(in->pair.target, fpfh_config(0));
    in->o3d_source_fpfh = o3reg::ComputeFPFHFeature(*in->pair.o3d_source, open3d_fpfh_param());
    in->o3d_target_fpfh = o3reg::ComputeFPFHFeature(*in->pair.o3d_target, open3d_fpfh_param());
    std::printf("rgbd pair at %.2f m voxels: %zu source, %zu target points\n", kGlobalVoxelM,
                in->pair.source.size(), in->pair.target.size());
    for (int t : kRegThreadCounts) {
        add_benchmark(fmt::format("registration_rgbd_fpfh/ours/{}thr", t), fpfh_ours, in, t);
        add_benchmark(fmt::format("registration_rgbd_fpfh/open3d/{}thr", t), fpfh_open3d, in, t);
        add_benchmark(fmt::format("registration_rgbd_global/ours/{}thr", t), global_ours, in, t);
        add_benchmark(fmt::format("registration_rgbd_global/open3d_ransac_mutual/{}thr", t),
                      global_open3d, in, true, t);
        add_benchmark(fmt::format("registration_rgbd_global/open3d_ransac/{}thr", t), global_open3d,
                      in, false, t);
    }
}

}  // namespace scantling::bench
