#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>
#include <scantling/perception/laser_pointers.hpp>

#include <fmt/format.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <string>

namespace scantling::perception {
namespace {

// Rim pixels whose laser share is below this add nothing to a centroid but noise.
constexpr double kMinRimShare = 0.05;
// Camera rays and lasers closer to parallel than this (sin² of the angle) do not triangulate.
constexpr double kMinSinSquared = 1e-12;

[[noreturn]] void bad_vector(std::string_view prefix, std::string_view field,
                             const Eigen::Vector3d& value, std::string_view expected) {
    throw ConfigError(fmt::format("{}.{} = [{}, {}, {}], expected {}", prefix, field, value.x(),
                                  value.y(), value.z(), expected));
}

Eigen::Vector3d chroma(const Eigen::Vector3d& rgb) {
    return rgb - Eigen::Vector3d::Constant(rgb.mean());
}

// Unit component of b − a normal to the lasers' direction: the across-beam axis e.
Eigen::Vector3d baseline_axis(const LaserPointerConfig& config) {
    const Eigen::Vector3d d = config.direction_camera.normalized();
    const Eigen::Vector3d b = config.origin_b_camera - config.origin_a_camera;
    return (b - b.dot(d) * d).normalized();
}

void check_image(const io::RgbImage& image, const PinholeIntrinsics& intrinsics) {
    if (image.width < 1 || image.height < 1 ||
        image.pixels.size() != static_cast<std::size_t>(image.width) * image.height) {
        throw InputError(
            fmt::format("laser_pointers: image.pixels.size() = {}, expected "
                        "image.width · image.height = {} · {} (both >= 1)",
                        image.pixels.size(), image.width, image.height));
    }
    if (image.width != intrinsics.width || image.height != intrinsics.height) {
        throw InputError(
            fmt::format("laser_pointers: image.width × image.height = {} × {}, expected the "
                        "intrinsics' {} × {}",
                        image.width, image.height, intrinsics.width, intrinsics.height));
    }
}

// Per-pixel laser share (0 where the hue is off) and the mask of spot pixels.
struct SpotPixels {
    std::vector<double> share;
    cv::Mat1b mask;
};

SpotPixels spot_pixels(const io::RgbImage& image, const LaserPointerConfig& config) {
    const Eigen::Vector3d laser_chroma = chroma(config.spot_rgb);
    const double laser_norm2 = laser_chroma.squaredNorm();
    SpotPixels out{std::vector<double>(image.pixels.size(), 0.0),
                   cv::Mat1b(image.height, image.width, std::uint8_t{0})};
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        const Eigen::Vector3d c = chroma(image.pixels[i].cast<double>());
        const double share = c.dot(laser_chroma) / laser_norm2;
        if ((c - share * laser_chroma).norm() > config.max_off_hue_dn) continue;
        out.share[i] = std::clamp(share, 0.0, 1.0);
        if (share >= config.min_laser_share) out.mask(static_cast<int>(i)) = 255;
    }
    return out;
}

// Share-weighted centroid of blob `label` over its box grown by one pixel (rim included).
Eigen::Vector2d weighted_centroid(const SpotPixels& pixels, const cv::Mat1i& labels,
                                  const cv::Mat1i& stats, int label) {
    const int u0 = std::max(0, stats(label, cv::CC_STAT_LEFT) - 1);
    const int v0 = std::max(0, stats(label, cv::CC_STAT_TOP) - 1);
    const int u1 = std::min(labels.cols - 1, u0 + stats(label, cv::CC_STAT_WIDTH) + 1);
    const int v1 = std::min(labels.rows - 1, v0 + stats(label, cv::CC_STAT_HEIGHT) + 1);
    Eigen::Vector2d sum = Eigen::Vector2d::Zero();
    double total = 0.0;
    for (int v = v0; v <= v1; ++v) {
        for (int u = u0; u <= u1; ++u) {
            if (labels(v, u) != label && labels(v, u) != 0) continue;  // another blob
            const double w = pixels.share[static_cast<std::size_t>(v) * labels.cols + u];
            if (w < kMinRimShare) continue;
            sum += w * Eigen::Vector2d(u, v);
            total += w;
        }
    }
    return sum / total;  // total > 0: the blob's own pixels have w >= min_laser_share
}

std::vector<Eigen::Vector2d> find_blobs(const io::RgbImage& image,
                                        const LaserPointerConfig& config) {
    const SpotPixels pixels = spot_pixels(image, config);
    cv::Mat1i labels;
    cv::Mat1i stats;
    cv::Mat1d centroids;
    const int count =
        cv::connectedComponentsWithStats(pixels.mask, labels, stats, centroids, 8, CV_32S);
    std::vector<Eigen::Vector2d> blobs;
    for (int label = 1; label < count; ++label) {
        const int area = stats(label, cv::CC_STAT_AREA);
        if (area < config.min_spot_area_px || area > config.max_spot_area_px) continue;
        blobs.push_back(weighted_centroid(pixels, labels, stats, label));
    }
    return blobs;
}

// The point of the laser line (origin + s·d) closest to the camera ray through `pixel`, when
// the pair is consistent (see the header), else nullopt.
std::optional<Eigen::Vector3d> hit_on_laser(const Eigen::Vector2d& pixel,
                                            const Eigen::Vector3d& origin_camera,
                                            const PinholeIntrinsics& intrinsics,
                                            const LaserPointerConfig& config) {
    const Eigen::Vector3d c = intrinsics.ray_direction(pixel).normalized();
    const Eigen::Vector3d d = config.direction_camera.normalized();
    const double b = c.dot(d);
    const double sin2 = 1.0 - b * b;
    if (sin2 < kMinSinSquared) return std::nullopt;
    // Stationarity of |t·c − origin − s·d|² in t and s.
    const double t = (c.dot(origin_camera) - b * d.dot(origin_camera)) / sin2;
    const double s = b * t - d.dot(origin_camera);
    if (t <= 0.0 || s < 0.0) return std::nullopt;
    const Eigen::Vector3d hit = origin_camera + s * d;
    const std::optional<Eigen::Vector2d> projected = intrinsics.project(hit);
    if (!projected || (*projected - pixel).norm() > config.max_reprojection_px) return std::nullopt;
    return hit;
}

LaserPointerMeasurement with_status(LaserPointerMeasurement m, LaserPointerStatus status,
                                    std::string message) {
    m.status = status;
    m.message = std::move(message);
    return m;
}

// Fills the geometry from the hits (file comment of the header, step 4).
LaserPointerMeasurement triangulated(LaserPointerMeasurement m, const LaserPointerConfig& config) {
    const Eigen::Vector3d delta = m.p_camera[1] - m.p_camera[0];
    m.distance_m = 0.5 * (m.p_camera[0].z() + m.p_camera[1].z());
    m.pitch_rad = std::atan2(delta.dot(config.direction_camera.normalized()),
                             delta.dot(baseline_axis(config)));
    m.mm_per_px = 1000.0 * delta.norm() / (m.spots_px[1] - m.spots_px[0]).norm();
    std::string message =
        fmt::format("distance {:.3f} m, pitch {:.2f} deg, {:.3f} mm/px", m.distance_m,
                    m.pitch_rad * 180.0 / std::numbers::pi, m.mm_per_px);
    return with_status(std::move(m), LaserPointerStatus::kOk, std::move(message));
}

LaserPointerMeasurement resolve_pair(LaserPointerMeasurement m, const PinholeIntrinsics& k,
                                     const LaserPointerConfig& config) {
    int pairs = 0;
    for (std::size_t i = 0; i < m.candidates_px.size(); ++i) {
        const auto hit_a = hit_on_laser(m.candidates_px[i], config.origin_a_camera, k, config);
        if (!hit_a) continue;
        for (std::size_t j = 0; j < m.candidates_px.size(); ++j) {
            if (j == i) continue;
            const auto hit_b = hit_on_laser(m.candidates_px[j], config.origin_b_camera, k, config);
            if (!hit_b) continue;
            if (++pairs > 1) continue;
            m.spots_px = {m.candidates_px[i], m.candidates_px[j]};
            m.p_camera = {*hit_a, *hit_b};
        }
    }
    if (pairs == 1) return triangulated(std::move(m), config);
    const std::size_t blobs = m.candidates_px.size();
    m.spots_px = {Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()};
    m.p_camera = {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
    return with_status(
        std::move(m), LaserPointerStatus::kAmbiguous,
        fmt::format("{} spot-coloured blobs, {} pairs match the lasers (need 1)", blobs, pairs));
}

}  // namespace

void LaserPointerConfig::validate(std::string_view prefix) const {
    using namespace config_checks;
    if (!origin_a_camera.allFinite())
        bad_vector(prefix, "origin_a_camera", origin_a_camera, "finite");
    if (!origin_b_camera.allFinite())
        bad_vector(prefix, "origin_b_camera", origin_b_camera, "finite");
    if (!direction_camera.allFinite() || !(direction_camera.z() > 0.0)) {
        bad_vector(prefix, "direction_camera", direction_camera, "finite with z > 0");
    }
    const Eigen::Vector3d d = direction_camera.normalized();
    const Eigen::Vector3d b = origin_b_camera - origin_a_camera;
    if (!((b - b.dot(d) * d).norm() > 1e-6)) {
        bad_vector(prefix, "origin_b_camera", origin_b_camera,
                   "at least 1e-6 m from laser a's line (a baseline across the beams)");
    }
    if (!(spot_rgb.minCoeff() >= 0.0 && spot_rgb.maxCoeff() <= 255.0) ||
        !(chroma(spot_rgb).norm() > 1.0)) {
        bad_vector(prefix, "spot_rgb", spot_rgb, "channels in [0, 255], not grey");
    }
    require(min_laser_share > 0.0 && min_laser_share <= 1.0, prefix, "min_laser_share",
            min_laser_share, "in (0, 1]");
    require_positive(max_off_hue_dn, prefix, "max_off_hue_dn");
    require_at_least(min_spot_area_px, 1, prefix, "min_spot_area_px");
    require_at_least(max_spot_area_px, min_spot_area_px, prefix, "max_spot_area_px");
    require_positive(max_reprojection_px, prefix, "max_reprojection_px");
}

LaserPointerMeasurement measure_laser_pointers(const io::RgbImage& image,
                                               const PinholeIntrinsics& intrinsics,
                                               const LaserPointerConfig& config) {
    config.validate();
    intrinsics.validate("laser_pointers.intrinsics");
    check_image(image, intrinsics);
    LaserPointerMeasurement m;
    m.candidates_px = find_blobs(image, config);
    if (m.candidates_px.empty()) {
        return with_status(std::move(m), LaserPointerStatus::kNoSpots, "no laser spot in view");
    }
    if (m.candidates_px.size() == 1) {
        return with_status(std::move(m), LaserPointerStatus::kOneSpot,
                           "one laser spot in view (the other is off the surface or hidden)");
    }
    return resolve_pair(std::move(m), intrinsics, config);
}

std::string_view to_string(LaserPointerStatus status) {
    switch (status) {
        case LaserPointerStatus::kOk:
            return "ok";
        case LaserPointerStatus::kNoSpots:
            return "no_spots";
        case LaserPointerStatus::kOneSpot:
            return "one_spot";
        case LaserPointerStatus::kAmbiguous:
            return "ambiguous";
    }
    return "unknown";
}

}  // namespace scantling::perception
