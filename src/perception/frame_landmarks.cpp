#include "scantling/perception/frame_landmarks.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <span>

#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>

#include "detail/angles.hpp"

namespace scantling::perception {
namespace {

using detail::radians;

using config_checks::require;
using config_checks::require_non_negative;
using config_checks::require_positive;

/// An orthonormal basis of a plate: along the ship, across it, out of the plate.
struct PlateBasis {
    Eigen::Vector3d along, across, normal;
};

PlateBasis plate_basis(const Plane& plate, const Eigen::Vector3d& axis) {
    const Eigen::Vector3d along = (axis - axis.dot(plate.normal) * plate.normal).normalized();
    return {along, plate.normal.cross(along), plate.normal};
}

/// How far the plane's points spread across the ship (a stiffener's own faces spread no more
/// than its height: they are not plating).
double across_extent(const Plane& plane, const PointCloud& cloud, const Eigen::Vector3d& axis) {
    const Eigen::Vector3d across = plane.normal.cross(axis).normalized();
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const std::size_t i : plane.inliers) {
        lo = std::min(lo, across.dot(cloud.points[i]));
        hi = std::max(hi, across.dot(cloud.points[i]));
    }
    return hi - lo;
}

/// Another plane reaches higher above the plate than a stiffener: a frame or a wall, whose
/// points must not be taken for stiffeners.
bool rises_above(const Plane& plate, const Plane& other, const PointCloud& cloud,
                 double max_height_m) {
    std::size_t above = 0;
    for (const std::size_t i : other.inliers) {
        if (plate.signed_distance(cloud.points[i]) > max_height_m) ++above;
    }
    return above * 10 > other.inliers.size();
}

std::vector<char> excluded_points(const FrameLandmarks& found, int plate, const PointCloud& cloud,
                                  const FrameLandmarkConfig& c) {
    std::vector<char> excluded(cloud.size(), 0);
    const Plane& p = found.planes[static_cast<std::size_t>(plate)];
    for (std::size_t k = 0; k < found.planes.size(); ++k) {
        const Plane& other = found.planes[k];
        const bool frame = std::find(found.frame_planes.begin(), found.frame_planes.end(),
                                     static_cast<int>(k)) != found.frame_planes.end();
        if (static_cast<int>(k) == plate ||
            (!frame && !rises_above(p, other, cloud, c.max_stiffener_height_m))) {
            continue;
        }
        for (const std::size_t i : other.inliers) excluded[i] = 1;
    }
    return excluded;
}

struct Sample {
    double across = 0.0, along = 0.0, height = 0.0;
};

std::vector<Sample> stiffener_samples(const FrameLandmarks& found, int plate,
                                      const PointCloud& cloud, const FrameLandmarkConfig& c,
                                      const PlateBasis& basis) {
    const std::vector<char> excluded = excluded_points(found, plate, cloud, c);
    const Plane& p = found.planes[static_cast<std::size_t>(plate)];
    std::vector<Sample> samples;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const double h = p.signed_distance(cloud.points[i]);
        if (excluded[i] || h < c.min_stiffener_height_m || h > c.max_stiffener_height_m) continue;
        samples.push_back({basis.across.dot(cloud.points[i]), basis.along.dot(cloud.points[i]), h});
    }
    std::sort(samples.begin(), samples.end(),
              [](const Sample& a, const Sample& b) { return a.across < b.across; });
    return samples;
}

double quantile(std::vector<double> values, double q) {
    const auto k =
        static_cast<std::size_t>(std::clamp(std::ceil(q * static_cast<double>(values.size())) - 1.0,
                                            0.0, static_cast<double>(values.size() - 1)));
    std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
    return values[k];
}

/// Least-squares line across = a + b·along through the samples (the stiffener's direction in
/// the plate: the frame axis is only known to a few degrees).
Eigen::Vector2d fit_across(std::span<const Sample> samples) {
    Eigen::Matrix2d A = Eigen::Matrix2d::Zero();
    Eigen::Vector2d b = Eigen::Vector2d::Zero();
    for (const Sample& s : samples) {
        const Eigen::Vector2d row(1.0, s.along);
        A += row * row.transpose();
        b += row * s.across;
    }
    return A.ldlt().solve(b);
}

