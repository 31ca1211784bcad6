// Registration on simulated tank scans against Open3D 0.16 (issue 5, item 9), kTankPairs pairs
// with known truth per tank and kind (registration_tank_scans.hpp): scan-to-CAD-map and
// scan-to-scan. One benchmark iteration registers every pair once; the counters give the
// success rate (3DMatch criterion: rotation < 15°, translation < 0.3 m) and median errors; the
// time is for all pairs.
// - ICP (point-to-point, point-to-plane) from the truth perturbed by ±0.2 m / ±10° per DoF,
//   0.5 m correspondence distance, at most 30 iterations on both sides, each side building its
//   own target tree per call, both on the same points and target normals (the map's triangle
//   normals; a scan's: ours, k = 30, facing its sensor). Our ICP runs with its defaults
//   otherwise (clustered covariance included), Open3D's with ICPConvergenceCriteria defaults.
// - FPFH of each source scan (targets' features precomputed, untimed), same points and normals.
// - Global: our mutual matching + robust registration (cloud overload: hypothesis verification
//   by overlap with its defaults) against Open3D's RANSAC (the settings of
//   registration_bench_global.cpp, mutual filter on), each on its own features, without a
//   guess; the map kind uses the local map (SPEC §7: the robot knows its compartment).
#include <algorithm>
#include <array>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <omp.h>
#include <open3d/pipelines/registration/CorrespondenceChecker.h>
#include <open3d/pipelines/registration/Feature.h>
#include <open3d/pipelines/registration/Registration.h>

#include <scantling/core/normals.hpp>
#include <scantling/registration/feature_matching.hpp>
#include <scantling/registration/fpfh.hpp>
#include <scantling/registration/icp.hpp>
#include <scantling/registration/robust_registration.hpp>

#include "registration_bench.hpp"
#include "registration_tank_scans.hpp"

namespace scantling::bench {
namespace {

namespace o3reg = open3d::pipelines::registration;

constexpr int kTankPairs = 50;
constexpr std::uint64_t kSeed = 5;
constexpr double kVoxelM = kGlobalVoxelM, kIcpMaxDistanceM = 0.5;
constexpr double kGuessTransM = 0.2, kGuessRotRad = 10.0 * M_PI / 180.0;
constexpr int kIcpMaxIterations = 30;

/// One cloud on both sides, with both libraries' features when they are needed.
struct Cloud {
    PointCloud points;
    std::shared_ptr<open3d::geometry::PointCloud> o3d;
    registration::FeatureMatrix fpfh;
    std::shared_ptr<o3reg::Feature> o3d_fpfh;
};

/// Scan-to-map: against the CAD map (ICP: all of it, triangle normals; global: the local map).
/// Scan-to-scan: against a second scan from nearby (scan_near), like two 3DMatch fragments.
enum class PairKind { kMap, kScan };

struct TankPair {
    std::shared_ptr<const Cloud> source, icp_target, global_target;
    Eigen::Isometry3d T_true = Eigen::Isometry3d::Identity();  ///< T_target_source
    Eigen::Isometry3d T_guess = Eigen::Isometry3d::Identity();
};

/// `points` (with normals) on both sides, with features when `features`.
std::shared_ptr<const Cloud> make_cloud(PointCloud points, bool features) {
    auto c = std::make_shared<Cloud>();
    c->points = std::move(points);
    c->o3d = to_open3d(c->points);
    if (features) {
        c->fpfh = registration::compute_fpfh(c->points, fpfh_config(0));
        c->o3d_fpfh = o3reg::ComputeFPFHFeature(*c->o3d, open3d_fpfh_param());
    }
    return c;
}

/// A scan with normals as our FPFH pipeline makes them (k = 30, facing the sensor).
std::shared_ptr<const Cloud> scan_cloud(PointCloud body) {
    NormalEstimationConfig normals;
    normals.num_neighbors = 30;
    estimate_normals(body, normals);  // viewpoint: the body origin, i.e. the sensor
    return make_cloud(std::move(body), true);
}

std::vector<TankPair> make_pairs(TankScene scene, PairKind kind) {
    const TankScanner scanner(scene, kVoxelM, kSeed);
    const auto map = make_cloud(scanner.map(), false);
    const auto local_map = make_cloud(scanner.local_map(), true);
    std::vector<TankPair> pairs;
    for (int i = 0; i < kTankPairs; ++i) {
        Rng rng = Rng(kSeed).split(static_cast<std::uint64_t>(i));
        TankScan a = scanner.scan(rng);
        TankPair p;
        p.source = scan_cloud(std::move(a.body));
        if (kind == PairKind::kMap) {
            p.T_true = a.T_map_body;
            p.icp_target = map;
            p.global_target = local_map;
        } else {
            TankScan b = scanner.scan_near(a.T_map_body, rng);
            p.T_true = b.T_map_body.inverse() * a.T_map_body;
            p.icp_target = p.global_target = scan_cloud(std::move(b.body));
        }
        p.T_guess = perturbed(p.T_true, kGuessTransM, kGuessRotRad, false, rng);
        pairs.push_back(std::move(p));
    }
    return pairs;
}

/// Built on first use (the scans and the features take a while), then kept.
const std::vector<TankPair>& tank_pairs(TankScene scene, PairKind kind) {
    static std::array<std::unique_ptr<std::vector<TankPair>>, 4> cache;
    auto& slot = cache[(scene == TankScene::kColumn ? 2 : 0) + (kind == PairKind::kScan ? 1 : 0)];
    if (!slot) slot = std::make_unique<std::vector<TankPair>>(make_pairs(scene, kind));
    return *slot;
}

/// Success rate and median errors over one pass through the pairs.
struct PassStats {
    std::vector<double> rot_deg, trans_cm;
    int successes = 0;

