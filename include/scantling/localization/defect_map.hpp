#pragma once
/// @file
/// The defects of a survey: every view of a defect (defect_lifting.hpp) merged into one
/// position with a covariance (SPEC §7, issue 12 item 4).
///
/// Merging: the views' measurement errors (range, pixel) are independent, so they are merged
/// by their information (the weighted mean, covariance (Σ Wᵢ)⁻¹); the fused pose's errors of
/// views a few seconds apart are nearly the same error, which no number of views averages out,
/// so the merged covariance adds their mean pose covariance rather than shrinking it. A view
/// whose squared Mahalanobis distance (its own covariance) to the views' coordinate-wise median
/// exceeds outlier_chi2 is dropped and the rest merged again: a wrong support plane (a
/// stiffener in front of the patch) must not drag the defect. When every view would be dropped
/// none is (there is no majority to trust).
///
/// Thread-safety: not thread-safe; reentrant across instances. Deterministic.

#include <Eigen/Core>
#include <cstddef>
#include <map>
#include <string_view>
#include <vector>

#include <scantling/localization/defect_lifting.hpp>

namespace scantling::localization {

struct DefectMapConfig {
    /// χ²(3) at 0.999: a view this far from the others is not the same measurement, > 0.
    double outlier_chi2 = 16.27;

    void validate(std::string_view prefix = "defect_map") const;
};

struct MappedDefect {
    int defect_id = 0;
    Eigen::Vector3d position_world = Eigen::Vector3d::Zero();
    Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
    Eigen::Vector3d normal_world = Eigen::Vector3d::UnitZ();  ///< of the best view
    std::size_t views = 0;                                    ///< merged
    std::size_t outlier_views = 0;                            ///< dropped by the χ² test
    double first_seen_s = 0.0, last_seen_s = 0.0;
    /// The view with the smallest measurement covariance (near and frontal): its image is the
    /// defect's crop, its returns the local cloud.
    DefectObservation best_view;

    /// √ of the largest eigenvalue of `covariance`, metres.
    double largest_sigma_m() const;
};

class DefectMap {
  public:
    explicit DefectMap(DefectMapConfig config = {});
    /// Keeps only the best view's local cloud (the others' are dropped here).
    void add(DefectObservation view);
    /// One per defect seen, ascending id.
    std::vector<MappedDefect> defects() const;
    std::size_t num_views() const { return num_views_; }

  private:
    DefectMapConfig config_;
    std::map<int, std::vector<DefectObservation>> views_;
    std::size_t num_views_ = 0;
};

/// The merge of `views` (non-empty, one defect) described above.
MappedDefect merge_views(const std::vector<DefectObservation>& views,
                         const DefectMapConfig& config = {});

}  // namespace scantling::localization
