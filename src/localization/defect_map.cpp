#include "scantling/localization/defect_map.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <utility>

#include <scantling/core/error.hpp>

#include "detail/config_checks.hpp"

namespace scantling::localization {
namespace {

/// Whether view `a` is the sharper one (the smaller measurement covariance): the view whose
/// crop and cloud the defect keeps.
bool sharper(const DefectObservation& a, const DefectObservation& b) {
    return a.measurement_covariance.trace() < b.measurement_covariance.trace();
}

/// The index of the sharpest view among `used`.
std::size_t best_of(const std::vector<DefectObservation>& views, const std::vector<bool>& used) {
    std::size_t best = views.size();
    for (std::size_t i = 0; i < views.size(); ++i) {
        if (used[i] && (best == views.size() || sharper(views[i], views[best]))) best = i;
    }
    return best;
}

/// Information-weighted mean of the used views' measurements plus their mean pose covariance.
MappedDefect merge_used(const std::vector<DefectObservation>& views,
                        const std::vector<bool>& used) {
    Eigen::Matrix3d information = Eigen::Matrix3d::Zero();
    Eigen::Vector3d weighted = Eigen::Vector3d::Zero();
    Eigen::Matrix3d pose_sum = Eigen::Matrix3d::Zero();
    MappedDefect d;
    for (std::size_t i = 0; i < views.size(); ++i) {
        if (!used[i]) continue;
        const Eigen::Matrix3d W = views[i].measurement_covariance.inverse();
        information += W;
        weighted += W * views[i].position_world;
        pose_sum += views[i].pose_covariance;
        ++d.views;
    }
    const Eigen::Matrix3d merged_measurement = information.inverse();
    d.position_world = merged_measurement * weighted;
    d.covariance = merged_measurement + pose_sum / static_cast<double>(d.views);
    return d;
}

Eigen::Vector3d coordinate_median(const std::vector<DefectObservation>& views) {
    Eigen::Vector3d median;
    std::vector<double> values(views.size());
    for (int k = 0; k < 3; ++k) {
        for (std::size_t i = 0; i < views.size(); ++i) values[i] = views[i].position_world[k];
        std::sort(values.begin(), values.end());
        const std::size_t n = values.size();
        median[k] = n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
    }
    return median;
}

}  // namespace

void DefectMapConfig::validate(std::string_view prefix) const {
    detail::require_positive(outlier_chi2, prefix, "outlier_chi2");
}

double MappedDefect::largest_sigma_m() const {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(covariance);
    return std::sqrt(std::max(eig.eigenvalues().maxCoeff(), 0.0));
}

MappedDefect merge_views(const std::vector<DefectObservation>& views,
                         const DefectMapConfig& config) {
    if (views.empty()) throw InputError("merge_views: no view to merge");
    std::vector<bool> used(views.size(), true);
    MappedDefect d = merge_used(views, used);
    // Residuals to the median, not to the mean, which the outlier itself drags.
    const Eigen::Vector3d median = coordinate_median(views);
    std::size_t dropped = 0;
    for (std::size_t i = 0; i < views.size(); ++i) {
        const Eigen::Vector3d r = views[i].position_world - median;
        if (r.dot(views[i].covariance().ldlt().solve(r)) > config.outlier_chi2) {
            used[i] = false;
            ++dropped;
        }
    }
    if (dropped > 0 && dropped < views.size()) {
        d = merge_used(views, used);
    } else {
        std::fill(used.begin(), used.end(), true);  // all disagree: no majority to trust
        dropped = 0;
    }
    d.defect_id = views.front().defect_id;
    d.outlier_views = dropped;
    d.best_view = views[best_of(views, used)];
    d.normal_world = d.best_view.normal_world;
    d.first_seen_s = views.front().stamp_s;
    d.last_seen_s = views.back().stamp_s;
    for (const DefectObservation& v : views) {
        d.first_seen_s = std::min(d.first_seen_s, v.stamp_s);
        d.last_seen_s = std::max(d.last_seen_s, v.stamp_s);
    }
    return d;
}

DefectMap::DefectMap(DefectMapConfig config) : config_(std::move(config)) { config_.validate(); }

void DefectMap::add(DefectObservation view) {
    std::vector<DefectObservation>& list = views_[view.defect_id];
    ++num_views_;
    // Only the best view's cloud is ever written: keep one, not one per view.
    const auto best = std::min_element(list.begin(), list.end(), sharper);
    if (best != list.end()) {
        if (sharper(view, *best)) {
            best->local_cloud_world = PointCloud{};
        } else {
            view.local_cloud_world = PointCloud{};
        }
    }
    list.push_back(std::move(view));
}

std::vector<MappedDefect> DefectMap::defects() const {
    std::vector<MappedDefect> out;
    for (const auto& [id, views] : views_) out.push_back(merge_views(views, config_));
    return out;
}

}  // namespace scantling::localization
