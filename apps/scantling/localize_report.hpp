#pragma once
/// @file
/// What `scantling localize` measures and writes: errors against the ground truth, counts of
/// frame outcomes, timings; the event log and the summary.

#include <Eigen/Geometry>
#include <map>
#include <string>
#include <vector>

#include <scantling/io/tum.hpp>
#include <scantling/localization/localizer.hpp>

namespace scantling::app {

/// Mean, standard deviation, 95th percentile and maximum of a set of errors.
struct ErrorStats {
    std::size_t count = 0;
    double mean = 0.0, std = 0.0, p95 = 0.0, max = 0.0;
};
ErrorStats error_stats(std::vector<double> values);

/// The ground truth, interpolated (the pose at the nearest end outside its span).
class GroundTruth {
  public:
    explicit GroundTruth(std::vector<io::StampedPose> poses) : poses_(std::move(poses)) {}
    Eigen::Isometry3d at(double stamp_s) const;
    bool empty() const { return poses_.empty(); }

  private:
    std::vector<io::StampedPose> poses_;
};

struct LocalizeRun {
    std::vector<localization::FusedState> fused;
    std::vector<io::StampedPose> vio_alone;  ///< VIO in the world through the first true pose
    std::vector<localization::FrameEvent> events;
    std::vector<localization::LocalizerWarning> warnings;
    double wall_s = 0.0;
    double duration_s = 0.0;  ///< of the recording's VIO
};

struct LocalizeMetrics {
    ErrorStats fused_m, vio_m, accepted_registration_m, all_registrations_m;
    ErrorStats fused_yaw_deg;
    double nees_mean = 0.0;  ///< of the fused (δp, δθ), one sample per second
    std::size_t nees_samples = 0;
    double nees_low = 0.0, nees_high = 0.0;       ///< 95 % band of the mean (χ²(6 n) / n)
    std::map<std::string, std::size_t> outcomes;  ///< "registered", "rejected:overlap", ...
    ErrorStats tracking_ms, relocalization_ms;
    double first_fix_s = -1.0;  ///< time from the first frame to the first absolute pose
};

LocalizeMetrics measure(const LocalizeRun& run, const GroundTruth& truth);

/// The event log: one row per frame and per warning, in time order, with the error of the
/// frame's registration against the ground truth.
void write_events_csv(std::ostream& out, const LocalizeRun& run, const GroundTruth& truth);
std::string summary_json(const LocalizeMetrics& m, const LocalizeRun& run,
                         const std::map<std::string, std::string>& settings);
void print_summary(std::ostream& out, const LocalizeMetrics& m, const LocalizeRun& run);

}  // namespace scantling::app
