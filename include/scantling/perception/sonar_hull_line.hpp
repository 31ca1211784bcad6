#pragma once
/// @file
/// The hull line in one forward multibeam sonar ping (SPEC §5, issue 14 item 2): the input of
/// the hull-relative adaptation (stand-off distance and facing angle) and of the sonar
/// inspection map (per-beam features).
///
/// Pipeline: the polar image (rows = beams, columns = range bins) is scaled to 8 bits,
/// optionally blurred along range and edge-detected (Canny); per beam the closest edge pixel is
/// the feature (a locally flat hull is the first thing each beam sees). Its range is refined to
/// a fraction of a bin (the vertex of the rising intensity step) and taken as the centre of the
/// first bin past the step, where the surface lies; the feature is placed at (r cos β, r sin β)
/// in the sonar frame (x boresight, y left). SPEC §5's outlier filter then rejects a feature whose
/// mean distance to the features of the s/2 beams before and after it exceeds a threshold, and a
/// RANSAC line through the rest is refitted by least squares on its inliers.
///
/// Cost: O(num_beams · num_bins) for the image and edges, O(iterations · features) for RANSAC.
/// Thread-safety: a pure function. @note Deterministic: the same ping and config (seed) give
/// the same result, bit for bit.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <scantling/io/sonar_ping.hpp>

namespace scantling::perception {

struct SonarHullLineConfig {
    /// Echo amplitude mapped to 255 in the 8-bit edge image (linear; louder cells clip), > 0.
    /// The default suits the simulator's sonar at gain 1 (hull echoes ≈ 0.1–1 at 1–5 m).
    double intensity_full_scale = 1.0;
    /// Side of the Gaussian blur along range before Canny, in pixels (odd; 1 = none). Off by
    /// default: it smears a one-bin echo towards the sonar (−2 cm at a 30 m range setting on the
    /// simulator's sonar); turn it on for a speckle-heavy real sonar.
    int blur_kernel_px = 1;
    double canny_low_threshold = 40.0;    ///< Canny hysteresis low threshold (8-bit gradient), > 0
    double canny_high_threshold = 100.0;  ///< Canny high threshold, >= canny_low_threshold
    /// Beams on each side of a feature's window are outlier_window_beams / 2: SPEC §5's s
    /// (window of s + 1 beams); even, >= 2.
    int outlier_window_beams = 4;
    /// A feature whose mean distance to the other features in its window exceeds this is an
    /// outlier (SPEC §5 threshold), m, > 0. The default allows neighbours ~0.1 m apart on a
    /// wall seen obliquely at a few metres.
    double outlier_distance_m = 0.25;
    double ransac_inlier_distance_m = 0.03;  ///< point-to-line distance of an inlier, m, > 0
    int ransac_iterations = 200;             ///< line hypotheses (pairs of features), >= 1
    std::uint64_t seed = 1;                  ///< seeds the RANSAC sampling
    /// Fewer filtered features than this gives kTooFewFeatures, and fewer RANSAC inliers gives
    /// kFitFailed, >= 2.
    std::size_t min_inliers = 10;

    /// Throws ConfigError naming "<prefix>.<field>", its value and what was expected.
    void validate(std::string_view prefix = "sonar_hull_line") const;
};

/// The closest edge of one beam, in the sonar frame.
struct SonarFeature {
    int beam = 0;                                       ///< index into the ping's beams
    double range_m = 0.0;                               ///< the edge bin's centre range
    double bearing_rad = 0.0;                           ///< the beam's bearing, positive left
    Eigen::Vector2d p_sonar = Eigen::Vector2d::Zero();  ///< (x forward, y left), m
    double window_mean_distance_m = 0.0;  ///< mean distance to the window's other features
    bool outlier = false;                 ///< rejected by the window filter (SPEC §5)
    bool inlier = false;                  ///< supports the final line
};

enum class SonarHullLineStatus {
    kOk,              ///< a line was fitted
    kNoReturn,        ///< no edge in the image at all
    kTooFewFeatures,  ///< fewer than min_inliers features survive the outlier filter
    kFitFailed,       ///< no line with min_inliers inliers (or a degenerate refit)
};

/// The hull line n · p = distance_m (p in the sonar frame, n = normal_sonar), with n pointing
/// from the sonar towards the hull, so distance_m >= 0 is the perpendicular stand-off.
struct SonarHullLine {
    SonarHullLineStatus status = SonarHullLineStatus::kNoReturn;
    std::string message;                 ///< what happened, one line, for logs and events
    std::vector<SonarFeature> features;  ///< one per beam with an edge, by increasing beam
    Eigen::Vector2d normal_sonar = Eigen::Vector2d::UnitX();  ///< unit, towards the hull
    double distance_m = 0.0;  ///< perpendicular distance from the sonar origin to the line
    /// atan2(n_y, n_x) in (−π, π]: the bearing of the hull's closest point. 0 when the sonar
    /// faces the hull squarely; positive when the hull's closest point (the foot of the
    /// perpendicular) lies to the left (+y), i.e. yawing the sonar left (counter-clockwise
    /// about z up) by angle_rad makes it face the hull. Equivalently the hull's outward
    /// normal, which points back at the sonar, has bearing angle_rad + π.
    double angle_rad = 0.0;
    std::size_t num_inliers = 0;
    double rms_m = 0.0;  ///< RMS point-to-line distance of the inliers after the refit

    bool ok() const { return status == SonarHullLineStatus::kOk; }
};

/// The hull line of one ping. Throws InputError (ping.validate) for a malformed ping and
/// ConfigError for a bad config; an image without returns or a failed fit is a status.
SonarHullLine detect_hull_line(const io::SonarPing& ping, const SonarHullLineConfig& config = {});

/// "ok", "no_return", "too_few_features" or "fit_failed".
std::string_view to_string(SonarHullLineStatus status);

}  // namespace scantling::perception
