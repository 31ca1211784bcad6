// Ray casting against a bare Embree 3 loop: the rays of one OS1-64 64 × 2048 sweep cast at the
// real DTC hull (~117k triangles) in its dry dock, by RayCaster::cast_batch and by a loop of
// rtcIntersect1 over a scene built here with the same flags; 1 and 2 threads. The simulated
// flight benchmark is in sim_bench_flight.cpp.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include <embree3/rtcore.h>
#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <scantling/core/error.hpp>
#include <scantling/sim/ray_caster.hpp>
#include <scantling/sim/spinning_lidar.hpp>
#include <scantling/sim/world_hull.hpp>

#include "bench_support.hpp"
#include "sim_bench.hpp"

namespace scantling::bench {
namespace {

const char* const kHullMesh = "meshes/dtc-container-ship-hull-model-scale.stl";
constexpr int kColumns = 2048;            // OS1-64 in its densest mode
constexpr double kStandoffM = 12.0;       // sensor to the hull's widest point, along y
constexpr double kWallClearanceM = 25.0;  // dock wall behind the sensor, 13 m further
constexpr std::size_t kGrain = 256;       // rays per parallel chunk, as RayCaster's
constexpr int kThreadCounts[] = {1, 2};

/// A bare Embree scene of a triangle mesh (vertices relative to `offset`, as RayCaster stores
/// them, so both trace the same float geometry).
struct BareScene {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    Eigen::Vector3d offset = Eigen::Vector3d::Zero();

    BareScene(const TriangleMesh& mesh, const Eigen::Vector3d& offset_m) : offset(offset_m) {
        device = rtcNewDevice(nullptr);
        scene = rtcNewScene(device);
        rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);  // RayCasterConfig::robust default
        rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
        RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
        fill_buffers(geometry, mesh);
        rtcSetGeometryBuildQuality(geometry, RTC_BUILD_QUALITY_HIGH);
        rtcCommitGeometry(geometry);
        rtcAttachGeometry(scene, geometry);
        rtcReleaseGeometry(geometry);
        rtcCommitScene(scene);
        if (rtcGetDeviceError(device) != RTC_ERROR_NONE) throw Error("bare Embree scene failed");
    }
    void fill_buffers(RTCGeometry geometry, const TriangleMesh& mesh) const {
        auto* vertices = static_cast<float*>(
            rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                    3 * sizeof(float), mesh.num_vertices()));
        auto* indices = static_cast<unsigned*>(
            rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                    3 * sizeof(unsigned), mesh.num_triangles()));
        for (std::size_t i = 0; i < mesh.num_vertices(); ++i) {
            const Eigen::Vector3f p = (mesh.vertices[i] - offset).cast<float>();
            for (int k = 0; k < 3; ++k) vertices[3 * i + k] = p[k];
        }
        for (std::size_t i = 0; i < mesh.num_triangles(); ++i) {
            for (int k = 0; k < 3; ++k)
                indices[3 * i + k] = static_cast<unsigned>(mesh.triangles[i][k]);
        }
    }
    BareScene(const BareScene&) = delete;
    BareScene& operator=(const BareScene&) = delete;
    ~BareScene() {
        rtcReleaseScene(scene);
        rtcReleaseDevice(device);
    }

    /// Traces rays [begin, end) one by one; writes each hit distance (inf for a miss).
    void trace(const std::vector<sim::Ray>& rays, std::size_t begin, std::size_t end,
               std::vector<float>& range_m) const {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        for (std::size_t i = begin; i < end; ++i) {
            const sim::Ray& ray = rays[i];
            const Eigen::Vector3f origin = (ray.origin - offset).cast<float>();
            RTCRayHit rh{};
            rh.ray.org_x = origin.x();
            rh.ray.org_y = origin.y();
            rh.ray.org_z = origin.z();
            rh.ray.dir_x = static_cast<float>(ray.direction.x());
            rh.ray.dir_y = static_cast<float>(ray.direction.y());
            rh.ray.dir_z = static_cast<float>(ray.direction.z());
            rh.ray.tnear = static_cast<float>(ray.min_range_m);
            rh.ray.tfar = static_cast<float>(ray.max_range_m);
            rh.ray.mask = 0xFFFFFFFFu;
            rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
            rtcIntersect1(scene, &context, &rh);
            range_m[i] = rh.hit.geomID == RTC_INVALID_GEOMETRY_ID
                             ? std::numeric_limits<float>::infinity()
                             : rh.ray.tfar;
        }
    }
};

struct RayInputs {
    sim::World world;
    std::unique_ptr<sim::RayCaster> caster;
    std::unique_ptr<BareScene> bare;
    std::vector<sim::Ray> rays;
};

RayInputs& inputs() {
    static RayInputs in;
    return in;
}

/// One OS1-64 sweep (ring-major within a column, as SpinningLidar casts it) from a level sensor
/// kStandoffM beside the hull's widest point at mid length and mid height, facing the hull.
std::vector<sim::Ray> sweep_rays(const Aabb& hull) {
    const sim::SpinningLidarConfig lidar = sim::ouster_os1_64(kColumns, 10.0);
    const Eigen::Vector3d origin(0.5 * (hull.min.x() + hull.max.x()), hull.max.y() + kStandoffM,
                                 0.5 * (hull.min.z() + hull.max.z()));
    const double facing_rad = -0.5 * std::numbers::pi;  // sensor x along world −y
    std::vector<sim::Ray> rays;
    rays.reserve(static_cast<std::size_t>(kColumns) * lidar.rings());
    for (int c = 0; c < kColumns; ++c) {
        const double azimuth =
            facing_rad + lidar.start_azimuth_rad - 2 * std::numbers::pi * c / kColumns;
        for (double elevation : lidar.ring_elevations_rad) {
            const Eigen::Vector3d direction(std::cos(elevation) * std::cos(azimuth),
                                            std::cos(elevation) * std::sin(azimuth),
                                            std::sin(elevation));
            rays.push_back({origin, direction, lidar.max_range_m, lidar.min_range_m});
        }
    }
    return rays;
}