    void add(const Eigen::Isometry3d& T, const Eigen::Isometry3d& T_ref) {
        const Eigen::Isometry3d E = T_ref.inverse() * T;
        rot_deg.push_back(Eigen::AngleAxisd(E.linear()).angle() * 180.0 / M_PI);
        trans_cm.push_back(E.translation().norm() * 100.0);
        successes += is_3dmatch_success(T, T_ref) ? 1 : 0;
    }
};

double median(std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
}

void set_counters(benchmark::State& state, const PassStats& s, std::size_t pairs) {
    const double n = static_cast<double>(pairs);
    state.counters["success_rate"] = n > 0 ? s.successes / n : 0.0;
    state.counters["rot_err_med_deg"] = median(s.rot_deg);
    state.counters["trans_err_med_cm"] = median(s.trans_cm);
    state.counters["pairs"] = n;
}

void icp_ours(benchmark::State& state, TankScene scene, PairKind kind, int method, int threads,
              registration::BackFaces back_faces) {
    const auto& pairs = tank_pairs(scene, kind);
    registration::IcpConfig c;
    c.method = static_cast<registration::IcpMethod>(method);
    c.back_faces = back_faces;
    c.max_correspondence_distance_m = kIcpMaxDistanceM;
    c.max_iterations = kIcpMaxIterations;
    c.parallel = threads_config(threads);
    PassStats s;
    for (auto _ : state) {
        s = {};
        for (const TankPair& p : pairs) {
            const auto r =
                registration::align(p.source->points, p.icp_target->points, p.T_guess, c);
            s.add(r.T_target_source, p.T_true);
        }
    }
    set_counters(state, s, pairs.size());
}

void icp_open3d(benchmark::State& state, TankScene scene, PairKind kind, int method, int threads) {
    const auto& pairs = tank_pairs(scene, kind);
    omp_set_num_threads(threads);
    const o3reg::ICPConvergenceCriteria criteria(1e-6, 1e-6, kIcpMaxIterations);
    const o3reg::TransformationEstimationPointToPoint p2point;
    const o3reg::TransformationEstimationPointToPlane p2plane;
    const o3reg::TransformationEstimation& estimation =
        method == 1 ? static_cast<const o3reg::TransformationEstimation&>(p2plane) : p2point;
    PassStats s;
    for (auto _ : state) {
        s = {};
        for (const TankPair& p : pairs) {
            const auto r =
                o3reg::RegistrationICP(*p.source->o3d, *p.icp_target->o3d, kIcpMaxDistanceM,
                                       p.T_guess.matrix(), estimation, criteria);
            Eigen::Isometry3d T;
            T.matrix() = r.transformation_;
            s.add(T, p.T_true);
        }
    }
    set_counters(state, s, pairs.size());
}

/// FPFH of every source scan (a new scan's features are the per-registration cost).
void fpfh_ours(benchmark::State& state, TankScene scene, int threads) {
    const auto& pairs = tank_pairs(scene, PairKind::kMap);
    for (auto _ : state) {
        for (const TankPair& p : pairs) {
            auto f = registration::compute_fpfh(p.source->points, fpfh_config(threads));
            benchmark::DoNotOptimize(f.data());
        }
    }
    set_counters(state, {}, pairs.size());
}

void fpfh_open3d(benchmark::State& state, TankScene scene, int threads) {
    const auto& pairs = tank_pairs(scene, PairKind::kMap);
    omp_set_num_threads(threads);
    for (auto _ : state) {
        for (const TankPair& p : pairs) {
            auto f = o3reg::ComputeFPFHFeature(*p.source->o3d, open3d_fpfh_param());
            benchmark::DoNotOptimize(f->data_.data());
        }
    }
    set_counters(state, {}, pairs.size());
}

void global_ours(benchmark::State& state, TankScene scene, PairKind kind, int threads) {
    const auto& pairs = tank_pairs(scene, kind);
    registration::MatchConfig match;
    match.parallel = threads_config(threads);
    registration::RobustRegistrationConfig robust;
    robust.noise_bound_m = kVoxelM;
    robust.parallel = threads_config(threads);
    PassStats s;
    int other_wins = 0;
    for (auto _ : state) {
        s = {};
        other_wins = 0;
        for (const TankPair& p : pairs) {
            const Cloud& t = *p.global_target;
            const auto m = registration::match_features(p.source->fpfh, t.fpfh, match);
            const auto r = registration::robust_register(p.source->points, t.points, m, robust);
            s.add(r.registration.T_target_source, p.T_true);
            other_wins += r.winning_hypothesis != 0 ? 1 : 0;
        }
    }
    set_counters(state, s, pairs.size());
    // Pairs where hypothesis verification preferred another clique's pose to the maximum one.
    state.counters["not_max_clique"] = other_wins;
}

void global_open3d(benchmark::State& state, TankScene scene, PairKind kind, int threads) {
    const auto& pairs = tank_pairs(scene, kind);
    omp_set_num_threads(threads);
    const o3reg::CorrespondenceCheckerBasedOnEdgeLength edge(0.9);
    const o3reg::CorrespondenceCheckerBasedOnDistance distance(kRansacDistanceM);
    PassStats s;
    for (auto _ : state) {
        s = {};
        for (const TankPair& p : pairs) {
            const Cloud& t = *p.global_target;
            const auto r = o3reg::RegistrationRANSACBasedOnFeatureMatching(
                *p.source->o3d, *t.o3d, *p.source->o3d_fpfh, *t.o3d_fpfh, true, kRansacDistanceM,
                o3reg::TransformationEstimationPointToPoint(false), 3, {edge, distance},
                o3reg::RANSACConvergenceCriteria(100000, 0.999));
            Eigen::Isometry3d T;
            T.matrix() = r.transformation_;
            s.add(T, p.T_true);
        }
    }
    set_counters(state, s, pairs.size());
}

template <typename Fn, typename... Args>
void add_pass(const std::string& name, Fn fn, Args... args) {
    benchmark::RegisterBenchmark(name.c_str(), fn, args...)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime()
        ->Iterations(1);
}

void register_pair_kind(TankScene scene, PairKind kind, int th) {
    const std::string prefix =
        fmt::format("registration_{}_{}", scene == TankScene::kColumn ? "column" : "mockup",
                    kind == PairKind::kMap ? "map" : "scan");
    // The CAD map holds both faces of every plate: our default pairs scans with the visible
    // face (more accurate, extra searches); "_keep" pairs with the nearest point, as Open3D does.
    std::vector<registration::BackFaces> modes{registration::BackFaces::kPreferFront};
    if (kind == PairKind::kMap) modes.push_back(registration::BackFaces::kKeep);
    for (const registration::BackFaces mode : modes) {
        const std::string suffix = mode == registration::BackFaces::kKeep ? "_keep" : "";
        for (int m : {0, 1}) {
            const std::string icp = prefix + (m == 0 ? "_icp_p2point" : "_icp_p2plane") + suffix;
            add_pass(fmt::format("{}/ours/{}thr", icp, th), icp_ours, scene, kind, m, th, mode);
            add_pass(fmt::format("{}/open3d/{}thr", icp, th), icp_open3d, scene, kind, m, th);
        }
    }
    const std::string g = prefix + "_global";
    add_pass(fmt::format("{}/ours/{}thr", g, th), global_ours, scene, kind, th);
    add_pass(fmt::format("{}/open3d_ransac_mutual/{}thr", g, th), global_open3d, scene, kind, th);
}

}  // namespace

void register_tank_benchmarks() {
    for (TankScene scene : {TankScene::kMockup, TankScene::kColumn}) {
        for (int th : kRegThreadCounts) {
            const std::string f = fmt::format("registration_{}_fpfh",
                                              scene == TankScene::kColumn ? "column" : "mockup");
            add_pass(fmt::format("{}/ours/{}thr", f, th), fpfh_ours, scene, th);
            add_pass(fmt::format("{}/open3d/{}thr", f, th), fpfh_open3d, scene, th);
            register_pair_kind(scene, PairKind::kMap, th);
            register_pair_kind(scene, PairKind::kScan, th);
        }
    }
}

}  // namespace scantling::bench
