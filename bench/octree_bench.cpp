// Issue 16 items 1 and 5: the exploration's occupancy octree (mapping::OccupancyOctree, SPEC §8)
// against plain OctoMap on the same depth frames. 100 frames of a 320 × 240 depth camera with
// the L515's 70° × 55° FOV, ray-cast analytically inside a closed 10 × 4 × 3 m compartment
// (longer than the 5 m max depth, so some rays are misses), the camera moving along it and
// panning; 1 cm depth noise and 0.2 % no-returns (NaN), seeded.
//   ours      OccupancyOctree::insert_depth_frame (sensor-frame double points, discretize on)
//   per_point the same with discretize off: one ray per point, as OctoMap's default
//   octomap    octomap::OcTree::insertPointCloud(cloud, origin, 5 m) with default arguments, the
//             clouds given already in the world frame as float octomap::Pointcloud with the NaN
//             removed (its natural input: the conversion we do inside ours is free for it).
// One iteration inserts all frames into a fresh map at 0.1 or 0.05 m (SPEC §8's resolutions);
// counters: points/s (items_per_second) and the final leaf count of each.
//   gain_…    one OccupancyOctree::visible_unknown_volume call (SPEC §8's E(M, ξ), the default
//             32 × 24-ray, 5 m frustum) from the compartment's middle looking along it, on the
//             map of all 100 frames (built once, untimed: rays stop at walls, all seen) and on an
//             empty map (the worst case: every ray runs 5 m through unknown voxels).
// Results in docs/benchmarks.md, "Occupancy octree insertion (issue 16)".
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <octomap/OcTree.h>

#include <scantling/core/random.hpp>
#include <scantling/mapping/occupancy_octree.hpp>

#include "bench_support.hpp"

