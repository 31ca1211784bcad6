#include "scantling/localization/defect_lifting.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

#include <scantling/core/error.hpp>
#include <scantling/perception/plane_ransac.hpp>

#include "detail/config_checks.hpp"

namespace scantling::localization {
namespace {

/// Camera-frame returns projecting within `radius_px` of `pixel`, nearest to it first.
std::vector<Eigen::Vector3d> support_of(const Eigen::Vector2d& pixel, double radius_px,
                                        const PinholeIntrinsics& K,
                                        const Eigen::Isometry3d& T_camera_world,
                                        const PointCloud& depth_world) {
    std::vector<std::pair<double, Eigen::Vector3d>> near;
    for (const Eigen::Vector3d& p_world : depth_world.points) {
        const Eigen::Vector3d p = T_camera_world * p_world;
        if (!(p.z() > 0.0)) continue;
        const Eigen::Vector2d uv(K.fx * p.x() / p.z() + K.cx, K.fy * p.y() / p.z() + K.cy);
        const double d2 = (uv - pixel).squaredNorm();
        if (d2 <= radius_px * radius_px) near.emplace_back(d2, p);
    }
    std::stable_sort(near.begin(), near.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<Eigen::Vector3d> support;
    support.reserve(near.size());
    for (const auto& [d2, p] : near) support.push_back(p);
    return support;
}

/// The plane of the surface the sighting's centre is on: the support may span two (a stiffener
/// beside the patch, a bulkhead meeting the deck), and one least-squares plane through both
/// would tilt and slide the ray's intersection along the plate. So the support (nearest to the
/// centre first) is split into planes by RANSAC and the one holding most of the central
/// quarter of the returns is kept (a majority, not the single nearest return, which noise may
/// have put in a band of leftovers); with no plane found, the least-squares plane of all.
perception::Plane support_plane(const std::vector<Eigen::Vector3d>& support,
                                const DefectLiftingConfig& c) {
    perception::PlaneRansacConfig ransac;
    ransac.distance_threshold_m = c.plane_inlier_m;
    ransac.min_inliers = c.min_support_points;
    ransac.max_planes = 3;
    PointCloud cloud;
    cloud.points = support;
    const std::vector<perception::Plane> planes = perception::segment_planes(cloud, ransac);
    if (planes.empty()) return perception::fit_plane(support);
    const std::size_t central = std::max(c.min_support_points, support.size() / 4);
    std::size_t best = 0, best_count = 0;
    for (std::size_t k = 0; k < planes.size(); ++k) {
        const auto& in = planes[k].inliers;  // sorted indices
        const auto count =
            static_cast<std::size_t>(std::lower_bound(in.begin(), in.end(), central) - in.begin());
        if (count > best_count) best = k, best_count = count;
    }
    return planes[best];
}

/// Range noise along the ray, pixel noise across it, both stretched by 1 / cos(incidence).
Eigen::Matrix3d measurement_covariance_camera(const Eigen::Vector3d& ray_unit, double range_m,
                                              double cos_incidence, std::size_t inliers,
                                              const PinholeIntrinsics& K,
                                              const DefectLiftingConfig& c) {
    const double along_m = c.range_sigma_m / std::sqrt(static_cast<double>(inliers));
    const double across_m = c.pixel_sigma_px * range_m / std::min(K.fx, K.fy);
    const Eigen::Matrix3d along = ray_unit * ray_unit.transpose();
    const Eigen::Matrix3d across = Eigen::Matrix3d::Identity() - along;
    return (along_m * along_m * along + across_m * across_m * across) /
           (cos_incidence * cos_incidence);
}

Eigen::Matrix3d pose_covariance_at(const Eigen::Vector3d& q_world, const LiftingView& view) {
    Eigen::Matrix<double, 3, 6> J;
    J << Eigen::Matrix3d::Identity(), -hat(q_world - view.p_world_body);
    return J * view.body_covariance * J.transpose();
}

PointCloud local_cloud(const PointCloud& depth_world, const Eigen::Vector3d& centre,
                       double radius_m) {
    PointCloud cloud;
    for (const Eigen::Vector3d& p : depth_world.points) {
        if ((p - centre).squaredNorm() <= radius_m * radius_m) cloud.points.push_back(p);
    }
    return cloud;
}

}  // namespace

void DefectLiftingConfig::validate(std::string_view prefix) const {
    using namespace detail;
    require_positive(max_frame_offset_s, prefix, "max_frame_offset_s");
    require_positive(min_support_radius_px, prefix, "min_support_radius_px");
    require_count_at_least(min_support_points, 3, prefix, "min_support_points");
    require_positive(plane_inlier_m, prefix, "plane_inlier_m");
    require_positive(range_sigma_m, prefix, "range_sigma_m");
    require_positive(pixel_sigma_px, prefix, "pixel_sigma_px");
    require(max_incidence_deg > 0.0 && max_incidence_deg < 90.0, prefix, "max_incidence_deg",
            max_incidence_deg, "in (0, 90)");
    require_positive(local_cloud_radius_m, prefix, "local_cloud_radius_m");
}

LiftResult lift_defect(const io::DefectSighting& sighting, const LiftingView& view,
                       const PointCloud& depth_world, const DefectLiftingConfig& config) {
    const double radius_px = std::max(sighting.radius_px, config.min_support_radius_px);
    const Eigen::Isometry3d T_camera_world = view.T_world_camera.inverse();
    const std::vector<Eigen::Vector3d> support =
        support_of(sighting.pixel, radius_px, view.intrinsics, T_camera_world, depth_world);
    if (support.size() < config.min_support_points) {
        return {std::nullopt, fmt::format("no_depth: {} returns within {:.1f} px, expected >= {}",
                                          support.size(), radius_px, config.min_support_points)};
    }
    std::optional<perception::Plane> fitted;
    try {
        fitted = support_plane(support, config);
    } catch (const InputError&) {  // the returns lie on a line (a plate seen edge-on)
        return {std::nullopt,
                fmt::format("degenerate: the {} returns are collinear", support.size())};
    }
    const perception::Plane& plane = *fitted;
    const Eigen::Vector3d ray =
        view.intrinsics.unproject(sighting.pixel, 1.0).normalized();  // camera frame
    const double cos_incidence = std::abs(plane.normal.dot(ray));
    if (cos_incidence < std::cos(config.max_incidence_deg * std::numbers::pi / 180.0)) {
        return {std::nullopt, fmt::format("oblique: the plate is seen at {:.0f} deg",
                                          std::acos(cos_incidence) * 180.0 / std::numbers::pi)};
    }
    const double range_m = -plane.offset_m / plane.normal.dot(ray);
    if (!(range_m > 0.0)) return {std::nullopt, "behind: the support plane is behind the camera"};
    DefectObservation o;
    o.defect_id = sighting.defect_id;
    o.image = sighting.image;
    o.stamp_s = sighting.stamp_s;
    o.pixel = sighting.pixel;
    o.radius_px = sighting.radius_px;
    o.range_m = range_m;
    o.support_points = plane.inliers.size();
    o.position_world = view.T_world_camera * (range_m * ray);
    const Eigen::Vector3d normal = plane.normal.dot(ray) < 0.0 ? plane.normal : -plane.normal;
    o.normal_world = view.T_world_camera.linear() * normal;
    const Eigen::Matrix3d R = view.T_world_camera.linear();
    o.measurement_covariance =
        R *
        measurement_covariance_camera(ray, range_m, cos_incidence, o.support_points,
                                      view.intrinsics, config) *
        R.transpose();
    o.pose_covariance = pose_covariance_at(o.position_world, view);
    o.local_cloud_world = local_cloud(depth_world, o.position_world, config.local_cloud_radius_m);
    return {std::move(o), ""};
}

}  // namespace scantling::localization
