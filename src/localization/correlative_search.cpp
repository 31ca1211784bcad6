#include "scantling/localization/correlative_search.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include <scantling/core/error.hpp>
#include <scantling/core/kdtree.hpp>
#include <scantling/core/voxel_grid.hpp>

#include "detail/config_checks.hpp"

namespace scantling::localization {
namespace {

/// At most `n` points of `cloud`, evenly spaced in its (voxel key) order.
std::vector<Eigen::Vector3d> thinned(const PointCloud& cloud, std::size_t n) {
    std::vector<Eigen::Vector3d> out;
    const std::size_t m = cloud.size();
    const std::size_t keep = std::min(n, m);
    for (std::size_t k = 0; k < keep; ++k) out.push_back(cloud.points[k * m / keep]);
    return out;
}

double wrapped(double angle) { return std::remainder(angle, 2.0 * M_PI); }

/// Keeps the best candidate of every neighbourhood, best first, at most `n`.
std::vector<SearchCandidate> suppress(std::vector<SearchCandidate> all,
                                      const CorrelativeSearchConfig& c) {
    std::stable_sort(all.begin(), all.end(),
                     [](const auto& a, const auto& b) { return a.score > b.score; });
    std::vector<SearchCandidate> kept;
    for (const SearchCandidate& s : all) {
        const double yaw = std::atan2(s.T_world_gravity(1, 0), s.T_world_gravity(0, 0));
        const bool near = std::any_of(kept.begin(), kept.end(), [&](const SearchCandidate& k) {
            const double k_yaw = std::atan2(k.T_world_gravity(1, 0), k.T_world_gravity(0, 0));
            return (k.T_world_gravity.translation() - s.T_world_gravity.translation()).norm() <
                       c.separation_m &&
                   std::abs(wrapped(k_yaw - yaw)) < c.separation_yaw_rad;
        });
        if (!near) kept.push_back(s);
        if (kept.size() == c.num_candidates) break;
    }
    return kept;
}

}  // namespace

void LikelihoodFieldConfig::validate(std::string_view prefix) const {
    detail::require_positive(resolution_m, prefix, "resolution_m");
    detail::require_positive(sigma_m, prefix, "sigma_m");
    detail::require_non_negative(margin_m, prefix, "margin_m");
    detail::require(max_cells >= 1, prefix, "max_cells", static_cast<double>(max_cells), ">= 1");
    parallel.validate(std::string(prefix) + ".parallel");
}

void CorrelativeSearchConfig::validate(std::string_view prefix) const {
    detail::require_positive(translation_step_m, prefix, "translation_step_m");
    detail::require(std::isfinite(yaw_step_rad) && yaw_step_rad > 0 && yaw_step_rad <= M_PI, prefix,
                    "yaw_step_rad", yaw_step_rad, "in (0, pi]");
    detail::require_positive(scan_voxel_m, prefix, "scan_voxel_m");
    detail::require(max_scan_points >= 10, prefix, "max_scan_points",
                    static_cast<double>(max_scan_points), ">= 10");
    detail::require_non_negative(min_clearance_m, prefix, "min_clearance_m");
    detail::require(num_candidates >= 1, prefix, "num_candidates",
                    static_cast<double>(num_candidates), ">= 1");
    detail::require_non_negative(separation_m, prefix, "separation_m");
    detail::require_non_negative(separation_yaw_rad, prefix, "separation_yaw_rad");
    parallel.validate(std::string(prefix) + ".parallel");
}

LikelihoodField::LikelihoodField(const PointCloud& map, const LikelihoodFieldConfig& config) {
    config.validate();
    check_usable(map, "likelihood field map");
    bounds_ = compute_bounds(map);
    bounds_.min -= Eigen::Vector3d::Constant(config.margin_m);
    bounds_.max += Eigen::Vector3d::Constant(config.margin_m);
    inverse_resolution_ = 1.0 / config.resolution_m;
    const Eigen::Array3d extent = (bounds_.max - bounds_.min).array() * inverse_resolution_;
    const Eigen::Array3d cells = extent.ceil().max(1.0);
    if (cells.prod() > static_cast<double>(config.max_cells)) {
        throw ConfigError(fmt::format(
            "likelihood_field: {:.0f} cells for a {:.1f} x {:.1f} x {:.1f} m map at {} m, more "
            "than "
            "max_cells = {}",
            cells.prod(), extent.x() * config.resolution_m, extent.y() * config.resolution_m,
            extent.z() * config.resolution_m, config.resolution_m, config.max_cells));
    }
    size_ = cells.cast<int>();
    const std::size_t n = static_cast<std::size_t>(size_.prod());
    score_.assign(n, 0.0f);
    distance_.assign(n, 0.0f);
    const KdTree tree(map.points);
    const double two_sigma2 = 2.0 * config.sigma_m * config.sigma_m;
    parallel_for(config.parallel, n, 4096, [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) {
            const int x = static_cast<int>(i % size_.x());
            const int y = static_cast<int>((i / size_.x()) % size_.y());
            const int z = static_cast<int>(i / (static_cast<std::size_t>(size_.x()) * size_.y()));
            const Eigen::Vector3d centre =
                bounds_.min +
                (Eigen::Vector3d(x, y, z).array() + 0.5).matrix() * config.resolution_m;
            const double d = std::sqrt(tree.nearest(centre)->distance_sq_m2);
            distance_[i] = static_cast<float>(d);
            score_[i] = static_cast<float>(std::exp(-d * d / two_sigma2));
        }
    });
}