namespace scantling::bench {
namespace {

using Eigen::Vector3d;

constexpr int kFrames = 100, kWidth = 320, kHeight = 240;
constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kMaxRangeM = 5.0;
constexpr std::uint64_t kSeed = 16;
const Eigen::AlignedBox3d kRoom(Vector3d(-5.0, -2.0, -1.5), Vector3d(5.0, 2.0, 1.5));

struct Frame {
    PointCloud points_sensor;
    Eigen::Isometry3d T_world_sensor = Eigen::Isometry3d::Identity();
    octomap::Pointcloud cloud_world;  ///< the baseline's input: finite points, world frame
};

double room_range(const Vector3d& o, const Vector3d& d) {
    double t = std::numeric_limits<double>::infinity();
    for (int i = 0; i < 3; ++i) {
        if (d[i] > 0.0) t = std::min(t, (kRoom.max()[i] - o[i]) / d[i]);
        if (d[i] < 0.0) t = std::min(t, (kRoom.min()[i] - o[i]) / d[i]);
    }
    return t;
}

/// Frame k: along the room's axis, panning 37° per frame, pitch cycling −25°, 0, 25°.
Eigen::Isometry3d view(int k) {
    const Eigen::Matrix3d R_body_optical =
        (Eigen::Matrix3d() << 0, 0, 1, -1, 0, 0, 0, -1, 0).finished();
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Vector3d(-4.0 + 8.0 * k / (kFrames - 1), 0.5 * std::sin(0.3 * k), 0.2);
    T.linear() = (Eigen::AngleAxisd(37.0 * kDeg * k, Vector3d::UnitZ()) *
                  Eigen::AngleAxisd(25.0 * kDeg * (k % 3 - 1), Vector3d::UnitY()))
                     .toRotationMatrix() *
                 R_body_optical;
    return T;
}

Frame make_frame(int k, Rng& rng) {
    Frame f;
    f.T_world_sensor = view(k);
    const double tx = std::tan(35.0 * kDeg), ty = std::tan(27.5 * kDeg);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (int v = 0; v < kHeight; ++v) {
        for (int u = 0; u < kWidth; ++u) {
            const Vector3d ray = Vector3d(tx * (2.0 * (u + 0.5) / kWidth - 1.0),
                                          ty * (2.0 * (v + 0.5) / kHeight - 1.0), 1.0)
                                     .normalized();
            const double range_m =
                room_range(f.T_world_sensor.translation(), f.T_world_sensor.linear() * ray);
            const bool dropped = rng.uniform() < 0.002;
            f.points_sensor.points.push_back(dropped ? Vector3d(nan, nan, nan)
                                                     : ray * (range_m + rng.normal(0.0, 0.01)));
        }
    }
    for (const Vector3d& p : f.points_sensor.points) {
        if (!p.allFinite()) continue;
        const Vector3d p_world = f.T_world_sensor * p;
        f.cloud_world.push_back(static_cast<float>(p_world.x()), static_cast<float>(p_world.y()),
                                static_cast<float>(p_world.z()));
    }
    return f;
}

std::vector<Frame> make_frames() {
    Rng rng(kSeed);
    std::vector<Frame> frames;
    frames.reserve(kFrames);
    for (int k = 0; k < kFrames; ++k) frames.push_back(make_frame(k, rng));
    return frames;
}

std::int64_t finite_points(const std::vector<Frame>& frames) {
    std::int64_t n = 0;
    for (const Frame& f : frames) n += static_cast<std::int64_t>(f.cloud_world.size());
    return n;
}

void bench_ours(benchmark::State& state, const std::vector<Frame>* frames, double res_m,
                bool discretize) {
    mapping::OccupancyOctreeConfig config;
    config.resolution_m = res_m;
    config.max_range_m = kMaxRangeM;
    config.discretize = discretize;
    std::size_t leaves = 0;
    double explored_m3 = 0.0;
    for (auto _ : state) {
        mapping::OccupancyOctree map(config);
        for (const Frame& f : *frames) map.insert_depth_frame(f.points_sensor, f.T_world_sensor);
        leaves = map.num_leaves();
        explored_m3 = map.explored_volume_m3();
    }
    state.SetItemsProcessed(state.iterations() * finite_points(*frames));
    state.counters["leaves"] = static_cast<double>(leaves);
    state.counters["explored_m3"] = explored_m3;
}

void bench_octomap(benchmark::State& state, const std::vector<Frame>* frames, double res_m) {
    std::size_t leaves = 0;
    for (auto _ : state) {
        octomap::OcTree tree(res_m);
        for (const Frame& f : *frames) {
            const Vector3d o = f.T_world_sensor.translation();
            tree.insertPointCloud(
                f.cloud_world,
                octomap::point3d(static_cast<float>(o.x()), static_cast<float>(o.y()),
                                 static_cast<float>(o.z())),
                kMaxRangeM);
        }
        leaves = tree.getNumLeafNodes();
    }
    state.SetItemsProcessed(state.iterations() * finite_points(*frames));
    state.counters["leaves"] = static_cast<double>(leaves);
}

void bench_gain(benchmark::State& state, const std::vector<Frame>* frames, double res_m,
                bool explored) {
    mapping::OccupancyOctreeConfig config;
    config.resolution_m = res_m;
    config.max_range_m = kMaxRangeM;
    mapping::OccupancyOctree map(config);
    if (explored)
        for (const Frame& f : *frames) map.insert_depth_frame(f.points_sensor, f.T_world_sensor);
    Eigen::Isometry3d T_world_camera = Eigen::Isometry3d::Identity();  // x forward: along it
    T_world_camera.translation() = Vector3d(0.3, 0.1, 0.2);
    mapping::VisibleVolume seen;
    for (auto _ : state) {
        seen = map.visible_unknown_volume(T_world_camera);
        benchmark::DoNotOptimize(seen);
    }
    state.counters["unknown_m3"] = seen.unknown_m3;
    state.counters["rays_blocked"] = static_cast<double>(seen.rays_blocked);
}

}  // namespace
}  // namespace scantling::bench

int main(int argc, char** argv) {
    using namespace scantling::bench;
    const std::vector<Frame> frames = make_frames();  // outlives the benchmarks: run_all below
    fmt::print("{} frames of {} x {}, {} finite points\n", frames.size(), kWidth, kHeight,
               finite_points(frames));
    for (const double res_m : {0.1, 0.05}) {
        const std::string name = fmt::format("frames100_320x240_res{:.2f}", res_m);
        benchmark::RegisterBenchmark((name + "/ours/1thr").c_str(), bench_ours, &frames, res_m,
                                     true)
            ->Unit(benchmark::kMillisecond)
            ->UseRealTime()
            ->Iterations(1);
        benchmark::RegisterBenchmark((name + "/per_point/1thr").c_str(), bench_ours, &frames, res_m,
                                     false)
            ->Unit(benchmark::kMillisecond)
            ->UseRealTime()
            ->Iterations(1);
        benchmark::RegisterBenchmark((name + "/octomap/1thr").c_str(), bench_octomap, &frames,
                                     res_m)
            ->Unit(benchmark::kMillisecond)
            ->UseRealTime()
            ->Iterations(1);
        // Own case names: "<case>/gain" would pair with "<case>/ours" in the ratio table.
        for (const bool explored : {true, false}) {
            benchmark::RegisterBenchmark(fmt::format("gain_res{:.2f}/{}/1thr", res_m,
                                                     explored ? "explored_map" : "empty_map")
                                             .c_str(),
                                         bench_gain, &frames, res_m, explored)
                ->Unit(benchmark::kMicrosecond)
                ->UseRealTime();
        }
    }
    return run_all(argc, argv);
}
