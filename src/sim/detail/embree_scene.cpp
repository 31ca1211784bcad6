#include "embree_scene.hpp"

#include <scantling/core/error.hpp>
#include <scantling/core/parallel.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

namespace scantling::sim::detail {
namespace {

// Below this |cos| between ray and triangle plane the float range from Embree is kept: the
// double-precision plane intersection would divide by (almost) zero.
constexpr double kMinPlaneCosine = 1e-9;

const char* error_name(RTCError code) {
    switch (code) {
        case RTC_ERROR_NONE:
            return "no error";
        case RTC_ERROR_UNKNOWN:
            return "unknown error";
        case RTC_ERROR_INVALID_ARGUMENT:
            return "invalid argument";
        case RTC_ERROR_INVALID_OPERATION:
            return "invalid operation";
        case RTC_ERROR_OUT_OF_MEMORY:
            return "out of memory";
        case RTC_ERROR_UNSUPPORTED_CPU:
            return "unsupported CPU";
        case RTC_ERROR_CANCELLED:
            return "cancelled";
    }
    return "unrecognised error code";
}

void record_error(void* user, RTCError code, const char* text) {
    auto* sink = static_cast<EmbreeErrorSink*>(user);
    const std::lock_guard lock(sink->mutex);
    sink->message = fmt::format("{} ({})", text != nullptr ? text : "", error_name(code));
}

struct GeometryReleaser {
    void operator()(RTCGeometryTy* geometry) const { rtcReleaseGeometry(geometry); }
};
using GeometryHandle = std::unique_ptr<RTCGeometryTy, GeometryReleaser>;

float to_float_range(double range_m) {
    return std::isinf(range_m) ? std::numeric_limits<float>::infinity()
                               : static_cast<float>(range_m);
}

}  // namespace

EmbreeScene::EmbreeScene(const TriangleMesh& mesh, std::span<const int> tags,
                         const RayCasterConfig& config)
    : tags_(tags.begin(), tags.end()), bounds_(compute_bounds(mesh)) {
    if (!bounds_.empty()) offset_ = bounds_.center();
    store_planes(mesh);
    build(mesh, config);
}

EmbreeScene::Handles::~Handles() {
    if (scene != nullptr) rtcReleaseScene(scene);
    if (device != nullptr) rtcReleaseDevice(device);
}

void EmbreeScene::check(const char* call) {
    const RTCError code = rtcGetDeviceError(embree_.device);
    if (code == RTC_ERROR_NONE) return;
    const std::lock_guard lock(errors_.mutex);
    throw Error(fmt::format("Embree {} failed: {}", call,
                            errors_.message.empty() ? error_name(code) : errors_.message));
}

void EmbreeScene::create_device() {
    embree_.device = rtcNewDevice(nullptr);
    if (embree_.device == nullptr) {
        throw Error(
            fmt::format("Embree rtcNewDevice failed: {}", error_name(rtcGetDeviceError(nullptr))));
    }
    rtcSetDeviceErrorFunction(embree_.device, record_error, &errors_);
}

void EmbreeScene::store_planes(const TriangleMesh& mesh) {
    normals_.resize(mesh.num_triangles());
    plane_offsets_.resize(mesh.num_triangles());
    for (std::size_t i = 0; i < mesh.num_triangles(); ++i) {
        normals_[i] = triangle_normal(mesh, i);
        plane_offsets_[i] = normals_[i].dot(mesh.vertices[mesh.triangles[i][0]]);
    }
}

void EmbreeScene::attach_triangles(const TriangleMesh& mesh, RTCBuildQuality quality) {
    GeometryHandle geometry(rtcNewGeometry(embree_.device, RTC_GEOMETRY_TYPE_TRIANGLE));
    check("rtcNewGeometry");
    auto* vertices = static_cast<float*>(
        rtcSetNewGeometryBuffer(geometry.get(), RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                3 * sizeof(float), mesh.num_vertices()));
    check("rtcSetNewGeometryBuffer(vertex)");
    auto* indices = static_cast<unsigned*>(
        rtcSetNewGeometryBuffer(geometry.get(), RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                3 * sizeof(unsigned), mesh.num_triangles()));
    check("rtcSetNewGeometryBuffer(index)");
    for (std::size_t i = 0; i < mesh.num_vertices(); ++i) {
        const Eigen::Vector3f p = (mesh.vertices[i] - offset_).cast<float>();
        std::copy(p.data(), p.data() + 3, vertices + 3 * i);
    }
    for (std::size_t i = 0; i < mesh.num_triangles(); ++i) {
        for (int k = 0; k < 3; ++k) {
            indices[3 * i + k] = static_cast<unsigned>(mesh.triangles[i][k]);
        }
    }
    rtcSetGeometryBuildQuality(geometry.get(), quality);
    rtcCommitGeometry(geometry.get());
    rtcAttachGeometry(embree_.scene, geometry.get());
    check("rtcAttachGeometry");
}

void EmbreeScene::build(const TriangleMesh& mesh, const RayCasterConfig& config) {
    create_device();
    embree_.scene = rtcNewScene(embree_.device);
    check("rtcNewScene");
    rtcSetSceneFlags(embree_.scene, config.robust ? RTC_SCENE_FLAG_ROBUST : RTC_SCENE_FLAG_NONE);
    const RTCBuildQuality quality = config.build_quality == BuildQuality::High
                                        ? RTC_BUILD_QUALITY_HIGH
                                        : RTC_BUILD_QUALITY_MEDIUM;
    rtcSetSceneBuildQuality(embree_.scene, quality);
    if (!mesh.empty()) attach_triangles(mesh, quality);
    // Embree's TBB builder runs in the caller's arena: with_threads bounds its thread count
    // without touching process-global TBB state.
    with_threads(config.build_parallel, [&] { rtcCommitScene(embree_.scene); });
    check("rtcCommitScene");
}

void EmbreeScene::set_ray(RTCRay& out, const Ray& ray) const {
    const Eigen::Vector3f origin = (ray.origin - offset_).cast<float>();
    out.org_x = origin.x();
    out.org_y = origin.y();
    out.org_z = origin.z();
    out.dir_x = static_cast<float>(ray.direction.x());
    out.dir_y = static_cast<float>(ray.direction.y());
    out.dir_z = static_cast<float>(ray.direction.z());
    out.tnear = static_cast<float>(ray.min_range_m);
    out.tfar = to_float_range(ray.max_range_m);
    out.time = 0.0f;
    out.mask = 0xFFFFFFFFu;
    out.id = 0;
    out.flags = 0;
}

void EmbreeScene::set_lane(RTCRayHit16& packet, std::size_t k, const Ray& ray) const {
    const Eigen::Vector3f origin = (ray.origin - offset_).cast<float>();
    packet.ray.org_x[k] = origin.x();
    packet.ray.org_y[k] = origin.y();
    packet.ray.org_z[k] = origin.z();
    packet.ray.dir_x[k] = static_cast<float>(ray.direction.x());
    packet.ray.dir_y[k] = static_cast<float>(ray.direction.y());
    packet.ray.dir_z[k] = static_cast<float>(ray.direction.z());
    packet.ray.tnear[k] = static_cast<float>(ray.min_range_m);
    packet.ray.tfar[k] = to_float_range(ray.max_range_m);
    packet.ray.time[k] = 0.0f;
    packet.ray.mask[k] = 0xFFFFFFFFu;
    packet.ray.id[k] = static_cast<unsigned>(k);
    packet.ray.flags[k] = 0;
    packet.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
    packet.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
}

RayHit EmbreeScene::make_hit(const Ray& ray, unsigned triangle, float range_f,
                             const Eigen::Vector3d& embree_normal) const {
    RayHit out;
    out.hit = true;
    out.triangle = triangle;
    out.surface_tag = tags_.empty() ? 0 : tags_[triangle];
    Eigen::Vector3d normal = normals_[triangle];
    if (normal.squaredNorm() == 0.0) {  // sliver: fall back on Embree's normal
        normal = embree_normal.normalized();
    }
    const double cosine = normal.dot(ray.direction);
    double range_m = range_f;
    if (std::abs(cosine) > kMinPlaneCosine && normals_[triangle].squaredNorm() > 0.0) {
        range_m = (plane_offsets_[triangle] - normal.dot(ray.origin)) / cosine;
    }
    out.range_m = std::clamp(range_m, ray.min_range_m, ray.max_range_m);
    out.point = ray.origin + out.range_m * ray.direction;
    out.normal = cosine > 0.0 ? Eigen::Vector3d(-normal) : normal;
    return out;
}

RayHit EmbreeScene::cast(const Ray& ray) const {
    if (embree_.scene == nullptr || normals_.empty()) return {};
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit ray_hit;
    set_ray(ray_hit.ray, ray);
    ray_hit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    ray_hit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(embree_.scene, &context, &ray_hit);
    if (ray_hit.hit.geomID == RTC_INVALID_GEOMETRY_ID) return {};
    const RTCHit& hit = ray_hit.hit;
    return make_hit(ray, hit.primID, ray_hit.ray.tfar,
                    Eigen::Vector3d(hit.Ng_x, hit.Ng_y, hit.Ng_z));
}

// Casts rays[begin, end) (at most 16) as one Embree packet: neighbouring rays of a sensor
// sweep are coherent, so packet traversal shares node visits between them.
void EmbreeScene::cast_packet(std::span<const Ray> rays, std::span<RayHit> out) const {
    if (embree_.scene == nullptr || normals_.empty()) {
        std::fill(out.begin(), out.end(), RayHit{});
        return;
    }
    alignas(64) int valid[kPacketSize];
    alignas(64) RTCRayHit16 packet;
    for (std::size_t k = 0; k < kPacketSize; ++k) {
        valid[k] = k < rays.size() ? -1 : 0;
        set_lane(packet, k, rays[k < rays.size() ? k : 0]);  // idle lanes repeat ray 0
    }
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    rtcIntersect16(valid, embree_.scene, &context, &packet);
    for (std::size_t k = 0; k < rays.size(); ++k) {
        if (packet.hit.geomID[k] == RTC_INVALID_GEOMETRY_ID) {
            out[k] = RayHit{};
            continue;
        }
        const Eigen::Vector3d embree_normal(packet.hit.Ng_x[k], packet.hit.Ng_y[k],
                                            packet.hit.Ng_z[k]);
        out[k] = make_hit(rays[k], packet.hit.primID[k], packet.ray.tfar[k], embree_normal);
    }
}

bool EmbreeScene::occluded(const Eigen::Vector3d& from, const Eigen::Vector3d& to) const {
    const double distance_m = (to - from).norm();
    if (normals_.empty() || distance_m <= 2.0 * RayCaster::kLineOfSightMargin_m) return false;
    Ray ray{from, (to - from) / distance_m, distance_m - RayCaster::kLineOfSightMargin_m,
            RayCaster::kLineOfSightMargin_m};
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay embree_ray;
    set_ray(embree_ray, ray);
    rtcOccluded1(embree_.scene, &context, &embree_ray);
    return embree_ray.tfar < 0.0f;  // Embree sets tfar = -inf on occlusion
}

}  // namespace scantling::sim::detail
