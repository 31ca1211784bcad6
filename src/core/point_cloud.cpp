#include <scantling/core/error.hpp>
#include <scantling/core/point_cloud.hpp>

#include <fmt/format.h>

namespace scantling {
namespace {

template <typename Field>
void check_field(const Field& field, std::size_t n, std::string_view name, std::string_view what) {
    if (!field.empty() && field.size() != n) {
        throw InputError(
            fmt::format("{}: field '{}' has {} values for {} points", what, name, field.size(), n));
    }
}

template <typename Field>
void copy_selected(const Field& src, Field& dst, std::span<const std::size_t> indices) {
    if (src.empty()) return;
    dst.resize(indices.size());
    for (std::size_t i = 0; i < indices.size(); ++i) dst[i] = src[indices[i]];
}

template <typename Field>
void check_append_field(const Field& dst, const Field& src, std::string_view name) {
    if (dst.empty() != src.empty()) {
        throw InputError(fmt::format("append: field '{}' present in one cloud only", name));
    }
}

template <typename Field>
void append_field(Field& dst, const Field& src) {
    dst.insert(dst.end(), src.begin(), src.end());
}

void check_indices(std::span<const std::size_t> indices, std::size_t n) {
    for (std::size_t i = 0; i < indices.size(); ++i) {
        if (indices[i] >= n) {
            throw InputError(
                fmt::format("select: index {} at position {} is out of range for {} "
                            "points",
                            indices[i], i, n));
        }
    }
}

}  // namespace

void PointCloud::reserve(std::size_t n) {
    points.reserve(n);
    if (has_normals()) normals.reserve(n);
    if (has_covariances()) covariances.reserve(n);
    if (has_intensities()) intensities.reserve(n);
    if (has_rings()) rings.reserve(n);
    if (has_times()) times_s.reserve(n);
    if (has_colors()) colors.reserve(n);
}

void check_consistent(const PointCloud& cloud, std::string_view what) {
    const std::size_t n = cloud.size();
    check_field(cloud.normals, n, "normals", what);
    check_field(cloud.covariances, n, "covariances", what);
    check_field(cloud.intensities, n, "intensities", what);
    check_field(cloud.rings, n, "rings", what);
    check_field(cloud.times_s, n, "times_s", what);
    check_field(cloud.colors, n, "colors", what);
}

void check_finite(const PointCloud& cloud, std::string_view what) {
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        if (!cloud.points[i].allFinite()) {
            throw InputError(fmt::format("{}: point {} is not finite ({}, {}, {})", what, i,
                                         cloud.points[i].x(), cloud.points[i].y(),
                                         cloud.points[i].z()));
        }
    }
}

void check_usable(const PointCloud& cloud, std::string_view what) {
    if (cloud.empty()) throw InputError(fmt::format("{}: the cloud is empty", what));
    check_consistent(cloud, what);
    check_finite(cloud, what);
}

std::vector<std::string> field_names(const PointCloud& cloud) {
    std::vector<std::string> names{"x", "y", "z"};
    if (cloud.has_normals()) names.insert(names.end(), {"normal_x", "normal_y", "normal_z"});
    if (cloud.has_intensities()) names.emplace_back("intensity");
    if (cloud.has_rings()) names.emplace_back("ring");
    if (cloud.has_times()) names.emplace_back("time");
    if (cloud.has_colors()) names.emplace_back("rgb");
    if (cloud.has_covariances()) names.emplace_back("covariance");
    return names;
}

PointCloud select(const PointCloud& cloud, std::span<const std::size_t> indices) {
    check_consistent(cloud, "select");
    check_indices(indices, cloud.size());
    PointCloud out;
    out.stamp_s = cloud.stamp_s;
    copy_selected(cloud.points, out.points, indices);
    copy_selected(cloud.normals, out.normals, indices);
    copy_selected(cloud.covariances, out.covariances, indices);
    copy_selected(cloud.intensities, out.intensities, indices);
    copy_selected(cloud.rings, out.rings, indices);
    copy_selected(cloud.times_s, out.times_s, indices);
    copy_selected(cloud.colors, out.colors, indices);
    return out;
}

PointCloud remove_non_finite(const PointCloud& cloud) {
    std::vector<std::size_t> keep;
    keep.reserve(cloud.size());
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const bool normal_ok = !cloud.has_normals() || cloud.normals[i].allFinite();
        if (cloud.points[i].allFinite() && normal_ok) keep.push_back(i);
    }
    return select(cloud, keep);
}

void append(PointCloud& dst, const PointCloud& src) {
    check_consistent(dst, "append (destination)");
    check_consistent(src, "append (source)");
    // An empty side imposes no field layout; otherwise check every field before touching dst
    // so that a mismatch leaves dst unchanged.
    if (src.empty()) return;
    if (!dst.empty()) {
        check_append_field(dst.normals, src.normals, "normals");
        check_append_field(dst.covariances, src.covariances, "covariances");
        check_append_field(dst.intensities, src.intensities, "intensities");
        check_append_field(dst.rings, src.rings, "rings");
        check_append_field(dst.times_s, src.times_s, "times_s");
        check_append_field(dst.colors, src.colors, "colors");
    }
    append_field(dst.normals, src.normals);
    append_field(dst.covariances, src.covariances);
    append_field(dst.intensities, src.intensities);
    append_field(dst.rings, src.rings);
    append_field(dst.times_s, src.times_s);
    append_field(dst.colors, src.colors);
    append_field(dst.points, src.points);
}

void transform_in_place(PointCloud& cloud, const Eigen::Isometry3d& T_to_from) {
    const Eigen::Matrix3d R = T_to_from.linear();
    for (auto& p : cloud.points) p = T_to_from * p;
    for (auto& n : cloud.normals) n = R * n;
    for (auto& c : cloud.covariances) c = R * c * R.transpose();
}

PointCloud transformed(const PointCloud& cloud, const Eigen::Isometry3d& T_to_from) {
    PointCloud out = cloud;
    transform_in_place(out, T_to_from);
    return out;
}

Aabb compute_bounds(const PointCloud& cloud) { return compute_bounds(std::span(cloud.points)); }

Aabb compute_bounds(std::span<const Eigen::Vector3d> points) {
    Aabb box;
    for (const auto& p : points) box.extend(p);
    return box;
}

}  // namespace scantling