void set_rate(benchmark::State& state, double seconds) {
    const double rays = static_cast<double>(inputs().rays.size() * state.iterations());
    state.counters["Mrays_per_s"] = rays / seconds * 1e-6;
}

void rays_ours(benchmark::State& state, int threads) {
    std::vector<sim::RayHit> hits(inputs().rays.size());
    const ParallelConfig parallel{.num_threads = threads};
    double seconds = 0.0;
    for (auto _ : state) {
        const auto start = std::chrono::steady_clock::now();
        inputs().caster->cast_batch(inputs().rays, hits, parallel);
        seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        benchmark::DoNotOptimize(hits.data());
    }
    set_rate(state, seconds);
}

void rays_bare(benchmark::State& state, int threads) {
    const auto& rays = inputs().rays;
    std::vector<float> range_m(rays.size());
    tbb::task_arena arena(threads);
    double seconds = 0.0;
    for (auto _ : state) {
        const auto start = std::chrono::steady_clock::now();
        if (threads == 1) {
            inputs().bare->trace(rays, 0, rays.size(), range_m);
        } else {
            arena.execute([&] {
                tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rays.size(), kGrain),
                                  [&](const auto& r) {
                                      inputs().bare->trace(rays, r.begin(), r.end(), range_m);
                                  });
            });
        }
        seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        benchmark::DoNotOptimize(range_m.data());
    }
    set_rate(state, seconds);
}

/// Hit counts of both and the largest range difference on rays both hit.
void print_agreement() {
    const auto& rays = inputs().rays;
    const std::vector<sim::RayHit> ours = inputs().caster->cast_batch(rays);
    std::vector<float> bare(rays.size());
    inputs().bare->trace(rays, 0, rays.size(), bare);
    std::size_t ours_hits = 0, bare_hits = 0, both = 0;
    double max_diff_m = 0.0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        ours_hits += ours[i].hit;
        bare_hits += std::isfinite(bare[i]);
        if (!ours[i].hit || !std::isfinite(bare[i])) continue;
        ++both;
        max_diff_m = std::max(max_diff_m, std::abs(ours[i].range_m - bare[i]));
    }
    std::printf(
        "check hits: ours %zu / %zu rays, bare embree %zu (%s); on the %zu rays both hit, max "
        "|range difference| %.2e m (ours refines the float range in double precision)\n",
        ours_hits, rays.size(), bare_hits, ours_hits == bare_hits ? "equal" : "DIFFERENT", both,
        max_diff_m);
}

bool load_ray_inputs(const std::string& data_dir) {
    const std::filesystem::path path = std::filesystem::path(data_dir) / kHullMesh;
    if (!std::filesystem::exists(path)) {
        std::printf("SKIP: ray-casting benchmark: %s is absent (shared data not checked out)\n",
                    path.c_str());
        return false;
    }
    sim::HullMeshDockConfig config;
    config.path = path.string();
    config.surroundings.wall_clearance_m = kWallClearanceM;
    RayInputs& in = inputs();
    in.world = sim::build_hull_mesh_in_dock(config);
    in.caster = std::make_unique<sim::RayCaster>(in.world.mesh, in.world.surface_tags);
    in.bare = std::make_unique<BareScene>(in.world.mesh, in.caster->bounds().center());
    in.rays = sweep_rays(surface_bounds(in.world, "hull"));
    std::printf("input: %s in a dry dock, %zu triangles; one OS1-64 64 x %d sweep, %zu rays\n",
                path.c_str(), in.world.mesh.num_triangles(), kColumns, in.rays.size());
    print_agreement();
    return true;
}

void register_ray_benchmarks() {
    for (int t : kThreadCounts) {
        benchmark::RegisterBenchmark(fmt::format("rays_os1_64x2048_dtc_hull/ours/{}thr", t).c_str(),
                                     rays_ours, t)
            ->Unit(benchmark::kMillisecond)
            ->UseRealTime();
        benchmark::RegisterBenchmark(
            fmt::format("rays_os1_64x2048_dtc_hull/embree_rtcIntersect1/{}thr", t).c_str(),
            rays_bare, t)
            ->Unit(benchmark::kMillisecond)
            ->UseRealTime();
    }
}

}  // namespace

Aabb surface_bounds(const sim::World& world, std::string_view surface) {
    const int tag = sim::find_surface(world.metadata, surface);
    Aabb box;
    for (std::size_t i = 0; i < world.mesh.num_triangles(); ++i) {
        if (world.surface_tags[i] != tag) continue;
        for (int k = 0; k < 3; ++k) box.extend(world.mesh.vertices[world.mesh.triangles[i][k]]);
    }
    return box;
}

}  // namespace scantling::bench

int main(int argc, char** argv) {
    using namespace scantling::bench;
    const bool dtc = load_ray_inputs(SCANTLING_SHARED_DATA_DIR);
    if (dtc) register_ray_benchmarks();
    register_flight_benchmarks(dtc ? &inputs().world : nullptr,
                               dtc ? inputs().caster.get() : nullptr);
    return run_all(argc, argv);
}