/// The top edge of one stiffener from its samples, or nothing when it is too short or sparse.
std::optional<StiffenerLine> line_of(std::span<const Sample> samples, const Plane& plate,
                                     const PlateBasis& basis, const FrameLandmarkConfig& c) {
    if (samples.size() < c.min_line_points) return std::nullopt;
    std::vector<double> heights;
    double lo = samples.front().along, hi = lo;
    for (const Sample& s : samples) {
        heights.push_back(s.height);
        lo = std::min(lo, s.along);
        hi = std::max(hi, s.along);
    }
    if (hi - lo < c.min_line_length_m) return std::nullopt;
    const Eigen::Vector2d ab = fit_across(samples);
    const double mid = 0.5 * (lo + hi);
    StiffenerLine line;
    line.height_m = quantile(std::move(heights), c.height_quantile);
    line.direction = (basis.along + ab.y() * basis.across).normalized();
    line.plate_normal = basis.normal;
    line.point = basis.along * mid + basis.across * (ab.x() + ab.y() * mid) +
                 basis.normal * (line.height_m - plate.offset_m);
    // The seen extent along the line's own direction, about its point.
    const double scale = std::sqrt(1.0 + ab.y() * ab.y());
    line.axial_min_m = (lo - mid) * scale;
    line.axial_max_m = (hi - mid) * scale;
    line.num_points = samples.size();
    return line;
}

void find_lines(FrameLandmarks& found, int plate, const PointCloud& cloud,
                const FrameLandmarkConfig& c) {
    const Plane& p = found.planes[static_cast<std::size_t>(plate)];
    const PlateBasis basis = plate_basis(p, c.frame_axis.normalized());
    const std::vector<Sample> samples = stiffener_samples(found, plate, cloud, c, basis);
    std::size_t begin = 0;
    for (std::size_t i = 1; i <= samples.size(); ++i) {
        if (i < samples.size() && samples[i].across - samples[i - 1].across <= c.stiffener_gap_m)
            continue;
        const std::span<const Sample> cluster(samples.data() + begin, i - begin);
        if (auto line = line_of(cluster, p, basis, c)) {
            line->plate = plate;
            found.lines.push_back(*line);
        }
        begin = i;
    }
}

/// The seen extent of a frame plane in its own 2-D coordinates.
struct FrameExtent {
    Eigen::Vector3d e1, e2;
    Eigen::Vector2d min, max;
};

FrameExtent extent_of(const Plane& frame, const PointCloud& cloud) {
    FrameExtent e;
    e.e1 = frame.normal.unitOrthogonal();
    e.e2 = frame.normal.cross(e.e1);
    e.min = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
    e.max = -e.min;
    for (const std::size_t i : frame.inliers) {
        const Eigen::Vector2d q(e.e1.dot(cloud.points[i]), e.e2.dot(cloud.points[i]));
        e.min = e.min.cwiseMin(q);
        e.max = e.max.cwiseMax(q);
    }
    return e;
}

/// Where the line meets the frame, if the stiffener reaches it there (it ends at the frame,
/// within max_gap_to_frame_m, and the meeting point is on the part of the frame seen).
std::optional<Eigen::Vector3d> meeting_point(const StiffenerLine& line, const Plane& frame,
                                             const FrameExtent& extent,
                                             const FrameLandmarkConfig& c) {
    const double along = frame.normal.dot(line.direction);
    if (std::abs(along) < std::cos(radians(c.axis_tolerance_deg))) return std::nullopt;
    const double t = -frame.signed_distance(line.point) / along;
    const double gap = std::max(line.axial_min_m - t, t - line.axial_max_m);
    if (gap > c.max_gap_to_frame_m || gap < -c.max_gap_to_frame_m) return std::nullopt;
    const Eigen::Vector3d x = line.point + t * line.direction;
    const Eigen::Vector2d q(extent.e1.dot(x), extent.e2.dot(x));
    const double m = c.frame_extent_margin_m;
    if ((q.array() < extent.min.array() - m).any() || (q.array() > extent.max.array() + m).any())
        return std::nullopt;
    return x;
}