std::ptrdiff_t LikelihoodField::cell(const Eigen::Vector3d& p) const {
    // Scalar code: this runs ~10⁷ times per search. NaN fails every comparison below.
    const double x = (p.x() - bounds_.min.x()) * inverse_resolution_;
    const double y = (p.y() - bounds_.min.y()) * inverse_resolution_;
    const double z = (p.z() - bounds_.min.z()) * inverse_resolution_;
    if (!(x >= 0.0 && y >= 0.0 && z >= 0.0 && x < size_.x() && y < size_.y() && z < size_.z())) {
        return -1;
    }
    return (static_cast<std::ptrdiff_t>(z) * size_.y() + static_cast<std::ptrdiff_t>(y)) *
               size_.x() +
           static_cast<std::ptrdiff_t>(x);
}

float LikelihoodField::score(const Eigen::Vector3d& p) const {
    const std::ptrdiff_t i = cell(p);
    return i < 0 ? 0.0f : score_[static_cast<std::size_t>(i)];
}

float LikelihoodField::distance(const Eigen::Vector3d& p) const {
    const std::ptrdiff_t i = cell(p);
    return i < 0 ? 0.0f : distance_[static_cast<std::size_t>(i)];
}

std::vector<SearchCandidate> correlative_search(const LikelihoodField& field,
                                                const PointCloud& scan_gravity,
                                                const Aabb& search_box,
                                                const CorrelativeSearchConfig& config) {
    config.validate();
    if (scan_gravity.empty() || search_box.empty() || field.empty()) return {};
    const std::vector<Eigen::Vector3d> points =
        thinned(voxel_downsample(scan_gravity, {config.scan_voxel_m, config.parallel}),
                config.max_scan_points);
    std::vector<Eigen::Vector3d> positions;
    const Eigen::Array3d steps =
        ((search_box.max - search_box.min).array() / config.translation_step_m).floor() + 1.0;
    for (int z = 0; z < steps.z(); ++z) {
        for (int y = 0; y < steps.y(); ++y) {
            for (int x = 0; x < steps.x(); ++x) {
                const Eigen::Vector3d t =
                    search_box.min + Eigen::Vector3d(x, y, z) * config.translation_step_m;
                if (field.distance(t) >= config.min_clearance_m) positions.push_back(t);
            }
        }
    }
    const int num_yaws =
        std::max(1, static_cast<int>(std::lround(2.0 * M_PI / config.yaw_step_rad)));
    std::vector<std::vector<SearchCandidate>> per_yaw(static_cast<std::size_t>(num_yaws));
    parallel_for(config.parallel, per_yaw.size(), 1, [&](std::size_t begin, std::size_t end) {
        for (std::size_t k = begin; k < end; ++k) {
            const double yaw = -M_PI + 2.0 * M_PI * static_cast<double>(k) / num_yaws;
            const Eigen::Matrix3d R =
                Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
            std::vector<Eigen::Vector3d> rotated(points.size());
            for (std::size_t i = 0; i < points.size(); ++i) rotated[i] = R * points[i];
            std::vector<SearchCandidate> best;
            for (const Eigen::Vector3d& t : positions) {
                double sum = 0.0;
                for (const Eigen::Vector3d& p : rotated) sum += field.score(p + t);
                SearchCandidate c;
                c.T_world_gravity.linear() = R;
                c.T_world_gravity.translation() = t;
                c.score = sum / static_cast<double>(rotated.size());
                best.push_back(c);
            }
            per_yaw[k] = suppress(std::move(best), config);
        }
    });
    std::vector<SearchCandidate> all;
    for (auto& v : per_yaw) all.insert(all.end(), v.begin(), v.end());
    return suppress(std::move(all), config);
}

}  // namespace scantling::localization
