#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>
#include <scantling/core/random.hpp>
#include <scantling/perception/sonar_hull_line.hpp>

#include <fmt/format.h>
#include <Eigen/Eigenvalues>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <optional>
#include <string>

namespace scantling::perception {
namespace {

struct Line {
    Eigen::Vector2d normal = Eigen::Vector2d::UnitX();  // unit
    double offset_m = 0.0;                              // n · p = offset_m on the line

    double distance(const Eigen::Vector2d& p) const { return std::abs(normal.dot(p) - offset_m); }
};

struct EdgeImages {
    cv::Mat image;  // 8-bit, blurred: rows = beams, columns = bins
    cv::Mat edges;  // Canny of image
};

// The polar image scaled to 8 bits and blurred along range only: beams are independent
// measurements, so speckle in one must not leak into its neighbours.
EdgeImages edge_images(const io::SonarPing& ping, const SonarHullLineConfig& config) {
    EdgeImages out{cv::Mat(ping.num_beams, ping.num_bins, CV_8UC1), cv::Mat()};
    const double scale = 255.0 / config.intensity_full_scale;
    for (int b = 0; b < ping.num_beams; ++b) {
        auto* row = out.image.ptr<std::uint8_t>(b);
        for (int j = 0; j < ping.num_bins; ++j) {
            const double v = std::clamp(scale * ping.at(b, j), 0.0, 255.0);
            row[j] = static_cast<std::uint8_t>(std::lround(v));
        }
    }
    if (config.blur_kernel_px > 1) {
        cv::GaussianBlur(out.image, out.image, cv::Size(config.blur_kernel_px, 1), 0.0, 0.0,
                         cv::BORDER_REPLICATE);
    }
    cv::Canny(out.image, out.edges, config.canny_low_threshold, config.canny_high_threshold);
    return out;
}

// Sub-pixel position of the step near edge pixel e of one row (between pixels u − ½ and u + ½
// at u): the vertex of the parabola through the forward differences I[k + 1] − I[k] around
// their maximum next to e. Canny marks either pixel of a step (ties go left) and a one-bin echo
// (a 30 m range setting) only on the pixel before it: up to a bin of bias (~6 cm) without this.
double step_position(const std::uint8_t* row, int num_bins, int e) {
    const auto rise = [&](int k) { return double(row[k + 1]) - double(row[k]); };
    int k = std::clamp(e, 0, num_bins - 2);
    for (int c = std::max(0, e - 1); c <= std::min(e + 1, num_bins - 2); ++c) {
        if (rise(c) > rise(k)) k = c;
    }
    if (k < 1 || k + 1 > num_bins - 2) return k + 0.5;
    const double curvature = rise(k - 1) - 2.0 * rise(k) + rise(k + 1);
    if (!(curvature < 0.0)) return k + 0.5;  // flat top: keep the pixel boundary
    return k + 0.5 + std::clamp(0.5 * (rise(k - 1) - rise(k + 1)) / curvature, -0.5, 0.5);
}

// The hull range of a step at fractional pixel u: the centre of the first bin past it (the
// surface lies somewhere in that bin), interpolated on the ping's bin centres.
double range_after_step(const io::SonarPing& ping, double u) {
    const double v = std::clamp(u + 0.5, 0.0, double(ping.num_bins - 1));
    const auto j = std::min(static_cast<std::size_t>(v), ping.ranges_m.size() - 1);
    if (j + 1 >= ping.ranges_m.size()) return ping.ranges_m[j];
    return ping.ranges_m[j] + (v - double(j)) * (ping.ranges_m[j + 1] - ping.ranges_m[j]);
}

// Per beam the closest edge pixel (SPEC §5: a locally flat hull is the first echo of a beam).
std::vector<SonarFeature> closest_edges(const io::SonarPing& ping, const EdgeImages& images) {
    std::vector<SonarFeature> features;
    for (int b = 0; b < ping.num_beams; ++b) {
        const auto* row = images.edges.ptr<std::uint8_t>(b);
        const auto* hit = std::find_if(row, row + ping.num_bins, [](auto v) { return v != 0; });
        if (hit == row + ping.num_bins) continue;
        const double u =
            step_position(images.image.ptr<std::uint8_t>(b), ping.num_bins, int(hit - row));
        SonarFeature f;
        f.beam = b;
        f.range_m = range_after_step(ping, u);
        f.bearing_rad = ping.bearings_rad[static_cast<std::size_t>(b)];
        f.p_sonar = f.range_m * Eigen::Vector2d(std::cos(f.bearing_rad), std::sin(f.bearing_rad));
        features.push_back(f);
    }
    return features;
}

// SPEC §5 outlier filter: the mean distance from a feature to the features of the s/2 beams
// before and after it (a window of s + 1 beams). A feature with no neighbour in its window is
// isolated speckle and rejected too.
void flag_outliers(std::vector<SonarFeature>& features, const SonarHullLineConfig& config) {
    const int half = config.outlier_window_beams / 2;
    for (std::size_t i = 0; i < features.size(); ++i) {
        double sum_m = 0.0;
        int count = 0;
        for (std::size_t j = 0; j < features.size(); ++j) {
            if (j == i || std::abs(features[j].beam - features[i].beam) > half) continue;
            sum_m += (features[j].p_sonar - features[i].p_sonar).norm();
            ++count;
        }
        features[i].window_mean_distance_m = count > 0 ? sum_m / count : 0.0;
        features[i].outlier = count == 0 || sum_m / count > config.outlier_distance_m;
    }
}

std::optional<Line> line_through(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    const Eigen::Vector2d d = b - a;
    if (d.norm() < 1e-9) return std::nullopt;
    const Eigen::Vector2d n = Eigen::Vector2d(-d.y(), d.x()).normalized();
    return Line{n, n.dot(a)};
}

std::vector<std::size_t> inliers_of(const Line& line, const std::vector<Eigen::Vector2d>& points,
                                    double threshold_m) {
    std::vector<std::size_t> inliers;
    for (std::size_t i = 0; i < points.size(); ++i) {
        if (line.distance(points[i]) <= threshold_m) inliers.push_back(i);
    }
    return inliers;
}

// The hypothesis with most inliers (the first one on ties, so the result is reproducible).
std::vector<std::size_t> ransac_inliers(const std::vector<Eigen::Vector2d>& points,
                                        const SonarHullLineConfig& config) {
    Rng rng(config.seed);
    std::vector<std::size_t> best;
    for (int it = 0; it < config.ransac_iterations; ++it) {
        const std::vector<std::size_t> pair = rng.sample_indices(points.size(), 2);
        const auto line = line_through(points[pair[0]], points[pair[1]]);
        if (!line) continue;
        auto inliers = inliers_of(*line, points, config.ransac_inlier_distance_m);
        if (inliers.size() > best.size()) best = std::move(inliers);
    }
    return best;
}

// Total least squares: the normal is the covariance's smallest-eigenvalue eigenvector, turned
// to point from the sonar towards the hull (offset >= 0).
std::optional<Line> refit(const std::vector<Eigen::Vector2d>& points,
                          const std::vector<std::size_t>& indices) {
    if (indices.size() < 2) return std::nullopt;
    Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
    for (const std::size_t i : indices) centroid += points[i];
    centroid /= static_cast<double>(indices.size());
    Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();
    for (const std::size_t i : indices) {
        const Eigen::Vector2d d = points[i] - centroid;
        covariance += d * d.transpose();
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver(covariance);
    if (solver.info() != Eigen::Success || solver.eigenvalues()(1) <= 0.0) return std::nullopt;
    Line line{solver.eigenvectors().col(0).normalized(), 0.0};
    line.offset_m = line.normal.dot(centroid);
    if (line.offset_m < 0.0) line = Line{-line.normal, -line.offset_m};
    return line;
}

SonarHullLine with_status(SonarHullLine result, SonarHullLineStatus status, std::string message) {
    result.status = status;
    result.message = std::move(message);
    return result;
}

// RANSAC on the features kept by the outlier filter, then the least-squares refit; marks the
// refitted line's inliers among them.
SonarHullLine fit_line(SonarHullLine result, const SonarHullLineConfig& config) {
    std::vector<Eigen::Vector2d> points;
    std::vector<std::size_t> feature_of;
    for (std::size_t i = 0; i < result.features.size(); ++i) {
        if (result.features[i].outlier) continue;
        points.push_back(result.features[i].p_sonar);
        feature_of.push_back(i);
    }
    if (points.size() < config.min_inliers) {
        std::string message = fmt::format(
            "{} features after the outlier filter ({} edges), expected >= min_inliers = {}",
            points.size(), result.features.size(), config.min_inliers);
        return with_status(std::move(result), SonarHullLineStatus::kTooFewFeatures,
                           std::move(message));
    }
    const auto line = refit(points, ransac_inliers(points, config));
    const auto inliers = line ? inliers_of(*line, points, config.ransac_inlier_distance_m)
                              : std::vector<std::size_t>{};
    if (!line || inliers.size() < config.min_inliers) {
        return with_status(std::move(result), SonarHullLineStatus::kFitFailed,
                           fmt::format("best line has {} inliers of {} features, expected >= "
                                       "min_inliers = {}",
                                       inliers.size(), points.size(), config.min_inliers));
    }
    double sum_sq_m2 = 0.0;
    for (const std::size_t i : inliers) {
        result.features[feature_of[i]].inlier = true;
        sum_sq_m2 += std::pow(line->distance(points[i]), 2);
    }
    result.normal_sonar = line->normal;
    result.distance_m = line->offset_m;
    result.angle_rad = std::atan2(line->normal.y(), line->normal.x());
    result.num_inliers = inliers.size();
    result.rms_m = std::sqrt(sum_sq_m2 / static_cast<double>(inliers.size()));
    std::string message =
        fmt::format("hull at {:.3f} m, {:.2f} deg, {} inliers", result.distance_m,
                    result.angle_rad * 180.0 / std::numbers::pi, result.num_inliers);
    return with_status(std::move(result), SonarHullLineStatus::kOk, std::move(message));
}

}  // namespace

void SonarHullLineConfig::validate(std::string_view prefix) const {
    using namespace config_checks;
    require_positive(intensity_full_scale, prefix, "intensity_full_scale");
    require(blur_kernel_px >= 1 && blur_kernel_px <= 31 && blur_kernel_px % 2 == 1, prefix,
            "blur_kernel_px", blur_kernel_px, "odd in [1, 31]");
    require_positive(canny_low_threshold, prefix, "canny_low_threshold");
    require(std::isfinite(canny_high_threshold) && canny_high_threshold >= canny_low_threshold,
            prefix, "canny_high_threshold", canny_high_threshold, ">= canny_low_threshold");
    require(outlier_window_beams >= 2 && outlier_window_beams % 2 == 0, prefix,
            "outlier_window_beams", outlier_window_beams, "even >= 2");
    require_positive(outlier_distance_m, prefix, "outlier_distance_m");
    require_positive(ransac_inlier_distance_m, prefix, "ransac_inlier_distance_m");
    require_at_least(ransac_iterations, 1, prefix, "ransac_iterations");
    require_count_at_least(min_inliers, 2, prefix, "min_inliers");
}

SonarHullLine detect_hull_line(const io::SonarPing& ping, const SonarHullLineConfig& config) {
    config.validate();
    ping.validate();
    SonarHullLine result;
    result.features = closest_edges(ping, edge_images(ping, config));
    if (result.features.empty()) {
        return with_status(std::move(result), SonarHullLineStatus::kNoReturn,
                           "no edge in the sonar image");
    }
    flag_outliers(result.features, config);
    return fit_line(std::move(result), config);
}

std::string_view to_string(SonarHullLineStatus status) {
    switch (status) {
        case SonarHullLineStatus::kOk:
            return "ok";
        case SonarHullLineStatus::kNoReturn:
            return "no_return";
        case SonarHullLineStatus::kTooFewFeatures:
            return "too_few_features";
        case SonarHullLineStatus::kFitFailed:
            return "fit_failed";
    }
    return "unknown";
}

}  // namespace scantling::perception