void intersect(FrameLandmarks& found, const PointCloud& cloud, const FrameLandmarkConfig& c) {
    for (const int f : found.frame_planes) {
        const Plane& frame = found.planes[static_cast<std::size_t>(f)];
        const FrameExtent extent = extent_of(frame, cloud);
        for (std::size_t l = 0; l < found.lines.size(); ++l) {
            const StiffenerLine& line = found.lines[l];
            const auto x = meeting_point(line, frame, extent, c);
            if (!x) continue;
            found.landmarks.push_back(
                {*x, frame.normal, line.plate_normal, f, static_cast<int>(l)});
        }
    }
}

}  // namespace

void FrameLandmarkConfig::validate(std::string_view prefix) const {
    planes.validate(fmt::format("{}.planes", prefix));
    require(frame_axis.allFinite() && frame_axis.norm() > 1e-9, prefix, "frame_axis",
            frame_axis.norm(), "a finite non-zero vector");
    require(axis_tolerance_deg > 0.0 && axis_tolerance_deg < 45.0, prefix, "axis_tolerance_deg",
            axis_tolerance_deg, "in (0, 45)");
    require_positive(min_stiffener_height_m, prefix, "min_stiffener_height_m");
    require(
        std::isfinite(max_stiffener_height_m) && max_stiffener_height_m > min_stiffener_height_m,
        prefix, "max_stiffener_height_m", max_stiffener_height_m,
        "finite > min_stiffener_height_m");
    config_checks::require_count_at_least(min_plate_inliers, 3, prefix, "min_plate_inliers");
    require_positive(stiffener_gap_m, prefix, "stiffener_gap_m");
    require_positive(min_line_length_m, prefix, "min_line_length_m");
    config_checks::require_count_at_least(min_line_points, 3, prefix, "min_line_points");
    require(height_quantile > 0.0 && height_quantile <= 1.0, prefix, "height_quantile",
            height_quantile, "in (0, 1]");
    require_non_negative(max_gap_to_frame_m, prefix, "max_gap_to_frame_m");
    require_non_negative(frame_extent_margin_m, prefix, "frame_extent_margin_m");
}

FrameLandmarks detect_frame_landmarks(const PointCloud& cloud, const Eigen::Vector3d& viewpoint,
                                      const FrameLandmarkConfig& config) {
    config.validate();
    if (!viewpoint.allFinite()) throw InputError("frame landmarks: non-finite viewpoint");
    FrameLandmarks found;
    if (cloud.empty()) return found;
    check_usable(cloud, "frame landmarks: cloud");
    const Eigen::Vector3d axis = config.frame_axis.normalized();
    const double cos_tol = std::cos(radians(config.axis_tolerance_deg));
    const double sin_tol = std::sin(radians(config.axis_tolerance_deg));
    for (Plane& p : segment_planes(cloud, config.planes)) {
        found.planes.push_back(facing(std::move(p), viewpoint));
        const double along = std::abs(found.planes.back().normal.dot(axis));
        const int index = static_cast<int>(found.planes.size()) - 1;
        if (along >= cos_tol) found.frame_planes.push_back(index);
        if (along <= sin_tol && found.planes.back().inliers.size() >= config.min_plate_inliers &&
            across_extent(found.planes.back(), cloud, axis) > config.max_stiffener_height_m) {
            found.plate_planes.push_back(index);
        }
    }
    FrameLandmarkConfig refined = config;
    if (!found.frame_planes.empty()) {
        // Stiffeners run square to the frames: the largest frame's normal is the axis as seen,
        // free of the prediction's yaw and pitch error.
        const Eigen::Vector3d& n =
            found.planes[static_cast<std::size_t>(found.frame_planes[0])].normal;
        refined.frame_axis = n.dot(axis) < 0.0 ? Eigen::Vector3d(-n) : n;
    }
    for (const int plate : found.plate_planes) find_lines(found, plate, cloud, refined);
    intersect(found, cloud, config);
    return found;
}

}  // namespace scantling::perception
