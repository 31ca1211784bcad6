#pragma once
// The Embree 3 scene behind RayCaster (private: Embree types stay out of public headers).

#include <scantling/sim/ray_caster.hpp>

#include <embree3/rtcore.h>

#include <Eigen/Core>
#include <mutex>
#include <span>
#include <string>
#include <vector>

namespace scantling::sim::detail {

// Embree reports the text of an error only through a callback; the code alone is vague.
struct EmbreeErrorSink {
    std::mutex mutex;
    std::string message;
};

/// Owns an Embree device and a committed scene of one triangle mesh, plus double-precision
/// triangle planes for range refinement. Queries are const and thread-safe; inputs are assumed
/// valid (RayCaster checks them).
class EmbreeScene {
  public:
    static constexpr std::size_t kPacketSize = 16;  ///< rays per rtcIntersect16 packet

    /// `tags` empty or one per triangle; the mesh must be valid (checked by the caller).
    EmbreeScene(const TriangleMesh& mesh, std::span<const int> tags, const RayCasterConfig& config);
    EmbreeScene(const EmbreeScene&) = delete;
    EmbreeScene& operator=(const EmbreeScene&) = delete;

    RayHit cast(const Ray& ray) const;
    /// At most kPacketSize rays traced as one packet (rtcIntersect16).
    void cast_packet(std::span<const Ray> rays, std::span<RayHit> out) const;
    bool occluded(const Eigen::Vector3d& from, const Eigen::Vector3d& to) const;

    std::size_t num_triangles() const { return normals_.size(); }
    const Aabb& bounds() const { return bounds_; }

  private:
    // Released by its destructor, so a constructor that throws half-way leaks nothing.
    struct Handles {
        RTCDevice device = nullptr;
        RTCScene scene = nullptr;
        Handles() = default;
        Handles(const Handles&) = delete;
        Handles& operator=(const Handles&) = delete;
        ~Handles();
    };

    void check(const char* call);
    void create_device();
    void store_planes(const TriangleMesh& mesh);
    void attach_triangles(const TriangleMesh& mesh, RTCBuildQuality quality);
    void build(const TriangleMesh& mesh, const RayCasterConfig& config);
    void set_ray(RTCRay& out, const Ray& ray) const;
    void set_lane(RTCRayHit16& packet, std::size_t k, const Ray& ray) const;
    // The hit in double precision; `embree_normal` is used only for zero-area triangles.
    RayHit make_hit(const Ray& ray, unsigned triangle, float range_f,
                    const Eigen::Vector3d& embree_normal) const;

    EmbreeErrorSink errors_;  // declared first: outlives the device that writes into it
    Handles embree_;
    Eigen::Vector3d offset_ = Eigen::Vector3d::Zero();  // scene point = world point - offset
    std::vector<Eigen::Vector3d> normals_;              // unit normal per triangle, world frame
    std::vector<double> plane_offsets_;                 // normal · (any vertex), world frame
    std::vector<int> tags_;
    Aabb bounds_;
};

}  // namespace scantling::sim::detail
