#include "scenes.hpp"

#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include <scantling/core/random.hpp>
#include <scantling/core/se3.hpp>

namespace scantling::registration::test {
namespace {

/// An axis-aligned rectangle: a corner, two edge vectors.
struct Rect {
    Eigen::Vector3d origin;
    Eigen::Vector3d u;
    Eigen::Vector3d v;
    double area() const { return u.cross(v).norm(); }
};

/// The five visible faces of a box standing on the floor (z from `lo.z()` to `hi.z()`).
void add_box(std::vector<Rect>& rects, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
    const Eigen::Vector3d d = hi - lo;
    const Eigen::Vector3d ex(d.x(), 0, 0), ey(0, d.y(), 0), ez(0, 0, d.z());
    rects.push_back({Eigen::Vector3d(lo.x(), lo.y(), hi.z()), ex, ey});  // top
    rects.push_back({lo, ex, ez});
    rects.push_back({lo, ey, ez});
    rects.push_back({lo + ex, ey, ez});
    rects.push_back({lo + ey, ex, ez});
}

std::vector<Rect> room_corner() {
    // Room [0, 6] × [0, 4] × [0, 3] shifted by −(3, 2, 1.5) so the origin is its centre.
    const Eigen::Vector3d o(-3.0, -2.0, -1.5);
    std::vector<Rect> rects = {
        {o, Eigen::Vector3d(6, 0, 0), Eigen::Vector3d(0, 4, 0)},  // floor
        {o, Eigen::Vector3d(0, 4, 0), Eigen::Vector3d(0, 0, 3)},  // wall x = −3
        {o, Eigen::Vector3d(6, 0, 0), Eigen::Vector3d(0, 0, 3)},  // wall y = −2
    };
    add_box(rects, o + Eigen::Vector3d(2.0, 1.5, 0.0), o + Eigen::Vector3d(3.0, 2.5, 1.0));
    add_box(rects, o + Eigen::Vector3d(4.0, 0.5, 0.0), o + Eigen::Vector3d(4.8, 1.1, 0.6));
    return rects;
}

PointCloud sample_rects(const std::vector<Rect>& rects, std::size_t n, Rng& rng, double sigma) {
    double total = 0.0;
    for (const Rect& r : rects) total += r.area();
    PointCloud cloud;
    cloud.points.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
        double pick = rng.uniform(0.0, total);
        std::size_t k = 0;
        while (k + 1 < rects.size() && pick > rects[k].area()) pick -= rects[k++].area();
        const Rect& r = rects[k];
        const Eigen::Vector3d p = r.origin + rng.uniform() * r.u + rng.uniform() * r.v;
        cloud.points.push_back(sigma > 0.0 ? Eigen::Vector3d(p + rng.normal3(sigma)) : p);
    }
    return cloud;
}

}  // namespace

PointCloud sample_room_corner(std::size_t n, std::uint64_t seed, double noise_sigma_m) {
    Rng rng(seed);
    return sample_rects(room_corner(), n, rng, noise_sigma_m);
}

PointCloud sample_plated_room_corner(std::size_t n, std::uint64_t seed, double thickness_m,
                                     bool hidden_faces) {
    const Eigen::Vector3d o(-3.0, -2.0, -1.5);
    const Eigen::Vector3d ex(6, 0, 0), ey(0, 4, 0), ez(0, 0, 3);
    // (face, normal into the room): floor, wall x = −3, wall y = −2.
    const std::array<std::pair<Rect, Eigen::Vector3d>, 3> plates = {{
        {{o, ex, ey}, Eigen::Vector3d::UnitZ()},
        {{o, ey, ez}, Eigen::Vector3d::UnitX()},
        {{o, ex, ez}, Eigen::Vector3d::UnitY()},
    }};
    std::vector<Rect> rects;
    std::vector<Eigen::Vector3d> normals;
    for (const auto& [rect, normal] : plates) {
        rects.push_back(rect);
        normals.push_back(normal);
        if (!hidden_faces) continue;
        rects.push_back({rect.origin - thickness_m * normal, rect.u, rect.v});
        normals.push_back(-normal);
    }
    Rng rng(seed);
    PointCloud cloud = sample_rects(rects, n, rng, 0.0);
    // sample_rects does not say which rectangle a point came from: find it by its offset.
    for (const Eigen::Vector3d& p : cloud.points) {
        std::size_t best = 0;
        for (std::size_t k = 1; k < rects.size(); ++k) {
            if (std::abs(normals[k].dot(p - rects[k].origin)) <
                std::abs(normals[best].dot(p - rects[best].origin)))
                best = k;
        }
        cloud.normals.push_back(normals[best]);
    }
    return cloud;
}

PointCloud sample_plane(std::size_t n, std::uint64_t seed, double half_size_m) {
    Rng rng(seed);
    const double s = 2.0 * half_size_m;
    const std::vector<Rect> rects = {{Eigen::Vector3d(-half_size_m, -half_size_m, 0.0),
                                      Eigen::Vector3d(s, 0, 0), Eigen::Vector3d(0, s, 0)}};
    return sample_rects(rects, n, rng, 0.0);
}

PointCloud sample_clutter(std::size_t n, std::uint64_t seed) {
    Rng rng(seed);
    PointCloud cloud;
    for (std::size_t i = 0; i < n; ++i) {
        cloud.points.emplace_back(rng.uniform(-3.0, 3.0), rng.uniform(-2.0, 2.0),
                                  rng.uniform(-1.5, 1.5));
    }
    return cloud;
}

Eigen::Isometry3d make_pose(double roll_rad, double pitch_rad, double yaw_rad,
                            const Eigen::Vector3d& t_m) {
    return make_isometry(rotation_from_euler_zyx(roll_rad, pitch_rad, yaw_rad), t_m);
}

}  // namespace scantling::registration::test
